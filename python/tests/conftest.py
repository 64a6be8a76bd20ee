"""Shared fixtures: the module built in build/python (CTest sets PYTHONPATH),
the source tree, and the apps of the same build."""
import os
import pathlib
import shutil
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("MAG_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("MAG_BUILD_DIR", SOURCE / "build"))
if str(BUILD / "python") not in sys.path:
    sys.path.insert(0, str(BUILD / "python"))
sys.path.insert(0, str(pathlib.Path(__file__).parent))  # oracles


@pytest.fixture
def copy_case(tmp_path):
    """Copy a tutorial or test case into a scratch folder (results land there)."""
    def copy(relative, name=None):
        dst = tmp_path / (name or pathlib.Path(relative).name)
        shutil.copytree(SOURCE / relative, dst, ignore=shutil.ignore_patterns("postProcessing", "VTK", "log.*", "*.png"))
        return dst
    return copy


@pytest.fixture
def app():
    """Path of one of the build's apps (build/bin)."""
    def path(name):
        p = BUILD / "bin" / name
        if not p.exists():
            pytest.skip(f"{p} not built")
        return str(p)
    return path
