"""swarmplan.plan makes the CLI's run; swarmplan.bench runs the CLI's matrix."""

from __future__ import annotations

import json

import pytest

import swarmplan
from conftest import read_jsonl, run_cli


def test_plan_equals_the_cli_plan_for_the_same_seed(cli, tmp_path):
    out = tmp_path / "out"
    run_cli(cli, "plan", "--scenario", "paper-case1", "--seed", "11", "--evaluations", "3000",
            "--no-figures", "--out", str(out))
    want_plan = json.loads((out / "plan.json").read_text())
    want_run = json.loads((out / "run.json").read_text())
    got = swarmplan.plan("paper-case1", seed=11, evaluations=3000)
    assert got["plan"] == want_plan
    assert got["run"]["assessment"] == want_run["assessment"]
    for k in ("method", "seed", "budget", "evaluations", "iterations", "termination"):
        assert got["run"][k] == want_run[k], k
    assert got["feasible"] == want_run["assessment"]["feasible"]
    assert got["verdict"].startswith("FEASIBLE" if got["feasible"] else "INFEASIBLE")
    assert (got["outcome"] is None) == got["feasible"]
    conv = got["convergence"]
    assert conv[0]["iteration"] == 0 and conv[-1]["evaluations"] == 3000
    assert len(got["uav_costs"]) == len(conv) and len(got["uav_costs"][0]) == 5


def test_an_infeasible_plan_says_whether_any_plan_exists():
    # Twenty evaluations leave Case 1 infeasible; nothing rules every plan out there.
    r = swarmplan.plan("paper-case1", evaluations=20)
    assert not r["feasible"]
    assert r["outcome"].startswith("none found: "), r["outcome"]
    assert "widest way between the threats keeps" in r["outcome"]


def test_plan_defaults_are_the_cli_defaults():
    r = swarmplan.plan("tiny", evaluations=400)
    assert r["run"]["method"] == "swarmplan"
    assert r["run"]["seed"] == swarmplan.plan("tiny", evaluations=400)["run"]["seed"]


def test_bench_records_equal_the_cli_records(cli, tmp_path):
    out = tmp_path / "b"
    run_cli(cli, "bench", "--scenarios", "tiny", "--methods", "gwo,pso", "--runs", "2",
            "--evaluations", "400", "--seed", "3", "--out", str(out))
    want = read_jsonl(out / "runs.jsonl")
    got = swarmplan.bench(["tiny"], ["gwo", "pso"], runs=2, evaluations=400, seed=3)
    assert len(got) == 4
    key = lambda r: (r["method"], r["run"])
    for g, w in zip(sorted(got, key=key), sorted(want, key=key)):
        g.pop("seconds"), w.pop("seconds")
        assert g == w


def test_bench_writes_a_resumable_folder_and_a_frame(tmp_path):
    import pandas as pd
    first = swarmplan.bench(["tiny"], ["gwo"], runs=1, evaluations=300, out=tmp_path / "r")
    assert (tmp_path / "r" / "runs.jsonl").exists() and len(first) == 1
    again = swarmplan.bench(["tiny"], ["gwo"], runs=1, evaluations=300, out=tmp_path / "r",
                            resume=True)
    assert again == first  # nothing left to run: the folder's records come back
    with pytest.raises(swarmplan.SwarmplanError, match="different experiment"):
        swarmplan.bench(["tiny"], ["gwo"], runs=2, evaluations=300, out=tmp_path / "r",
                        resume=True)
    frame = swarmplan.bench(["tiny"], ["gwo"], runs=2, evaluations=300, as_frame=True)
    assert isinstance(frame, pd.DataFrame) and len(frame) == 2
    assert {"method", "cost_per_uav", "feasible", "seed"} <= set(frame.columns)


def planned_by_cli(cli, out, *args):
    """``swarmplan plan ARGS --no-figures --out OUT``: its run.json and plan.json."""
    run_cli(cli, "plan", *args, "--no-figures", "--out", str(out))
    return json.loads((out / "run.json").read_text()), json.loads((out / "plan.json").read_text())


def test_plan_attempts_equal_the_cli_attempts(cli, tmp_path):
    want_run, want_plan = planned_by_cli(cli, tmp_path / "att", "--scenario", "paper-case2",
                                         "--evaluations", "300", "--attempts", "3")
    got = swarmplan.plan("paper-case2", evaluations=300, attempts=3)
    def strip(records):  # wall times differ between two runs
        return [{k: v for k, v in r.items() if k != "seconds"} for r in records]

    assert strip(got["run"]["attempts"]) == strip(want_run["attempts"])
    assert got["run"]["seed"] == want_run["seed"]
    assert got["plan"] == want_plan
    assert "attempts" not in swarmplan.plan("tiny", evaluations=300)["run"]
    with pytest.raises(swarmplan.SwarmplanError, match="attempts"):
        swarmplan.plan("tiny", attempts=0)


def test_plan_flight_margin_equals_the_cli_flight_margin(cli, tmp_path):
    want_run, want_plan = planned_by_cli(cli, tmp_path / "margin", "--scenario", "tiny",
                                         "--seed", "2", "--flight-margin", "8")
    got = swarmplan.plan("tiny", seed=2, flight_margin=8)
    assert got["plan"] == want_plan
    assert got["run"]["assessment"] == want_run["assessment"]
    assert got["run"]["flight_margin"] == want_run["flight_margin"] == 8
    assert got["margin_verdict"].startswith("FEASIBLE"), got["margin_verdict"]
    assert swarmplan.plan("tiny", evaluations=300)["margin_verdict"] is None
    with pytest.raises(swarmplan.SwarmplanError, match="flight_margin: flight margin -1"):
        swarmplan.plan("tiny", flight_margin=-1)
