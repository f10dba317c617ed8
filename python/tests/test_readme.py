"""The Python examples of the READMEs run as written."""

import re

import pytest

from conftest import REPO

BLOCKS = [
    (name, i, block)
    for name in ["README.md", "python/README.md"]
    for i, block in enumerate(re.findall(r"```python\n(.*?)```", (REPO / name).read_text(), re.S))
]


def test_the_readmes_have_python_examples():
    assert {name for name, _, _ in BLOCKS} == {"README.md", "python/README.md"}


@pytest.mark.parametrize("name,index,block", BLOCKS, ids=[f"{n}#{i}" for n, i, _ in BLOCKS])
def test_a_readme_example_runs(name, index, block, capsys):
    exec(compile(block, f"{name} python block {index}", "exec"), {})
    printed = capsys.readouterr().out.split()
    assert printed[0] == "True"  # feasible
    value = float(printed[1])
    assert value > 0
