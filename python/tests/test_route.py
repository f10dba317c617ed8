"""A whole route of one's own: stops and a schedule per hop, against the joint optimum."""

import pytest

import swarmplan

REQUESTS = ["r00001", "r00023", "r00100"]


def stops_of(plan):
    hops = plan.plan["hops"]
    return [hops[0]["from"]] + [h["to"] for h in hops]


@pytest.mark.parametrize("request_id", REQUESTS)
def test_a_plans_own_route_and_schedules_give_its_delivery_time(paper, request_id):
    plan = paper.plan(request_id, sharing="pb", route="optimal")
    assert plan.plan["outcome"]["kind"] == "delivered"
    schedules = [h["transfers"] for h in plan.plan["hops"]]
    got = paper.evaluate_route(request_id, stops_of(plan), schedules, reference=False)
    assert got.delivered and got.dt_proven
    assert got.dt_min == pytest.approx(plan.plan["dt_min"], rel=1e-9)
    assert got.tt_min == pytest.approx(plan.plan["tt_min"], rel=1e-9)
    assert got.nt_min == pytest.approx(plan.plan["nt_min"], rel=1e-9)
    assert [h["hop"]["path"] for h in got.hops] == [h["path"] for h in plan.plan["hops"]]


@pytest.mark.parametrize("request_id", REQUESTS)
def test_the_reference_is_the_joint_optimum_of_the_swarm(paper, request_id):
    best = paper.plan(request_id, sharing="exact", route="optimal")
    # The optimum's own route and schedules reach it; a policy of our own is at or above it.
    own = paper.evaluate_route(request_id, stops_of(best), [h["transfers"] for h in best.plan["hops"]])
    assert own.reference["dt_min"] == best.plan["dt_min"]
    assert own.reference["kind"] == "optimal"
    assert own.gap["reference"] == "optimal"
    assert abs(own.gap["relative"]) <= 1e-9
    seen = []

    def idle(hop):
        seen.append(hop)
        return []

    pb = paper.plan(request_id, sharing="pb", route="optimal")
    mine = paper.evaluate_route(request_id, stops_of(pb), idle)
    assert all(isinstance(h, swarmplan.Hop) for h in seen)
    assert [h.path for h in seen] == [h["path"] for h in pb.plan["hops"]][: len(seen)]
    assert all(list(h.battery_mah) == list(h.capacity_mah) for h in seen)  # every hop departs full
    if mine.delivered:
        assert mine.gap["relative"] >= -1e-12
        assert mine.dt_min == pytest.approx(best.plan["dt_min"] * (1 + mine.gap["relative"]), rel=1e-9)
    else:
        assert mine.gap is None and mine.gap_label == "not_delivered"


def test_no_sharing_on_the_idle_support_route_is_that_plan(paper):
    plan = paper.plan("r00023", sharing="idle-support", route="optimal")
    got = paper.evaluate_route("r00023", stops_of(plan), lambda hop: [], reference=False)
    assert got.dt_min == pytest.approx(plan.plan["dt_min"], rel=1e-9)


def test_bad_stops_are_coded(paper):
    r = paper.request("r00023")
    s, d = r["source"], r["destination"]
    pads = [n["id"] for n in paper.network["nodes"] if n["pads"] > 0 and n["id"] not in (s, d)]
    bare = next(n["id"] for n in paper.network["nodes"] if n["pads"] == 0 and n["id"] not in (s, d))

    def code(stops, policy=lambda hop: []):
        with pytest.raises(swarmplan.SwarmplanError) as e:
            paper.evaluate_route("r00023", stops, policy, reference=False)
        return e.value.code

    assert code([d, s]) == "E0022"
    assert code([s, "n999", d]) == "E0023"
    assert code([s, bare, d]) == "E0024"
    assert code([s, pads[0], pads[0], d]) == "E0025"
    assert code([s, d], policy=[[], []][:0]) == "E0026"
    assert code([s, d], policy=lambda hop: [dict(support=0, consumer=0, start_min=0.0, end_min=0.1)]) == "C3002"
    assert code([s, d], policy=lambda hop: "not a schedule") == "E0026"


def test_a_policy_that_raises_raises(paper):
    r = paper.request("r00023")

    def broken(hop):
        raise ValueError("my policy broke")

    with pytest.raises(ValueError, match="my policy broke"):
        paper.evaluate_route("r00023", [r["source"], r["destination"]], broken)
