"""The Python comparisons' record: the first 20,000 samples of Kocaeli 1999 ATS-090 (../shared/records/slammer), the
record of bench_sliding and bench_flexible (bench/kocaeli_record.hpp), with k_y = 20 % of its PGA."""
import pathlib
import sys

import numpy as np

root = pathlib.Path(__file__).resolve().parents[1]


def build_dir():
    """The build folder given as the first argument, else build/release."""
    return pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "build" / "release"


def load(n=20000):
    """(accel_g, dt_s, ky_g): the record's first n samples in g, its step and 20 % of its PGA."""
    record = root.parent / "shared" / "records" / "slammer" / "Kocaeli_1999_ATS-090.csv"
    data = np.loadtxt(record, delimiter=",", comments="#")[:n]
    accel_g = data[:, 1]
    return accel_g, float(data[1, 0] - data[0, 0]), 0.20 * float(np.max(np.abs(accel_g)))
