"""Paper ``stiffness``: see linkwork.papers."""
