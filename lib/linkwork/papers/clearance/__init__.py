"""Paper ``clearance``: see linkwork.papers."""
