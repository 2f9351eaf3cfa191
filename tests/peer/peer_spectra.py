#!/usr/bin/env python3
"""Peer values for tests/motion/test_spectra.cpp, computed at test time by pyrotd and eqsig (scripts/test-venv.sh).

Usage: peer_spectra.py ACCEL_FILE DT PERIODS_JSON UPSAMPLE PAD_S
  ACCEL_FILE  acceleration samples in m/s2, one per line (written by the test from topple's reader)
  DT          their interval, s
  PERIODS     JSON list of oscillator periods, s
  UPSAMPLE    integer k: pyrotd gets the record linearly interpolated at dt/k (the same piecewise-linear function)
  PAD_S       seconds of zeros appended before pyrotd's FFT, so that its circular response does not wrap around

Prints one JSON object:
  pyrotd_psa     5 %-damped PSA (m/s2) of the upsampled, padded record (frequency-domain method)
  eqsig_nj_sd    5 %-damped SD (m) by eqsig's Nigam-Jennings recurrence on the record as given
  eqsig_arias    Arias intensity (m/s), eqsig's trapezoid rule and g = 9.81
  eqsig_cav      CAV (m/s), trapezoid rule of |a|
  eqsig_d5_95    D5-95 (s), sample-level crossings of eqsig's Husid curve
"""
import json
import sys

import numpy as np
import eqsig
import eqsig.im
import eqsig.sdof
import pyrotd


def main():
    path, dt, periods, up, pad = sys.argv[1], float(sys.argv[2]), json.loads(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
    acc = np.loadtxt(path, dtype=float)
    periods = np.asarray(periods, dtype=float)
    n = len(acc)
    fine_t = np.arange((n - 1) * up + 1) * (dt / up)
    fine = np.interp(fine_t, np.arange(n) * dt, acc)
    fine = np.concatenate([fine, np.zeros(int(round(pad / (dt / up))))])
    psa = pyrotd.calc_spec_accels(dt / up, fine, 1.0 / periods, osc_damping=0.05).spec_accel
    sd, _, _ = eqsig.sdof.pseudo_response_spectra(acc, dt, periods, 0.05)
    asig = eqsig.AccSignal(acc, dt)
    out = {
        "pyrotd_psa": [float(x) for x in psa],
        "eqsig_nj_sd": [float(x) for x in sd],
        "eqsig_arias": float(eqsig.im.calc_arias_intensity(asig)[-1]),
        "eqsig_cav": float(eqsig.im.calc_cav(asig)[-1]),
        "eqsig_d5_95": float(eqsig.im.calc_sig_dur(asig)),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
