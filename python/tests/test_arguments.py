"""Bad arguments are coded errors naming the Python argument; transfers are any sequence of
numbers; every gap has one shape. Each case is replayed by name; the expected numbers are
worked out by hand (instances/eaas/known_optima.json gives the working)."""

import json

import numpy as np
import pytest

import swarmplan
from conftest import REPO


def coded(call, *args, **kwargs):
    """The SwarmplanError a call raises."""
    with pytest.raises(swarmplan.SwarmplanError) as e:
        call(*args, **kwargs)
    return e.value


def assert_python_words(error):
    """No command-line option in the error's message, cause, action or field."""
    for text in (str(error), error.field, error.cause, error.action):
        assert "--" not in text, text


def known_hop(name, end):
    """An instance of instances/eaas/known_optima.json as a hop, with pads `end` (None: into a
    destination, scored by the lowest delivery arrival battery)."""
    known = json.loads((REPO / "instances" / "eaas" / "known_optima.json").read_text())
    problem = next(i for i in known["instances"] if i["name"] == name)["problem"]
    file = dict(schema_version=1, request_id="known", hop_index=0, **{"from": "S"}, to="T",
                path=["S", "T"], end=end, hop=problem)
    return swarmplan.Hop.from_json(json.dumps(file))


@pytest.fixture(scope="module")
def needy():
    # Delivery drones 0 and 1 at 25 of 100 mAh using 10 mAh/min, support drone 2 (100 mAh, no
    # consumption) serving either at 10 mAh/min, one 4-minute leg; optimum 5 mAh.
    return known_hop("needy_pair_max_min", None)


@pytest.fixture(scope="module")
def hop42(paper):
    return paper.hop("r00042")


# ---- Integers: negative numbers and bools are E0026 naming the argument.


def test_hop_index_minus_one(paper):
    e = coded(paper.hop, "r00042", index=-1)
    assert (e.code, e.field) == ("E0026", "index")
    assert "-1 is negative" in e.cause


def test_hop_index_true(paper):
    e = coded(paper.hop, "r00042", index=True)
    assert (e.code, e.field) == ("E0026", "index")
    assert "bool" in e.cause


def test_generate_minus_one():
    e = coded(swarmplan.Instance.generate, -1)
    assert (e.code, e.field) == ("E0026", "seed")


@pytest.mark.parametrize("argument", ["nodes", "requests", "requests_seed"])
def test_generate_counts_refuse_negative_numbers_and_bools(argument):
    for bad in (-1, True):
        e = coded(swarmplan.Instance.generate, 7, **{argument: bad})
        assert (e.code, e.field) == ("E0026", argument)


def test_plan_node_limit_minus_one(paper):
    e = coded(paper.plan, "r00001", node_limit=-1)
    assert (e.code, e.field) == ("E0026", "node_limit")
    e = coded(paper.plan, "r00001", hop_node_limit=-1)
    assert (e.code, e.field) == ("E0026", "hop_node_limit")


def test_plan_support_true(paper):
    e = coded(paper.plan, "r00001", support=True)
    assert (e.code, e.field) == ("E0026", "support")


def test_hop_node_limits_minus_one(hop42):
    for call in (lambda: hop42.solve("pb", node_limit=-1),
                 lambda: hop42.compare(["pb"], node_limit=-1),
                 lambda: hop42.evaluate([], node_limit=-1)):
        e = coded(call)
        assert (e.code, e.field) == ("E0026", "node_limit")


def test_evaluate_route_limits_and_support(paper):
    for argument in ("node_limit", "hop_node_limit", "support"):
        e = coded(paper.evaluate_route, "r00001", ["n000", "n001"], [], **{argument: -1})
        assert (e.code, e.field) == ("E0026", argument)


def test_a_numpy_integer_is_an_index(paper):
    assert paper.hop("r00042", index=np.int64(0)).index == 0


def test_a_float_index_stays_a_type_error(paper):
    with pytest.raises(TypeError):
        paper.hop("r00042", index=1.0)


