"""The typed results: the attributes the stub declares, `to_dict()` for JSON, equality."""

import ast
import json

import pytest

import swarmplan
from conftest import REPO

CLASSES = ["Plan", "HopResult", "HopEvaluation", "RouteEvaluation"]


def stub_properties(name):
    tree = ast.parse((REPO / "python/swarmplan/_swarmplan.pyi").read_text())
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == name)
    return {
        f.name for f in cls.body
        if isinstance(f, ast.FunctionDef)
        and any(isinstance(d, ast.Name) and d.id == "property" for d in f.decorator_list)
    }


@pytest.mark.parametrize("name", CLASSES)
def test_a_result_has_the_attributes_the_stub_declares(name):
    cls = getattr(swarmplan, name)
    declared = stub_properties(name)
    assert declared
    got = {k for k, v in vars(cls).items() if type(v).__name__ == "getset_descriptor"}
    assert got == declared
    assert callable(cls.to_dict) and callable(cls.to_json)


def test_every_field_of_the_document_is_an_attribute(paper):
    hop = paper.hop("r00042")
    plan = paper.plan("r00042", gap=True)
    results = [plan, hop.solve("pb"), hop.evaluate([]),
               paper.evaluate_route("r00042", [plan.plan["hops"][0]["from"]]
                                    + [h["to"] for h in plan.plan["hops"]], [[]] * len(plan.plan["hops"]),
                                    reference=False)]
    for result in results:
        document = result.to_dict()
        assert set(document) <= stub_properties(type(result).__name__)
        for key, value in document.items():
            assert getattr(result, key) == value, key
        assert json.loads(result.to_json()) == document
        assert type(result).__name__ in repr(result)


def test_results_compare_by_their_documents(paper):
    a = paper.plan("r00007", sharing="none")
    b = paper.plan("r00007", sharing="none")
    assert a != paper.plan("r00008", sharing="none")
    assert a.plan["dt_min"] == b.plan["dt_min"]
    assert a != a.to_dict()  # a result is not its dict
