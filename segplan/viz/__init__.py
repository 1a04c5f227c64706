"""Pictures and measurements of plans: plots, animations, path metrics."""

__all__: list[str] = []