def test_bench_limit_minus_one_and_threads_true():
    e = coded(swarmplan.bench, limit=-1)
    assert (e.code, e.field) == ("E0026", "limit")
    e = coded(swarmplan.bench, limit=True)
    assert (e.code, e.field) == ("E0026", "limit")
    e = coded(swarmplan.bench, limit=1, threads=-1)
    assert (e.code, e.field) == ("E0026", "threads")
    e = coded(swarmplan.bench, limit=1, threads=True)
    assert (e.code, e.field) == ("E0026", "threads")
    e = coded(swarmplan.bench, limit=1, exact_limit=-1)
    assert (e.code, e.field) == ("E0026", "exact_limit")


# ---- Transfers: any sequence of numbers in the order (support, consumer, start_min, end_min
# [, consumer_slot]), or a dict.

# Drone 0 served on [0, 1.75), drone 1 on [1.75, 4): by hand b0 = 25 - 40 + 17.5 = 2.5 and
# b1 = 25 - 17.5 = 7.5 (falling until served, then level): the lowest arrival is 2.5 mAh.
AS_DICTS = [dict(support=2, consumer=0, start_min=0.0, end_min=1.75),
            dict(support=2, consumer=1, start_min=1.75, end_min=4.0)]
LOWEST_ARRIVAL_MAH = 2.5


class Row:
    """A sequence of one's own: the sequence protocol only (`__len__`, `__getitem__`)."""

    def __init__(self, *numbers):
        self.numbers = numbers

    def __len__(self):
        return len(self.numbers)

    def __getitem__(self, i):
        return self.numbers[i]


@pytest.mark.parametrize("form", ["dict", "tuple", "list", "tuple with slot", "numpy float rows",
                                  "numpy int rows", "custom sequence"])
def test_transfers_in_every_sequence_form(needy, form):
    # Drones 0 and 1 fly in slots 0 and 1 of the hop (its initial_slot).
    schedule = {
        "dict": AS_DICTS,
        "tuple": [(2, 0, 0.0, 1.75), (2, 1, 1.75, 4.0)],
        "list": [[2, 0, 0.0, 1.75], [2, 1, 1.75, 4.0]],
        "tuple with slot": [(2, 0, 0.0, 1.75, 0), (2, 1, 1.75, 4.0, 1)],
        "numpy float rows": np.array([[2, 0, 0.0, 1.75], [2, 1, 1.75, 4.0]]),
        "numpy int rows": [np.array([2, 0, 0, 2]), np.array([2, 1, 2, 4])],
        "custom sequence": [Row(2, 0, 0.0, 1.75), Row(2, 1, 1.75, 4.0)],
    }[form]
    assert needy.initial_slot[:2] == [0, 1]
    got = needy.evaluate(schedule, reference=False)
    if form == "numpy int rows":
        # Served on [0, 2) and [2, 4): 20 mAh each, b0 = 25 - 40 + 20 = 5, b1 = 25 - 20 = 5.
        assert got.value == pytest.approx(5.0)
    else:
        assert got.value == pytest.approx(LOWEST_ARRIVAL_MAH)
    assert [(t["support"], t["consumer"]) for t in got.transfers] == [(2, 0), (2, 1)]


@pytest.mark.parametrize("bad,cause", [
    ([(True, 0, 0.0, 1.0)], "bool"),
    ([dict(support=True, consumer=0, start_min=0.0, end_min=1.0)], "bool"),
    ([[2, -1, 0.0, 1.0]], "negative"),
    ([np.array([2.0, 0.5, 0.0, 1.0])], "whole number"),
    ([(2, 0, 0.0)], "not 4 or 5"),
    ([(2, 0, False, 1.0)], "bool"),
])
def test_bad_transfers_are_e0026_naming_the_schedule(needy, bad, cause):
    e = coded(needy.evaluate, bad, reference=False)
    assert (e.code, e.field) == ("E0026", "schedule")
    assert "schedule[0]" in e.cause and cause in e.cause


# ---- One shape for every gap: {"relative", "reference"}.


