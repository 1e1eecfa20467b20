"""Type stubs of the Rust extension behind ``swarmplan`` (use the ``swarmplan`` package)."""

from typing import List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class SwarmplanError(ValueError): ...

class Problem:
    def __init__(
        self,
        scenario: str,
        terrain: Optional[str] = ...,
        method: str = ...,
        encoding: Optional[str] = ...,
        init: Optional[str] = ...,
        profile: Optional[str] = ...,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def method(self) -> str: ...
    @property
    def encoding(self) -> str: ...
    @property
    def profile(self) -> str: ...
    @property
    def dimension(self) -> int: ...
    @property
    def uav_count(self) -> int: ...
    @property
    def block_size(self) -> int: ...
    @property
    def notes(self) -> List[str]: ...
    def bounds(
        self,
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
    def evaluate(
        self, x: npt.NDArray[np.float64]
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def sample_initial(self, count: int, seed: int) -> npt.NDArray[np.float64]: ...
    def decode(self, x: npt.NDArray[np.float64]) -> str: ...
    def assess(self, x: npt.NDArray[np.float64]) -> str: ...
    def evaluate_plan(self, path: str, allow_other_terrain: bool = ...) -> str: ...
    def encode_plan(self, path: str, allow_other_terrain: bool = ...) -> npt.NDArray[np.float64]: ...
    def flight_plan(self, path: str, allow_other_terrain: bool = ...) -> str: ...
    def terrain_heights(
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]
    ) -> npt.NDArray[np.float64]: ...
    def ground_coverage(
        self, agl: Optional[float] = ...
    ) -> Tuple[npt.NDArray[np.bool_], Tuple[float, float], float, float, float]: ...

def scenarios() -> List[str]: ...
def plan(
    scenario: str = ...,
    method: str = ...,
    seed: Optional[int] = ...,
    evaluations: Optional[int] = ...,
    iterations: Optional[int] = ...,
    population: Optional[int] = ...,
    params: Optional[str] = ...,
    terrain: Optional[str] = ...,
    profile: Optional[str] = ...,
    time_limit: Optional[float] = ...,
    until_feasible: bool = ...,
    attempts: int = ...,
    flight_margin: float = ...,
) -> str: ...
def bench(
    out: str,
    scenarios: List[str],
    methods: List[str],
    runs: int = ...,
    seed: int = ...,
    evaluations: Optional[int] = ...,
    iterations: Optional[int] = ...,
    budget: str = ...,
    population: Optional[int] = ...,
    params: Optional[str] = ...,
    terrain: Optional[str] = ...,
    profile: Optional[str] = ...,
    threads: int = ...,
    resume: bool = ...,
) -> List[str]: ...
def is_scenario_name(name: str) -> bool: ...
