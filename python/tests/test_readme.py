"""The Python examples of the guide's Python page and of the package's README run as written."""

import re

import pytest

from conftest import REPO

BLOCKS = [
    (name, i, block)
    for name in ["docs/src/python.md", "python/README.md"]
    for i, block in enumerate(re.findall(r"```python\n(.*?)```", (REPO / name).read_text(), re.S))
]


def test_the_guide_and_the_readme_have_python_examples():
    assert {name for name, _, _ in BLOCKS} == {"docs/src/python.md", "python/README.md"}


@pytest.mark.parametrize("name,index,block", BLOCKS, ids=[f"{n}#{i}" for n, i, _ in BLOCKS])
def test_a_readme_example_runs(name, index, block, capsys):
    exec(compile(block, f"{name} python block {index}", "exec"), {})
    printed = capsys.readouterr().out.split()
    assert printed[0] == "True"  # feasible
    value = float(printed[1])
    assert value > 0
