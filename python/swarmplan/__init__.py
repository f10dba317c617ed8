"""swarmplan: an optimization-backed planner for swarm-based drone delivery with in-flight
energy sharing, and the exact references to measure heuristics against.

The package is the Python front of the swarmplan Rust crate: the same instances, methods,
defaults, codes and JSON fields as the ``swarmplan`` command line.

>>> import swarmplan
>>> instance = swarmplan.Instance.embedded("paper-195")
>>> hop = instance.hop("r00042")
>>> result = swarmplan.evaluate(hop, [])        # the empty schedule, scored
>>> result.feasible, result.gap_label is None
(True, True)
"""

from __future__ import annotations

import os
import sys
import tempfile
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

from ._swarmplan import (
    DEFAULT_BACKEND,
    DEFAULT_DISTANCE_BUCKET_KM,
    DEFAULT_EXACT_LIMIT,
    DEFAULT_HOP_NODE_LIMIT,
    DEFAULT_MAX_PACKAGE_KG,
    DEFAULT_NODE_LIMIT,
    DEFAULT_NODES,
    DEFAULT_SPACING_M,
    Hop,
    HopEvaluation,
    HopResult,
    Instance,
    Plan,
    RouteEvaluation,
    SwarmplanError,
    __version__,
    plot,
    shipped_names,
)
from ._swarmplan import run_bench as _run_bench

__all__ = [
    "DEFAULT_BACKEND",
    "DEFAULT_DISTANCE_BUCKET_KM",
    "DEFAULT_EXACT_LIMIT",
    "DEFAULT_HOP_NODE_LIMIT",
    "DEFAULT_MAX_PACKAGE_KG",
    "DEFAULT_NODE_LIMIT",
    "DEFAULT_NODES",
    "DEFAULT_SPACING_M",
    "BenchResult",
    "Hop",
    "HopEvaluation",
    "HopResult",
    "Instance",
    "Plan",
    "RouteEvaluation",
    "SwarmplanError",
    "__version__",
    "bench",
    "evaluate",
    "plot",
    "shipped_names",
]

Schedule = Sequence[Union[Dict[str, Any], Sequence[float]]]


def evaluate(hop: Hop, schedule: Schedule, **options: Any) -> HopEvaluation:
    """Flies ``schedule`` on ``hop`` exactly as written and scores it against the exact optimum.

    The same as ``hop.evaluate(schedule, **options)``.

    Parameters
    ----------
    hop : Hop
        The hop flown.
    schedule : sequence of transfers
        Each transfer a dict (``support``, ``consumer``, ``start_min``, ``end_min``, optionally
        ``consumer_slot`` and ``energy_mah``) or a sequence of numbers (a tuple, a list, a
        numpy row) in the order ``(support, consumer, start_min, end_min[, consumer_slot])``.
    **options
        The keywords of :meth:`Hop.evaluate` (``reference``, ``reorder``, ``time_limit_s``,
        ``node_limit``, ``backend``).

    Returns
    -------
    HopEvaluation
        ``feasible`` False when a drone runs out of battery; otherwise ``value`` (node time in
        minutes at a stop, or lowest delivery arrival battery in mAh into a destination) with
        its ``gap`` against the continuous-time optimum of the ``reorder`` mode,
        ``{"relative": loss, "reference": kind}`` as every gap of the package: the relative
        loss, positive when worse under either objective, and the kind of its reference
        (``optimal``, ``infimum``; docs/src/exact.md, "What a gap is").

    Raises
    ------
    SwarmplanError
        With the checker's code (``C3001``-``C3013``, docs/src/errors.md) for a schedule
        that breaks a rule of the hop model; E0026 for one that is not a list of transfers.
    """
    return hop.evaluate(schedule, **options)


