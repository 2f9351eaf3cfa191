#!/usr/bin/env python3
"""Peer RotD50 / RotD100 for tests/motion/test_motion_set.cpp, computed at test time by pyrotd (scripts/test-venv.sh).

Usage: peer_rotd.py ACCEL_A ACCEL_B DT PERIODS_JSON UPSAMPLE PAD_S
  ACCEL_A, ACCEL_B  the two horizontal components in m/s2, one sample per line, equal lengths (written by the test)
  DT                their interval, s
  PERIODS           JSON list of oscillator periods, s
  UPSAMPLE          integer k: pyrotd gets the records linearly interpolated at dt/k (the same piecewise-linear
                    functions topple integrates exactly)
  PAD_S             seconds of zeros appended before pyrotd's FFT, so that its circular response does not wrap around

Prints one JSON object:
  psa_rotd50, psa_rotd100   5 %-damped PSA (m/s2) at the periods, pyrotd.calc_rotated_spec_accels, method="rigorous"
                            (every time step; "optimized" looks only at samples above a threshold, Stewart et al. 2017)
  pga_rotd50, pga_rotd100   of the records as given, pyrotd.calc_rotated_percentiles (rigorous)
"""
import json
import sys

import numpy as np
import pyrotd


def fine(acc, dt, up, pad):
    n = len(acc)
    t = np.arange((n - 1) * up + 1) * (dt / up)
    f = np.interp(t, np.arange(n) * dt, acc)
    return np.concatenate([f, np.zeros(int(round(pad / (dt / up))))])


def main():
    a = np.loadtxt(sys.argv[1], dtype=float)
    b = np.loadtxt(sys.argv[2], dtype=float)
    dt, periods, up, pad = float(sys.argv[3]), np.asarray(json.loads(sys.argv[4])), int(sys.argv[5]), float(sys.argv[6])
    angles = np.arange(0, 180, step=1)
    res = pyrotd.calc_rotated_spec_accels(dt / up, fine(a, dt, up, pad), fine(b, dt, up, pad), 1.0 / periods,
                                          osc_damping=0.05, percentiles=[50, 100], angles=angles, method="rigorous")
    out = {"psa_rotd50": [], "psa_rotd100": []}
    for f in 1.0 / periods:
        for pct, key in ((50, "psa_rotd50"), (100, "psa_rotd100")):
            row = res[(np.isclose(res.osc_freq, f)) & (res.percentile == pct)]
            out[key].append(float(row.spec_accel[0]))
    pga = pyrotd.calc_rotated_percentiles([a, b], angles, [50, 100], method="rigorous")
    out["pga_rotd50"] = float(pga.spec_accel[0])
    out["pga_rotd100"] = float(pga.spec_accel[1])
    print(json.dumps(out))


if __name__ == "__main__":
    main()
