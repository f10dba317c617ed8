"""The package's defaults are the crate's (the same values the command line's --help shows), and
an unknown choice names its argument and lists every choice."""

import ast
import re

import pytest

import swarmplan
from conftest import REPO, without_times


def help_default(cli, command, option):
    """The ``[default: ...]`` the command line's --help gives for ``option``."""
    text = cli(*command, "--help").stdout
    at = text.index(option + " <")
    return re.search(r"\[default: ([^\]]+)\]", text[at:]).group(1)


@pytest.mark.parametrize("name,command,option", [
    ("DEFAULT_NODE_LIMIT", ["solve"], "--node-limit"),
    ("DEFAULT_HOP_NODE_LIMIT", ["solve"], "--hop-node-limit"),
    ("DEFAULT_BACKEND", ["bench"], "--backend"),
    ("DEFAULT_EXACT_LIMIT", ["bench"], "--exact-limit"),
    ("DEFAULT_DISTANCE_BUCKET_KM", ["bench"], "--distance-bucket-km"),
    ("DEFAULT_NODES", ["generate", "network"], "--nodes"),
    ("DEFAULT_SPACING_M", ["generate", "network"], "--spacing-m"),
    ("DEFAULT_MAX_PACKAGE_KG", ["generate", "requests"], "--max-package-kg"),
])
def test_a_default_is_the_command_lines(cli, name, command, option):
    value = getattr(swarmplan, name)
    shown = help_default(cli, command, option)
    if isinstance(value, str):
        assert value == shown
    else:
        assert value == type(value)(float(shown))


def test_the_stub_states_the_defaults():
    stub = (REPO / "python/swarmplan/_swarmplan.pyi").read_text()
    for name, doc in re.findall(r"^(DEFAULT_\w+): \w+\n\"\"\"(.*?)\"\"\"", stub, re.M | re.S):
        value = getattr(swarmplan, name)
        stated = re.search(r": (``\"\w+\"``|\d[\d_]*(?:\.\d+)?)", doc).group(1).strip("`\"")
        assert (stated if isinstance(value, str) else ast.literal_eval(stated)) == value, name
    assert 'node_limit: Optional[int] = %s,' % f"{swarmplan.DEFAULT_HOP_NODE_LIMIT:_}" in stub


def test_none_takes_the_defaults(paper):
    a = paper.plan("r00042", sharing="exact", node_limit=None, hop_node_limit=None, backend=None)
    b = paper.plan("r00042", sharing="exact", node_limit=swarmplan.DEFAULT_NODE_LIMIT,
                   hop_node_limit=swarmplan.DEFAULT_HOP_NODE_LIMIT,
                   backend=swarmplan.DEFAULT_BACKEND)
    assert without_times(a.plan) == without_times(b.plan)
    assert a.settings == b.settings


CHOICES = {
    "sharing": ["none", "idle-support", "pb", "fb", "exact", "fair"],
    "positioning": ["location-aware", "energy-aware"],
    "route": ["sequential", "astar", "dijkstra", "floyd-warshall", "optimal"],
    "hop_paths": ["rule", "any"],
    "reorder": ["paper", "free", "none"],
}


@pytest.mark.parametrize("argument", sorted(CHOICES))
def test_an_unknown_choice_lists_the_choices(paper, argument):
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.plan("r00001", **{argument: "nothing"})
    assert (e.value.code, e.value.field) == ("E0026", argument)
    assert "`nothing` is not a choice" in e.value.cause
    assert e.value.action == "give one of " + ", ".join(CHOICES[argument])


def test_an_unknown_method_lists_the_methods(paper):
    with pytest.raises(swarmplan.SwarmplanError) as e:
        paper.hop("r00042").solve("simplex")
    assert (e.value.code, e.value.field) == ("E0026", "method")
    assert e.value.action == "give one of none, pb, fb, continuous, milp, fluid, fair"
