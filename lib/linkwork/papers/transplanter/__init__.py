"""Paper ``transplanter``: see linkwork.papers."""
