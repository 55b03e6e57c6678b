"""The README's "Use" block runs verbatim, as a newcomer would paste it into a script."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def use_block() -> str:
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Use"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@pytest.mark.slow
def test_the_use_block_runs_verbatim(tmp_path) -> None:
    script = tmp_path / "use.py"
    script.write_text(use_block())
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "Traceback" not in out.stderr


def test_the_use_block_defines_what_it_uses() -> None:
    """Every name the block calls is imported or assigned in it (the old block stopped at
    an undefined ``scene``, ``variants`` and ``pool``)."""
    code = use_block()
    compile(code, "README Use", "exec")
    for name in ("variants", "pool"):
        assert re.search(rf"\b{name}\b\s*=|as {name}\b", code), name
