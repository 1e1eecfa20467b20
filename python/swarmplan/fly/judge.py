"""What a flown fleet kept: the plan's hard limits measured on the trajectories as flown.

Per UAV: cross-track error (the distance from each flown point to the planned path, 3-D)
and along-track lag (how far behind the point due at that time, along the path), both from
departure to arrival; the least clearance over the terrain (the scenario's terrain, as the
model interpolates it); the least margin to every threat's hard zone (horizontal distance
to the axis less r + size); the least separation to every other UAV at equal times outside
the take-off and landing zones (as docs/model.md, "Feasibility", waives them: a UAV is
exempt until it first leaves ``zone_radius`` around its start, and from when it last
enters it around UGV0); staying in the map box; and the energy drawn beside the model's and
the usable battery. The verdict: every hard limit kept, with its margin.

The altitude band, the climb and turn limits and the speeds are limits on the plan's
waypoints and segments, which the flown trajectory has no counterpart of; they are not
judged here (the model checked them on the plan).
"""

from typing import Any, Callable, Dict, List, Optional

import numpy as np

#: Sampling of the fleet's common clock for separation, s.
SEPARATION_STEP_S = 0.1


def _cross_track(planned: Dict[str, Any], flown: Dict[str, Any]):
    """Per flown point after departure: distance to the planned polyline, and the lag (arc
    length due at that time less the nearest point's)."""
    p = np.stack([planned["x"], planned["y"], planned["z"]], axis=1)
    t = np.asarray(planned["t"], float)
    seg = np.diff(p, axis=0)
    lengths = np.linalg.norm(seg, axis=1)
    arc = np.concatenate([[0.0], np.cumsum(lengths)])
    q = np.stack([flown["x"], flown["y"], flown["z"]], axis=1)
    ft = np.asarray(flown["t"], float)
    keep = (ft >= t[0]) & (ft <= t[-1])
    q, ft = q[keep], ft[keep]
    if len(q) == 0 or len(seg) == 0:
        return np.zeros(0), np.zeros(0), ft
    # Distance from every point to every segment (paths have hundreds of each).
    d = q[:, None, :] - p[None, :-1, :]
    l2 = np.maximum(lengths ** 2, 1e-12)
    f = np.clip(np.einsum("nkc,kc->nk", d, seg) / l2, 0.0, 1.0)
    e = d - f[..., None] * seg[None]
    dist = np.linalg.norm(e, axis=2)
    k = np.argmin(dist, axis=1)
    rows = np.arange(len(q))
    near_arc = arc[k] + f[rows, k] * lengths[k]
    due_arc = np.interp(ft, t, arc)
    return dist[rows, k], due_arc - near_arc, ft


def _on_clock(flown: Dict[str, Any], clock: np.ndarray, start, end_t: float) -> np.ndarray:
    """Positions on the common clock: at the start before the flight, at the last flown
    point after it."""
    out = np.empty((len(clock), 3))
    ft = np.asarray(flown["t"], float)
    for c, name in enumerate(("x", "y", "z")):
        out[:, c] = np.interp(clock, ft, np.asarray(flown[name], float), left=start[c])
    return out


def _exempt(pos: np.ndarray, clock: np.ndarray, start, landing, radius: float) -> np.ndarray:
    """Where a UAV is in its take-off zone (until it first leaves it) or its landing zone
    (from when it last enters it), horizontally."""
    out_start = np.hypot(pos[:, 0] - start[0], pos[:, 1] - start[1]) > radius
    left = np.argmax(out_start) if out_start.any() else len(clock)
    in_landing = np.hypot(pos[:, 0] - landing[0], pos[:, 1] - landing[1]) <= radius
    outside = np.nonzero(~in_landing)[0]
    entered = outside[-1] + 1 if len(outside) else 0
    exempt = np.zeros(len(clock), bool)
    exempt[:left] = True
    exempt[entered:] = True
    return exempt


