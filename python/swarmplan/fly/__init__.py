"""Fly a plan: every UAV of a plan folder replayed in JSBSim's F450 quadrotor with the
autopilot of :mod:`swarmplan.fly.autopilot`, and judged on what it flew (docs/flight.md).

Why: swarmplan checks its plans against its own model (flown arcs at a turning radius,
speed, climb, clearance, separation); whether an aircraft can follow them is a different
question, answered here by a flight-dynamics model with an autopilot between the plan and
the rotors. ``jsbsim`` is an optional dependency (``pip install "./python[fly]"``).

Each UAV is flown alone (JSBSim has no collisions), from its start at its launch time,
hovering until its departure, then along the flown path the model assessed (arcs
included, at the planned timing); the fleet is then judged together on the mission clock
(:mod:`swarmplan.fly.judge`).
"""

import csv
import json
import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

PathLike = Union[str, "os.PathLike[str]"]


def _require_jsbsim() -> None:
    try:
        import jsbsim  # noqa: F401
    except ModuleNotFoundError:
        raise ModuleNotFoundError(
            "swarmplan.fly needs JSBSim, an optional dependency: "
            'pip install "./python[fly]" (or pip install jsbsim==1.3.3)'
        ) from None


def fly(
    plan_dir: PathLike,
    *,
    wind: Tuple[float, float] = (0.0, 0.0),
    turbulence: Optional[str] = None,
    seed: int = 0,
    out: Optional[PathLike] = None,
    figure: bool = True,
    allow_other_terrain: bool = False,
) -> Dict[str, Any]:
    """Flies every UAV of the plan in ``plan_dir`` (a ``plan`` output folder: its
    ``scenario.toml`` and ``plan.json``) and returns the report
    (:func:`swarmplan.fly.judge.judge`): per UAV the cross-track error, lag, least
    clearance, threat margins, separation and energy as flown, and the verdict ``kept``
    with every limit ``losses`` lists.

    ``wind`` is the air mass's velocity (east, north), m/s; ``turbulence`` None (calm),
    "light", "moderate" or "severe" (JSBSim's Dryden model, random seed ``seed``). Writes
    ``flight.json`` (the report), ``flight.csv`` (the flown trajectories) and, with
    ``figure``, ``flight.png`` into ``out`` (default ``plan_dir/flight``).
    """
    _require_jsbsim()
    from .. import Problem, SwarmplanError
    from .autopilot import fly_path
    from .judge import judge

    folder = os.fspath(plan_dir)
    scenario = os.path.join(folder, "scenario.toml")
    plan_file = os.path.join(folder, "plan.json")
    for needed in (scenario, plan_file):
        if not os.path.isfile(needed):
            raise SwarmplanError(
                f"{needed}: not found; expected a `swarmplan plan --out DIR` folder "
                "(scenario.toml and plan.json)"
            )
    problem = Problem(scenario)
    plan = problem.flight_plan(plan_file, allow_other_terrain=allow_other_terrain)
    ground = problem.terrain_heights

    flown: List[Dict[str, Any]] = []
    for u in plan["uavs"]:
        # The clock starts at launch: the UAV hovers at its start until departure.
        hover = max(0.0, u["depart_s"] - u["launch_s"])
        flown.append(
            fly_path(u["t"], u["x"], u["y"], u["z"], hover=hover, wind=wind,
                     turbulence=turbulence, seed=seed + u["uav"])
        )
    report = judge(plan, flown, ground)
    report["wind"] = list(wind)
    report["turbulence"] = turbulence
    report["seed"] = seed
    target = os.fspath(out) if out is not None else os.path.join(folder, "flight")
    os.makedirs(target, exist_ok=True)
    with open(os.path.join(target, "flight.json"), "w") as fh:
        json.dump(report, fh, indent=1)
    _write_csv(os.path.join(target, "flight.csv"), plan, flown, ground)
    if figure:
        from .figure import draw

        draw(os.path.join(target, "flight.png"), plan, flown, report, ground)
    report["out"] = target
    return report


def _write_csv(path: str, plan: Dict[str, Any], flown: List[Dict[str, Any]], ground) -> None:
    """One row per flown sample: the UAV, mission time, the flown position, the planned
    position due at that time and the terrain under the flown one."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["uav", "t_s", "x_m", "y_m", "z_m", "x_plan_m", "y_plan_m", "z_plan_m", "ground_m"])
        for planned, f in zip(plan["uavs"], flown):
            t = np.asarray(f["t"])
            due = [np.interp(t, planned["t"], planned[c]) for c in ("x", "y", "z")]
            g = ground(np.asarray(f["x"]), np.asarray(f["y"]))
            for k in range(len(t)):
                w.writerow(
                    [planned["uav"], f"{t[k]:.3f}", f"{f['x'][k]:.3f}", f"{f['y'][k]:.3f}",
                     f"{f['z'][k]:.3f}", f"{due[0][k]:.3f}", f"{due[1][k]:.3f}",
                     f"{due[2][k]:.3f}", f"{g[k]:.3f}"]
                )
