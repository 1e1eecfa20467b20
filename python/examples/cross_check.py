"""Cross-check swarmplan's GWO and PSO against mealpy's on swarmplan's own problem.

Both sides minimise the same function (swarmplan's penalised cost, evaluated by the same Rust
code), from populations drawn by the same initialisation, with the same number of
evaluations per run; what differs is only the optimiser's implementation. Each run's final
plan is re-assessed by swarmplan, and the cost distributions are compared with a two-sided
Wilcoxon rank-sum test (scipy's Mann-Whitney U). docs/python.md reports the table.

    python python/examples/cross_check.py --runs 20 --evaluations 38700 --out cross-check.json

Needs mealpy (``pip install mealpy==3.0.3``) and scipy.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from typing import Any, Dict, List

import numpy as np

import swarmplan

# PSO as both libraries can state it: constant inertia, mealpy's default coefficients and
# velocity limit of half the box. swarmplan's own PSO preset (the paper's, with a damped
# inertia) is run too, for context.
MATCHED_PSO = """[pso]
inertia = 0.4
inertia_damping = 1.0
cognitive = 2.05
social = 2.05
velocity_clamp = 0.5
asynchronous = false
"""


def rust_runs(scenario: str, method: str, runs: int, seed: int, evaluations: int,
              params: str | None) -> List[Dict[str, Any]]:
    recs = swarmplan.bench([scenario], [method], runs=runs, seed=seed,
                           evaluations=evaluations, params=params)
    return [{"run": r["run"], "seed": r["seed"], "cost_per_uav": r["cost_per_uav"],
             "feasible": r["feasible"], "evaluations": r["evaluations"]} for r in recs]


def mealpy_runs(scenario: str, method: str, algorithm: str, runs: int, seed: int,
                evaluations: int, population: int) -> List[Dict[str, Any]]:
    from mealpy import GWO, PSO, FloatVar

    problem = swarmplan.Problem(scenario, method=method)
    counted = [0]

    def objective(x: np.ndarray) -> float:
        counted[0] += 1
        return problem.evaluate(x)[0]

    out = []
    for k in range(runs):
        run_seed = seed * 1000 + k
        if algorithm == "gwo":
            model = GWO.OriginalGWO(epoch=(evaluations - population) // population,
                                    pop_size=population)
        else:
            model = PSO.OriginalPSO(epoch=(evaluations - population) // population,
                                    pop_size=population, c1=2.05, c2=2.05, w=0.4)
        spec = {"obj_func": objective, "minmax": "min", "log_to": None,
                "bounds": FloatVar(lb=problem.lower.tolist(), ub=problem.upper.tolist())}
        start = problem.sample_initial(population, run_seed)
        counted[0] = 0
        best = model.solve(spec, termination={"max_fe": evaluations},
                           starting_solutions=list(start), seed=run_seed)
        report = problem.assess(best.solution)
        out.append({"run": k, "seed": run_seed, "cost_per_uav": report["cost"]["per_uav"],
                    "feasible": report["feasible"], "evaluations": counted[0]})
    return out


def describe(rows: List[Dict[str, Any]]) -> Dict[str, Any]:
    c = np.array([r["cost_per_uav"] for r in rows])
    return {"runs": len(rows), "feasible": int(sum(r["feasible"] for r in rows)),
            "median": float(np.median(c)), "best": float(c.min()), "worst": float(c.max()),
            "mean_evaluations": float(np.mean([r["evaluations"] for r in rows]))}


def main(argv: List[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenario", default="paper-case1")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--evaluations", type=int, default=38700)
    ap.add_argument("--out", default=None, help="write every run and the table as JSON")
    a = ap.parse_args(argv)
    import mealpy
    from scipy.stats import mannwhitneyu

    t0 = time.time()
    with tempfile.TemporaryDirectory() as d:
        matched = os.path.join(d, "pso-matched.toml")
        with open(matched, "w") as f:
            f.write(MATCHED_PSO)
        rows = {
            ("gwo", "swarmplan"): rust_runs(a.scenario, "gwo", a.runs, a.seed, a.evaluations, None),
            ("gwo", f"mealpy {mealpy.__version__} OriginalGWO"): mealpy_runs(
                a.scenario, "gwo", "gwo", a.runs, a.seed, a.evaluations, 50),
            ("pso", "swarmplan, matched parameters"): rust_runs(
                a.scenario, "pso", a.runs, a.seed, a.evaluations, matched),
            ("pso", "swarmplan, paper preset"): rust_runs(
                a.scenario, "pso", a.runs, a.seed, a.evaluations, None),
            ("pso", f"mealpy {mealpy.__version__} OriginalPSO"): mealpy_runs(
                a.scenario, "pso", "pso", a.runs, a.seed, a.evaluations, 50),
        }
    table = []
    for (algo, impl), r in rows.items():
        entry = {"algorithm": algo, "implementation": impl, **describe(r)}
        theirs = [v for (al, im), v in rows.items() if al == algo and im.startswith("mealpy")]
        if not impl.startswith("mealpy") and theirs:
            p = mannwhitneyu([x["cost_per_uav"] for x in r],
                             [x["cost_per_uav"] for x in theirs[0]],
                             alternative="two-sided").pvalue
            entry["rank_sum_p_vs_mealpy"] = float(p)
        table.append(entry)
    print(f"{a.scenario}, {a.runs} runs each, {a.evaluations} evaluations per run, "
          f"swarmplan {swarmplan.__version__}, mealpy {mealpy.__version__} "
          f"({time.time() - t0:.0f} s)")
    print("| algorithm | implementation | FR | median cost / UAV | best | worst | evaluations / run | rank-sum p vs mealpy |")
    print("|---|---|---|---|---|---|---|---|")
    for e in table:
        p = e.get("rank_sum_p_vs_mealpy")
        print(f"| {e['algorithm']} | {e['implementation']} | {e['feasible']}/{e['runs']} | "
              f"{e['median']:.0f} | {e['best']:.0f} | {e['worst']:.0f} | "
              f"{e['mean_evaluations']:.0f} | {'-' if p is None else f'{p:.3g}'} |")
    if a.out:
        with open(a.out, "w") as f:
            json.dump({"args": vars(a), "mealpy": mealpy.__version__, "table": table,
                       "runs": {f"{k[0]} | {k[1]}": v for k, v in rows.items()}}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