def judge(
    plan: Dict[str, Any],
    flown: List[Dict[str, Any]],
    ground: Callable[[np.ndarray, np.ndarray], np.ndarray],
) -> Dict[str, Any]:
    """The report of a flown fleet (module doc): ``plan`` as ``Problem.flight_plan`` gives
    it, ``flown`` one :func:`autopilot.fly_path` result per UAV (in fleet order), ``ground``
    the terrain's height at arrays of x and y."""
    uavs = []
    clearance_limit = plan["clearance_m"]
    (x0, x1), (y0, y1) = plan["map"]
    for planned, f in zip(plan["uavs"], flown):
        xt, lag, _ = _cross_track(planned, f)
        fx, fy, fz = (np.asarray(f[c], float) for c in ("x", "y", "z"))
        clear = fz - ground(fx, fy)
        threats = []
        for j, th in enumerate(plan["threats"]):
            margin = np.hypot(fx - th["x"], fy - th["y"]) - (th["r"] + planned["size_m"])
            k = int(np.argmin(margin))
            threats.append({"threat": j, "margin_m": float(margin[k]), "t_s": float(f["t"][k])})
        box = float(min((fx - x0).min(), (x1 - fx).min(), (fy - y0).min(), (y1 - fy).min()))
        k = int(np.argmin(clear))
        uavs.append(
            {
                "uav": planned["uav"],
                "crashed": bool(f["crashed"]),
                "reason": f["reason"],
                "cross_track_max_m": float(xt.max()) if len(xt) else 0.0,
                "cross_track_rms_m": float(np.sqrt(np.mean(xt ** 2))) if len(xt) else 0.0,
                "lag_max_m": float(lag.max()) if len(lag) else 0.0,
                "lag_final_m": float(lag[-1]) if len(lag) else 0.0,
                "clearance_min_m": float(clear[k]),
                "clearance_at_s": float(f["t"][k]),
                "threats": threats,
                "threat_margin_min_m": min((t["margin_m"] for t in threats), default=float("inf")),
                "box_margin_m": box,
                "energy_flown_j": float(f["energy_j"]),
                "energy_model_j": planned["model_energy_j"],
                "usable_j": planned["usable_j"],
                "wall_s": float(f["wall_s"]),
            }
        )
    pairs = _separation(plan, flown)
    for u in uavs:
        mine = [p for p in pairs if u["uav"] in (p["a"], p["b"])]
        u["separation_min_m"] = min((p["min_m"] for p in mine), default=float("inf"))
    losses = _losses(plan, uavs, pairs)
    return {
        "scenario": plan["scenario"],
        "model_feasible": plan["feasible"],
        "kept": not losses,
        "losses": losses,
        "uavs": uavs,
        "pairs": pairs,
    }


def _separation(plan: Dict[str, Any], flown: List[Dict[str, Any]]) -> List[Dict[str, Any]]:
    """Least distance of every pair at equal times while neither is exempt."""
    if len(flown) < 2:
        return []
    end = max(float(np.max(f["t"])) for f in flown)
    clock = np.arange(0.0, end + SEPARATION_STEP_S, SEPARATION_STEP_S)
    pos, exempt = [], []
    for planned, f in zip(plan["uavs"], flown):
        start = (planned["x"][0], planned["y"][0], planned["z"][0])
        p = _on_clock(f, clock, start, planned["arrival_s"])
        pos.append(p)
        exempt.append(_exempt(p, clock, start, planned["landing"], plan["zone_radius_m"]))
    pairs = []
    for a in range(len(flown)):
        for b in range(a + 1, len(flown)):
            judged = ~(exempt[a] | exempt[b])
            if not judged.any():
                pairs.append({"a": a, "b": b, "min_m": float("inf"), "t_s": None})
                continue
            d = np.linalg.norm(pos[a] - pos[b], axis=1)
            d = np.where(judged, d, np.inf)
            k = int(np.argmin(d))
            pairs.append({"a": a, "b": b, "min_m": float(d[k]), "t_s": float(clock[k])})
    return pairs


def _losses(plan, uavs, pairs) -> List[Dict[str, Any]]:
    """Every hard limit broken as flown, with the amount."""
    out: List[Dict[str, Any]] = []

    def lost(kind: str, uav: int, by: float, t: Optional[float], other: Optional[int] = None):
        out.append({"kind": kind, "uav": uav, "other": other, "by_m_or_j": by, "t_s": t})

    for u in uavs:
        if u["crashed"]:
            lost("crash", u["uav"], 0.0, None)
        if u["clearance_min_m"] < plan["clearance_m"]:
            lost("terrain", u["uav"], plan["clearance_m"] - u["clearance_min_m"], u["clearance_at_s"])
        for th in u["threats"]:
            if th["margin_m"] < 0:
                lost("threat", u["uav"], -th["margin_m"], th["t_s"], th["threat"])
        if u["box_margin_m"] < 0:
            lost("map box", u["uav"], -u["box_margin_m"], None)
        if u["energy_flown_j"] > u["usable_j"]:
            lost("energy", u["uav"], u["energy_flown_j"] - u["usable_j"], None)
    for p in pairs:
        if p["min_m"] < plan["separation_m"]:
            lost("separation", p["a"], plan["separation_m"] - p["min_m"], p["t_s"], p["b"])
    return out
