"""The robot's world: polygons, their convex split, the swept segment, collision, scenarios, random floors.

Knows no planner.
"""

__all__: list[str] = []
