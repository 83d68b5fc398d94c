"""stopscan: where a robot should stop and scan when every scan costs time.

The Python face of the Rust library. Every function runs the library's own pipelines, so a
run record made here equals the command line's, byte for byte (see ``explore_json``).

Geometry goes in as shapely geometries, any object with ``__geo_interface__``, GeoJSON dicts,
or numpy float64 arrays of shape (n, 2); it comes out as numpy arrays, and regions expose
``__geo_interface__``.
"""

from __future__ import annotations

import json
import os
from typing import Any, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from ._stopscan import (
    Environment,
    Region,
    Strategy,
    __version__,
    corner_circle as _corner_circle,
    explore_json as _explore_json,
    from_geojson as _from_geojson,
    load as _load,
    visibility as _visibility,
)

__all__ = [
    "Environment",
    "Region",
    "Strategy",
    "__version__",
    "corner_circle",
    "environment",
    "explore",
    "explore_json",
    "load",
    "visibility",
]

Point = Tuple[float, float]


def load(path: Union[str, os.PathLike], start: Optional[Point] = None,
         simplify: Optional[float] = None) -> Environment:
    """Reads an environment file of any format the CLI reads: GeoJSON, WKT, ``.pol``, the
    benchmark format, or a ROS map's YAML (its free region holding ``start``, simplified
    within ``simplify`` metres)."""
    return _load(os.fspath(path), None if start is None else _point(start), simplify)


def environment(domain: Any, name: str = "polygon") -> Environment:
    """An environment from an ``Environment``, a path, a shapely Polygon (or any object with
    ``__geo_interface__``), a GeoJSON dict, or an outer ring as an (n, 2) array (with no
    holes)."""
    if isinstance(domain, Environment):
        return domain
    if isinstance(domain, (str, os.PathLike)):
        return load(domain)
    geo = getattr(domain, "__geo_interface__", None)
    if geo is None and isinstance(domain, dict):
        geo = domain
    if geo is None:
        ring = _points(domain)
        geo = {"type": "Polygon", "coordinates": [ring.tolist()]}
    return _from_geojson(json.dumps(geo), name)


def _points(points: Any) -> np.ndarray:
    """Points as a C-contiguous float64 array of shape (n, 2)."""
    geo = getattr(points, "__geo_interface__", None)
    if geo is not None:
        coords = geo["coordinates"]
        points = [coords] if geo["type"] == "Point" else coords
    elif isinstance(points, (list, tuple)) and any(hasattr(p, "__geo_interface__") for p in points):
        points = [_point(p) for p in points]
    a = np.ascontiguousarray(np.asarray(points, dtype=np.float64))
    if a.ndim == 1 and a.shape[0] == 2:
        a = a.reshape(1, 2)
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError(f"expected points of shape (n, 2), got {a.shape}")
    return a


def _point(p: Any) -> Point:
    a = _points(p)
    if a.shape[0] != 1:
        raise ValueError(f"expected one point, got {a.shape[0]}")
    return (float(a[0, 0]), float(a[0, 1]))


def visibility(domain: Any, points: Any, range: Optional[float] = None) -> list:
    """The region seen from each point (an (n, 2) array, or shapely points), with a sensor
    of ``range`` metres if given. Returns one ``Region`` per point."""
    return _visibility(environment(domain), _points(points), range)


def explore_json(domain: Any, start: Optional[Any] = None, **options: Any) -> str:
    """The run record of an exploration as JSON text, exactly as ``stopscan explore --out``
    writes it. Options: ``strategy`` (default "depth_first"), ``scan_time`` (1), ``move_time``
    (0), ``speed`` (1), ``range``, ``robot_radius``, ``seed`` (0), ``optimum_seconds`` (5),
    ``optimum_nodes``."""
    env = environment(domain)
    return _explore_json(env, None if start is None else _point(start), **options)


def explore(domain: Any, start: Optional[Any] = None, **options: Any) -> dict:
    """Explores ``domain`` from ``start`` (by default the file's start) and returns the run
    record as a dict (see ``explore_json`` for the options)."""
    return json.loads(explore_json(domain, start, **options))


def corner_circle(d: float) -> dict:
    """The circle strategy around a corner at distance ``d`` (the circle paper): its stops,
    ratio and bound, as ``stopscan corner circle --format json`` reports them."""
    return json.loads(_corner_circle(d))
