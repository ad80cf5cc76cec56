"""Shared fixtures of the Python suite: the command line (for agreement checks) and the test data."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(os.environ.get("MINKSUM_TEST_DATA", ROOT / "tests" / "data"))


def pytest_configure(config):
    config.addinivalue_line("markers", "dask: starts a Dask LocalCluster (run alone: ctest python.dask)")
    # Debian's distributed 2022.12 with its tornado: a deprecation inside tornado, not ours.
    config.addinivalue_line("filterwarnings", "ignore:make_current is deprecated:DeprecationWarning")


def minksum_bin() -> str:
    path = os.environ.get("MINKSUM_BIN")
    if not path:
        pytest.fail("MINKSUM_BIN is not set: run the suite through ctest (python.pytest), or set it to build/bin/minksum")
    return path


def cli_json(*args: str) -> dict:
    """Run `minksum ARGS --json` and parse its one JSON object."""
    out = subprocess.run([minksum_bin(), *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


@pytest.fixture
def data() -> Path:
    return DATA
