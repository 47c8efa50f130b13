"""Errors the pipeline reports to the user in one line (no traceback)."""


class ConfigError(ValueError):
    """A config value is invalid; the message names the key and the value."""
