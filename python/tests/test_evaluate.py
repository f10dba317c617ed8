"""Bring your own policy: a schedule written in Python, flown as written, judged by the
independent checker, scored against the exact optimum of the same re-ordering mode."""

import json
import math

import numpy as np
import pytest

import swarmplan
from conftest import REPO

HOPS = [("r00001", 0), ("r00001", 3), ("r00002", 0), ("r00042", 0), ("r00023", 1)]


@pytest.mark.parametrize("request_id,index", HOPS)
def test_the_empty_schedule_is_eaas_none(paper, cli_json, tmp_path, request_id, index):
    path = tmp_path / "hop.json"
    hop = paper.hop(request_id, index)
    hop.write(path)
    want = cli_json("eaas", "--hop-file", path, "--methods", "none,continuous", "--json")["rows"]
    got = swarmplan.evaluate(hop, [])
    assert got.feasible == want[0]["feasible"]
    assert got.value == want[0]["objective"]
    assert got.mode == "none" and got.shared_mah == 0.0
    ref = got.reference
    assert ref["status"] == want[1]["status"] and ref["value"] == pytest.approx(want[1]["objective"], rel=1e-12)
    if got.feasible:
        # A gap is a loss, positive under either sense: node time minimised, arrival maximised.
        loss = got.value - ref["value"] if hop.end is not None else ref["value"] - got.value
        assert got.gap["relative"] == pytest.approx(loss / abs(ref["value"]))
    else:
        assert got.gap is None and got.gap_label == "infeasible"


def test_the_empty_schedule_batteries_are_hand_integrated(paper):
    hop = paper.hop("r00001", 3)
    got = hop.evaluate([], reference=False)
    # No transfer: every drone draws its own slot's rate on every leg.
    slot = hop.initial_slot
    used = np.einsum("l,ld->d", hop.durations_min, hop.rates_mah_per_min[:, np.arange(hop.drones), slot])
    np.testing.assert_allclose(got.final_battery_mah, hop.battery_mah - used, rtol=1e-12)
    assert got.reference is None and got.gap is None


@pytest.mark.parametrize("request_id,index", HOPS)
def test_pb_and_the_continuous_optimum_score_as_eaas_says(paper, request_id, index):
    hop = paper.hop(request_id, index)
    rows = {r.method: r for r in hop.compare(["pb", "continuous"], time_limit_s=None, node_limit=20000)}
    pb = hop.evaluate(rows["pb"].transfers)
    assert pb.feasible == rows["pb"].feasible
    if pb.feasible:
        assert pb.value == pytest.approx(rows["pb"].objective, rel=1e-9)
    best = rows["continuous"]
    if best.status == "optimal" and best.feasible:
        own = hop.evaluate(best.transfers)
        assert own.value == pytest.approx(best.objective, rel=1e-9, abs=1e-9)
        assert abs(own.gap["relative"]) <= 1e-9
        # The optimum is never beaten: a loss under either sense of the objective.
        if pb.feasible:
            assert pb.gap["relative"] >= -1e-9


def serve(hop, duration):
    """One transfer per support drone, each to its own in-range consumer, at the hop's end."""
    taken, out = set(), []
    for m in hop.moves("none"):
        if m["support"] in taken or m["consumer"] in {t["consumer"] for t in out}:
            continue
        taken.add(m["support"])
        out.append(dict(support=m["support"], consumer=m["consumer"],
                        start_min=hop.tt_min - duration, end_min=hop.tt_min))
    return out


def test_a_written_transfer_moves_rho_times_its_duration(paper):
    hop = paper.hop("r00002", 0)
    empty = hop.evaluate([], reference=False)
    schedule = serve(hop, 0.5)
    got = hop.evaluate(schedule, reference=False)
    moved = np.zeros(hop.drones)
    for t in schedule:
        moved[t["support"]] -= hop.rho_mah_per_min * 0.5
        moved[t["consumer"]] += hop.rho_mah_per_min * 0.5
    np.testing.assert_allclose(got.final_battery_mah, np.array(empty.final_battery_mah) + moved, rtol=1e-12)
    assert got.shared_mah == pytest.approx(hop.rho_mah_per_min * 0.5 * len(schedule))
    # Tuples read the same as dicts.
    tuples = [(t["support"], t["consumer"], t["start_min"], t["end_min"]) for t in schedule]
    assert hop.evaluate(tuples, reference=False).final_battery_mah == got.final_battery_mah


def test_a_swap_is_outside_the_none_mode(paper):
    hop = paper.hop("r00002", 0)
    swap = next(m for m in hop.moves("paper") if m["partner"] is not None)
    schedule = [dict(support=swap["support"], consumer=swap["consumer"], start_min=0.0,
                     end_min=0.1, consumer_slot=swap["consumer_slot"])]
    paper_mode = hop.evaluate(schedule, reorder="paper")
    assert paper_mode.mode == "paper" and paper_mode.gap is not None
    none_mode = hop.evaluate(schedule, reorder="none")
    assert none_mode.gap is None and none_mode.gap_label == "outside_reference"


def checker_code(hop, schedule):
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.evaluate(schedule, reference=False)
    assert "schedule" in e.value.action
    return e.value.code, {v["code"] for v in e.value.violations}


