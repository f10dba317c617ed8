"""Type stubs of the native part of swarmplan (built from python/src/, one module per concern)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

DEFAULT_NODE_LIMIT: int
"""Search nodes of the exact node time at every stop (``node_limit=None``): 20_000_000."""
DEFAULT_HOP_NODE_LIMIT: int
"""Branch-and-bound nodes of each hop model's MILP call (``hop_node_limit=None``): 20_000."""
DEFAULT_BACKEND: str
"""The MILP backend of ``backend=None``: ``"microlp"`` in the default build."""
DEFAULT_EXACT_LIMIT: int
"""Requests whose hops and stops a bench run solves again exactly: 5."""
DEFAULT_DISTANCE_BUCKET_KM: float
"""Width of a bench run's distance buckets, km: 1.0."""
DEFAULT_NODES: int
"""Nodes of ``Instance.generate``: 195."""
DEFAULT_SPACING_M: float
"""Grid spacing of ``Instance.generate``, m: 500.0."""
DEFAULT_MAX_PACKAGE_KG: float
"""Largest package of ``Instance.generate``, kg: 1.4."""

Sharing = Literal["none", "idle-support", "pb", "fb", "exact", "fair"]
Positioning = Literal["location-aware", "energy-aware"]
Route = Literal["sequential", "astar", "dijkstra", "floyd-warshall", "optimal"]
HopPaths = Literal["rule", "any"]
Reorder = Literal["paper", "none", "free"]
Method = Literal["none", "pb", "fb", "continuous", "milp", "fluid", "fair"]
Transfer = Union[Dict[str, Any], Sequence[float]]
"""One timed transfer: a dict with ``support``, ``consumer``, ``start_min``, ``end_min`` and
optionally ``consumer_slot`` and ``energy_mah``, or a sequence of numbers (a tuple, a list, a
numpy row) in the order ``(support, consumer, start_min, end_min[, consumer_slot])``. Drone and
slot indices are whole numbers >= 0 (a float with no fraction, as a numpy float row holds
them, is taken); a bool or a negative index is E0026."""
Schedule = Sequence[Transfer]
Gap = Dict[str, Any]
"""Every gap of the package: ``{"relative": loss or None, "reference": kind}``, the relative
loss against the reference (positive when worse, minimised or maximised; ``None`` when the
reference is 0) and the kind of the reference (``optimal``, ``infimum``, ``incumbent``,
``bound``). Where no gap is taken, ``gap`` is ``None`` and ``gap_label`` says why."""
RequestLike = Union[str, Dict[str, Any]]

class SwarmplanError(Exception):
    """An error of swarmplan, with the code of the error table in docs/src/errors.md (``E4111``,
    or the checker's ``C3006``), the field concerned (the Python argument, such as ``index`` or
    ``route``), the cause, what to do, and every violation as a dict with those four keys.

    Every integer argument (an index, a count, a limit, a seed) refuses a negative number and a
    bool with E0026 naming the argument; a value of another type is a ``TypeError``."""

    code: Optional[str]
    field: Optional[str]
    cause: Optional[str]
    action: Optional[str]
    violations: List[Dict[str, str]]

class Plan:
    """A planned request: the document ``swarmplan solve --json`` prints. It keeps the instance
    it was made on, which ``plot`` draws it on."""

    def to_dict(self) -> Dict[str, Any]:
        """The whole result as plain data (the command line's ``--json`` document)."""
    def to_json(self) -> str:
        """The whole result as JSON text."""
    def _repr_svg_(self) -> str:
        """The plan's figure, ``plot(self)``: Jupyter shows a plan as it."""

    @property
    def schema_version(self) -> int: ...
    @property
    def request(self) -> Dict[str, Any]: ...
    @property
    def options(self) -> Dict[str, Any]: ...
    @property
    def formation(self) -> str: ...
    @property
    def support_decision(self) -> Dict[str, Any]: ...
    @property
    def support_drones(self) -> int: ...
    @property
    def swarm(self) -> Dict[str, Any]: ...
    @property
    def plan(self) -> Dict[str, Any]:
        """The composed plan: ``hops``, ``dt_min``, ``tt_min``, ``nt_min``, ``outcome``, ..."""
    @property
    def execution_ms(self) -> float: ...
    @property
    def made_on(self) -> Optional[Dict[str, Any]]: ...
    @property
    def route_gap(self) -> Optional[Dict[str, Any]]:
        """With ``gap=True``: ``{"reference", "optimal_dt_min", "gap", ...}``."""
    @property
    def settings(self) -> Optional[Dict[str, Any]]: ...

