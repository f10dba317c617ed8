"""Instances: shipped by name, from files, generated; requests; bad input."""

import json

import pytest

import swarmplan
from conftest import REPO


def test_shipped_names_list_the_repository_instances():
    names = swarmplan.shipped_names()
    assert names["networks"] == ["paper-195", "findings-195", "sparse-195"]
    assert names["profiles"] == ["paper", "paper-findings", "fast-sharing", "redundancy-levels"]
    for n in names["networks"]:
        assert (REPO / "instances" / n / "network.json").exists()
    for p in names["profiles"]:
        assert (REPO / "instances" / "profiles" / f"{p}.toml").exists()


def test_embedded_instances_are_the_shipped_files(paper):
    shipped = json.loads((REPO / "instances/paper-195/network.json").read_text())
    assert paper.network["nodes"] == shipped["nodes"]
    requests = json.loads((REPO / "instances/paper-195/requests.json").read_text())["requests"]
    assert paper.request_ids == [r["id"] for r in requests]
    assert paper.request("r00042") == next(r for r in requests if r["id"] == "r00042")
    assert paper.profile["name"] == "paper"
    assert paper.network_name == "embedded paper-195 network"
    assert paper.profile_name == "embedded paper profile"
    assert paper.requests_name == "embedded paper-195 requests"
    assert repr(paper) == (
        "Instance(embedded paper-195 network, embedded paper profile, "
        "10000 request(s) of embedded paper-195 requests)"
    )


def test_findings_network_takes_its_own_profile_and_another_on_request():
    assert swarmplan.Instance.embedded("findings-195").profile["name"] == "paper-findings"
    fast = swarmplan.Instance.embedded("findings-195", profile="fast-sharing")
    assert fast.profile["name"] == "fast-sharing"
    assert "fast-sharing" in fast.profile_name


def test_literal_readings_are_the_papers_word_for_word():
    ours = swarmplan.Instance.embedded("paper-195").profile["readings"]
    literal = swarmplan.Instance.embedded("paper-195", literal=True).profile["readings"]
    assert ours != literal
    assert literal["pb_wait_for_support"] is False
    assert literal["fb_charge_skipped"] is True


def test_unknown_names_are_coded_errors():
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.embedded("paper-196")
    assert e.value.code == "E0020" and "paper-195" in e.value.action
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.embedded("paper-195", profile="papr")
    assert e.value.code == "E0021"


def test_from_files_reads_the_same_instance_as_embedded(paper):
    i = swarmplan.Instance.from_files(
        REPO / "instances/paper-195/network.json",
        profile=str(REPO / "instances/profiles/paper.toml"),
        requests=REPO / "instances/paper-195/requests.json",
    )
    assert i.network == paper.network and i.profile == paper.profile
    assert i.request_ids == paper.request_ids
    a = i.plan("r00007")
    b = paper.plan("r00007")
    assert a.plan == b.plan


def test_from_files_takes_requests_as_dicts_and_checks_them():
    net = REPO / "instances/tiny/line4.json"
    given = [{"id": "a", "source": "A", "destination": "D", "packages_kg": [0.5]}]
    i = swarmplan.Instance.from_files(net, requests=given)
    assert i.request_ids == ["a"]
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.from_files(
            net, requests=[{"id": "b", "source": "A", "destination": "Z", "packages_kg": [0.5]}]
        )
    assert e.value.code.startswith("E3")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.from_files(net, requests=[{"id": "c", "source": "A"}])
    assert e.value.code == "E0026" and e.value.field == "requests"


def test_missing_file_is_e0008():
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.from_files("no/such/network.json")
    assert e.value.code == "E0008"


def test_generate_is_the_command_lines_generator_and_seeded(cli, tmp_path):
    out = tmp_path / "net.json"
    cli("generate", "network", "--nodes", 30, "--seed", 7, "-o", out)
    g = swarmplan.Instance.generate(7, nodes=30, requests=20)
    assert g.network == json.loads(out.read_text())
    req = tmp_path / "req.json"
    cli("generate", "requests", "--network", out, "--count", 20, "--seed", 7, "-o", req)
    assert g.request_ids == [r["id"] for r in json.loads(req.read_text())["requests"]]
    again = swarmplan.Instance.generate(7, nodes=30, requests=20)
    assert again.network == g.network
    assert swarmplan.Instance.generate(8, nodes=30, requests=20).network != g.network


def test_generate_rejects_bad_sizes():
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.generate(1, nodes=1)
    assert e.value.code.startswith("E19")


def test_request_lookup_and_its_errors(paper):
    assert paper.request("r00001")["id"] == "r00001"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.request("r42")
    assert e.value.code == "E3401" and "r00042" in e.value.cause
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.request({"source": "n000"})
    assert e.value.code == "E0026"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.request({"source": "n000", "destination": "n999", "packages_kg": [1.0]})
    assert e.value.code.startswith("E3")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.request({"source": "n000", "destination": "n010", "packages_kg": [float("nan")]})
    assert e.value.code.startswith("E3")


def test_wrong_types_raise_type_errors():
    with pytest.raises(TypeError):
        swarmplan.Instance.embedded(5)
    with pytest.raises(TypeError):
        swarmplan.Instance.generate("seven")


def test_error_carries_every_violation():
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.Instance.from_files(REPO / "instances/tiny/invalid-network.json", requests=[])
    assert len(e.value.violations) >= 1
    assert all(set(v) == {"code", "field", "cause", "action"} for v in e.value.violations)
    assert e.value.code == e.value.violations[0]["code"]
