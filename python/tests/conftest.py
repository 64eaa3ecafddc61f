"""The pytest suite of passim's Python package (ctest label `python`; docs/python.md).

ctest runs it with PYTHONPATH at build/python and PASSIM_BIN at the built passim command."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("PASSIM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE


@pytest.fixture(scope="session")
def passim_bin():
    path = os.environ.get("PASSIM_BIN", str(SOURCE / "build" / "passim"))
    if not os.access(path, os.X_OK):
        pytest.skip(f"the passim command is not at {path} (set PASSIM_BIN)")
    return path
