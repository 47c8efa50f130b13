"""Paper ``heald``: see linkwork.papers."""
