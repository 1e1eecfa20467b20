"""Shared fixtures: the command-line tool the Python results are checked against."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any, Dict, List

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> str:
    """Path of the `swarmplan` binary: $SWARMPLAN_CLI, or the release build of this
    checkout (built here if it is missing or stale)."""
    given = os.environ.get("SWARMPLAN_CLI")
    if given:
        return given
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "swarmplan"], cwd=ROOT, check=True)
    return str(ROOT / "target" / "release" / "swarmplan")


def run_cli(cli: str, *args: str, ok: bool = True) -> subprocess.CompletedProcess:
    p = subprocess.run([cli, *args], capture_output=True, text=True)
    if ok:
        assert p.returncode == 0, p.stderr
    return p


def cli_json(cli: str, *args: str) -> Dict[str, Any]:
    return json.loads(run_cli(cli, *args).stdout)


def cli_error(cli: str, *args: str) -> str:
    """The message of the CLI's `error: ...` line for a failing command."""
    p = run_cli(cli, *args, ok=False)
    assert p.returncode == 2, p.stderr
    lines = [l for l in p.stderr.splitlines() if l.startswith("error: ")]
    assert lines, p.stderr
    return lines[-1][len("error: "):]


def read_jsonl(path: Path) -> List[Dict[str, Any]]:
    return [json.loads(l) for l in path.read_text().splitlines() if l.strip()]
