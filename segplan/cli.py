"""Command line: ``segplan plan``, ``segplan draw``, ``segplan scenarios``.

``segplan plan SCENARIO [--heuristic a|b|c] [--refine] [--out P.png] [--animate P.gif
[--frames N] [--fps N] [--dpi N]]`` plans a forward-only path of the oriented-segment robot
(Campoy et al., 1989) on a scenario file (see :mod:`segplan.floor.scenario` for the format),
prints its cost (LONGD, the front-wheel path length), nodes, expansions and time, and
optionally draws and animates it (:mod:`segplan.viz.animate`). ``--poses FILE.csv`` and
``--trajectory FILE.csv`` (with ``--v-max``, ``--a-max``, ``--a-lat-max``,
``--steer-rate-max``, ``--step``) write the plan sampled and timed
(:meth:`segplan.Plan.poses`, :meth:`segplan.Plan.trajectory`); ``--nav-path FILE.yaml``
writes the timed poses as a ROS ``nav_msgs/Path``-shaped message
(:meth:`segplan.planning.trajectory.Trajectory.nav_path`, frame ``map``).

SCENARIO is a scenario file or the name of a shipped scenario (``segplan plan
fig5_example1``), or a ROS ``map_server`` map with the poses and the robot: ``segplan plan
map.yaml --start X Y THETA_DEG --goal X Y THETA_DEG --L 1.2 [--half-width 0.35]
[--max-steer-deg 45] [--overhangs FRONT REAR] [--rectangle]`` (:func:`segplan.load_ros_map`).

``segplan draw FLOOR [--out FLOOR.png]`` draws a floor before planning: FLOOR as SCENARIO
above, a map with or without the poses and the robot. ``segplan scenarios`` lists the
shipped scenarios, one line each; ``segplan scenarios NAME [--export FILE.json]`` prints one
or writes it to a new file to edit.

Also ``python -m segplan`` and ``segplan --version``. Errors (unreadable or invalid file or
option, no path) print one clear line on stderr and exit with a non-zero status, without a
traceback.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import sys
from pathlib import Path

from . import __version__
from .floor.maps import Floor
from .floor.ros_map import load_ros_map
from .floor.scenario import (
    FOOTPRINT_KEYS,
    Robot,
    Scenario,
    ScenarioError,
    load_scenario,
    make_scenario,
    save_scenario,
    shipped_scenarios,
)
from .planning.api import plan_scenario
from .planning.export import write_nav_path
from .planning.options import DefaultOptions, LatticeOptions, PaperOptions
from .planning.plan import NoPathError, Plan
from .planning.trajectory import DEFAULT_STEP, POSE_COLUMNS
from .viz import animate
from .viz.metrics import plan_clearance
from .viz.progress import ProgressLine

__all__ = ["CLI_LIMITS", "EXIT_BAD_INPUT", "EXIT_NO_PATH", "NAV_FRAME", "build_parser", "main"]

EXIT_NO_PATH = 1
EXIT_BAD_INPUT = 2

DESCRIPTION = """\
Trajectory planning for an oriented-segment mobile robot (Campoy et al., 1989).

The robot is the segment from the middle of the rear axle A to the front wheel B, of
length L; it drives forward only (--reverse: both ways), with the rear path's curvature at most
tan(max_steer) / L. A plan is a chain of nodes (poses x, y, theta) joined by cubic
unions, each in its optimal reference system; its cost is LONGD, the length of the
front wheel's path. The graph is built on-line (intermediate nodes on the bisectrix of
the obstacle vertex that blocks a union) and searched by A* with f = g + h'.
"""

PLAN_EPILOG = """\
heuristics h' (the paper's three choices):
  a  LONGD of the direct union from the node to the goal (fast, not admissible)
  b  distance between the points (admissible, slower)
  c  weighted average of a and b: w = p / (p + d_s / L), p the node's depth,
     d_s the median gap between neighbouring obstacles

scenario file (JSON, lengths in metres, angles in degrees):
  {"L": 1.2, "half_width": 0.35, "max_steer_deg": 45, "reverse": false,
   "start": [x, y, theta_deg], "goal": [x, y, theta_deg],
   "bounds": [xmin, ymin, xmax, ymax], "obstacles": [[[x, y], ...], ...]}
  optional, the body: "front_overhang": 0.3, "rear_overhang": 0.5, "rectangle": true
  an obstacle is any simple polygon (its vertices in order, not closed); a
  non-convex one (an L-shaped rack, a concave bay) is split into convex pieces
  before planning; example: segplan plan l_shaped_rack
  start from a shipped one (segplan scenarios lists them):
  segplan scenarios fig5_example1 --export my_floor.json; check it with
  segplan draw my_floor.json, then segplan plan my_floor.json

