"""Sweeps: many independent explorations, one task per run, in this process or on Ray.

The driver lists and loads the environment files once; each task runs one file with one
strategy; the rows gather in the order ``stopscan explore --env DIR`` writes them, and the
table's CSV equals that command's file byte for byte, whatever ran the tasks.
"""

from __future__ import annotations

import json
import os
import sys
import warnings
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union

from . import _stopscan

PathLike = Union[str, "os.PathLike[str]"]


class SweepTable:
    """The rows of a sweep, in order: one dict per run, keyed as the CSV's columns (with
    ``scans``, ``moves``, ``distance``, ``time`` and the time's terms at the top level)."""

    def __init__(self, rows: List[dict], lines: List[str], backend: str) -> None:
        self.rows = rows
        self._lines = lines
        #: What ran the tasks: "serial" or "ray".
        self.backend = backend

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self) -> Iterator[dict]:
        return iter(self.rows)

    def __getitem__(self, i: int) -> dict:
        return self.rows[i]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, SweepTable) and self._lines == other._lines

    def __repr__(self) -> str:
        return f"SweepTable({len(self.rows)} runs, by {self.backend})"

    @property
    def columns(self) -> List[str]:
        """The CSV's columns."""
        return _stopscan.sweep_csv_header().strip().split(",")

    def csv(self) -> str:
        """The table as ``stopscan explore --env DIR`` writes its CSV file."""
        return _stopscan.sweep_csv_header() + "".join(self._lines)

    def write_csv(self, path: PathLike) -> None:
        """Writes ``csv()`` to ``path`` (replaced whole: written beside it, then renamed)."""
        path = os.fspath(path)
        tmp = f"{path}.tmp{os.getpid()}"
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(self.csv())
        os.replace(tmp, path)

    def to_pandas(self) -> Any:
        """The table as a pandas DataFrame (needs pandas)."""
        import pandas as pd  # noqa: PLC0415 (optional dependency)

        return pd.DataFrame(self.rows, columns=self.columns)


def _files(envs: Union[PathLike, Sequence[PathLike]]) -> List[str]:
    if isinstance(envs, (str, os.PathLike)):
        path = os.fspath(envs)
        if os.path.isdir(path):
            return [os.fspath(p) for p in _stopscan.sweep_files(path)]
        files = [path]
    else:
        files = [os.fspath(p) for p in envs]
    missing = [f for f in files if not os.path.exists(f)]
    if missing:
        raise ValueError(f"{missing[0]}: no such file or folder")
    if not files:
        raise ValueError("no environment files to sweep")
    return files


def _run(input_json: str, strategy: str, options: Dict[str, Any]) -> Tuple[str, str]:
    """One task: one run of one strategy on one loaded environment."""
    return _stopscan.sweep_run(input_json, strategy, **options)


_remote_run: Optional[Any] = None


def _ray_run(ray: Any) -> Any:
    global _remote_run
    if _remote_run is None:
        _remote_run = ray.remote(num_cpus=1)(_run)
    return _remote_run


def _progress(progress: Union[bool, Callable[[int, int], None], None]) -> Callable[[int, int], None]:
    if callable(progress):
        return progress
    if not progress:
        return lambda done, total: None

    def show(done: int, total: int) -> None:
        sys.stderr.write(f"\r{done}/{total} runs")
        if done == total:
            sys.stderr.write("\n")
        sys.stderr.flush()

    return show