def test_evaluate_gap_shape(needy):
    got = swarmplan.evaluate(needy, AS_DICTS)
    # Arrival battery, maximised: 2.5 mAh against the optimum 5 is a loss of 50 %.
    assert got.gap == {"relative": pytest.approx(0.5), "reference": "optimal"}


def test_hop_solve_pb_has_a_gap():
    # pb_overshares_3_pads: PB shares 20 mAh (deficits 10, 10, 40): 40 min on 3 pads at 1
    # mAh/min, against the optimum 20 min (no sharing): a loss of (40 - 20) / 20 = 100 %.
    hop = known_hop("pb_overshares_3_pads", dict(pads=3, pad_rate_mah_per_min=1.0))
    row = hop.solve("pb")
    assert row.objective == pytest.approx(40.0)
    assert row.gap == {"relative": pytest.approx(1.0), "reference": "optimal"}
    assert hop.solve("pb", reference=False).gap is None
    assert hop.solve("continuous").gap is None  # the reference itself
    assert hop.compare(["pb", "continuous"])[0].gap == row.gap


def test_evaluate_route_gap_shape(paper):
    plan = paper.plan("r00023", sharing="exact", route="optimal")
    hops = plan.plan["hops"]
    stops = [hops[0]["from"]] + [h["to"] for h in hops]
    got = paper.evaluate_route("r00023", stops, [h["transfers"] for h in hops])
    assert set(got.gap) == {"relative", "reference"}
    assert got.gap["reference"] == got.reference["kind"] == "optimal"
    # The optimum's own route and schedules: no loss.
    assert abs(got.gap["relative"]) <= 1e-9


# ---- Error fields and messages in Python names.


def test_route_optimal_with_sharing_fair(paper):
    e = coded(paper.plan, "r00001", sharing="fair", route="optimal")
    assert (e.code, e.field) == ("E0015", "route")
    assert 'route="optimal"' in e.cause and 'sharing="exact"' in e.action
    assert_python_words(e)


def test_hop_paths_any_with_pb(paper):
    e = coded(paper.plan, "r00001", sharing="pb", route="optimal", hop_paths="any")
    assert (e.code, e.field) == ("E0016", "hop_paths")
    assert 'hop_paths="any"' in e.cause
    assert_python_words(e)


def test_reorder_free_on_a_route(paper):
    e = coded(paper.plan, "r00001", sharing="exact", reorder="free")
    assert (e.code, e.field) == ("E4113", "reorder")
    assert 'reorder="paper"' in e.action
    assert_python_words(e)


def test_exact_settings_name_their_keywords(paper):
    e = coded(paper.plan, "r00001", sharing="exact", hop_time_limit_s=-1.0, period_min=0.0)
    assert {(v["code"], v["field"]) for v in e.violations} == {
        ("E4105", "hop_time_limit_s"), ("E4101", "period_min")}
    assert_python_words(e)


def test_too_many_support_drones(paper):
    e = coded(paper.plan, "r00001", support=99)
    assert (e.code, e.field) == ("E0006", "support")
    assert "support=32" in e.action
    assert_python_words(e)


def test_hop_index_beyond_the_plan_names_index(paper):
    hops = len(paper.plan("r00042").plan["hops"])
    e = coded(paper.hop, "r00042", index=hops)
    assert (e.code, e.field) == ("E4110", "index")


def test_generate_options_name_their_keywords():
    e = coded(swarmplan.Instance.generate, 7, nodes=1, max_package_kg=0.0)
    assert {(v["code"], v["field"]) for v in e.violations} >= {("E1901", "nodes")}
    e = coded(swarmplan.Instance.generate, 7, requests=0)
    assert (e.code, e.field) == ("E3901", "requests")
    assert_python_words(e)


def test_highs_in_a_build_without_it(paper, hop42):
    try:
        hop42.solve("milp", backend="highs", time_limit_s=1.0)
    except swarmplan.SwarmplanError as e:
        assert (e.code, e.field) == ("E0012", "backend")
        assert "pip install" in e.action and "MATURIN_PEP517_ARGS" in e.action
        assert "cargo" not in e.action
    else:
        pytest.skip("this package was built with HiGHS")
