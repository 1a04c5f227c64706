"""What every planner shares: validity, links, plans, Dubins bound, refinement, the entry points."""

__all__: list[str] = []
