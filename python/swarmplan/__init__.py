"""swarmplan: an optimization-backed planner for swarm-based drone delivery with in-flight
energy sharing, and the exact references to measure heuristics against.

The package is the Python front of the swarmplan Rust crate: the same instances, methods,
defaults, codes and JSON fields as the ``swarmplan`` command line.

>>> import swarmplan
>>> instance = swarmplan.Instance.embedded("paper-195")
>>> hop = instance.hop("r00042")
>>> result = swarmplan.evaluate(hop, [])        # the empty schedule, scored
>>> result["feasible"], result["gap_label"] is None
(True, True)
"""

from __future__ import annotations

import os
import sys
import tempfile
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

from ._swarmplan import Hop, Instance, SwarmplanError, __version__, shipped_names
from ._swarmplan import run_bench as _run_bench

__all__ = [
    "BenchResult",
    "Hop",
    "Instance",
    "SwarmplanError",
    "__version__",
    "bench",
    "evaluate",
    "shipped_names",
]

Schedule = Sequence[Union[Dict[str, Any], Sequence[float]]]


def evaluate(hop: Hop, schedule: Schedule, **options: Any) -> Dict[str, Any]:
    """Flies ``schedule`` on ``hop`` exactly as written and scores it against the exact optimum.

    The same as ``hop.evaluate(schedule, **options)``. ``schedule`` is a sequence of transfers,
    each a dict (``support``, ``consumer``, ``start_min``, ``end_min``, optionally
    ``consumer_slot`` and ``energy_mah``) or a sequence of numbers (a tuple, a list, a numpy
    row) in the order ``(support, consumer, start_min, end_min[, consumer_slot])``. A schedule
    that breaks a rule of the hop model raises :class:`SwarmplanError` with the checker's code
    (``C3001``-``C3013``, README.md's error table); one
    that runs a drone out of battery returns ``feasible: False``; otherwise its ``value`` (node
    time in minutes at a stop, or lowest delivery arrival battery in mAh into a destination)
    comes with its ``gap`` against the continuous-time optimum of the ``reorder`` mode,
    ``{"relative": loss, "reference": kind}`` as every gap of the package: the relative loss,
    positive when worse under either objective, and the kind of its reference (``optimal``,
    ``infimum``; README.md, "What a gap is").
    """
    return hop.evaluate(schedule, **options)


class BenchResult:
    """The results of :func:`bench`: the summary, the configuration and the tables.

    ``tables`` maps each table (``requests``, ``hops``, ``stops``, ``timings``, ``joint``) to
    its rows as dicts, the same rows as the CSV files in ``out``.
    """

    def __init__(self, raw: Dict[str, Any], out: str) -> None:
        self.summary: Dict[str, Any] = raw["summary"]
        self.config: Dict[str, Any] = raw["config"]
        self.tables: Dict[str, List[Dict[str, Any]]] = raw["tables"]
        self.elapsed_s: float = raw["elapsed_s"]
        self.out: str = out

    def frame(self, table: str = "requests") -> Any:
        """One table as a pandas DataFrame (pandas is needed for this method only)."""
        if table not in self.tables:
            raise KeyError(f"no table {table!r}; the tables are {sorted(self.tables)}")
        try:
            import pandas
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError(
                "BenchResult.frame needs pandas (pip install pandas); "
                "the rows are in BenchResult.tables without it"
            ) from e
        return pandas.DataFrame.from_records(self.tables[table])

    def __repr__(self) -> str:
        sizes = ", ".join(f"{k} {len(v)}" for k, v in self.tables.items())
        return f"BenchResult(out={self.out!r}, {sizes})"


# Python names whose command-line flag is not the name with dashes.
_FLAGS = {"hop_time_limit_s": "--hop-time-limit", "distance_bucket_km": "--distance-bucket-km"}


def _argument_error(field: str, cause: str, action: str) -> SwarmplanError:
    """A coded error (E0026) of an argument checked on the Python side, as the native part
    raises them."""
    error = SwarmplanError(f"invalid input, 1 problem(s):\n  [E0026] {field}: {cause}; {action}")
    error.code, error.field, error.cause, error.action = "E0026", field, cause, action
    error.violations = [dict(code="E0026", field=field, cause=cause, action=action)]
    return error


def _check_whole(name: str, value: Any, flag: bool = False) -> None:
    """Refuses a negative integer, and a bool where a number is meant (``flag``: a bool is a
    switch such as ``joint=True``), for the options of :func:`bench`."""
    if isinstance(value, bool):
        if flag:
            return
        cause = f"{value!r} is a bool, not a number"
        raise _argument_error(name, cause, "give a whole number >= 0")
    if isinstance(value, int) and value < 0:
        raise _argument_error(name, f"{value} is negative", "give a whole number >= 0")


def _progress_printer() -> Callable[[int, int], None]:
    try:
        from tqdm import tqdm  # type: ignore
    except ImportError:
        tqdm = None
    if tqdm is not None:
        bar = tqdm(total=0, unit="plan")

        def update(done: int, total: int) -> None:
            bar.total = total
            bar.n = done
            bar.refresh()
            if done >= total > 0:
                bar.close()

        return update

    def line(done: int, total: int) -> None:
        sys.stderr.write(f"\rswarmplan bench: {done}/{total} plans")
        if done >= total > 0:
            sys.stderr.write("\n")
        sys.stderr.flush()

    return line


def bench(
    limit: Optional[int] = 500,
    out: Optional[Union[str, os.PathLike]] = None,
    *,
    progress: Union[None, bool, Callable[[int, int], None]] = None,
    force: bool = False,
    **options: Any,
) -> BenchResult:
    """Runs ``swarmplan bench`` and returns its tables.

    Every keyword is the command line's option of the same name (``sharing=["pb", "fb"]``,
    ``joint=True``, ``exact_limit=0``, ``threads=2``, ``hop_time_limit_s=10``, ...), with the
    same defaults. The files are written to ``out`` (a temporary directory when ``None``).
    ``progress`` is a callable ``progress(done, total)``, or ``True`` for a tqdm bar (a line on
    stderr without tqdm).
    """
    _check_whole("limit", limit)
    for key, value in options.items():
        if isinstance(value, (list, tuple)):
            for item in value:
                _check_whole(key, item, flag=False)
        else:
            _check_whole(key, value, flag=True)
    if out is None:
        out = tempfile.mkdtemp(prefix="swarmplan-bench-")
        force = True
    args: List[str] = ["--out", os.fspath(out)]
    if limit is not None:
        args += ["--request-limit", str(limit)]
    if force:
        args.append("--force")
    for key, value in options.items():
        flag = _FLAGS.get(key, "--" + key.replace("_", "-"))
        if value is None or value is False:
            continue
        if value is True:
            args.append(flag)
        elif isinstance(value, (list, tuple)):
            args += [flag, ",".join(str(v) for v in value)]
        else:
            args += [flag, str(value)]
    callback = _progress_printer() if progress is True else progress or None
    raw = _run_bench(args, callback)
    return BenchResult(raw, os.fspath(out))
