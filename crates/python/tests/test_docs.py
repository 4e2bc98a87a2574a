"""docs/python.md says what the package does: every ```python block of it runs,
in order and in one namespace (as a reader pasting them into one session would),
in a fresh directory; a block that raises fails the test."""

from __future__ import annotations

import os
import re

from conftest import ROOT


def blocks() -> list[str]:
    text = (ROOT / "docs" / "python.md").read_text()
    return re.findall(r"^```python\n(.*?)^```$", text, flags=re.S | re.M)


def test_every_python_block_of_the_docs_runs(tmp_path, capsys):
    code = blocks()
    assert len(code) >= 8, "docs/python.md lost its examples"
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace: dict = {"__name__": "docs_python"}
        for k, block in enumerate(code):
            try:
                exec(compile(block, f"docs/python.md block {k + 1}", "exec"), namespace)
            except Exception as e:  # noqa: BLE001 - name the block that failed
                raise AssertionError(f"docs/python.md block {k + 1} fails:\n{block}") from e
    finally:
        os.chdir(here)