class BenchResult:
    """The results of :func:`bench`: the summary, the configuration and the tables.

    Attributes
    ----------
    summary : dict
        ``summary.json``: the methods' statistics, findings, the command recorded;
        ``figures`` is empty (the command line alone draws them).
    config : dict
        ``config.json``: the run's inputs and settings.
    tables : dict
        Each table (``requests``, ``hops``, ``stops``, ``timings``, ``joint``) as its rows,
        dicts, the same rows as the CSV files in ``out``.
    elapsed_s : float
        Wall-clock time of the planning, s.
    out : str
        The output directory.
    """

    def __init__(self, raw: Dict[str, Any], out: str) -> None:
        self.summary: Dict[str, Any] = raw["summary"]
        self.config: Dict[str, Any] = raw["config"]
        self.tables: Dict[str, List[Dict[str, Any]]] = raw["tables"]
        self.elapsed_s: float = raw["elapsed_s"]
        self.out: str = out

    def to_dict(self) -> Dict[str, Any]:
        """The result as plain data: ``{"summary", "config", "tables", "elapsed_s", "out"}``."""
        return dict(summary=self.summary, config=self.config, tables=self.tables,
                    elapsed_s=self.elapsed_s, out=self.out)

    def frame(self, table: str = "requests") -> Any:
        """One table as a pandas DataFrame (pandas is needed for this method only).

        Parameters
        ----------
        table : str, default "requests"
            ``requests``, ``hops``, ``stops``, ``timings`` or ``joint``.

        Returns
        -------
        pandas.DataFrame
            The table's rows.

        Raises
        ------
        KeyError
            For a table that does not exist.
        ImportError
            Without pandas.
        """
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
    """Runs a bench run (the paper's experiments and the gap report) and returns its tables.

    The same run as ``swarmplan bench``, made by the planning core: the same tables
    (``requests.csv``, ``hops.csv``, ``stops.csv``, ``timings.csv``, ``joint.csv``),
    ``config.json`` and ``summary.json``, but no SVG figures (``figures/*.svg`` are drawn by
    the command line only; ``summary["figures"]`` is empty).

    Parameters
    ----------
    limit : int or None, default 500
        Plan only the first ``limit`` requests of the set (``None``: all of them).
    out : str or os.PathLike or None, default None
        Output directory; a new temporary directory when ``None``.
    progress : callable or bool or None, default None
        ``progress(done, total)``, called as plans are made; ``True`` for a tqdm bar (a line
        on stderr without tqdm).
    force : bool, default False
        Overwrite the files of an earlier run in ``out``.
    **options
        The run's other settings, each ``None`` (or left out) for the command line's default:
        ``sharing``, ``positioning``, ``route`` (lists of names; default ``["none", "pb",
        "fb"]``, both positionings, ``["sequential", "astar", "dijkstra",
        "floyd-warshall"]``), ``gap`` (bool, default True: plan the optimal routes the route
        gaps are measured against), ``joint`` (bool, default True: each request's joint
        optimum and every combination's gap to it split), ``exact_limit`` (default
        :data:`DEFAULT_EXACT_LIMIT`), ``backend`` (default :data:`DEFAULT_BACKEND`),
        ``hop_time_limit_s`` (default None), ``hop_node_limit`` (default
        :data:`DEFAULT_HOP_NODE_LIMIT`), ``period_min`` (default 1.0), ``reorder`` (default
        ``"paper"``), ``node_limit`` (default :data:`DEFAULT_NODE_LIMIT`),
        ``distance_bucket_km`` (default :data:`DEFAULT_DISTANCE_BUCKET_KM`), ``shard``
        (``"I/N"``), ``threads`` (default: every core), ``time_budget_s``, ``network``,
        ``profile`` (files), ``literal`` (bool), ``requests`` (a request file).

    Returns
    -------
    BenchResult
        The summary, the configuration and the tables of the run.

    Raises
    ------
    SwarmplanError
        E0026 for an unknown choice (``sharing=["pbx"]``), a negative count or a bool where a
        number is meant; E7005 when ``out`` holds an earlier run and ``force`` is False;
        E7006 for a bucket width that is not > 0; the run's own codes.
    TypeError
        For a keyword that is no setting of the run.
    """
    if out is None:
        out = tempfile.mkdtemp(prefix="swarmplan-bench-")
        force = True
    command = ["swarmplan.bench", f"limit={limit!r}"] + [
        f"{key}={value!r}" for key, value in sorted(options.items())
    ]
    callback = _progress_printer() if progress is True else progress or None
    raw = _run_bench(
        os.fspath(out),
        limit=limit,
        force=force,
        progress=callback,
        command=command,
        **options,
    )
    return BenchResult(raw, os.fspath(out))
