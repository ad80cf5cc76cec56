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


def interrupt_after_start(script: str, *args: str, what: str, limit: float) -> None:
    """Run `script` in a child interpreter; one second after it prints "started", send SIGINT.  The child
    must exit with status 3 after printing "KeyboardInterrupt after ..." (its own handler) within `limit`
    seconds of the signal; `what` names the interrupted call in the failure message."""
    import signal
    import sys
    import time

    proc = subprocess.Popen([sys.executable, "-c", script, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        assert proc.stdout.readline() == "started\n"
        time.sleep(1)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        try:
            out, err = proc.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{what} still running {limit} s after SIGINT")
        elapsed = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert proc.returncode == 3, (out, err)
    assert out.startswith("KeyboardInterrupt after"), (out, err)
    assert elapsed < limit


@pytest.fixture
def data() -> Path:
    return DATA
