"""The package's defaults are the crate's (the same values the command line's --help shows), and
an unknown choice names its argument and lists every choice."""

import ast
import inspect
import re

import pydoc

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


DOCUMENTED = [
    swarmplan.Instance.embedded, swarmplan.Instance.from_files, swarmplan.Instance.generate,
    swarmplan.Instance.request, swarmplan.Instance.plan, swarmplan.Instance.check,
    swarmplan.Instance.plot, swarmplan.Instance.hop, swarmplan.Instance.evaluate_route,
    swarmplan.Hop.from_file, swarmplan.Hop.from_json, swarmplan.Hop.write, swarmplan.Hop.moves,
    swarmplan.Hop.solve, swarmplan.Hop.compare, swarmplan.Hop.evaluate,
    swarmplan.evaluate, swarmplan.plot, swarmplan.bench, swarmplan.BenchResult.frame,
]


@pytest.mark.parametrize("function", DOCUMENTED, ids=lambda f: f.__qualname__)
def test_help_shows_numpydoc_sections(function):
    doc = inspect.getdoc(function)
    assert "Parameters\n----------" in doc
    assert "Returns\n-------" in doc or function.__name__ == "write"
    assert "Raises\n------" in doc
    # Every keyword of the signature is described.
    for name in inspect.signature(function).parameters:
        if name not in ("self", "options"):
            assert f"\n{name} :" in doc or doc.startswith(f"{name} :"), name


def test_help_of_plan_gives_the_defaults():
    text = pydoc.render_doc(swarmplan.Instance.plan, renderer=pydoc.plaintext)
    assert "node_limit=None" in text
    assert f"DEFAULT_NODE_LIMIT`\n    ({swarmplan.DEFAULT_NODE_LIMIT:,})" in swarmplan.Instance.plan.__doc__
    assert f"({swarmplan.DEFAULT_HOP_NODE_LIMIT:,})" in swarmplan.Instance.plan.__doc__
    assert f"(`{swarmplan.DEFAULT_BACKEND}`)" in swarmplan.Instance.plan.__doc__


@pytest.mark.parametrize("cls", [swarmplan.Instance, swarmplan.Hop, swarmplan.SwarmplanError,
                                 swarmplan.BenchResult])
def test_classes_document_their_attributes(cls):
    assert "Attributes\n----------" in inspect.getdoc(cls)


def test_no_signature_hides_a_default():
    for cls in (swarmplan.Instance, swarmplan.Hop):
        for name, function in vars(cls).items():
            if callable(function) and not name.startswith("_"):
                for p in inspect.signature(function).parameters.values():
                    assert p.default is not Ellipsis, f"{cls.__name__}.{name}({p.name})"
    evaluate = inspect.signature(swarmplan.Hop.evaluate).parameters
    assert evaluate["node_limit"].default == swarmplan.DEFAULT_HOP_NODE_LIMIT


def stub_methods():
    tree = ast.parse((REPO / "python/swarmplan/_swarmplan.pyi").read_text())
    for cls in (n for n in tree.body if isinstance(n, ast.ClassDef) and n.name in ("Instance", "Hop")):
        for f in cls.body:
            if isinstance(f, ast.FunctionDef) and not f.decorator_list == [ast.Name("property")] \
                    and not any(isinstance(d, ast.Name) and d.id == "property" for d in f.decorator_list):
                yield cls.name, f


@pytest.mark.parametrize("cls,method", [(c, f) for c, f in stub_methods()],
                         ids=[f"{c}.{f.name}" for c, f in stub_methods()])
def test_the_signature_is_the_stubs(cls, method):
    args = method.args.args
    defaults = [None] * (len(args) - len(method.args.defaults)) + method.args.defaults
    want = [(a.arg, ast.literal_eval(d) if d is not None else inspect.Parameter.empty)
            for a, d in zip(args, defaults) if a.arg != "self"]
    got = [(p.name, p.default) for p in
           inspect.signature(getattr(getattr(swarmplan, cls), method.name)).parameters.values()
           if p.name != "self"]
    # A tuple in the stub is a list at run time (methods=...).
    got = [(n, tuple(d) if isinstance(d, list) else d) for n, d in got]
    assert got == want