class HopResult:
    """One method's result on a hop: a row of ``swarmplan eaas --json``."""

    def to_dict(self) -> Dict[str, Any]:
        """The whole result as plain data (the command line's ``--json`` document)."""
    def to_json(self) -> str:
        """The whole result as JSON text."""

    @property
    def method(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def status(self) -> Optional[str]: ...
    @property
    def feasible(self) -> Optional[bool]: ...
    @property
    def objective(self) -> Optional[float]: ...
    @property
    def objective_proven(self) -> bool: ...
    @property
    def bound(self) -> Optional[float]: ...
    @property
    def qp_squared_deficits_mah2(self) -> Optional[float]: ...
    @property
    def gap(self) -> Optional[Gap]: ...
    @property
    def gap_label(self) -> Optional[str]: ...
    @property
    def epsilon(self) -> Optional[float]: ...
    @property
    def grid_step_min(self) -> Optional[float]: ...
    @property
    def solve_ms(self) -> float: ...
    @property
    def transfers(self) -> List[Dict[str, Any]]: ...
    @property
    def free_schedule(self) -> Optional[Dict[str, Any]]: ...

class HopEvaluation:
    """A hop schedule flown as written and scored (``Hop.evaluate``, ``swarmplan.evaluate``)."""

    def to_dict(self) -> Dict[str, Any]:
        """The whole result as plain data (the command line's ``--json`` document)."""
    def to_json(self) -> str:
        """The whole result as JSON text."""

    @property
    def feasible(self) -> bool: ...
    @property
    def failure(self) -> Optional[Dict[str, Any]]: ...
    @property
    def transfers(self) -> List[Dict[str, Any]]: ...
    @property
    def final_battery_mah(self) -> List[float]: ...
    @property
    def min_battery_mah(self) -> List[float]: ...
    @property
    def shared_mah(self) -> float: ...
    @property
    def objective(self) -> Union[str, Dict[str, Any]]: ...
    @property
    def value(self) -> Optional[float]: ...
    @property
    def value_proven(self) -> bool: ...
    @property
    def mode(self) -> str: ...
    @property
    def reference(self) -> Optional[Dict[str, Any]]: ...
    @property
    def gap(self) -> Optional[Gap]: ...
    @property
    def gap_label(self) -> Optional[str]: ...

class RouteEvaluation:
    """A route flown with a schedule per hop (``Instance.evaluate_route``)."""

    def to_dict(self) -> Dict[str, Any]:
        """The whole result as plain data (the command line's ``--json`` document)."""
    def to_json(self) -> str:
        """The whole result as JSON text."""

    @property
    def request_id(self) -> str: ...
    @property
    def stops(self) -> List[str]: ...
    @property
    def positioning(self) -> str: ...
    @property
    def support_drones(self) -> int: ...
    @property
    def delivered(self) -> bool: ...
    @property
    def tt_min(self) -> float: ...
    @property
    def nt_min(self) -> float: ...
    @property
    def dt_min(self) -> Optional[float]: ...
    @property
    def dt_proven(self) -> bool: ...
    @property
    def hops(self) -> List[Dict[str, Any]]: ...
    @property
    def mode(self) -> str: ...
    @property
    def reference(self) -> Optional[Dict[str, Any]]: ...
    @property
    def gap(self) -> Optional[Gap]: ...
    @property
    def gap_label(self) -> Optional[str]: ...

class Instance:
    """A skyway network, a parameter profile and a request set, validated together."""

    @staticmethod
    def embedded(
        network: str = "paper-195", profile: Optional[str] = None, literal: bool = False
    ) -> Instance:
        """A shipped network (``paper-195``, ``findings-195``, ``sparse-195``) with a shipped
        profile or a TOML file (default: the network's own) and the shipped 10,000 requests."""
    @staticmethod
    def from_files(
        network: Union[str, PathLike[str]],
        profile: Optional[str] = None,
        requests: Union[None, str, PathLike[str], Sequence[Dict[str, Any]]] = None,
        literal: bool = False,
    ) -> Instance:
        """A network file, a profile (shipped name or TOML file, default ``paper``) and a
        request file, a list of request dicts, or ``None`` for the shipped requests."""
    @staticmethod
    def generate(
        seed: int,
        nodes: Optional[int] = None,
        spacing_m: Optional[float] = None,
        requests: int = 100,
        requests_seed: Optional[int] = None,
        max_package_kg: Optional[float] = None,
        profile: Optional[str] = None,
    ) -> Instance:
        """A seeded synthetic network and request set (``swarmplan generate``)."""
    @property
    def network_name(self) -> str:
        """The network's name."""
    @property
    def profile_name(self) -> str:
        """The profile's name."""
    @property
    def requests_name(self) -> str:
        """The request set's name."""
    @property
    def request_ids(self) -> List[str]:
        """Ids of the requests, in order."""
    @property
    def network(self) -> Dict[str, Any]:
        """The network as its JSON reads."""
    @property
    def profile(self) -> Dict[str, Any]:
        """The profile as its TOML reads."""
    def request(self, id: RequestLike) -> Dict[str, Any]:
        """One request as a dict."""
    def plan(
        self,
        request: RequestLike,
        sharing: Sharing = "pb",
        positioning: Positioning = "location-aware",
        route: Route = "sequential",
        support: Optional[int] = None,
        hop_paths: HopPaths = "rule",
        node_limit: Optional[int] = None,
        gap: bool = False,
        backend: Optional[str] = None,
        hop_time_limit_s: Optional[float] = None,
        hop_node_limit: Optional[int] = None,
        period_min: float = 1.0,
        reorder: Reorder = "paper",
    ) -> Plan:
        """Plans one request; ``to_dict()`` is the document ``swarmplan solve --json`` prints."""
    def check(self, plan: Union[Plan, str, Dict[str, Any]]) -> List[Dict[str, str]]:
        """Every violation the independent checker finds in a plan (empty: it passes)."""
    def plot(
        self,
        plan: Union[Plan, str, Dict[str, Any]],
        compare: Union[None, Plan, str, Dict[str, Any]] = None,
        percent: bool = False,
    ) -> str:
        """The SVG ``swarmplan plot`` writes for the plan (and ``compare``) on this instance."""
    def hop(
        self,
        request: RequestLike,
        index: int = 0,
        sharing: Sharing = "pb",
        positioning: Positioning = "location-aware",
        route: Route = "sequential",
        support: Optional[int] = None,
    ) -> Hop:
        """Hop ``index`` of the request's plan (by default as ``swarmplan eaas`` takes it)."""
    def evaluate_route(
        self,
        request: RequestLike,
        stops: Sequence[str],
        policy: Union[Callable[[Hop], Schedule], Sequence[Schedule]],
        positioning: Positioning = "location-aware",
        support: Optional[int] = None,
        reference: bool = True,
        reorder: Reorder = "paper",
        backend: Optional[str] = None,
        hop_time_limit_s: Optional[float] = None,
        hop_node_limit: Optional[int] = None,
        node_limit: Optional[int] = None,
    ) -> RouteEvaluation:
        """Flies the request along ``stops`` with a schedule per hop and measures the delivery
        time against the joint optimum of the same swarm: ``gap`` is a ``Gap`` (``reference``
        ``optimal`` or ``incumbent``), or ``None`` with ``gap_label``."""

class Hop:
    """One hop's in-flight sharing problem and what it is scored by."""

    @staticmethod
    def from_file(path: Union[str, PathLike[str]], profile: Optional[str] = None) -> Hop:
        """Reads a hop file (``swarmplan eaas --write-hop``)."""
    @staticmethod
    def from_json(text: str, profile: Optional[str] = None) -> Hop:
        """A hop from a hop file's JSON text."""
    def to_json(self) -> str:
        """The hop file's JSON text."""
    def write(self, path: Union[str, PathLike[str]]) -> None:
        """Writes the hop file."""
    @property
    def request_id(self) -> str:
        """The request whose plan holds the hop."""
    @property
    def index(self) -> int:
        """Index of the hop in the plan."""
    @property
    def path(self) -> List[str]:
        """Node ids flown over."""
    @property
    def end(self) -> Optional[Dict[str, float]]:
        """The pads at the hop's end, or ``None`` into a destination."""
    @property
    def objective(self) -> Union[str, Dict[str, Any]]:
        """``{"node_time": {...}}`` (minimise, min) or ``"max_min_arrival"`` (maximise, mAh)."""
    @property
    def problem(self) -> Dict[str, Any]:
        """The whole problem, as the hop file's ``hop`` object."""
    @property
    def drones(self) -> int:
        """Number of drones (delivery drones first)."""
    @property
    def roles(self) -> List[str]:
        """``"delivery"`` or ``"support"`` per drone."""
    @property
    def capacity_mah(self) -> npt.NDArray[np.float64]:
        """Battery capacity per drone, mAh."""
    @property
    def battery_mah(self) -> npt.NDArray[np.float64]:
        """Battery per drone at departure, mAh."""
    @property
    def durations_min(self) -> npt.NDArray[np.float64]:
        """Duration per leg, min."""
    @property
    def rates_mah_per_min(self) -> npt.NDArray[np.float64]:
        """Consumption rates ``[leg, drone, slot]``, mAh/min."""
    @property
    def slots_m(self) -> npt.NDArray[np.float64]:
        """Slot positions ``[slot, 2]`` in the body frame, m."""
    @property
    def initial_slot(self) -> List[int]:
        """Slot of every drone outside transfers."""
    @property
    def rho_mah_per_min(self) -> float:
        """Sharing rate, mAh/min."""
    @property
    def range_m(self) -> float:
        """Largest support-consumer distance of a transfer, m."""
    @property
    def delta_mah(self) -> float:
        """Support reserve, mAh."""
    @property
    def tt_min(self) -> float:
        """Travel time, min."""
    def moves(self, reorder: Reorder = "paper") -> List[Dict[str, Optional[int]]]:
        """The moves a transfer may use in a re-ordering mode (``none`` or ``paper``): dicts
        with keys ``support``, ``consumer``, ``consumer_slot`` and ``partner`` (the delivery
        drone holding the consumer's slot meanwhile, ``None`` when the consumer stays). A
        transfer written as a sequence takes its numbers in another order, see ``Transfer``."""
    def solve(
        self,
        method: Method = "continuous",
        reorder: Reorder = "paper",
        time_limit_s: Optional[float] = 60.0,
        node_limit: Optional[int] = None,
        period_min: float = 1.0,
        backend: Optional[str] = None,
        reference: bool = True,
    ) -> HopResult:
        """One method's row of ``swarmplan eaas --json``.

        ``gap`` (a ``Gap``): with ``reference=True`` the row of ``none``, ``pb``, ``fb``,
        ``milp`` or ``fair`` is measured against the continuous model of the same ``reorder``
        mode, solved alongside with the same limits (as ``swarmplan eaas --methods
        M,continuous``). ``None`` for ``continuous`` (the reference itself) and ``fluid`` (a
        bound), with ``reference=False``, or when the continuous model gives no value within
        its limits; a heuristic schedule that swaps slots under ``reorder="none"`` gets
        ``gap_label: different_policy`` instead."""
    def compare(
        self,
        methods: Sequence[Method] = ("pb", "fb", "continuous", "milp", "fluid", "fair"),
        reorder: Reorder = "paper",
        time_limit_s: Optional[float] = 60.0,
        node_limit: Optional[int] = None,
        period_min: float = 1.0,
        backend: Optional[str] = None,
        label: bool = True,
    ) -> List[HopResult]:
        """Several methods side by side, gaps labelled against the best reference."""
    def evaluate(
        self,
        schedule: Schedule,
        reference: bool = True,
        reorder: Reorder = "paper",
        time_limit_s: Optional[float] = None,
        node_limit: Optional[int] = 20_000,  # DEFAULT_HOP_NODE_LIMIT; None: no limit
        backend: Optional[str] = None,
    ) -> HopEvaluation:
        """Flies a schedule as written, checked by the independent checker, and scores it
        against the continuous-time optimum of the ``reorder`` mode: ``gap`` is a ``Gap``
        (``reference`` ``optimal`` or ``infimum``), or ``None`` with ``gap_label``."""

def run_bench(
    out: Union[str, PathLike[str]],
    *,
    limit: Optional[int] = None,
    sharing: Optional[Sequence[Sharing]] = None,
    positioning: Optional[Sequence[Positioning]] = None,
    route: Optional[Sequence[Route]] = None,
    gap: bool = True,
    joint: bool = True,
    exact_limit: Optional[int] = None,
    backend: Optional[str] = None,
    hop_time_limit_s: Optional[float] = None,
    hop_node_limit: Optional[int] = None,
    period_min: float = 1.0,
    reorder: Reorder = "paper",
    node_limit: Optional[int] = None,
    distance_bucket_km: Optional[float] = None,
    shard: Optional[str] = None,
    threads: Optional[int] = None,
    time_budget_s: Optional[float] = None,
    network: Optional[Union[str, PathLike[str]]] = None,
    profile: Optional[Union[str, PathLike[str]]] = None,
    literal: bool = False,
    requests: Optional[Union[str, PathLike[str]]] = None,
    force: bool = False,
    progress: Optional[Callable[[int, int], None]] = None,
    command: Optional[Sequence[str]] = None,
) -> Dict[str, Any]:
    """A bench run of the core into ``out`` (no figures); see :func:`swarmplan.bench`."""

def plot(
    plan: Plan,
    compare: Union[None, Plan, str, Dict[str, Any]] = None,
    percent: bool = False,
) -> str:
    """The SVG ``swarmplan plot`` writes for the plan (and ``compare``, a plan of the same
    request), drawn on the instance the plan was made on; ``percent`` for batteries in % of
    capacity."""

def shipped_names() -> Dict[str, List[str]]:
    """The names of the shipped networks and profiles."""
