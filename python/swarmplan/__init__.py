"""swarmplan from Python: the cooperative UAV path-planning model and its planners.

The model and the optimisers are swarmplan's Rust code (the extension ``swarmplan._native``),
not a re-implementation, so a plan scored here is scored exactly as the command-line tool
scores it, and a Python optimiser can be compared with the Rust ones on equal terms.

- :class:`Problem`: a scenario as a box-bounded minimisation problem (``bounds``, a batch
  ``evaluate`` run in parallel in Rust, ``decode``, ``assess``).
- :func:`plan`: one planning run, the same as ``swarmplan plan`` for the same seed.
- :func:`bench`: an experiment matrix, the same runner as ``swarmplan bench``.

Every input error raises :class:`SwarmplanError` (a ``ValueError``) with the CLI's message,
which names the file or the field.
"""

from __future__ import annotations

import json
import operator
import os
import tempfile
import warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import SwarmplanError

__all__ = [
    "Problem",
    "SwarmplanError",
    "bench",
    "plan",
    "scenarios",
    "__version__",
]

__version__: str = _native.__version__

PathLike = Union[str, "os.PathLike[str]"]


def _path(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)


def _int(name: str, v: Any) -> Any:
    """A whole-number argument as a Python int (numpy integers included, whose own shifts
    the native layer cannot use); beyond 128 bits it is refused here, naming the argument.
    Anything else goes through as it is, for the native layer's message."""
    if v is None or isinstance(v, bool):
        return v
    try:
        i = operator.index(v)
    except TypeError:
        return v
    if not -(2**127) <= i < 2**127:
        raise SwarmplanError(f"{name}: {i} is too {'large' if i > 0 else 'small'}")
    return i


def _warn(notes: Sequence[str]) -> None:
    for n in notes:
        warnings.warn(n, stacklevel=3)


def scenarios() -> List[str]:
    """Names of the built-in scenarios.

    Generated scenarios (``gen-s3-u8-t12-w1``) and the outside benchmark's instances
    (``outside-0`` .. ``outside-3``) load by name too, as does any scenario TOML path.
    """
    return list(_native.scenarios())


