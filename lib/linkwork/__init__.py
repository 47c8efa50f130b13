"""linkwork: re-deriving published planar-linkage papers, number by number."""

__version__ = "0.1.0"
