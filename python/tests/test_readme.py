"""The README's Python example runs as written, from a copy of the tree's
tutorials it uses (so that the run's files land in the scratch folder)."""
import os
import re

from conftest import SOURCE


def test_readme_example_runs_as_written(copy_case, tmp_path):
    text = (SOURCE / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    (tmp_path / "tutorials").mkdir()
    for name in ("twoCubes", "dropMagnet"):
        copy_case(f"tutorials/{name}", f"tutorials/{name}")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        scope = {}
        exec(compile(code, "README.md#python", "exec"), scope)
    finally:
        os.chdir(cwd)
    assert scope["B"].shape == (1000, 3) and scope["F"].shape == (50, 3)
    assert scope["r"]["F"].shape == (301, 2, 3)
    assert len(scope["out"]["time"]) == 3  # t = 0, 0.005, 0.01
