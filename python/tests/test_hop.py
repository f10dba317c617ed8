"""Hops: the same problem as `swarmplan eaas --write-hop` writes, its arrays, moves and exact
solves as `swarmplan eaas --json` reports them."""

import json

import numpy as np
import pytest

import swarmplan
from conftest import without_times


@pytest.fixture(scope="module")
def hop_and_file(paper, cli, tmp_path_factory):
    path = tmp_path_factory.mktemp("hop") / "hop.json"
    cli("eaas", "--request-id", "r00002", "--hop", 0, "--methods", "pb", "--write-hop", path)
    return paper.hop("r00002", 0), json.loads(path.read_text()), path


def test_hop_is_the_hop_file_of_eaas(hop_and_file):
    hop, file, _ = hop_and_file
    assert json.loads(hop.to_json()) == file
    assert hop.request_id == "r00002" and hop.index == 0
    assert hop.path == file["path"] and hop.end == file["end"]
    p = file["hop"]
    assert hop.drones == len(p["drones"]) == 8
    assert hop.roles == [d["role"] for d in p["drones"]]
    np.testing.assert_array_equal(hop.capacity_mah, [d["capacity_mah"] for d in p["drones"]])
    np.testing.assert_array_equal(hop.battery_mah, [d["battery_mah"] for d in p["drones"]])
    np.testing.assert_array_equal(hop.durations_min, [l["duration_min"] for l in p["legs"]])
    rates = hop.rates_mah_per_min
    assert isinstance(rates, np.ndarray) and rates.shape == (len(p["legs"]), 8, 8)
    np.testing.assert_array_equal(rates, [l["rate_mah_per_min"] for l in p["legs"]])
    np.testing.assert_array_equal(hop.slots_m, p["slots_m"])
    assert hop.initial_slot == p["initial_slot"]
    assert hop.rho_mah_per_min == p["rho_mah_per_min"] and hop.range_m == p["range_m"]
    assert hop.delta_mah == p["delta_mah"]
    assert hop.tt_min == pytest.approx(sum(l["duration_min"] for l in p["legs"]), rel=1e-12)
    assert hop.problem == p
    assert hop.objective == "max_min_arrival"
    assert "r00002" in repr(hop)


def test_hop_files_round_trip(hop_and_file, tmp_path):
    hop, file, path = hop_and_file
    assert json.loads(swarmplan.Hop.from_file(path).to_json()) == file
    assert json.loads(swarmplan.Hop.from_json(json.dumps(file)).to_json()) == file
    out = tmp_path / "again.json"
    hop.write(out)
    assert json.loads(out.read_text()) == file
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Hop.from_json("{}")
    assert e.value.code.startswith("E")
    bad = dict(file, schema_version=9)
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Hop.from_json(json.dumps(bad))
    assert e.value.code == "E4112"
    nan = json.loads(json.dumps(file))
    nan["hop"]["legs"][0]["duration_min"] = -1.0
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Hop.from_json(json.dumps(nan))
    assert e.value.field.startswith("hop.")


def distance(hop, a, b):
    return float(np.hypot(*(hop.slots_m[a] - hop.slots_m[b])))


def test_moves_follow_the_range_rule(hop_and_file):
    hop, _, _ = hop_and_file
    roles = hop.roles
    slot = hop.initial_slot
    support = [d for d in range(hop.drones) if roles[d] == "support"]
    delivery = [d for d in range(hop.drones) if roles[d] == "delivery"]
    # none: every (support, consumer) pair within range in the consumer's own slot.
    expected = {
        (s, c, slot[c]) for s in support for c in delivery
        if distance(hop, slot[s], slot[c]) <= hop.range_m
    }
    none = hop.moves("none")
    assert {(m["support"], m["consumer"], m["consumer_slot"]) for m in none} == expected
    assert all(m["partner"] is None for m in none)
    # paper adds swaps: an out-of-range consumer into an in-range delivery drone's slot.
    paper = hop.moves("paper")
    swaps = [m for m in paper if m["partner"] is not None]
    assert swaps
    for m in swaps:
        assert distance(hop, slot[m["support"]], slot[m["consumer"]]) > hop.range_m
        assert distance(hop, slot[m["support"]], m["consumer_slot"]) <= hop.range_m
        assert roles[m["partner"]] == "delivery" and slot[m["partner"]] == m["consumer_slot"]
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.moves("free")
    assert e.value.code == "E0026"


METHODS = ["none", "pb", "fb", "continuous", "milp", "fluid", "fair"]


def test_compare_is_eaas(hop_and_file, cli_json):
    hop, _, path = hop_and_file
    rows = hop.compare(METHODS, time_limit_s=None, node_limit=20000)
    want = cli_json(
        "eaas", "--hop-file", path, "--methods", ",".join(METHODS),
        "--node-limit", 20000, "--time-limit", 1e6, "--json",
    )["rows"]
    assert all(isinstance(r, swarmplan.HopResult) for r in rows)
    assert without_times([r.to_dict() for r in rows]) == without_times(want)


def test_solve_is_one_row(hop_and_file, cli_json):
    hop, _, path = hop_and_file
    row = hop.solve("continuous", reorder="none", time_limit_s=None)
    want = cli_json("eaas", "--hop-file", path, "--methods", "continuous", "--reorder", "none", "--json")["rows"][0]
    assert row.status == want["status"] == "optimal"
    assert row.objective == want["objective"]
    assert row.transfers == want["transfers"]
    assert without_times(row.to_dict()) == without_times(want)


def test_solve_rejects_bad_settings(hop_and_file):
    hop, _, _ = hop_and_file
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.solve("simplex")
    assert e.value.code == "E0026" and "continuous" in e.value.action
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.solve("milp", time_limit_s=-1.0)
    assert e.value.code == "E4105"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        hop.solve("milp", period_min=0.0)
    assert e.value.code == "E4101"


def test_hop_index_beyond_the_plan_is_e4110(paper):
    hops = len(paper.plan("r00042").plan["hops"])
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.hop("r00042", hops)
    assert e.value.code == "E4110"
