"""The figure of a plan: `swarmplan.plot` returns the bytes `swarmplan plot` writes for the same
plans, its contents counted from the SVG's texts against the plan document (one legend entry
per drone, one pad label per drone and stop, both delivery times in a comparison's title), the
figure a Plan shows in Jupyter, and the refusals with their codes."""

import xml.etree.ElementTree as ET

import pytest

import swarmplan
from conftest import REPO

TINY = REPO / "instances/tiny"
# flat-stop, no sharing (tests/cli_plot.rs, instances/tiny/README.md): drones of 0.21, 0.21 and
# 0.44 kg stop at M (2 pads) with node time 13.31 min, delivered after 23.31 min.
STOP = dict(id="stop", source="A", destination="B", packages_kg=[0.21, 0.21, 0.44])


@pytest.fixture(scope="module")
def flat_stop():
    return swarmplan.Instance.from_files(
        TINY / "flat-stop.json", profile=str(TINY / "flat.toml"), requests=[STOP]
    )


@pytest.fixture(scope="module")
def stops_plan(paper):
    """A plan of paper-195 that recharges at a stop and shares energy in flight."""
    plan = paper.plan("r00023", sharing="pb")
    assert any(h.get("stop") for h in plan.plan["hops"]) and plan.support_drones > 0
    return plan


def texts(svg):
    """The texts of the SVG's <text> elements, read by an XML parser."""
    root = ET.fromstring(svg)
    assert root.tag.endswith("svg")
    return [(e.text or "").strip() for e in root.iter() if e.tag.endswith("}text") or e.tag == "text"]


def transfer_bands(svg):
    """The in-flight transfers drawn: the only rectangles filled with sky blue."""
    return sum(e.get("fill") == "#56B4E9" for e in ET.fromstring(svg).iter() if e.tag.endswith("rect"))


def tick(x):
    """A number as the figure's ticks write it: at most two decimals, none when whole."""
    r = round(x * 100) / 100
    return str(int(r)) if r == int(r) else repr(r)


def drone_legend(plan):
    """The legend entries the plan's swarm calls for: `drone D (role)`."""
    return [f"drone {d} ({drone['role']})" for d, drone in enumerate(plan.swarm["drones"])]


def recharging_stops(plan):
    return [h["stop"] for h in plan.plan["hops"] if h.get("stop") is not None]


def test_plot_is_the_command_lines_svg(paper, stops_plan, cli, tmp_path):
    path = tmp_path / "plan.json"
    path.write_text(stops_plan.to_json())
    want = cli("plot", "--plan", path, "-o", "-").stdout
    got = swarmplan.plot(stops_plan)
    assert got == want
    assert got.startswith("<svg") and got.rstrip().endswith("</svg>")
    other = tmp_path / "exact.json"
    exact = paper.plan("r00023", sharing="exact", route="optimal")
    other.write_text(exact.to_json())
    want = cli("plot", "--plan", path, "--compare", other, "--percent", "-o", "-").stdout
    assert swarmplan.plot(stops_plan, compare=exact, percent=True) == want


def test_plot_on_files_is_the_command_lines_svg(flat_stop, cli, tmp_path):
    plan = flat_stop.plan("stop", sharing="none")
    path = tmp_path / "stop.json"
    path.write_text(plan.to_json())
    want = cli(
        "plot", "--network", TINY / "flat-stop.json", "--profile", TINY / "flat.toml",
        "--plan", path, "-o", "-",
    ).stdout
    assert swarmplan.plot(plan) == want
    # The instance's own plot takes the document as a dict or as JSON text.
    assert flat_stop.plot(plan) == want
    assert flat_stop.plot(plan.to_dict()) == want
    assert flat_stop.plot(plan.to_json()) == want


def test_one_battery_series_per_drone_and_one_pad_bar_per_drone_and_stop(stops_plan):
    svg = swarmplan.plot(stops_plan)
    t = texts(svg)
    legend = drone_legend(stops_plan)
    assert len(legend) == len(stops_plan.swarm["drones"]) > 1
    assert [x for x in t if x.startswith("drone ")] == legend
    stops = recharging_stops(stops_plan)
    assert stops
    # Every drone charges once at every stop: its label once per stop, on one pad's row.
    for stop in stops:
        assert sorted(d for pad in stop["assignment"] for d in pad) == list(range(len(legend)))
    for d in range(len(legend)):
        assert t.count(f"d{d}") == len(stops), d
    bars = [x for x in t if x[:1] == "d" and x[1:].isdigit()]
    assert len(bars) == len(stops) * len(legend)
    for stop in stops:
        pads = "1 pad" if stop["pads"] == 1 else f"{stop['pads']} pads"
        assert f"{stop['node']}: {pads}" in t
    transfers = sum(len(h["transfers"]) for h in stops_plan.plan["hops"])
    assert transfers > 0 and transfer_bands(svg) == transfers
    capacities = {f"capacity {tick(d['capacity_mah'])}" for d in stops_plan.swarm["drones"]}
    assert {x for x in t if x.startswith("capacity ")} == capacities


