"""sim/energies stage of unsew (see docs/ARCHITECTURE.md)."""
