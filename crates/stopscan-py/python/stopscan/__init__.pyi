from os import PathLike
from typing import Any, Literal, Optional, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

Point = Tuple[float, float]
Points = npt.NDArray[np.float64]

__version__: str

class Environment:
    """A polygon with holes (validated), its frame and the start its file gives."""
    @property
    def name(self) -> str: ...
    @property
    def outer(self) -> Points: ...
    @property
    def holes(self) -> list[Points]: ...
    @property
    def area(self) -> float: ...
    @property
    def reflex_vertices(self) -> int: ...
    @property
    def start(self) -> Optional[Point]: ...
    @property
    def cell_size(self) -> Optional[float]: ...

class Region:
    """The region seen from one point."""
    @property
    def viewpoint(self) -> Point: ...
    @property
    def vertices(self) -> Points: ...
    @property
    def area(self) -> float: ...
    @property
    def windows(self) -> npt.NDArray[np.float64]: ...
    @property
    def __geo_interface__(self) -> dict[str, Any]: ...

class MoveAction(TypedDict):
    type: Literal["move"]
    to: Point

class OtherAction(TypedDict):
    type: Literal["scan", "done"]

class Strategy:
    """An online exploration strategy, driven step by step."""
    def __init__(
        self,
        name: str = "depth_first",
        scan_time: float = 1.0,
        move_time: float = 0.0,
        speed: float = 1.0,
        range: Optional[float] = None,
        robot_radius: Optional[float] = None,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    def observe(
        self,
        *,
        start: Optional[Point] = None,
        arrived: bool = False,
        region: Optional[Region] = None,
        failed: Optional[Point] = None,
        reason: Literal["blocked", "aborted", "timed_out"] = "blocked",
    ) -> None: ...
    def next_action(self) -> Union[MoveAction, OtherAction]: ...

Domain = Union[Environment, str, PathLike[str], dict[str, Any], Points, Any]

def load(path: Union[str, PathLike[str]], start: Optional[Point] = None, simplify: Optional[float] = None) -> Environment: ...
def environment(domain: Domain, name: str = "polygon") -> Environment: ...
def visibility(domain: Domain, points: Any, range: Optional[float] = None) -> list[Region]: ...
def explore_json(
    domain: Domain,
    start: Optional[Any] = None,
    *,
    strategy: str = "depth_first",
    scan_time: float = 1.0,
    move_time: float = 0.0,
    speed: float = 1.0,
    range: Optional[float] = None,
    robot_radius: Optional[float] = None,
    seed: int = 0,
    optimum_seconds: Optional[float] = None,
    optimum_nodes: Optional[int] = None,
) -> str: ...
def explore(domain: Domain, start: Optional[Any] = None, **options: Any) -> dict[str, Any]: ...
def corner_circle(d: float) -> dict[str, Any]: ...
