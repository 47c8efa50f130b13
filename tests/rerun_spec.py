"""The rerun table of docs/parameters.md, rendered from tests/rerun_spec.yaml (the specification the workflow test
checks).

Run `python tests/rerun_spec.py` to print the table; tests/test_workflow.py asserts that docs/parameters.md holds
exactly this text.
"""

from pathlib import Path

import yaml

SPEC_FILE = Path(__file__).resolve().parent / "rerun_spec.yaml"


def readme_table(spec: list[dict]) -> str:
    """Markdown table: edited key and value -> the jobs a dry run schedules (besides `all`)."""
    lines = ["| edit in `config/config.yaml` | jobs scheduled by `snakemake -n` (besides `all`) |", "|---|---|"]
    for row in spec:
        jobs = ", ".join(f"`{j}`" for j in row["jobs"])
        value = f"{row['value']:g}" if isinstance(row["value"], float) else row["value"]
        lines.append(f"| `{row['key']}: {value}` | {jobs} |")
    return "\n".join(lines)


if __name__ == "__main__":
    print(readme_table(yaml.safe_load(SPEC_FILE.read_text())))
