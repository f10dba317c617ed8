"""Planning a request: a typed Plan whose `to_dict()` is the document `swarmplan solve --json`
prints, checked by the independent checker; bad options get coded errors."""

import json

import pytest

import swarmplan
from conftest import without_times

COMBINATIONS = [
    ("none", "location-aware", "sequential"),
    ("pb", "location-aware", "sequential"),
    ("fb", "energy-aware", "astar"),
    ("pb", "energy-aware", "dijkstra"),
    ("fb", "location-aware", "floyd-warshall"),
    ("pb", "location-aware", "optimal"),
    ("exact", "location-aware", "sequential"),
    ("exact", "location-aware", "optimal"),
    ("fair", "location-aware", "astar"),
]


@pytest.mark.parametrize("sharing,positioning,route", COMBINATIONS)
def test_plan_is_the_command_lines_plan(paper, cli_json, sharing, positioning, route):
    got = paper.plan("r00023", sharing=sharing, positioning=positioning, route=route)
    want = cli_json(
        "solve", "--request-id", "r00023", "--sharing", sharing,
        "--positioning", positioning, "--route", route, "--json",
    )
    assert isinstance(got, swarmplan.Plan)
    assert without_times(got.to_dict()) == without_times(want)
    assert without_times(got.plan) == without_times(want["plan"])
    assert got.options == want["options"] and got.request == want["request"]
    assert paper.check(got) == []


def test_plan_with_gap_is_solve_gap(paper, cli_json):
    got = paper.plan("r00042", gap=True)
    want = cli_json("solve", "--request-id", "r00042", "--gap", "--json")
    assert got.route_gap == want["route_gap"]
    optimal = paper.plan("r00042", route="optimal").plan["dt_min"]
    assert got.route_gap["optimal_dt_min"] == optimal
    assert got.route_gap["gap"] == pytest.approx((got.plan["dt_min"] - optimal) / optimal)


def test_plan_of_a_request_given_as_a_dict(paper, cli_json):
    got = paper.plan({"source": "n000", "destination": "n194", "packages_kg": [1.2, 0.8, 0.5]}, sharing="fb")
    want = cli_json("solve", "--from", "n000", "--to", "n194", "--packages", "1.2,0.8,0.5", "--sharing", "fb", "--json")
    assert without_times(got.plan) == without_times(want["plan"])


def test_plans_are_reproducible(paper):
    a = paper.plan("r00100", sharing="exact", route="optimal")
    b = paper.plan("r00100", sharing="exact", route="optimal")
    assert without_times(a.to_dict()) == without_times(b.to_dict())


def test_check_finds_a_changed_number_and_accepts_json_text(paper):
    plan = paper.plan("r00001")
    assert paper.check(json.dumps(plan.to_dict())) == []
    assert paper.check(plan.to_json()) == []
    assert paper.check(plan.to_dict()) == []
    bad = plan.to_dict()
    bad["plan"]["dt_min"] += 5.0
    codes = {v["code"] for v in paper.check(bad)}
    assert codes and all(c.startswith("P5") for c in codes)
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.check("{not json")
    assert e.value.code == "E6001"


def test_bad_options_are_coded_errors(paper):
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", sharing="pbx")
    assert e.value.code == "E0026" and e.value.field == "sharing" and "fb" in e.value.action
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", sharing="fair", route="optimal")
    assert e.value.code == "E0015"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", sharing="pb", route="optimal", hop_paths="any")
    assert e.value.code == "E0016"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", sharing="exact", period_min=float("nan"))
    assert e.value.code == "E4101"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", backend="cplex")
    assert e.value.code == "E0026"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", support=99)
    assert e.value.code == "E0006"
    with pytest.raises(TypeError):
        paper.plan("r00001", support="two")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", support=-1)
    assert (e.value.code, e.value.field) == ("E0026", "support")


def test_a_plan_checked_on_another_instance_names_the_mismatch(paper):
    plan = paper.plan("r00042")
    findings = swarmplan.Instance.embedded("findings-195", profile="paper")
    assert [v["code"] for v in findings.check(plan)] == ["E6004"]
    fast = swarmplan.Instance.embedded("paper-195", profile="fast-sharing")
    assert [v["code"] for v in fast.check(plan)] == ["E6005"]
    both = swarmplan.Instance.embedded("findings-195")
    assert [v["code"] for v in both.check(plan)] == ["E6004", "E6005"]


def test_a_plan_of_a_request_given_inline_checks_clean(paper):
    # A dict without an id is planned as request "python": the plan carries it, and check takes
    # the plan's own request where the request set has none of that id.
    plan = paper.plan(dict(source="n000", destination="n194", packages_kg=[1.2, 0.8, 0.5]))
    assert plan.request["id"] == "python"
    assert paper.check(plan) == []
    changed = plan.to_dict()
    changed["plan"]["dt_min"] += 1.0
    assert paper.check(changed) != []