output: cost, nodes (x, y in m, theta in deg), expansions, generated nodes, time,
the planner. With --json, one JSON object on stdout instead (with the planner,
every option that made the plan, the robot's overhangs). With --out, a figure with the
obstacles (enlarged by half_width, lighter), the rear path (solid), the front-wheel
path (dashed) and the robot at intervals, the legend beside the floor. With --animate,
the robot (its body as wide as 2 half_width) driving the plan.

exit status: 0 plan found, 1 no path within the limits, 2 bad input.
examples:
  segplan plan fig5_example1
  segplan plan fig5_example1 --refine --animate fig5.gif
  segplan plan fig5_example1 --animate fig5.gif --frames 60 --fps 15 --dpi 120
  segplan plan scenarios/fig5_example1.json
  segplan plan scenarios/fig5_example1.json --heuristic c --out fig5.png
  segplan plan scenarios/turn_around.json --json
  segplan plan fig5_example1 --poses fig5_poses.csv --trajectory fig5_traj.csv --v-max 1.5
  segplan plan map.yaml --start 1 1.5 0 --goal 8.5 4.5 -90 --L 1.2 --half-width 0.35 \
      --trajectory traj.csv --nav-path path.yaml
"""


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line (the option named, a pointer to
    ``--help``) with our exit status for bad input."""

    def error(self, message):  # pragma: no cover - exercised through main()
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


REVERSE_HELP = """beyond the paper: the robot may also drive backwards (the scenario's "reverse": true); \
the default planner reverses where it pays (issue 26), the paper's search stays forward-only"""


def build_parser() -> argparse.ArgumentParser:
    """The ``segplan`` argument parser (sub-commands ``plan``, ``draw`` and ``scenarios``)."""
    parser = _Parser(
        prog="segplan", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--version", action="version", version=f"segplan {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    p = sub.add_parser(
        "plan",
        help="plan a path on a scenario file and print (or draw) it",
        description="Plan a path from the scenario's start pose to its goal pose (forward unless --reverse).",
        epilog=PLAN_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "scenario",
        metavar="SCENARIO",
        help="scenario file (JSON, see below) or the name of a shipped scenario: "
        + ", ".join(shipped_scenarios()),
    )
    p.add_argument(
        "--planner",
        choices=("lattice", "paper"),
        default="lattice",
        help="lattice (default, beyond the paper): the resolution-complete A* over a lattice of "
        "cubic-union primitives, refined; paper: the paper's search (the options --heuristic, "
        "--cost and --node-frames apply to it only)",
    )
    p.add_argument(
        "--clearance",
        type=float,
        default=0.0,
        metavar="M",
        help="safety margin in metres beyond half_width, honoured by the search and the "
        "refinement (default 0: the paper's model)",
    )
    p.add_argument("--reverse", action="store_true", help=REVERSE_HELP)
    p.add_argument("--heuristic", choices=("a", "b", "c"), default="a", help="h' of the search (default: a)")
    p.add_argument(
        "--cost",
        choices=("longd", "distance"),
        default="longd",
        help="link cost: LONGD (the method, default) or the distance between node points "
        "(the paper's comparison baseline); the printed cost is LONGD either way",
    )
    p.add_argument(
        "--node-frames",
        choices=("a", "b"),
        default="b",
        help="reference systems of intermediate nodes (Fig. 4): b one optimal frame per piece "
        "(default), a one frame shared by both pieces",
    )
    p.add_argument(
        "--refine",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="beyond the paper: shorten the plan found by shortcuts, splits and local moves "
        "of its nodes (segplan.refine); default: on for --planner lattice, off for paper",
    )
    p.add_argument("--out", metavar="PLAN.png", help="draw the plan to this image file")
    p.add_argument(
        "--animate",
        metavar="PLAN.gif",
        help="write an animation of the robot driving the plan (GIF, or an HTML page: the robot's "
        "body, rear and front-wheel traces); --frames, --fps and --dpi set it",
    )
    _add_animation_options(p)
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--progress", action="store_true", help="show the call's progress on stderr")
    p.add_argument(
        "--max-expansions",
        type=int,
        default=None,
        metavar="N",
        help=f"give up after N expansions (default {PaperOptions.max_expansions} for --planner paper, "
        f"{LatticeOptions.max_expansions} for lattice)",
    )
    p.add_argument(
        "--time-limit",
        type=float,
        default=DefaultOptions.time_limit,
        metavar="S",
        help="give up after S seconds; the refinement stops there too "
        f"(default {DefaultOptions.time_limit:g})",
    )
    _add_trajectory_options(p)
    _add_map_options(p, "SCENARIO", "then --start, --goal and --L are required.")
    _add_draw_command(sub)
    _add_scenarios_command(sub)
    return parser


def _add_draw_command(sub) -> None:
    """``segplan draw FLOOR [--out FLOOR.png]``: a floor drawn before planning."""
    d = sub.add_parser(
        "draw",
        help="draw a floor (a scenario, a shipped scenario or a ROS map) before planning",
        description="Draw a floor: its walls, its obstacles (enlarged by the robot's half-width, "
        "lighter) and the robot at start and goal, to check a floor before planning on it.",
        epilog="exit status: 0 drawn, 2 bad input.\nexamples:\n  segplan draw fig5_example1\n"
        "  segplan draw my_floor.json --out my_floor.png\n  segplan draw office.yaml\n"
        "  segplan draw office.yaml --start 1 2 0 --goal 9 4 90 --L 1.2 --half-width 0.35",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    d.add_argument(
        "scenario",
        metavar="FLOOR",
        help="scenario file (JSON, see segplan plan --help), the name of a shipped scenario "
        "(segplan scenarios lists them) or a ROS map_server .yaml file",
    )
    d.add_argument("--out", metavar="FLOOR.png", help="the image file (default: the floor's name, .png)")
    _add_map_options(
        d, "FLOOR", "with --start, --goal and --L it is drawn with the robot, without them bare."
    )


def _add_scenarios_command(sub) -> None:
    """``segplan scenarios [NAME [--export FILE.json]]``: the shipped floors."""
    c = sub.add_parser(
        "scenarios",
        help="list the shipped scenarios, or print or export one to edit",
        description="Without NAME, one line per shipped scenario: its name, the floor's size, its "
        "obstacles and its robot. With NAME, the scenario file (JSON) on stdout, or with --export "
        "written to a file to edit and plan on.",
        epilog="exit status: 0 done, 2 bad input.\nexamples:\n  segplan scenarios\n"
        "  segplan scenarios fig5_example1 --export my_floor.json\n  segplan plan my_floor.json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    c.add_argument("name", metavar="NAME", nargs="?", help="a shipped scenario")
    c.add_argument(
        "--export", metavar="FILE.json", help="write the scenario to this new file (never overwritten)"
    )


def _add_animation_options(p: argparse.ArgumentParser) -> None:
    """``--frames``, ``--fps``, ``--dpi`` of ``--animate`` (:func:`segplan.viz.animate.animate_path`)."""
    a = animate
    p.add_argument(
        "--frames",
        type=_frame_count,
        metavar="N",
        help=f"frames of the animation (>= 2; default: one every {a.FRAME_STEP:g} L of the front "
        f"wheel's travel, from {a.MIN_FRAMES} to {a.MAX_FRAMES})",
    )
    p.add_argument(
        "--fps",
        type=int,
        metavar="N",
        help=f"frames per second of the animation (1 to {a.MAX_FPS}; default {a.FPS})",
    )
    p.add_argument(
        "--dpi",
        type=float,
        metavar="N",
        help=f"pixels per inch of the animation ({a.DPI_RANGE[0]} to {a.DPI_RANGE[1]}; default {a.DPI}: "
        f"{a.FIGSIZE[0] * a.DPI:.0f} x {a.FIGSIZE[1] * a.DPI:.0f} pixels)",
    )


# -- trajectories out (issue 27): --poses, --trajectory and the limits --------------------------
#: Defaults of the time law's limits on the command line: set by hand (issue 27) for a slow
#: indoor vehicle of the book's size (L = 1.2 m); not measured. The library has none.
CLI_LIMITS = {"v_max": 1.0, "a_max": 0.5, "a_lat_max": 0.5, "steer_rate_max_deg": 30.0}
#: The frame of the poses ``--nav-path`` writes: a map_server map's, and a scenario file's
#: world coordinates.
NAV_FRAME = "map"


def _frame_count(text: str) -> int:
    """An argparse type: the number of frames of an animation (its range is checked later,
    with the other animation options)."""
    if text in ("a", "b"):
        raise argparse.ArgumentTypeError(
            f"expected a number of animation frames, got {text!r} (the reference systems of "
            "intermediate nodes are --node-frames a|b)"
        )
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None


def _positive(text: str) -> float:
    """An argparse type: a finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
    return value


def _add_trajectory_options(p: argparse.ArgumentParser) -> None:
    """``--poses``, ``--trajectory`` and the time law's limits (:meth:`segplan.Plan.trajectory`)."""
    g = p.add_argument_group(
        "trajectories out",
        "samples every --step m along the rear point's path, as CSV; a node where two unions "
        "meet is listed once per union (each side's curvature and steering angle)",
    )
    g.add_argument(
        "--poses",
        metavar="FILE.csv",
        help=f"write the poses in driving order: {','.join(POSE_COLUMNS)} (m, rad, 1/m; -1 reversing)",
    )
    g.add_argument(
        "--trajectory",
        metavar="FILE.csv",
        help="write a time law within the limits below, from rest to rest: t,s,v,a and the pose "
        "columns (s, m/s, m/s^2; v < 0 reversing); the robot stops at each cusp and to re-steer where the "
        "steering jumps at a node. Prints the total time and what the jumps cost",
    )
    g.add_argument(
        "--nav-path",
        metavar="FILE.yaml",
        help=f"write the time law's poses as a ROS nav_msgs/Path message, each stamped with its time "
        f"(frame {NAV_FRAME!r}; YAML for .yaml or .yml, JSON for .json; needs no ROS). A reversing pose "
        "keeps the robot's heading (the direction is in the CSVs)",
    )
    g.add_argument(
        "--step",
        type=_positive,
        default=DEFAULT_STEP,
        metavar="M",
        help=f"largest sample spacing along the rear path, m (default {DEFAULT_STEP:g})",
    )
    for name, key, unit, what in (
        ("v_max", "v_max", "m/s", "speed of the rear point"),
        ("a_max", "a_max", "m/s^2", "acceleration and braking"),
        ("a_lat_max", "a_lat_max", "m/s^2", "lateral acceleration"),
        ("steer_rate_max", "steer_rate_max_deg", "deg/s", "steering rate"),
    ):
        g.add_argument(
            "--" + name.replace("_", "-"),
            type=_positive,
            default=CLI_LIMITS[key],
            metavar=unit.upper().replace("/", "_").replace("^2", "2"),
            help=f"largest {what}, {unit} (default {CLI_LIMITS[key]:g})",
        )


def _trajectories_out(args, result: Plan) -> tuple[dict, list[str]]:
    """Write ``--poses``, ``--trajectory`` and ``--nav-path`` (one time law for both); their JSON
    entries and text lines. OSError and ValueError propagate to :func:`main`."""
    out: dict = {}
    lines: list[str] = []
    if args.poses:
        samples = result.poses(args.step)
        samples.to_csv(args.poses)
        out["poses"] = {"file": args.poses, "samples": len(samples), "step": args.step}
        lines.append(f"poses       {args.poses} ({len(samples)} samples, every {args.step:g} m or less)")
    if not (args.trajectory or args.nav_path):
        return out, lines
    law = result.trajectory(
        args.v_max, args.a_max, args.a_lat_max, math.radians(args.steer_rate_max), step=args.step
    )
    if args.trajectory:
        law.to_csv(args.trajectory)
        out["trajectory"] = {"file": args.trajectory, "samples": len(law)} | {
            k: getattr(law, k) for k in ("total_time", "jump_time", "dwell_time", "jumps", "cusps")
        }
        limits = {k: getattr(law, k) for k in ("v_max", "a_max", "a_lat_max")}
        out["trajectory"]["limits"] = limits | {"steer_rate_max_deg": args.steer_rate_max}
        lines += [
            f"trajectory  {args.trajectory} ({len(law)} samples)",
            f"  time      {law.total_time:.2f} s from rest to rest, of which {law.jump_time:.2f} s for "
            f"{law.jumps} steering jumps ({law.dwell_time:.2f} s re-steering standing), "
            f"stops at cusps: {law.cusps}",
        ]
    if args.nav_path:
        message = law.nav_path(NAV_FRAME)
        write_nav_path(args.nav_path, message)
        n = len(message["poses"])
        out["nav_path"] = {
            "file": args.nav_path,
            "poses": n,
            "frame_id": NAV_FRAME,
            "total_time": law.total_time,
        }
        lines.append(
            f"nav path    {args.nav_path} ({n} poses in frame {NAV_FRAME!r}, stamped by the time law, "
            f"{law.total_time:.2f} s)"
        )
    return out, lines


MAP_SUFFIXES = (".yaml", ".yml")


def _add_map_options(p: argparse.ArgumentParser, argument: str, poses: str) -> None:
    """The options of a ROS map (``argument`` a map_server .yaml file): poses and robot;
    ``poses`` says when they are needed."""
    g = p.add_argument_group(
        "maps",
        f"{argument} may be a ROS map_server map (a .yaml file naming a PGM or PNG image); {poses} "
        "Unknown cells are obstacles.",
    )
    g.add_argument("--start", nargs=3, type=float, metavar=("X", "Y", "THETA_DEG"), help="start pose")
    g.add_argument("--goal", nargs=3, type=float, metavar=("X", "Y", "THETA_DEG"), help="goal pose")
    g.add_argument("--L", type=float, metavar="M", help="robot length A->B in metres")
    g.add_argument("--half-width", type=float, metavar="M", help="robot half-width in metres (default 0)")
    g.add_argument("--overhangs", nargs=2, type=float, metavar=("FRONT", "REAR"), help="the body's reach "
                   "beyond the front wheel B and behind the rear axle A in metres (default 0 0)")  # fmt: skip
    g.add_argument("--rectangle", action="store_true", help="the body is a rectangle (default: round ends)")
    g.add_argument(
        "--max-steer-deg", type=float, metavar="DEG", help="steering limit in degrees (default 45)"
    )
    g.add_argument("--unknown-free", action="store_true", help="treat the map's unknown cells as free space")


def _load(args, *, poses_needed: bool = True) -> Scenario | Floor:
    """What ``args.scenario`` names: a scenario file, a shipped scenario's name, or a ROS map
    with the poses and the robot given (a :class:`Scenario`); without them, when
    ``poses_needed`` is false, the map's :class:`Floor`.

    Raises ScenarioError (one line, the file named) for any bad input.
    """
    is_map = Path(args.scenario).suffix.lower() in MAP_SUFFIXES
    options = {"--start": args.start, "--goal": args.goal, "--L": args.L, "--half-width": args.half_width}
    options |= {"--max-steer-deg": args.max_steer_deg, "--unknown-free": args.unknown_free or None}
    options |= {"--overhangs": args.overhangs, "--rectangle": args.rectangle or None}
    given = [flag for flag, value in options.items() if value is not None]
    if not is_map:
        if given:
            raise ScenarioError(
                f"{given[0]} applies to a map (a ROS map_server .yaml file), not a scenario file"
            )
        return load_scenario(args.scenario)
    needed = ("--start", "--goal", "--L")
    missing = [f for f in needed if options[f] is None]
    robot_given = [f for f in given if f not in ("--unknown-free", *needed)]
    if missing and (poses_needed or len(missing) < len(needed) or robot_given):
        raise ScenarioError(f"{args.scenario}: a map needs {', '.join(missing)} (poses in m and deg, L in m)")
    try:
        floor = load_ros_map(args.scenario, unknown_is_occupied=not args.unknown_free)
        if missing:
            return floor
        steer = math.radians(45.0 if args.max_steer_deg is None else args.max_steer_deg)
        front, rear = args.overhangs or (0.0, 0.0)
        robot = Robot(args.L, args.half_width or 0.0, steer, front, rear, args.rectangle)
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None
    start, goal = ((x, y, math.radians(th)) for x, y, th in (args.start, args.goal))
    return make_scenario(robot, start, goal, floor, name=Path(args.scenario).stem, source=args.scenario)


def _floor_facts(floor: Scenario | Floor) -> tuple[str, str, str]:
    """A floor in words: its size, its obstacles, its robot ("-" for a map's floor)."""
    b = floor.bounds
    size = "no walls" if b is None else f"{b[2] - b[0]:g} x {b[3] - b[1]:g} m"
    n = len(floor.outlines)
    obstacles = f"{n} obstacle{'s' if n != 1 else ''}"
    if len(floor.obstacles) != n:
        obstacles += f" ({len(floor.obstacles)} convex pieces)"
    if not isinstance(floor, Scenario):
        return size, obstacles, "-"
    r = floor.robot
    robot = f"L {r.L:g} m, half-width {r.half_width:g} m, steering {math.degrees(r.max_steer):.4g} deg"
    body = f", overhangs {r.front_overhang:g} m front, {r.rear_overhang:g} m rear" * (r.axis != (0, r.L))
    return size, obstacles, robot + body + ", rectangle" * r.rectangle


def _what_the_plan_is(result: Plan, scenario: Scenario) -> dict:
    """What a user needs to know of the plan besides its nodes (issue 27): which planner made
    it, the front and rear path lengths, the clearance beyond the half-width (sampled every
    centimetre), the largest curvature against the limit, the steering jumps at the nodes."""
    facts = result.facts(scenario.robot.max_steer)
    jumps = [float(j) for j in facts.steer_jump[1:-1]]
    return {
        "made_by": (
            "the paper's search"
            if result.planner == "paper"
            else "the default planner: its lattice"
            if result.version == "lattice"
            else "the default planner: the paper's search's plan, kept as the shorter"
        ),
        "front_length": facts.front_length,
        "rear_length": facts.rear_length,
        "clearance": plan_clearance(result, scenario, 0.01),
        "max_curvature": facts.max_curvature,
        "curvature_limit": facts.curvature_limit,
        "within_limit": facts.within_limit,
        "steering_jumps_deg": [math.degrees(j) for j in jumps],
        "cusps": list(result.cusps),
    }


def _format_facts(facts: dict) -> list[str]:
    jumps = facts["steering_jumps_deg"]
    shown = [f"{j:+.1f}" + (" (cusp)" if i in facts["cusps"] else "") for i, j in enumerate(jumps, 1)]
    return [
        f"made by     {facts['made_by']}",
        f"paths       front wheel {facts['front_length']:.3f} m, rear axle {facts['rear_length']:.3f} m",
        f"clearance   {1000.0 * facts['clearance']:.1f} mm beyond the half-width (sampled every 1 cm)",
        f"curvature   at most {facts['max_curvature']:.4f} 1/m, limit {facts['curvature_limit']:.4f} 1/m",
        "steering    "
        + (
            "no node: one union"
            if not jumps
            else f"jumps at the nodes {', '.join(shown)} deg "
            f"(largest {max(abs(j) for j in jumps):.1f} deg; a controller re-steers there)"
        ),
    ]


def _format_plan(result: Plan, name: str) -> str:
    lines = [
        f"scenario    {name}",
        f"cost        {result.cost:.4f} m (LONGD, front-wheel path length)",
        f"nodes       {len(result.nodes)} ({len(result.unions)} unions, cusps: {len(result.cusps)})",
    ]
    back = (0,) + tuple(d < 0 for d in result.link_directions)  # the node reached reversing
    for i, (p, kind) in enumerate(zip(result.nodes, result.kinds, strict=True)):
        kind += (" (reversing to it)" if back[i] else "") + (", cusp" if i in result.cusps else "")
        lines.append(f"  {i:3d}  x={p.x:9.4f}  y={p.y:9.4f}  theta={math.degrees(p.theta):9.3f} deg  {kind}")
    lines += [
        f"expansions  {result.expanded}",
        f"generated   {result.generated}",
        f"time        {1000.0 * result.seconds:.1f} ms",
        f"search      heuristic {result.heuristic}, cost {result.cost_kind}, node frames {result.version}",
        f"planner     {result.planner}",
    ]
    r = result.refinement
    if r is not None:
        lines.append(
            f"refined     LONGD {r.cost_before:.4f} -> {r.cost_after:.4f} m, nodes {r.nodes_before} -> "
            f"{r.nodes_after}, {1000.0 * r.seconds:.1f} ms of the time"
            + (" (stopped at the time limit)" if r.stopped else "")
        )
    return "\n".join(lines)


def _draw(path: str, scenario, unions, title: str, directions=()) -> None:
    """Write the floor and the plan's unions (:func:`segplan.viz.plot.plan_figure`; a reverse
    plan's ``directions``, :attr:`segplan.Plan.directions`) to ``path``; OSError propagates."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .viz import plot

    fig = plot.plan_figure(scenario, unions, title, directions)
    try:
        fig.savefig(path, dpi=120, bbox_inches="tight")
    finally:
        plt.close(fig)


def _animate(path: str, scenario, result: Plan, title: str, options: dict) -> None:
    """Write the animation of ``result`` (``options``: :func:`_animation_options`) as a GIF or
    an HTML page; OSError propagates."""
    import matplotlib

    matplotlib.use("Agg")

    anim = animate.animate_plan(result, scenario, title=title, **options)
    if Path(path).suffix.lower() == ".html":
        Path(path).write_text(animate.to_html(anim), encoding="utf-8")
    else:
        animate.save_gif(anim, path)


#: The figure formats of --out (matplotlib's, without a display) and the animation formats
#: of --animate (a GIF through Pillow, or a self-contained HTML page).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp")
ANIMATION_SUFFIXES = (".gif", ".html")
#: The formats of --nav-path (segplan.planning.export.write_nav_path: YAML, else JSON).
NAV_PATH_SUFFIXES = (".yaml", ".yml", ".json")
#: Exit status after Ctrl-C (128 + SIGINT, the shell's convention).
EXIT_INTERRUPTED = 130
#: Exit status when the reader of the output went away (128 + SIGPIPE, the shell's convention).
EXIT_BROKEN_PIPE = 141


def _check_outputs(args) -> str | None:
    """The error line for an output this command cannot make, or None; checked before planning,
    so a long plan is not lost to a typo: an --out, --animate or --nav-path file of a kind it
    cannot write, an animation option without --animate or out of range."""
    animation = getattr(args, "animate", None)
    for option, path, kinds, what in (
        ("--out", args.out, FIGURE_SUFFIXES, "a figure"),
        ("--animate", animation, ANIMATION_SUFFIXES, "an animation"),
        ("--nav-path", getattr(args, "nav_path", None), NAV_PATH_SUFFIXES, "a nav_msgs/Path file"),
    ):
        if path and Path(path).suffix.lower() not in kinds:
            return f"{option} {path}: cannot write {what} of this type; use one of {', '.join(kinds)}"
    if args.command != "plan":
        return None
    given = [flag for flag in ("--frames", "--fps", "--dpi") if getattr(args, flag[2:]) is not None]
    if given and not animation:
        return f"{given[0]} applies to --animate, and no animation is asked for"
    try:
        animate.check_animation(*_animation_options(args).values(), prefix="--")
    except ValueError as exc:
        return str(exc)
    return None


def _animation_options(args) -> dict:
    """``frames``, ``fps``, ``dpi`` of :func:`segplan.viz.animate.animate_path` from the command line."""
    fps = animate.FPS if args.fps is None else args.fps
    return {"frames": args.frames, "fps": fps, "dpi": animate.DPI if args.dpi is None else args.dpi}


def _planner_text(result: Plan, args) -> str:
    """Which planner made the plan, as a figure title says it."""
    if result.planner == "paper":
        return f"the paper's search, heuristic {args.heuristic}"
    if result.version == "lattice":
        return "default planner (lattice)"
    return f"default planner (the paper's search, heuristic {args.heuristic})"


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``segplan`` command; returns the exit status (0 a plan, 1 no plan,
    2 bad input, 130 interrupted by Ctrl-C). A closed output pipe (``segplan plan X | head``)
    ends it quietly, the Unix way."""
    try:
        return _main(argv)
    except KeyboardInterrupt:
        print("segplan: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        # the reader went away: nothing more can be printed; no traceback at exit either
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE


def _main(argv: list[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_BAD_INPUT
    if args.command == "scenarios":
        return _scenarios(args)
    bad = _check_outputs(args)
    if bad:
        return _error(bad)
    try:
        scenario = _load(args, poses_needed=args.command == "plan")
    except ScenarioError as exc:
        return _error(str(exc))
    name = getattr(scenario, "name", "") or Path(args.scenario).stem
    if getattr(args, "reverse", False) and isinstance(scenario, Scenario):
        scenario = dataclasses.replace(scenario, robot=dataclasses.replace(scenario.robot, reverse=True))
    if args.command == "draw":
        return _draw_floor(args, scenario, name)
    return _plan(args, scenario, name)


def _error(message: str) -> int:
    """Print one error line; the exit status of bad input."""
    print(f"segplan: error: {message}", file=sys.stderr)
    return EXIT_BAD_INPUT


def _scenarios(args) -> int:
    """``segplan scenarios``: list the shipped scenarios, or print or export one."""
    names = shipped_scenarios()
    if args.name is None:
        if args.export:
            return _error("--export needs the NAME of the scenario to write (segplan scenarios lists them)")
        rows = [("name", "floor", "obstacles", "robot")]
        rows += [(name, *_floor_facts(load_scenario(name))) for name in names]
        widths = [max(len(row[i]) for row in rows) for i in range(3)]
        for row in rows:
            print("  ".join(cell.ljust(w) for cell, w in zip(row[:3], widths, strict=True)) + "  " + row[3])
        return 0
    if args.name not in names:
        return _error(f"no shipped scenario {args.name!r}; the shipped ones: {', '.join(names)}")
    scenario = load_scenario(args.name)
    if not args.export:
        print(scenario.to_json(), end="")
        return 0
    path = Path(args.export)
    if path.exists():
        return _error(f"--export {path}: the file exists; choose another name (it is never overwritten)")
    try:
        save_scenario(scenario, path)
    except OSError as exc:
        return _error(f"cannot write {path}: {exc.strerror or exc}")
    print(f"scenario    {args.name} written to {path}; edit it, then: segplan plan {path}")
    return 0


def _draw_floor(args, floor: Scenario | Floor, name: str) -> int:
    """``segplan draw``: the floor's figure, to ``--out`` or ``NAME.png``."""
    path = args.out or f"{name}.png"
    size, obstacles, robot = _floor_facts(floor)
    title = f"{name}: {size}, {obstacles}" + (f"; {robot}" if isinstance(floor, Scenario) else "")
    try:
        _draw(path, floor, (), title)
    except OSError as exc:
        return _error(f"cannot write {path}: {exc.strerror or exc}")
    print(f"figure      {path}")
    return 0


def _plan(args, scenario: Scenario, name: str) -> int:
    """``segplan plan``: plan, print, and write what was asked for."""
    shown = ProgressLine() if args.progress else None
    try:
        result = plan_scenario(
            scenario,
            heuristic=args.heuristic,
            cost=args.cost,
            version=args.node_frames,
            max_expansions=args.max_expansions,
            time_limit=args.time_limit,
            refine=args.refine,
            planner=args.planner,
            clearance=args.clearance,
            progress=shown,
        )
    except NoPathError as exc:
        print(f"segplan: no path: {exc}", file=sys.stderr)
        if args.json:
            out = {"scenario": name, "found": False, "reason": exc.reason, "message": str(exc)}
            out.update({"expanded": exc.expanded, "generated": exc.generated, "seconds": exc.seconds})
            print(json.dumps(out, indent=2))
        if args.out:
            try:
                partial = f"{name}: no path (closest partial plan)"
                _draw(args.out, scenario, exc.best.unions, partial, exc.best.directions)
            except OSError as err:
                print(f"segplan: error: cannot write {args.out}: {err.strerror or err}", file=sys.stderr)
        return EXIT_NO_PATH
    except ValueError as exc:
        return _error(str(exc))
    finally:
        if shown is not None:
            shown.close()
    try:
        written, written_lines = _trajectories_out(args, result)
    except OSError as exc:
        return _error(f"cannot write {exc.filename}: {exc.strerror or exc}")
    except ValueError as exc:
        return _error(str(exc))
    facts = _what_the_plan_is(result, scenario)
    if args.json:
        body = {k: v for k, v in scenario.to_dict().items() if k in FOOTPRINT_KEYS}  # only when set
        out = {"scenario": name, "found": True, **result.to_dict(), **body, "plan_facts": facts, **written}
        print(json.dumps(out, indent=2))
    else:
        print("\n".join([_format_plan(result, name), *_format_facts(facts), *written_lines]))
    title = f"{name}: LONGD {result.cost:.2f} m, {_planner_text(result, args)}"
    if args.out:
        try:
            _draw(args.out, scenario, result.unions, title, result.directions)
        except OSError as exc:
            return _error(f"cannot write {args.out}: {exc.strerror or exc}")
        if not args.json:
            print(f"figure      {args.out}")
    if args.animate:
        try:
            _animate(args.animate, scenario, result, title, _animation_options(args))
        except OSError as exc:
            return _error(f"cannot write {args.animate}: {exc.strerror or exc}")
        if not args.json:
            print(f"animation   {args.animate}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
