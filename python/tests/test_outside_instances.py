"""python/examples/outside_instances.py draws the shared folder's outside instances again.

The script makes fresh development instances from the outside generator (docs/results.md,
"Fresh instances"); this checks that it makes them as the shared folder's README says its
own were made: RandomState 11's first draw is outside-4, threats, start and goal exactly and
the terrain to the hundredth of a metre the grid files hold.
"""

from __future__ import annotations

import gzip
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "python" / "examples" / "outside_instances.py"


def shared_outside() -> Path:
    """The instances' folder as swarmplan finds it: `$SWARMPLAN_SHARED/data/outside`, else
    `shared/data/outside` in the checkout or the nearest of its ancestors holding one."""
    shared = os.environ.get("SWARMPLAN_SHARED")
    if shared:
        return Path(shared) / "data" / "outside"
    for folder in [ROOT, *ROOT.parents]:
        candidate = folder / "shared" / "data" / "outside"
        if candidate.is_dir():
            return candidate
    return ROOT.parent / "shared" / "data" / "outside"


def grid(path: Path) -> np.ndarray:
    with gzip.open(path, "rt") as f:
        return np.loadtxt(f, skiprows=6)


def test_random_state_11_draws_outside_4_again(tmp_path: Path) -> None:
    shared = shared_outside()
    assert (shared / "outside-4.json").exists(), f"needs the shared folder: {shared}"
    run = subprocess.run(
        [sys.executable, str(SCRIPT), "--state", "11", "--count", "1", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    made = tmp_path / "data" / "outside"
    assert json.loads((made / "outside-0.json").read_text()) == json.loads(
        (shared / "outside-4.json").read_text()
    )
    assert np.abs(grid(made / "outside-0.asc.gz") - grid(shared / "outside-4.asc.gz")).max() <= 0.005 + 1e-9
    assert "RandomState 11" in (made / "README.md").read_text()


def test_a_missing_out_folder_is_refused_with_the_reason() -> None:
    run = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True)
    assert run.returncode != 0
    assert "--out is required" in run.stderr