def sweep(
    envs: Union[PathLike, Sequence[PathLike]],
    strategy: Union[str, Sequence[str]] = "all",
    *,
    scan_time: float = 1.0,
    move_time: float = 0.0,
    speed: float = 1.0,
    range: Optional[float] = None,
    simplify: Optional[float] = None,
    bounds_seconds: Optional[float] = None,
    bounds_steps: Optional[int] = None,
    backend: str = "auto",
    address: Optional[str] = None,
    workers: Optional[int] = None,
    progress: Union[bool, Callable[[int, int], None]] = False,
) -> SweepTable:
    """Explores every environment of ``envs`` (a folder, as ``stopscan explore --env DIR``
    reads it, or a list of files) with ``strategy`` (a name, a list of names, or "all").

    Each run is one task. ``backend="ray"`` runs them on Ray: on the cluster Ray is already
    connected to, else on ``address`` (``"auto"``, ``"ray://head:10001"``), else on a local
    cluster started here with ``workers`` CPUs (all by default), which stays up for the next
    sweep. ``backend="serial"`` runs them one after the other in this process, and
    ``"auto"`` is Ray when it is installed. The environments are read here, once, and sent
    to the tasks, so the workers need no shared file system.

    The table's rows and CSV are the command line's for the same folder and options, byte for
    byte, whatever ran the tasks, when the lower bounds have a budget of steps
    (``bounds_steps``, the CLI's ``--bounds-steps``: the same cut on every machine), or when
    they finish within ``bounds_seconds`` (``--bounds-seconds``, 5 s) in both: a deadline
    cuts them where the machine's load puts it. ``progress`` shows ``done/total`` on
    standard error, or is called with them.
    """
    if backend == "auto":
        try:
            import ray  # noqa: F401, PLC0415 (optional dependency)

            backend = "ray"
        except ImportError:
            backend = "serial"
    if backend not in ("serial", "ray"):
        raise ValueError(f"backend: expected 'auto', 'serial' or 'ray', got {backend!r}")
    names = [strategy] if isinstance(strategy, str) else list(strategy)
    if not names:
        raise ValueError("strategy: give a name, a list of names, or 'all'")
    strategies: List[str] = []
    for name in names:
        found, warning = _stopscan.sweep_check(
            name, scan_time, move_time, speed, range, simplify, bounds_seconds, bounds_steps)
        strategies.extend(s for s in found if s not in strategies)
        if warning:
            warnings.warn(warning, stacklevel=2)
    files = _files(envs)
    options = dict(scan_time=scan_time, move_time=move_time, speed=speed, range=range,
                   bounds_seconds=bounds_seconds, bounds_steps=bounds_steps)
    loaded = []
    for f in files:
        name, input_json, error = _stopscan.sweep_load(f, simplify)
        if error is not None:
            warnings.warn(f"{name}: not swept: {error}", stacklevel=2)
        loaded.append((name, input_json, error))
    tasks = [(i, s) for i, (_, input_json, _) in enumerate(loaded) if input_json is not None
             for s in strategies]
    show = _progress(progress)
    total = len(tasks)
    results: Dict[Tuple[int, str], Tuple[str, str]] = {}
    if backend == "serial":
        for done, (i, s) in enumerate(tasks, 1):
            results[(i, s)] = _run(loaded[i][1], s, options)
            show(done, total)
    else:
        results = _on_ray(loaded, tasks, options, address, workers, show)
    rows: List[dict] = []
    lines: List[str] = []
    for i, (name, input_json, error) in enumerate(loaded):
        for s in strategies:
            if input_json is None:
                row_json, line = _stopscan.sweep_failed(name, s, error)
            else:
                row_json, line = results[(i, s)]
            rows.append(json.loads(row_json))
            lines.append(line)
    return SweepTable(rows, lines, backend)


def _on_ray(loaded: list, tasks: list, options: Dict[str, Any], address: Optional[str],
            workers: Optional[int], show: Callable[[int, int], None]) -> Dict[Tuple[int, str], Tuple[str, str]]:
    import ray  # noqa: PLC0415 (optional dependency)

    if not ray.is_initialized():
        if address is not None:
            ray.init(address=address)
        else:
            ray.init(num_cpus=workers, include_dashboard=False)
    run = _ray_run(ray)
    # Each environment goes into the object store once, for all its strategies.
    refs = {i: ray.put(loaded[i][1]) for i in sorted({i for i, _ in tasks})}
    pending = {run.remote(refs[i], s, options): (i, s) for i, s in tasks}
    results: Dict[Tuple[int, str], Tuple[str, str]] = {}
    total = len(pending)
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=min(len(pending), 16), timeout=1.0)
        for ref in ready:
            results[pending.pop(ref)] = ray.get(ref)
        if ready:
            show(len(results), total)
    return results