class Problem:
    """A scenario's planning problem in one encoding, for numpy optimisers.

    A decision vector ``x`` holds ``uav_count`` blocks of ``block_size`` values (one UAV's
    path each). ``evaluate`` returns the penalised cost (what swarmplan's paper methods
    minimise) and the violation measure (0 exactly when every hard constraint of the
    scenario's feasibility profile holds).

    Args:
        scenario: a built-in or generated name, or a scenario TOML path.
        terrain: a GeoTIFF or ESRI ASCII grid replacing the scenario's terrain.
        method: the method whose encoding and initialisation to use (``swarmplan``,
            ``gwo``, ``pso``, ... or ``optimizer/encoding/init``).
        encoding: replaces the method's encoding (``spherical``, ``cartesian``, ``angle``).
        init: replaces the method's initialisation (``uniform``, ``line``, ``corridor``,
            ``fan``, ``route``, ``band``, ``line-corridor``, ``line-band``).
        profile: ``strict`` or ``paper``, replacing the scenario's feasibility profile.
    """

    def __init__(
        self,
        scenario: PathLike = "paper-case1",
        *,
        terrain: Optional[PathLike] = None,
        method: str = "swarmplan",
        encoding: Optional[str] = None,
        init: Optional[str] = None,
        profile: Optional[str] = None,
    ) -> None:
        self._p = _native.Problem(
            os.fspath(scenario), _path(terrain), method, encoding, init, profile
        )
        # Kept to pickle the problem (process pools) by building it again from them, with
        # files as absolute paths: the unpickling process may run in another folder. Made
        # after the load, so a bad argument is reported as the load reports it.
        self._args = (
            _pickled_scenario(os.fspath(scenario)),
            None if terrain is None else os.path.abspath(os.fspath(terrain)),
            method,
            encoding,
            init,
            profile,
        )
        lo, hi, periodic = self._p.bounds()
        self._lower: np.ndarray = lo
        self._upper: np.ndarray = hi
        self._periodic: np.ndarray = periodic
        for a in (self._lower, self._upper, self._periodic):
            a.setflags(write=False)
        _warn(self._p.notes)

    def __reduce__(self) -> Tuple[Any, ...]:
        """Pickled as the arguments it was made from (files are read again where it is
        unpickled), so a process pool can evaluate it."""
        return (_rebuild, self._args)

    def __repr__(self) -> str:
        return (
            f"Problem({self.name!r}, method={self.method!r}, profile={self.profile!r}, "
            f"uavs={self.uav_count}, dimension={self.dimension})"
        )

    @property
    def name(self) -> str:
        """The scenario's name."""
        return self._p.name

    @property
    def method(self) -> str:
        """The method label whose encoding and initialisation this problem uses."""
        return self._p.method

    @property
    def encoding(self) -> str:
        return self._p.encoding

    @property
    def profile(self) -> str:
        """The feasibility profile: ``strict`` or ``paper``."""
        return self._p.profile

    @property
    def dimension(self) -> int:
        return self._p.dimension

    @property
    def uav_count(self) -> int:
        return self._p.uav_count

    @property
    def block_size(self) -> int:
        """Values per UAV: one UAV's path is one block of the vector."""
        return self._p.block_size

    @property
    def notes(self) -> List[str]:
        """Notes on how the terrain was read, and warnings about causes that make every
        plan infeasible (also issued as Python warnings when the problem is built)."""
        return list(self._p.notes)

    @property
    def bounds(self) -> np.ndarray:
        """Array of shape (dimension, 2): the lower and upper bound of each variable."""
        return np.stack([self._lower, self._upper], axis=1)

    @property
    def lower(self) -> np.ndarray:
        return self._lower

    @property
    def upper(self) -> np.ndarray:
        return self._upper

    @property
    def periodic(self) -> np.ndarray:
        """True for angles that wrap around (values outside wrap instead of clamping)."""
        return self._periodic

    def evaluate(self, X: Any) -> Tuple[np.ndarray, np.ndarray]:
        """Costs and violation measures of a batch.

        Args:
            X: shape (population, dimension), or one vector of shape (dimension,).
                Values outside the box are brought into it as the Rust optimisers bring
                theirs (periodic values wrap, the others are clamped).

        Returns:
            ``(cost, violation)``, two float arrays of length ``population`` (scalars for a
            single vector). Rows are evaluated in parallel in Rust; each result is the
            same whatever the thread count.
        """
        a = np.asarray(X, dtype=np.float64)
        single = a.ndim == 1
        if single:
            a = a.reshape(1, -1)
        if a.ndim != 2:
            raise SwarmplanError(
                f"X: expected shape (population, {self.dimension}) or ({self.dimension},), "
                f"got {a.shape}"
            )
        cost, violation = self._p.evaluate(np.ascontiguousarray(a))
        if single:
            return float(cost[0]), float(violation[0])
        return cost, violation

    def _vector(self, x: Any) -> np.ndarray:
        a = np.ascontiguousarray(np.asarray(x, dtype=np.float64))
        if a.ndim != 1:
            raise SwarmplanError(f"x: expected shape ({self.dimension},), got {a.shape}")
        return a

    def sample_initial(self, count: int, seed: int) -> np.ndarray:
        """``count`` starting points drawn as the method initialises its population.

        Useful to start an outside optimiser from the population swarmplan's own would use.
        """
        return self._p.sample_initial(_int("count", count), _int("seed", seed))

    def decode(self, x: Any) -> List[np.ndarray]:
        """The waypoints of each UAV, arrays of shape (waypoints, 3): x, y and height
        above ground in metres, start and goal included."""
        return [np.asarray(u["waypoints"], dtype=np.float64) for u in self.plan_file(x)["uavs"]]

    def plan_file(self, x: Any) -> Dict[str, Any]:
        """The plan of ``x`` as ``plan.json`` holds it (loadable by ``swarmplan evaluate``)."""
        return json.loads(self._p.decode(self._vector(x)))

    def assess(self, x: Any) -> Dict[str, Any]:
        """The full assessment of the plan of ``x``: what ``swarmplan evaluate --json``
        prints (feasible, violation, cost terms, per-UAV report, violations)."""
        return json.loads(self._p.assess(self._vector(x)))

    def evaluate_plan(self, path: PathLike, *, allow_other_terrain: bool = False) -> Dict[str, Any]:
        """``swarmplan evaluate --json --plan PATH`` on this scenario."""
        return json.loads(self._p.evaluate_plan(os.fspath(path), allow_other_terrain))

    def encode_plan(self, path: PathLike, *, allow_other_terrain: bool = False) -> np.ndarray:
        """The decision vector nearest to a plan file's plan in this encoding."""
        return self._p.encode_plan(os.fspath(path), allow_other_terrain)

    def flight_plan(self, path: PathLike, *, allow_other_terrain: bool = False) -> Dict[str, Any]:
        """What a flight replay needs of a plan file (docs/flight.md): per UAV its launch,
        departure and arrival, its flown path as assessed (arcs densified) as arrays ``t``,
        ``x``, ``y``, ``z`` (absolute altitude), the model's energy and the usable battery;
        and the scenario's threats, separation, zone radius, clearance, UGV0 and map box."""
        return json.loads(self._p.flight_plan(os.fspath(path), allow_other_terrain))

    def terrain_heights(self, x: Any, y: Any) -> np.ndarray:
        """The terrain's height above the datum at each (x, y), metres, as the model
        interpolates it."""
        return self._p.terrain_heights(
            np.ascontiguousarray(x, dtype=np.float64), np.ascontiguousarray(y, dtype=np.float64)
        )

    def ground_coverage(self, agl: Optional[float] = None) -> Dict[str, Any]:
        """Where a UAV ``agl`` metres above ground (default: the top of the altitude band)
        has a direct link to a ground node under the nominal range and the line of sight,
        as ``plan`` and the top view report it (docs/model.md, "Where no path can keep a
        direct ground link").

        Returns a dict: ``linked`` (bool array, rows along y from the map's y minimum,
        columns along x), ``origin`` ((x, y) of the first cell's corner), ``cell`` (metres),
        ``agl`` (metres) and ``dead_share`` (the share of cells without a link).
        """
        linked, origin, cell, height, dead_share = self._p.ground_coverage(agl)
        linked.setflags(write=False)
        return {
            "linked": linked,
            "origin": origin,
            "cell": cell,
            "agl": height,
            "dead_share": dead_share,
        }


