"""The cross-check example runs end to end against mealpy (small budget)."""

from __future__ import annotations

import json
import runpy
import sys

from conftest import ROOT


def test_cross_check_example_runs(tmp_path, capsys):
    mod = runpy.run_path(str(ROOT / "python" / "examples" / "cross_check.py"))
    out = tmp_path / "x.json"
    assert mod["main"](["--runs", "2", "--evaluations", "300", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "| gwo | swarmplan |" in printed and "OriginalPSO" in printed
    data = json.loads(out.read_text())
    rows = {(e["algorithm"], e["implementation"]): e for e in data["table"]}
    assert len(rows) == 5
    assert all(e["runs"] == 2 and e["mean_evaluations"] == 300 for e in rows.values())
    assert all("rank_sum_p_vs_mealpy" in e for k, e in rows.items() if not k[1].startswith("mealpy"))
