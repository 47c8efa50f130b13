"""Shared fixtures: the project's config, schema and published numbers."""

from pathlib import Path

import pytest
import yaml

PROJECT = Path(__file__).resolve().parent.parent


def load_yaml(rel: str):
    with open(PROJECT / rel) as fh:
        return yaml.safe_load(fh)


@pytest.fixture()
def config():
    return load_yaml("config/config.yaml")


@pytest.fixture()
def schema():
    return load_yaml("config/schema.yaml")


@pytest.fixture(scope="session")
def stiffness_published():
    return load_yaml("config/published/stiffness.yaml")
