from os import PathLike
from typing import Any, Callable, Iterator, Literal, Optional, Sequence, Tuple, TypedDict, Union

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
    """An online exploration strategy, driven step by step.

    Coordinates are the driver's own, georeferenced ones included: the strategy computes in
    a frame at the start, rounded to a multiple of 1,024 m, and answers in the driver's."""
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
def visibility(
    domain: Domain, points: Any, range: Optional[float] = None, threads: Optional[int] = None
) -> list[Region]: ...
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
def corner_ratio(
    strategy: Literal["unirec", "exprec", "circle", "stops"],
    delta: float,
    stops_deg: Optional[Sequence[float]] = None,
    *,
    last_step: Literal["capped", "nominal"] = "capped",
    exprec: Literal["table_i", "appendix"] = "table_i",
    route: Literal["arc", "chord"] = "arc",
    allow_large: bool = False,
) -> dict[str, Any]: ...
def corner_policy(
    belief: str,
    *,
    truth: Optional[str] = None,
    distance: float = 10.0,
    scan_time: float = 2.0,
    move_time: float = 0.0,
    speed: float = 0.5,
    memory: Literal["none", "last"] = "last",
    reading: Literal["conditional", "literal"] = "conditional",
    step_deg: float = 5.0,
    solver: Literal["backward", "general"] = "backward",
) -> dict[str, Any]: ...

Cell = Tuple[int, int]

class GridRegion:
    mask: np.ndarray
    origin: Cell
    start: Optional[Cell]
    cell_size: float
    name: str
    def __init__(
        self,
        mask: Any,
        start: Optional[Cell] = None,
        origin: Cell = (0, 0),
        cell_size: float = 1.0,
        name: str = "roi",
    ) -> None: ...
    @property
    def cells(self) -> np.ndarray: ...
    def text_grid(self) -> str: ...

def load_region(
    path: Union[str, PathLike[str]],
    *,
    cell_size: float = 1.0,
    cell_px: int = 1,
    invert_mask: bool = False,
    start: Optional[Cell] = None,
) -> GridRegion: ...

class MissionIncomplete(RuntimeError):
    record: dict[str, Any]

def roi_json(
    region: Union[str, PathLike[str], GridRegion, np.ndarray, None] = None,
    *,
    random: Optional[int] = None,
    robots: int = 1,
    cell_size: float = 1.0,
    cell_px: int = 1,
    invert_mask: bool = False,
    start: Optional[Cell] = None,
    name: str = "roi",
    robot_speed: float = 1.0,
    roi_speed: float = 0.0,
    roi_heading_deg: float = 0.0,
    battery_s: Optional[float] = None,
    scan_time: float = 0.0,
    move_time: float = 0.0,
    camera: bool = False,
    frames: int = 5,
    search_box: Optional[Tuple[int, int, int, int]] = None,
    launch: Optional[Cell] = None,
    paths: bool = True,
    seed: int = 0,
    svg: Union[str, PathLike[str], None] = None,
    report: Union[str, PathLike[str], None] = None,
    mcap: Union[str, PathLike[str], None] = None,
    allow_large: bool = False,
) -> str: ...
def roi(region: Union[str, PathLike[str], GridRegion, np.ndarray, None] = None, **options: Any) -> dict[str, Any]: ...

class SweepTable:
    rows: list[dict[str, Any]]
    backend: str
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[dict[str, Any]]: ...
    def __getitem__(self, i: int) -> dict[str, Any]: ...
    @property
    def columns(self) -> list[str]: ...
    def csv(self) -> str: ...
    def write_csv(self, path: Union[str, PathLike[str]]) -> None: ...
    def to_pandas(self) -> Any: ...

def sweep(
    envs: Union[str, PathLike[str], Sequence[Union[str, PathLike[str]]]],
    strategy: Union[str, Sequence[str]] = "all",
    *,
    scan_time: float = 1.0,
    move_time: float = 0.0,
    speed: float = 1.0,
    range: Optional[float] = None,
    simplify: Optional[float] = None,
    bounds_seconds: Optional[float] = None,
    bounds_steps: Optional[int] = None,
    backend: Literal["auto", "serial", "ray"] = "auto",
    address: Optional[str] = None,
    workers: Optional[int] = None,
    progress: Union[bool, Callable[[int, int], None]] = False,
) -> SweepTable: ...