def test_the_hand_computed_stop_is_drawn(flat_stop):
    plan = flat_stop.plan("stop", sharing="none")
    assert plan.plan["dt_min"] == pytest.approx(23.31)
    t = texts(swarmplan.plot(plan))
    assert [x for x in t if x.startswith("drone ")] == [f"drone {d} (delivery)" for d in range(3)]
    assert sorted(x for x in t if x in ("d0", "d1", "d2")) == ["d0", "d1", "d2"]
    assert "M: 2 pads" in t
    assert sum("nt 13.31 min (optimal)" in x for x in t) == 1
    assert sum(x.endswith("| dt 23.31 min | delivered") for x in t) == 1


def test_compare_draws_both_plans_with_their_delivery_times(paper, stops_plan):
    exact = paper.plan("r00023", sharing="exact", route="optimal")
    t = texts(swarmplan.plot(stops_plan, compare=exact))
    a, b = stops_plan.plan["dt_min"], exact.plan["dt_min"]
    assert a != b
    assert sum(x.startswith("plan (") and f"dt {a:.2f} min" in x for x in t) == 1
    assert sum(x.startswith("reference (") and f"dt {b:.2f} min" in x for x in t) == 1
    gap = (a - b) / b
    assert sum("gap" in x and x.endswith(f"{100 * gap:+.2f}%") for x in t) == 1
    # Both plans' batteries: the legend of each swarm, the plan's first.
    assert [x for x in t if x.startswith("drone ")] == drone_legend(stops_plan) + drone_legend(exact)
    # A single plan's title names neither.
    alone = texts(swarmplan.plot(stops_plan))
    assert not any(x.startswith(("plan (", "reference (")) for x in alone)


def test_percent_changes_the_battery_axis(stops_plan):
    mah = texts(swarmplan.plot(stops_plan))
    percent = texts(swarmplan.plot(stops_plan, percent=True))
    assert "battery (mAh)" in mah and "battery (% of capacity)" not in mah
    assert "battery (% of capacity)" in percent and "battery (mAh)" not in percent
    # In percent every capacity is 100.
    assert {x for x in percent if x.startswith("capacity ")} == {"capacity 100"}


def test_a_plan_shows_as_its_figure(stops_plan):
    assert stops_plan._repr_svg_() == swarmplan.plot(stops_plan)
    assert repr(stops_plan).startswith("Plan(request.id=r00023, ")


def test_a_failed_plan_marks_where_a_drone_runs_dry():
    deadend = swarmplan.Instance.from_files(
        TINY / "flat-deadend.json", profile=str(TINY / "flat.toml"),
        requests=[dict(id="far", source="A", destination="B", packages_kg=[0.21])],
    )
    plan = deadend.plan("far", support=0, route="dijkstra")
    assert plan.plan["outcome"]["kind"] == "hop-infeasible"
    t = texts(plan._repr_svg_())
    assert sum("runs dry" in x for x in t) == 1


def test_plot_refuses_with_the_command_lines_codes(paper, stops_plan):
    other = paper.plan("r00024")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.plot(stops_plan, compare=other)
    assert (e.value.code, e.value.field) == ("E8001", "compare")
    assert "r00023" in e.value.cause and "r00024" in e.value.cause
    # Plans made on another network, with another profile.
    findings = swarmplan.Instance.embedded("findings-195", profile="paper")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.plot(stops_plan, compare=findings.plan("r00023"))
    assert e.value.code == "E6004"
    with pytest.raises(swarmplan.SwarmplanError) as e:
        findings.plot(stops_plan)
    assert e.value.code == "E6004"
    fast = swarmplan.Instance.embedded("paper-195", profile="fast-sharing")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        fast.plot(stops_plan)
    assert e.value.code == "E6005"
    # Text that is no plan; a dict has no instance of its own.
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plot("{not json")
    assert (e.value.code, e.value.field) == ("E6001", "plan")
    with pytest.raises(TypeError):
        swarmplan.plot(stops_plan.to_dict())
