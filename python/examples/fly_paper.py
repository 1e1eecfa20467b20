"""Flies swarmplan's plans of the paper cases in JSBSim (issue 48's table, docs/flight.md).

For each case and seed: `swarmplan plan --scenario CASE --seed S`, then `swarmplan.fly` on
the plan, calm and under a 5 m/s westerly with moderate Dryden turbulence. Prints one row
per plan and condition (worst UAV's cross-track RMS and max, whether every hard limit held
as flown, the limits lost and by how much, the fleet's wall time) and a summary.

    python python/examples/fly_paper.py --swarmplan target/release/swarmplan --seeds 10

With ``--margin M`` each case is planned on a copy of its scenario whose UAV sizes (the
threats' hard-zone margin) and separation are M metres larger, and each plan is then
judged, and flown, against the original scenario (docs/flight.md, "What it takes").
"""

import argparse
import os
import re
import shutil
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
                    help="plan with UAV sizes and separation this much larger, m (default 0)")
    args = ap.parse_args()
    conditions = [("calm", (0.0, 0.0), None), ("windy", (args.wind, 0.0), "moderate")]
    print("| case | seed | air | cross-track RMS, worst UAV (m) | max (m) | kept | lost as flown | wall (s) |")
    print("|---|---|---|---|---|---|---|---|")
    totals = {}
    with tempfile.TemporaryDirectory() as tmp:
        for case in args.cases.split(","):
            original = os.path.join(tmp, f"{case}-original")
            subprocess.run([args.swarmplan, "plan", "--scenario", case, "--out", original,
                            "--no-figures", "--evaluations", "100"], check=True, capture_output=True)
            planned_on = case
            if args.margin > 0:
                planned_on = os.path.join(tmp, f"{case}-margin.toml")
                with open(os.path.join(original, "scenario.toml")) as fh:
                    text = fh.read()
                grow = lambda m: f"{m.group(1)}{float(m.group(2)) + args.margin!r}"  # noqa: E731
                text = re.sub(r"(?m)^(size = )([0-9.]+)", grow, text)
                text = re.sub(r"(?m)^(separation = )([0-9.]+)", grow, text)
                with open(planned_on, "w") as fh:
                    fh.write(text)
            for seed in range(1, args.seeds + 1):
                out = os.path.join(tmp, f"{case}-{seed}")
                subprocess.run(
                    [args.swarmplan, "plan", "--scenario", planned_on, "--seed", str(seed), "--out",
                     out, "--no-figures"],
                    check=True, capture_output=True,
                )
                # Judged against the scenario as given, whatever it was planned on.
                shutil.copy(os.path.join(original, "scenario.toml"), os.path.join(out, "scenario.toml"))
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
