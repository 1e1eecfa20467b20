"""Problem.evaluate and assess give what the CLI's `evaluate` gives."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import swarmplan
from conftest import cli_json, run_cli


def assert_same(a, b, rel=1e-12, path="report"):
    """Equal structures, floats to `rel` relative."""
    if isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            assert_same(a[k], b[k], rel, f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, rel, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert math.isclose(a, b, rel_tol=rel, abs_tol=0.0) or a == b, f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def test_evaluate_plan_equals_cli_evaluate_on_a_saved_plan(cli, tmp_path):
    out = tmp_path / "out"
    run_cli(cli, "plan", "--scenario", "paper-case1", "--method", "gwo", "--evaluations", "600",
            "--seed", "4", "--no-figures", "--out", str(out))
    plan = out / "plan.json"
    want = cli_json(cli, "evaluate", "--scenario", "paper-case1", "--plan", str(plan), "--json")
    got = swarmplan.Problem("paper-case1").evaluate_plan(plan)
    assert_same(got, want)


@pytest.mark.parametrize("scenario,method", [("paper-case1", "gwo"), ("paper-case2", "pso"),
                                             ("tiny", "swarmplan")])
def test_decoded_vector_scores_as_the_cli_scores_its_plan_file(cli, tmp_path, scenario, method):
    p = swarmplan.Problem(scenario, method=method)
    X = p.sample_initial(3, 17)
    cost, violation = p.evaluate(X)
    for i, x in enumerate(X):
        path = tmp_path / f"plan{i}.json"
        path.write_text(json.dumps(p.plan_file(x)))
        want = cli_json(cli, "evaluate", "--scenario", scenario, "--plan", str(path), "--json")
        assert_same(p.assess(x), want)
        assert math.isclose(cost[i], want["cost"]["total"], rel_tol=1e-12)
        assert math.isclose(violation[i], want["violation"], rel_tol=1e-12, abs_tol=0.0)
        assert (violation[i] == 0.0) == want["feasible"]


def test_batch_evaluation_equals_one_by_one():
    p = swarmplan.Problem("paper-case1", method="gwo")
    rng = np.random.default_rng(5)
    X = np.vstack([p.sample_initial(40, 2), rng.uniform(p.lower, p.upper, size=(40, p.dimension))])
    cost, violation = p.evaluate(X)
    assert cost.shape == violation.shape == (80,)
    for i, x in enumerate(X):
        c, v = p.evaluate(x)
        assert c == cost[i] and v == violation[i]
    # Same batch again (other thread interleaving): bit-identical.
    c2, v2 = p.evaluate(X)
    assert np.array_equal(cost, c2) and np.array_equal(violation, v2)


def test_values_outside_the_box_are_projected_as_the_rust_optimizers_do():
    p = swarmplan.Problem("paper-case1", method="gwo")
    x = p.sample_initial(1, 3)[0]
    wide = x + np.where(p.periodic, p.upper - p.lower, 0.0)  # a full turn on every angle
    wide[~p.periodic] = np.where(np.arange(p.dimension)[~p.periodic] % 2 == 0, 1e9, -1e9)
    clamped = x.copy()
    clamped[~p.periodic] = np.where(np.arange(p.dimension)[~p.periodic] % 2 == 0,
                                    p.upper[~p.periodic], p.lower[~p.periodic])
    assert p.evaluate(wide) == p.evaluate(clamped)


def test_bounds_decode_and_shape():
    p = swarmplan.Problem("paper-case1")
    assert p.bounds.shape == (p.dimension, 2)
    assert np.all(p.lower <= p.upper)
    assert p.dimension == p.uav_count * p.block_size
    paths = p.decode(p.sample_initial(1, 1)[0])
    assert len(paths) == p.uav_count and all(w.shape[1] == 3 for w in paths)
    assert "paper-case1" in repr(p)


def test_encode_plan_round_trips_the_cli_plan(cli, tmp_path):
    out = tmp_path / "out"
    run_cli(cli, "plan", "--scenario", "tiny", "--evaluations", "500", "--seed", "2",
            "--no-figures", "--out", str(out))
    p = swarmplan.Problem("tiny")
    x = p.encode_plan(out / "plan.json")
    want = json.loads((out / "run.json").read_text())["assessment"]["cost"]["total"]
    assert math.isclose(p.evaluate(x)[0], want, rel_tol=1e-9)


@pytest.mark.parametrize("waypoints", [2, 8])
def test_encode_plan_refuses_a_plan_with_another_number_of_waypoints(cli, tmp_path, waypoints):
    # A plan of `tiny` edited to 2 or 8 free waypoints (tiny has 4): same name and
    # terrain, so only its shape tells. It used to panic (fewer) or encode another plan
    # without a word (more).
    scenario = run_cli(cli, "scenario", "show", "tiny").stdout
    edited = tmp_path / "edited.toml"
    edited.write_text(scenario.replace("waypoints = 4", f"waypoints = {waypoints}"))
    out = tmp_path / "out"
    run_cli(cli, "plan", "--scenario", str(edited), "--evaluations", "300", "--seed", "1",
            "--no-figures", "--out", str(out))
    p = swarmplan.Problem("tiny")
    with pytest.raises(swarmplan.SwarmplanError, match=r"UAV 0 has \d+ waypoints.*has 6"):
        p.encode_plan(out / "plan.json")


def test_a_problem_pickles_for_process_pools():
    import copy
    import pickle

    p = swarmplan.Problem("tiny", method="gwo", profile="paper")
    q = pickle.loads(pickle.dumps(p))
    x = p.sample_initial(3, 7)
    assert np.array_equal(p.evaluate(x)[0], q.evaluate(x)[0])
    assert (q.method, q.profile, q.dimension) == (p.method, p.profile, p.dimension)
    assert copy.deepcopy(p).name == p.name


def test_a_pickled_problem_of_a_file_loads_from_another_folder(cli, tmp_path, monkeypatch):
    import pickle

    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    scenario = run_cli(cli, "scenario", "show", "tiny").stdout
    (tmp_path / "a" / "mine.toml").write_text(scenario.replace('name = "tiny"', 'name = "mine"'))
    monkeypatch.chdir(tmp_path / "a")
    p = swarmplan.Problem(Path("mine.toml"))
    named = pickle.dumps(swarmplan.Problem("tiny"))
    data = pickle.dumps(p)
    # Unpickled in another folder (as a process pool started elsewhere would): the file is
    # found by its absolute path, and a built-in name stays a name.
    monkeypatch.chdir(tmp_path / "b")
    q = pickle.loads(data)
    assert q.name == p.name == "mine"
    x = p.sample_initial(2, 3)
    assert np.array_equal(p.evaluate(x)[0], q.evaluate(x)[0])
    assert pickle.loads(named).name == "tiny"
