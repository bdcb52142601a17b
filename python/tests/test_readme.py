"""The Python examples of README.md and python/README.md run as written: each file's
``python`` blocks in order, in one namespace, in a scratch directory whose ``fixtures/`` is the
repository's; and the ``>>>`` examples of the package's docstrings."""

import doctest
import os
import re

import pytest

from conftest import ROOT


def python_blocks(markdown: str) -> list:
    return re.findall(r"```python\n(.*?)```", markdown, flags=re.S)


@pytest.mark.parametrize("readme", ["README.md", "python/README.md"])
def test_readme_python_examples_run(readme, tmp_path, monkeypatch):
    blocks = python_blocks((ROOT / readme).read_text())
    assert blocks, f"{readme} has no python example"
    os.symlink(ROOT / "fixtures", tmp_path / "fixtures")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for block in blocks:
        exec(compile(block, f"{readme} example", "exec"), namespace)
    if "codes" in namespace:
        codes = namespace["codes"]
        assert codes.dtype.name == "int8" and set(codes.tolist()) <= {0, 1, 2}
    if "inside_fraction" in namespace:
        # Uniform points of [-1, 1]^2 against the lune: area / 4, up to sampling noise.
        area = namespace["domain"].area
        assert abs(float(namespace["inside_fraction"]) - area / 4) < 2e-3


def test_docstring_examples_run():
    import inrs

    failed, tried = doctest.testmod(inrs, report=True)
    assert tried > 0 and failed == 0
