"""The paper's mathematics: poses, the cubic union, LONGD ([1], [2]), Romberg, the optimal frame.

Knows no floor and no planner.
"""

__all__: list[str] = []
