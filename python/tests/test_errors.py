"""Bad input raises SwarmplanError (a ValueError) naming the field, with the CLI's message;
nothing panics across the boundary."""

from __future__ import annotations

import numpy as np
import pytest

import swarmplan
from conftest import ROOT, cli_error, run_cli

TINY = (ROOT / "scenarios" / "tiny.toml").read_text()


def raised(f, *a, **k) -> str:
    with pytest.raises(swarmplan.SwarmplanError) as e:
        f(*a, **k)
    assert isinstance(e.value, ValueError)
    return str(e.value)


def test_unknown_scenario_has_the_cli_message(cli):
    msg = raised(swarmplan.Problem, "no-such-scenario")
    assert msg == cli_error(cli, "evaluate", "--scenario", "no-such-scenario", "--plan", "x.json")
    assert "no-such-scenario" in msg


def test_bad_scenario_field_is_named_as_the_cli_names_it(cli, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TINY.replace("r = 25.0", "r = -25.0"))
    msg = raised(swarmplan.Problem, bad)
    assert "threats" in msg and str(bad) in msg
    assert msg == cli_error(cli, "plan", "--scenario", str(bad), "--out", str(tmp_path / "o"))
    typo = tmp_path / "typo.toml"
    typo.write_text(TINY.replace("hills = 4", "hils = 4"))
    assert "hils" in raised(swarmplan.plan, typo)


def test_bad_plan_file_is_named_as_the_cli_names_it(cli, tmp_path):
    plan = tmp_path / "plan.json"
    plan.write_text('{"uavs": [{"waypoints": [[30, 30, 60], ["a", 1, 2]]}]}')
    msg = raised(swarmplan.Problem("tiny").evaluate_plan, plan)
    assert "uavs[0].waypoints[1]" in msg
    assert msg == cli_error(cli, "evaluate", "--scenario", "tiny", "--plan", str(plan))


def test_missing_terrain_file_names_the_argument(cli, tmp_path):
    missing = tmp_path / "none.tif"
    msg = raised(swarmplan.Problem, "tiny", terrain=missing)
    assert str(missing) in msg
    assert msg == cli_error(cli, "evaluate", "--scenario", "tiny", "--terrain", str(missing),
                            "--plan", "x.json")


def test_bad_batches_name_the_row_and_column():
    p = swarmplan.Problem("tiny")
    assert "expected 24 columns" in raised(p.evaluate, np.zeros((3, 5)))
    X = p.sample_initial(2, 1)
    X[1, 4] = np.nan
    assert "X[1, 4]: expected a finite number, got NaN (None reads as NaN)" in raised(p.evaluate, X)
    row = [float(v) for v in X[0]]
    row[2] = None
    assert "expected a finite number, got NaN (None reads as NaN)" in raised(p.evaluate, row)
    assert "expected shape" in raised(p.evaluate, np.zeros((2, 2, 2)))
    assert "x: expected 24 values" in raised(p.assess, np.zeros(3))
    assert "count: expected at least 1" in raised(p.sample_initial, 0, 1)
    assert "count: expected at most" in raised(p.sample_initial, 10**15, 1)


@pytest.mark.parametrize("kwargs,field", [
    ({"evaluations": 0}, "evaluations: expected at least 1, got 0"),
    ({"iterations": -3}, "iterations: expected at least 1, got -3"),
    ({"seed": -1}, "seed: expected a whole number in [0, 2^64 - 1], got -1"),
    ({"seed": 2**64}, "seed: expected a whole number"),
    ({"method": "nope"}, "method: unknown method \"nope\""),
    ({"profile": "lax"}, "profile: expected `strict` or `paper`, got `lax`"),
    ({"population": 2}, "population: expected a whole number in [4, 100000], got 2"),
    ({"time_limit": -1.0}, "time_limit: expected seconds in (0, 1e7], got -1"),
    ({"seed": 2**200}, f"seed: {2**200} is too large"),
    ({"evaluations": -(2**130)}, "evaluations: -"),
])
def test_bad_plan_arguments_name_the_argument(kwargs, field):
    assert field in raised(swarmplan.plan, "tiny", **kwargs)


def test_bad_bench_arguments_name_the_argument(tmp_path):
    assert "runs: expected at least 1" in raised(swarmplan.bench, ["tiny"], ["gwo"], runs=0)
    assert "is more than 10000000 runs" in raised(swarmplan.bench, ["tiny"], ["gwo"], runs=10**12)
    assert "methods: `gwo` appears twice" in raised(swarmplan.bench, ["tiny"], ["gwo", "gwo"])
    assert "budget: expected `equal` or `paper`" in raised(
        swarmplan.bench, ["tiny"], ["gwo"], budget="fair")
    assert "threads" in raised(swarmplan.bench, ["tiny"], ["gwo"], threads=-1)
    assert "single string" in raised(swarmplan.bench, "tiny", ["gwo"])
    assert "no-such" in raised(swarmplan.bench, ["no-such"], ["gwo"], out=tmp_path / "b")
    bad = tmp_path / "p.toml"
    bad.write_text("[gwo]\npopulation = 1\n")
    assert str(bad) in raised(swarmplan.bench, ["tiny"], ["gwo"], params=bad)


def test_numpy_integers_are_whole_numbers():
    # numpy's unsigned integers used to fail inside the conversion ("ufunc 'right_shift'
    # not supported"); they are seeds and counts like any int.
    p = swarmplan.Problem("tiny")
    a = p.sample_initial(np.int64(2), np.uint64(3))
    b = p.sample_initial(2, 3)
    assert np.array_equal(a, b)
    assert "seed: expected a whole number" in raised(
        swarmplan.plan, "tiny", seed=np.int64(-1), evaluations=100)


def test_a_folder_with_records_is_named_in_python_terms(tmp_path):
    out = tmp_path / "x--out-b"  # a path that names a flag stays as it is
    swarmplan.bench(["tiny"], ["gwo"], evaluations=100, out=out)
    message = raised(swarmplan.bench, ["tiny"], ["gwo"], evaluations=100, out=out)
    assert "pass resume=True" in message and "another out" in message, message
    assert "x--out-b" in message and "--resume" not in message, message


def test_a_bench_into_a_plan_folder_is_refused(cli, tmp_path):
    out = tmp_path / "p"
    run_cli(cli, "plan", "--scenario", "tiny", "--evaluations", "100", "--no-figures",
            "--out", str(out))
    message = raised(swarmplan.bench, ["tiny"], ["gwo"], evaluations=100, out=out)
    assert "holds a plan (plan.json)" in message, message
    assert not (out / "runs.jsonl").exists()


def test_a_plan_of_another_scenario_names_the_keyword_that_allows_it(cli, tmp_path):
    out = tmp_path / "p"
    run_cli(cli, "plan", "--scenario", "tiny", "--evaluations", "100", "--no-figures",
            "--out", str(out))
    other = swarmplan.Problem("paper-case1")
    message = raised(other.evaluate_plan, out / "plan.json")
    assert "allow_other_terrain=True" in message and "--allow" not in message, message


def test_resuming_a_folder_of_another_build_warns(tmp_path):
    out = tmp_path / "b"
    swarmplan.bench(["tiny"], ["gwo"], evaluations=100, out=out)
    (out / "builds.json").write_text('["0123456789ab"]')
    with pytest.warns(RuntimeWarning, match="made by build 0123456789ab"):
        swarmplan.bench(["tiny"], ["gwo"], evaluations=100, out=out, resume=True)