def _pickled_scenario(scenario: str) -> str:
    """A scenario argument as a pickle keeps it: a name as it is (names load before
    files), a file's path made absolute."""
    if _native.is_scenario_name(scenario):
        return scenario
    return os.path.abspath(scenario)


def _rebuild(scenario, terrain, method, encoding, init, profile) -> Problem:
    """A pickled :class:`Problem` made again from its arguments."""
    return Problem(
        scenario, terrain=terrain, method=method, encoding=encoding, init=init, profile=profile
    )


def plan(
    scenario: PathLike = "paper-case1",
    *,
    method: str = "swarmplan",
    seed: Optional[int] = None,
    evaluations: Optional[int] = None,
    iterations: Optional[int] = None,
    population: Optional[int] = None,
    params: Optional[PathLike] = None,
    terrain: Optional[PathLike] = None,
    profile: Optional[str] = None,
    time_limit: Optional[float] = None,
    until_feasible: bool = False,
    attempts: int = 1,
    flight_margin: float = 0.0,
) -> Dict[str, Any]:
    """Plans a scenario: the run ``swarmplan plan`` makes with the same arguments.

    ``flight_margin=M`` is ``plan --flight-margin M``: the search runs on the scenario with
    every hard geometric limit M metres tighter (UAV sizes, separation, terrain clearance,
    the map box M m inside), and the plan is judged against the scenario as given;
    ``margin_verdict`` is the verdict with the margin (docs/flight.md, "A flight margin").

    ``attempts=K`` is ``plan --attempts K``: up to K runs from derived seeds, stopping at the
    first feasible plan (each spends the whole budget); ``run["attempts"]`` lists them and
    ``run["seed"]`` is the seed of the plan kept.

    The default budget is the method's (38,700 evaluations for ``swarmplan``, 200
    iterations for the paper's methods); the default seed is the scenario's.

    Returns:
        A dict with ``run`` (``run.json``: method, seed, budget, evaluations and ``assessment``,
        the per-UAV summaries and the violations), ``plan`` (``plan.json``), ``feasible``,
        ``violations``, ``convergence`` (a list of dicts per iteration; past 65,536
        iterations every s-th, each dict naming its iteration), ``uav_costs``
        (per row of ``convergence`` and UAV), ``verdict`` (the verdict line ``plan``
        prints), ``outcome`` (the line ``plan`` prints after an infeasible verdict,
        ``no plan exists: ...`` or ``none found: ...``; None for a feasible plan),
        ``notes`` and ``margin_verdict`` (None without a flight margin).
    """
    out = json.loads(
        _native.plan(
            os.fspath(scenario),
            method,
            _int("seed", seed),
            _int("evaluations", evaluations),
            _int("iterations", iterations),
            _int("population", population),
            _path(params),
            _path(terrain),
            profile,
            time_limit,
            until_feasible,
            _int("attempts", attempts),
            float(flight_margin),
        )
    )
    _warn(out["notes"])
    out["feasible"] = out["run"]["assessment"]["feasible"]
    out["violations"] = out["run"]["assessment"]["violations"]
    return out


