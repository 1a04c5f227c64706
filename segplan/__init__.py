"""segplan: Campoy et al. (1989), trajectory planning for an oriented-segment robot."""

from .collision import (
    CollisionStats,
    ConvexPolygon,
    collides,
    pose_collides,
    pose_in_bounds,
    union_free,
    union_in_bounds,
)
from .cost import longd, longd_approx, longd_exact
from .frame import optimal_alpha, optimal_alpha_intrinsic
from .metrics import PathMetrics, measure_path, measure_scenario_path, plan_poses
from .pose import Pose
from .refine import Refinement, refine
from .search import NoPathError, Plan, plan, plan_scenario
from .union import Union
from .world import (
    Robot,
    Scenario,
    ScenarioError,
    load_scenario,
    make_scenario,
    random_world,
    save_scenario,
    shipped_scenarios,
)

__version__ = "0.1.0"

__all__ = ["Pose", "Union", "longd_exact"]
__all__ += ["CollisionStats", "ConvexPolygon", "collides", "pose_collides", "pose_in_bounds"]
__all__ += ["union_free", "union_in_bounds"]
__all__ += ["Robot", "Scenario", "ScenarioError", "load_scenario", "make_scenario"]
__all__ += ["random_world", "save_scenario", "shipped_scenarios"]
__all__ += ["NoPathError", "Plan", "plan", "plan_scenario"]
__all__ += ["longd", "longd_approx"]
__all__ += ["PathMetrics", "measure_path", "measure_scenario_path", "plan_poses"]
__all__ += ["optimal_alpha", "optimal_alpha_intrinsic"]
__all__ += ["Refinement", "refine"]
