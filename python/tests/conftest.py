"""Shared fixtures: the CLI to compare with, records in ../shared (skipped when absent), a record made here."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED_RECORDS = ROOT.parent / "shared" / "records"


@pytest.fixture(scope="session")
def cli():
    path = pathlib.Path(os.environ.get("TOPPLE_CLI", ROOT / "build" / "release" / "cli" / "topple"))
    if not path.is_file():
        pytest.skip(f"no topple CLI at {path} (build it, or set TOPPLE_CLI)")

    def run(*args, check=True):
        proc = subprocess.run([str(path), *map(str, args)], capture_output=True, text=True)
        if check and proc.returncode != 0:
            raise AssertionError(f"topple {' '.join(map(str, args))} failed: {proc.stderr}")
        return proc

    def run_json(*args):
        return json.loads(run(*args, "--json").stdout)

    run.json = run_json
    return run


@pytest.fixture(scope="session")
def made_record(tmp_path_factory):
    """A plain CSV record made here (always available): time_s,accel_g, 1500 samples at 0.01 s."""
    t = np.arange(1500) * 0.01
    a = 0.5 * np.sin(2 * np.pi * 1.7 * t) * np.exp(-((t - 5.0) / 3.0) ** 2) + 0.1 * np.sin(2 * np.pi * 5.3 * t)
    return write_record(tmp_path_factory.mktemp("records") / "made.csv", t, a, time_decimals=2)


def write_record(path, t, a_g, time_decimals):
    """A plain CSV record time_s,accel_g (times rounded to time_decimals, accelerations exact); returns its path."""
    with open(path, "w") as f:
        f.write("time_s,accel_g\n")
        for ti, ai in zip(t, a_g):
            f.write(f"{ti:.{time_decimals}f},{float(ai)!r}\n")
    return str(path)


def shared_record(name):
    path = SHARED_RECORDS / name
    if not path.is_file():
        pytest.skip(f"{path} absent (../shared)")
    return str(path)
