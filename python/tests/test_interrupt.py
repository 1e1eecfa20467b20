"""Ctrl-C stops a long call within a moment, and a bench keeps the records it wrote."""

from __future__ import annotations

import json
import os
import signal
import threading
import time

import pytest

import swarmplan


def interrupt_after(seconds: float) -> threading.Timer:
    """Sends this process SIGINT (Ctrl-C) after `seconds`."""
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_plan():
    started = time.monotonic()
    interrupt_after(1.0)
    with pytest.raises(KeyboardInterrupt):
        # Uninterrupted it would run for its 30 s time limit.
        swarmplan.plan("paper-case1", evaluations=10**8, time_limit=30)
    assert time.monotonic() - started < 10


def test_ctrl_c_stops_a_long_bench_and_keeps_its_records(tmp_path):
    out = tmp_path / "b"
    started = time.monotonic()
    interrupt_after(1.5)
    with pytest.raises(KeyboardInterrupt):
        # 400 runs of about 0.1 s each on one thread.
        swarmplan.bench(["tiny"], ["gwo"], runs=400, evaluations=20000, threads=1, out=out)
    assert time.monotonic() - started < 10
    lines = (out / "runs.jsonl").read_text().splitlines()
    assert 0 < len(lines) < 400
    assert all(json.loads(line)["method"] == "gwo" for line in lines)
