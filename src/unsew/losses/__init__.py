"""losses stage of unsew (see docs/ARCHITECTURE.md)."""
