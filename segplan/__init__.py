"""segplan: Campoy et al. (1989), trajectory planning for an oriented-segment robot.

The stable API is ``segplan.__all__``: these names keep their signatures across
releases. The modules' own exported names (each module's ``__all__``) are the library's
parts, for studies and extensions; they may move between releases. Names with a leading
underscore are private. The modules are layered, every dependency pointing down (the
README's diagram; enforced by the import-linter contract in ``pyproject.toml``)::

    apps      cli, animate, studies/, fit/ (above plot)
    api       api (plan, plan_scenario), refine
    search    search (A*), expansion (the paper's intermediate nodes), lattice, approach
    problem   problem, links, validity, path, metrics, primitives, clearance
    world     world, floors, collision, sweep
    numerics  frame (above frame_exact), cost, geometry, decompose (non-convex polygons)
    base      union, constants (the stored fits), romberg, pose, derivation, dubins
"""

from .floor.collision import CollisionStats, collides, union_free, union_in_bounds
from .floor.decompose import convex_pieces
from .floor.geometry import ConvexPolygon, pose_collides, pose_in_bounds
from .floor.random_floors import random_world
from .floor.scenario import (
    Robot,
    Scenario,
    ScenarioError,
    load_scenario,
    make_scenario,
    save_scenario,
    shipped_scenarios,
)
from .model.cost import longd, longd_approx, longd_exact
from .model.frame import optimal_alpha, optimal_alpha_intrinsic
from .model.pose import Pose
from .model.union import Union
from .planning.api import plan, plan_scenario
from .planning.plan import NoPathError, Plan, Refinement
from .planning.refine import refine
from .viz.metrics import PathMetrics, measure_path, measure_scenario_path, plan_poses

__version__ = "0.1.0"

__all__ = ["Pose", "Union", "longd_exact"]
__all__ += ["CollisionStats", "ConvexPolygon", "collides", "pose_collides", "pose_in_bounds"]
__all__ += ["union_free", "union_in_bounds"]
__all__ += ["Robot", "Scenario", "ScenarioError", "load_scenario", "make_scenario"]
__all__ += ["random_world", "save_scenario", "shipped_scenarios"]
__all__ += ["convex_pieces"]
__all__ += ["NoPathError", "Plan", "plan", "plan_scenario"]
__all__ += ["longd", "longd_approx"]
__all__ += ["PathMetrics", "measure_path", "measure_scenario_path", "plan_poses"]
__all__ += ["optimal_alpha", "optimal_alpha_intrinsic"]
__all__ += ["Refinement", "refine"]