def test_malformed_schedules_raise_the_checkers_codes(paper):
    hop = paper.hop("r00002", 0)
    tt = hop.tt_min
    support = hop.roles.index("support")
    far = next(m for m in hop.moves("paper") if m["partner"] is not None)
    ok = hop.moves("none")[0]
    # A delivery drone cannot give.
    assert checker_code(hop, [dict(support=0, consumer=1, start_min=0.0, end_min=0.1)])[0] == "C3002"
    # A support drone cannot receive.
    assert checker_code(hop, [dict(support=support, consumer=support, start_min=0.0, end_min=0.1)])[0] == "C3003"
    # Beyond the hop's end.
    assert "C3004" in checker_code(hop, [dict(support=ok["support"], consumer=ok["consumer"], start_min=tt - 0.1, end_min=tt + 1.0)])[1]
    # Energy that is not rho x duration.
    assert checker_code(hop, [dict(support=ok["support"], consumer=ok["consumer"], start_min=0.0, end_min=0.1, energy_mah=1e3)])[0] == "C3005"
    # A consumer out of range in its own slot.
    assert checker_code(hop, [dict(support=far["support"], consumer=far["consumer"], start_min=0.0, end_min=0.1)])[0] == "C3006"
    # One support drone serving two consumers at once.
    other = next(m for m in hop.moves("none") if m["support"] == ok["support"] and m["consumer"] != ok["consumer"])
    codes = checker_code(hop, [dict(support=ok["support"], consumer=ok["consumer"], start_min=0.0, end_min=0.2),
                               dict(support=other["support"], consumer=other["consumer"], start_min=0.1, end_min=0.3)])[1]
    assert "C3008" in codes
    # Indices that do not exist, and numbers that are not numbers: coded, never a crash.
    assert checker_code(hop, [dict(support=99, consumer=0, start_min=0.0, end_min=0.1)])[0] == "C3001"
    assert checker_code(hop, [dict(support=ok["support"], consumer=ok["consumer"], start_min=math.nan, end_min=0.1)])[0] == "C3004"
    assert checker_code(hop, [dict(support=ok["support"], consumer=ok["consumer"], start_min=0.0, end_min=math.inf)])[0] == "C3004"


def test_schedules_of_the_wrong_shape_are_e0026(paper):
    hop = paper.hop("r00002", 0)
    for bad in ["abc", {"support": 1}, [1, 2, 3], [dict(support=1)], [dict(support=7, consumer=0, start_min=0, end_min=1, colour="red")], [("a", 0, 0.0, 1.0)], None, 5]:
        with pytest.raises(swarmplan.SwarmplanError) as e:
            hop.evaluate(bad, reference=False)
        assert e.value.code == "E0026" and e.value.field == "schedule"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.evaluate([(-1, 0, 0.0, 1.0)], reference=False)
    assert e.value.code == "E0026"


def test_a_schedule_that_runs_a_drone_dry_is_a_result(paper):
    file = json.loads(paper.hop("r00001", 3).to_json())
    file["hop"]["drones"][0]["battery_mah"] = 1.0
    hop = swarmplan.Hop.from_json(json.dumps(file))
    rate = hop.rates_mah_per_min[0, 0, hop.initial_slot[0]]
    assert 1.0 / rate < hop.durations_min[0]  # dry within the first leg
    got = hop.evaluate([])
    assert got.feasible is False and got.value is None
    assert got.failure["drone"] == 0
    assert got.failure["time_min"] == pytest.approx(1.0 / rate, rel=1e-9)
    assert got.gap is None and got.gap_label == "infeasible"


def needy_pair(end):
    """The needy pair of instances/eaas/known_optima.json as a hop file: delivery drones 0 and 1
    at 25 of 100 mAh using 10 mAh/min, support drone 2 (100 mAh, no consumption) serving either
    at 10 mAh/min, one 4-minute leg; optimum 5 mAh (max-min arrival), 95 min on 3 pads."""
    known = json.loads((REPO / "instances" / "eaas" / "known_optima.json").read_text())
    problem = next(i for i in known["instances"] if i["name"] == "needy_pair_max_min")["problem"]
    file = dict(schema_version=1, request_id="needy", hop_index=0, **{"from": "S"}, to="T",
                path=["S", "T"], end=end, hop=problem)
    return swarmplan.Hop.from_json(json.dumps(file))


# Drone 0 served on [0, 1.75), drone 1 on [1.75, 4): 17.5 and 22.5 mAh shared; by hand
# b0 = 25 - 40 + 17.5 = 2.5 and b1 = 25 - 17.5 (falling until served, then level) = 7.5.
LOPSIDED = [dict(support=2, consumer=0, start_min=0.0, end_min=1.75),
            dict(support=2, consumer=1, start_min=1.75, end_min=4.0)]


def test_a_maximised_loss_reads_as_a_positive_gap():
    got = swarmplan.evaluate(needy_pair(None), LOPSIDED)
    assert got.value == pytest.approx(2.5)
    assert got.reference["value"] == pytest.approx(5.0)
    # Arrival battery, maximised: 2.5 mAh against 5 is a loss of (5 - 2.5) / 5 = 50 %.
    assert got.gap["reference"] == "optimal"
    assert got.gap["relative"] == pytest.approx(0.5)


def test_a_minimised_loss_reads_as_a_positive_gap():
    got = swarmplan.evaluate(needy_pair(dict(pads=3, pad_rate_mah_per_min=1.0)), LOPSIDED)
    # Deficits 97.5, 92.5 and 40 (all shared) on 3 pads at 1 mAh/min: 97.5 min against 95.
    assert got.value == pytest.approx(97.5)
    assert got.reference["value"] == pytest.approx(95.0)
    assert got.gap["relative"] == pytest.approx(2.5 / 95.0)
