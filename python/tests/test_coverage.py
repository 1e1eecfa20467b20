"""Problem.ground_coverage is the map behind the CLI's dead-zone note and the top view's
hatch."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

import swarmplan
from conftest import run_cli


def short_range_tiny(cli, tmp_path):
    """`tiny` with a fixed 100 m range under `relay`, as a scenario file."""
    text = run_cli(cli, "scenario", "show", "tiny").stdout
    text = re.sub(r"(?m)^requirement = .*$", 'requirement = "relay"', text)
    text = re.sub(r"(?m)^range = .*$", "range = 100.0", text)
    text = re.sub(r"(?m)^shadowing_sigma_db = .*$", "shadowing_sigma_db = 0.0", text)
    path = tmp_path / "short.toml"
    path.write_text(text)
    return path


def test_the_map_has_the_shape_and_height_of_the_cli_and_refuses_bad_heights():
    p = swarmplan.Problem("tiny")
    cov = p.ground_coverage()
    linked = cov["linked"]
    assert linked.dtype == np.bool_
    assert cov["agl"] == 80.0 and cov["cell"] == 10.0 and cov["origin"] == (0.0, 0.0)
    assert linked.shape == (20, 30)  # 200 m north by 300 m east in 10 m cells
    assert linked[3, 3], "the cell of the start, where the ground station is"
    assert 0.0 <= cov["dead_share"] <= 1.0
    low = p.ground_coverage(10.0)
    assert low["agl"] == 10.0 and low["linked"].shape == linked.shape
    with pytest.raises(swarmplan.SwarmplanError, match="agl"):
        p.ground_coverage(-1.0)


def test_the_dead_share_is_the_one_the_cli_reports(cli, tmp_path):
    scenario = short_range_tiny(cli, tmp_path)
    plan = tmp_path / "straight.json"
    straight = {"waypoints": [[30.0, 30.0, 60.0], [270.0, 170.0, 60.0]]}
    plan.write_text(json.dumps({"uavs": [straight, straight]}))
    out = run_cli(cli, "evaluate", "--scenario", str(scenario), "--plan", str(plan)).stdout
    m = re.search(r"no direct ground link from (\d+) % of the map even at 80 m AGL", out)
    assert m, out
    cov = swarmplan.Problem(str(scenario)).ground_coverage()
    assert round(100 * cov["dead_share"]) == int(m.group(1))
    assert cov["dead_share"] > 0.5, "most of the map is beyond 100 m of both ground nodes"
