"""sim stage of unsew (see docs/ARCHITECTURE.md)."""
