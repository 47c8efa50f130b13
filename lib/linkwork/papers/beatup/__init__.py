"""Paper ``beatup``: see linkwork.papers."""
