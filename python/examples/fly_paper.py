"""Flies swarmplan's plans of the paper cases in JSBSim (issue 48's table, docs/flight.md).

For each case and seed: `swarmplan plan --scenario CASE --seed S`, then `swarmplan.fly` on
the plan, calm and under a 5 m/s westerly with moderate Dryden turbulence. Prints one row
per plan and condition (worst UAV's cross-track RMS and max, whether every hard limit held
as flown, the limits lost and by how much, the fleet's wall time) and a summary.

    python python/examples/fly_paper.py --swarmplan target/release/swarmplan --seeds 10

With ``--margin M`` each case is planned with ``swarmplan plan --flight-margin M``: searched
on the scenario with UAV sizes (the threats' hard-zone margin), separation and terrain
clearance M metres larger and the map box M metres inside, and judged, and flown, against
the scenario as given (docs/flight.md, "A flight margin").
"""

import argparse
import os
import subprocess
import tempfile

from swarmplan.fly import fly


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swarmplan", default="target/release/swarmplan", help="the CLI binary")
    ap.add_argument("--cases", default="paper-case1,paper-case2")
    ap.add_argument("--seeds", type=int, default=10, help="seeds 1..N")
    ap.add_argument("--wind", type=float, default=5.0, help="wind speed of the windy runs, m/s")
    ap.add_argument("--margin", type=float, default=0.0,
                    help="plan --flight-margin, m (default 0)")
    args = ap.parse_args()
    conditions = [("calm", (0.0, 0.0), None), ("windy", (args.wind, 0.0), "moderate")]
    print("| case | seed | air | cross-track RMS, worst UAV (m) | max (m) | kept | lost as flown | wall (s) |")
    print("|---|---|---|---|---|---|---|---|")
    totals = {}
    with tempfile.TemporaryDirectory() as tmp:
        for case in args.cases.split(","):
            for seed in range(1, args.seeds + 1):
                out = os.path.join(tmp, f"{case}-{seed}")
                # With a margin, plan searches on the tightened scenario and writes the
                # scenario as given into the folder, which the flight is judged against.
                subprocess.run(
                    [args.swarmplan, "plan", "--scenario", case, "--seed", str(seed), "--out",
                     out, "--no-figures", "--flight-margin", repr(args.margin)],
                    check=True, capture_output=True,
                )
                for name, wind, turbulence in conditions:
                    r = fly(out, wind=wind, turbulence=turbulence, seed=seed, figure=False,
                            out=os.path.join(out, f"flight-{name}"))
                    rms = max(u["cross_track_rms_m"] for u in r["uavs"])
                    top = max(u["cross_track_max_m"] for u in r["uavs"])
                    wall = sum(u["wall_s"] for u in r["uavs"])
                    lost = "; ".join(
                        f"{l['kind']} UAV {l['uav']}"
                        + (f"-{l['other']}" if l["kind"] == "separation" else "")
                        + f" by {l['by_m_or_j']:.2f}"
                        + (f" at {l['t_s']:.1f} s" if l["t_s"] is not None else "")
                        for l in r["losses"]
                    ) or "-"
                    print(f"| {case} | {seed} | {name} | {rms:.2f} | {top:.2f} | "
                          f"{'yes' if r['kept'] else 'no'} | {lost} | {wall:.1f} |", flush=True)
                    t = totals.setdefault((case, name), [0, 0, 0.0, 0.0])
                    t[0] += 1
                    t[1] += int(r["kept"])
                    t[2] = max(t[2], rms)
                    t[3] = max(t[3], top)
    print()
    print("| case | air | plans kept as flown | worst cross-track RMS (m) | worst max (m) |")
    print("|---|---|---|---|---|")
    for (case, name), (n, kept, rms, top) in totals.items():
        print(f"| {case} | {name} | {kept}/{n} | {rms:.2f} | {top:.2f} |")


if __name__ == "__main__":
    main()
