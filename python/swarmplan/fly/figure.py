"""The flight figure: top view and altitude profiles, planned against flown, with the
places where a hard limit was lost as flown marked."""

from typing import Any, Callable, Dict, List

import numpy as np


def draw(
    path: str,
    plan: Dict[str, Any],
    flown: List[Dict[str, Any]],
    report: Dict[str, Any],
    ground: Callable[[np.ndarray, np.ndarray], np.ndarray],
) -> None:
    """Writes the figure to ``path`` (PNG): left the top view (threats at radius r, each
    UAV's planned path dashed and flown path solid), right each UAV's altitude over time,
    planned and flown, with the terrain under the flown path; a red cross where a limit was
    lost."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, side) = plt.subplots(1, 2, figsize=(14, 6.5), gridspec_kw={"width_ratios": [1, 1.3]})
    for th in plan["threats"]:
        top.add_patch(plt.Circle((th["x"], th["y"]), th["r"], color="tab:red", alpha=0.25, lw=0))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for planned, f in zip(plan["uavs"], flown):
        c = colours[planned["uav"] % len(colours)]
        top.plot(planned["x"], planned["y"], "--", color=c, lw=1)
        top.plot(f["x"], f["y"], "-", color=c, lw=1.2, label=f"UAV {planned['uav']}")
        side.plot(planned["t"], planned["z"], "--", color=c, lw=1)
        side.plot(f["t"], f["z"], "-", color=c, lw=1.2)
        side.plot(f["t"], ground(np.asarray(f["x"]), np.asarray(f["y"])), ":", color=c, lw=0.8)
    for loss in report["losses"]:
        f = flown[loss["uav"]]
        if loss["t_s"] is None:
            continue
        k = int(np.argmin(np.abs(np.asarray(f["t"]) - loss["t_s"])))
        top.plot(f["x"][k], f["y"][k], "x", color="red", ms=10, mew=2)
        side.plot(f["t"][k], f["z"][k], "x", color="red", ms=10, mew=2)
        top.annotate(loss["kind"], (f["x"][k], f["y"][k]), color="red", fontsize=8)
    (x0, x1), (y0, y1) = plan["map"]
    top.set_xlim(x0, x1)
    top.set_ylim(y0, y1)
    top.set_aspect("equal")
    top.set_xlabel("x (east), m")
    top.set_ylabel("y (north), m")
    top.set_title("top view: planned (dashed), flown (solid)")
    top.legend(loc="best", fontsize=8)
    side.set_xlabel("mission time, s")
    side.set_ylabel("altitude, m")
    side.set_title("altitude: planned (dashed), flown (solid), terrain under it (dotted)")
    verdict = "every hard limit kept as flown" if report["kept"] else f"{len(report['losses'])} limit(s) lost as flown"
    fig.suptitle(f"{plan['scenario']}: flown in JSBSim (F450), {verdict}")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
