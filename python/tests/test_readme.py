"""The README's Python example runs as printed (in a scratch folder)."""

import os
import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def test_the_readme_script_runs(tmp_path, capsys):
    text = README.read_text(encoding="utf-8")
    section = text.split("## sylva from Python", 1)[1]
    script = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert len(script.strip().splitlines()) <= 22
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(script, "README.md", "exec"), {})
    finally:
        os.chdir(here)
    out = capsys.readouterr().out
    assert "trees," in out and "bones" in out and "F[+F[+A][-A]]" in out
    assert (tmp_path / "forest.glb").read_bytes()[:4] == b"glTF"
