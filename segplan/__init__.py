"""segplan: Campoy et al. (1989), trajectory planning for an oriented-segment robot.

A first plan, and a trajectory a controller can drive::

    import math, segplan

    scenario = segplan.load_scenario("fig5_example1")  # or make_scenario(...), load_ros_map(...)
    plan = segplan.plan_scenario(scenario)             # nodes, unions (cubics), cost (LONGD)
    law = plan.trajectory(v_max=1.0, a_max=0.5, a_lat_max=0.5, steer_rate_max=math.radians(30))
    law.to_csv("trajectory.csv")

The stable API is ``segplan.__all__``: these names keep their signatures across
releases. The modules' own exported names (each module's ``__all__``) are the library's
parts, for studies and extensions; they may move between releases. Names with a leading
underscore are private.

The API by concept (the book's chapter "API reference" groups it by the paper's sections):

* model, the paper's mathematics: ``Pose``, ``Union``, ``longd``, ``longd_exact``,
  ``longd_approx``, ``optimal_alpha``, ``optimal_alpha_intrinsic``;
* floor, the robot's world: ``Robot``, ``Scenario``, ``make_scenario``, ``load_scenario``,
  ``save_scenario``, ``shipped_scenarios``, ``random_world``, ``ConvexPolygon``,
  ``convex_pieces``, ``collides``, ``union_free``, ``union_in_bounds``, ``pose_collides``,
  ``pose_in_bounds``, ``CollisionStats``, ``ScenarioError``; beyond the paper, maps:
  ``Floor`` (obstacles and walls, from polygons or an occupancy grid) and ``load_ros_map``
  (a ROS ``map_server`` YAML file and its image);
* planning: ``plan``, ``plan_scenario``, ``Plan``, ``NoPathError``, ``refine``,
  ``Refinement``, and the options objects ``PaperOptions``, ``DefaultOptions``,
  ``LatticeOptions``, ``RefineOptions`` (every tuning value of a planner, with its provenance);
  a plan's trajectory for a controller and its file: ``Plan.poses``, ``Plan.trajectory``,
  ``Plan.facts``, ``Plan.save``, ``Plan.load`` (beyond the paper, :mod:`segplan.planning.trajectory`);
* measure: ``measure_path``, ``measure_scenario_path``, ``plan_poses``, ``plan_clearance``,
  ``PathMetrics``.

The house, every dependency pointing down (enforced by the import-linter contracts in
``pyproject.toml``, checked by ``tests/test_layers.py``)::

    cli | studies/                 the command line, the book's studies
    fit/                           the fits behind model/constants.json
    planning/ | viz/               the planners; plots, animations, path measures
    floor/                         geometry, decompose, occupancy, sweep, maps, collision, scenario,
                                   ros_map, random_floors
    model/                         pose, union, romberg, cost, frame, frame_exact, derivation, constants

    planning/:  planner > api > default > refine | stages > paper/ | lattice/ > context | plan
                > links | options > schedule | trajectory
                > validity | dubins | checks | export
    paper/ (the paper's search):  search > problem | expansion > bisectrix
    lattice/ (beyond the paper):  search > escape | shortcut > astar > approach | guide
                                  > edges | clearance | primitives > frame

``planning.paper`` and ``planning.lattice`` never import each other: the paper's search
stays exactly as reproduced whatever the default planner becomes.
"""

from .floor.collision import CollisionStats, collides, union_free, union_in_bounds
from .floor.decompose import convex_pieces
from .floor.geometry import ConvexPolygon, pose_collides, pose_in_bounds
from .floor.maps import Floor
from .floor.random_floors import random_world
from .floor.ros_map import load_ros_map
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
from .planning.options import DefaultOptions, LatticeOptions, PaperOptions, RefineOptions
from .planning.plan import NoPathError, Plan, Refinement
from .planning.planner import Planner
from .planning.refine import refine
from .viz.metrics import PathMetrics, measure_path, measure_scenario_path, plan_clearance, plan_poses

__version__ = "0.1.0"

__all__ = ["Pose", "Union", "longd_exact"]
__all__ += ["CollisionStats", "ConvexPolygon", "collides", "pose_collides", "pose_in_bounds"]
__all__ += ["union_free", "union_in_bounds"]
__all__ += ["Robot", "Scenario", "ScenarioError", "load_scenario", "make_scenario"]
__all__ += ["random_world", "save_scenario", "shipped_scenarios"]
__all__ += ["convex_pieces"]
__all__ += ["NoPathError", "Plan", "Planner", "plan", "plan_scenario"]
__all__ += ["longd", "longd_approx"]
__all__ += ["PathMetrics", "measure_path", "measure_scenario_path", "plan_poses", "plan_clearance"]
__all__ += ["optimal_alpha", "optimal_alpha_intrinsic"]
__all__ += ["Refinement", "refine"]
__all__ += ["DefaultOptions", "LatticeOptions", "PaperOptions", "RefineOptions"]
__all__ += ["Floor", "load_ros_map"]