def bench(
    scenarios: Sequence[PathLike],
    methods: Sequence[str],
    *,
    runs: int = 1,
    seed: int = 1,
    evaluations: Optional[int] = None,
    iterations: Optional[int] = None,
    budget: str = "equal",
    population: Optional[int] = None,
    params: Optional[PathLike] = None,
    terrain: Optional[PathLike] = None,
    profile: Optional[str] = None,
    threads: int = 0,
    out: Optional[PathLike] = None,
    resume: bool = False,
    as_frame: bool = False,
) -> Any:
    """Runs every method on every scenario ``runs`` times: ``swarmplan bench``.

    The default budget is equal for every method (38,700 evaluations); ``budget="paper"``
    gives each its paper setting. Run k of every method has the same seed (derived from
    ``seed``, the scenario and k). With ``out``, records go to ``OUT/runs.jsonl`` as the CLI
    writes them (``resume=True`` continues a folder); without, a temporary folder is used.

    Returns:
        The records, a list of dicts (the lines of ``runs.jsonl``), or with
        ``as_frame=True`` a pandas DataFrame of them (needs pandas).
    """
    if isinstance(scenarios, (str, os.PathLike)) or isinstance(methods, str):
        raise SwarmplanError("scenarios and methods: expected lists of names, got a single string")

    def run(folder: str) -> List[str]:
        return _native.bench(
            folder,
            [os.fspath(s) for s in scenarios],
            list(methods),
            _int("runs", runs),
            _int("seed", seed),
            _int("evaluations", evaluations),
            _int("iterations", iterations),
            budget,
            _int("population", population),
            _path(params),
            _path(terrain),
            profile,
            _int("threads", threads),
            resume,
        )

    if out is None:
        with tempfile.TemporaryDirectory(prefix="swarmplan-bench-") as d:
            lines = run(d)
    else:
        lines = run(os.fspath(out))
    records = [json.loads(line) for line in lines]
    if as_frame:
        import pandas as pd  # optional dependency

        return pd.DataFrame.from_records(records)
    return records
