"""``python -m swarmplan.fly DIR``: fly a plan folder in JSBSim and print what was kept."""

import argparse
import math
import sys

from . import fly


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m swarmplan.fly",
        description="Fly every UAV of a `swarmplan plan --out DIR` folder in JSBSim's F450 "
        "with swarmplan's autopilot, and judge the flown fleet against the scenario's hard limits.",
    )
    parser.add_argument("plan_dir", help="a plan output folder (scenario.toml, plan.json)")
    parser.add_argument("--wind-speed", type=float, default=0.0, help="constant wind, m/s (default 0)")
    parser.add_argument("--wind-from", type=float, default=270.0,
                        help="direction the wind blows from, degrees clockwise from north (default 270, a westerly)")
    parser.add_argument("--turbulence", choices=["none", "light", "moderate", "severe"], default="none")
    parser.add_argument("--seed", type=int, default=0, help="turbulence seed (default 0)")
    parser.add_argument("--out", help="output folder (default PLAN_DIR/flight)")
    parser.add_argument("--no-figure", action="store_true", help="skip flight.png")
    args = parser.parse_args(argv)
    if not (math.isfinite(args.wind_speed) and args.wind_speed >= 0):
        parser.error(f"--wind-speed: expected a finite speed >= 0 m/s, got {args.wind_speed}")
    towards = math.radians(args.wind_from + 180.0)
    wind = (args.wind_speed * math.sin(towards), args.wind_speed * math.cos(towards))
    try:
        report = fly(
            args.plan_dir,
            wind=wind,
            turbulence=None if args.turbulence == "none" else args.turbulence,
            seed=args.seed,
            out=args.out,
            figure=not args.no_figure,
        )
    except (ModuleNotFoundError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    for u in report["uavs"]:
        print(
            f"UAV {u['uav']}: cross-track max {u['cross_track_max_m']:.2f} m, RMS {u['cross_track_rms_m']:.2f} m; "
            f"lag max {u['lag_max_m']:.1f} m; clearance {u['clearance_min_m']:.1f} m; "
            f"threat margin {u['threat_margin_min_m']:.1f} m; separation {u['separation_min_m']:.1f} m; "
            f"energy {u['energy_flown_j']:.0f} J flown, {u['energy_model_j']:.0f} J modelled, "
            f"{u['usable_j']:.0f} J usable{'; CRASHED: ' + u['reason'] if u['crashed'] else ''}"
        )
    if report["kept"]:
        print("KEPT: every hard limit held as flown")
    else:
        print(f"LOST: {len(report['losses'])} limit(s) broken as flown")
        for loss in report["losses"]:
            other = f" and UAV {loss['other']}" if loss["kind"] == "separation" else (
                f" (threat {loss['other']})" if loss["kind"] == "threat" else "")
            when = f" at t = {loss['t_s']:.1f} s" if loss["t_s"] is not None else ""
            print(f"  {loss['kind']}: UAV {loss['uav']}{other}{when}, by {loss['by_m_or_j']:.2f}")
    print(f"wrote {report['out']}/flight.json, flight.csv" + ("" if args.no_figure else ", flight.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
