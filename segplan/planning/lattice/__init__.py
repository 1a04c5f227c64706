"""Beyond the paper: the lattice planner of cubic-union primitives and its helpers."""

__all__: list[str] = []
