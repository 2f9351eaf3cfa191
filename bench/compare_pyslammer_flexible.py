#!/usr/bin/env python3
"""Side-by-side: pySLAMMER's decoupled and coupled analyses vs topple's, same record, same sliding mass, one run.

Usage: scripts/bench-venv.sh && .venv-bench/bin/python bench/compare_pyslammer_flexible.py [build/release]

Record: the first 20,000 samples of Kocaeli 1999 ATS-090 (../shared/records/slammer), as in bench_flexible. Sliding
mass: H = 50 m, V_s = V_b = 600 m/s, material damping -5 % (15 % with the impedance damping), k_y = 20 % of PGA,
linear elastic, one-way. topple's figures come from bench_flexible (BM_SlammerDecoupled, BM_SlammerCoupled);
pySLAMMER's from timing Decoupled and Coupled on the same samples (best of 3 runs). Both in CPU time (Google
Benchmark's, and time.process_time here, all of the process' threads): on a shared machine wall time counts the other
processes' turns against pySLAMMER only.
"""
import json
import subprocess
import time

import pyslammer

from kocaeli_record import build_dir, load

build = build_dir()
accel_g, dt, ky_g = load()

gm = pyslammer.GroundMotion(accel_g, dt, "Kocaeli_1999_ATS-090")

out = subprocess.run([str(build / "bench" / "bench_flexible"), "--benchmark_filter=BM_Slammer(Dec|C)oupled$",
                      "--benchmark_format=json", "--benchmark_min_time=0.5"],
                     check=True, capture_output=True, text=True).stdout
ours = {b["name"]: b for b in json.loads(out)["benchmarks"]}

print(f"record: Kocaeli 1999 ATS-090, {len(accel_g)} samples, dt = {dt} s; ky = {ky_g:.5f} g (20 % of PGA), one-way")
print("sliding mass: H = 50 m, Vs = Vb = 600 m/s, damping -5 % + 20 % impedance, linear elastic")
for name, cls in (("BM_SlammerDecoupled", pyslammer.Decoupled), ("BM_SlammerCoupled", pyslammer.Coupled)):
    best = float("inf")
    for _ in range(3):
        start = time.process_time()
        result = cls(ky_g, gm, 50.0, 600.0, 600.0, -0.05)
        best = min(best, time.process_time() - start)
    py_rate = len(accel_g) / best
    py_cm = 100.0 * result.max_sliding_disp
    rate = ours[name]["items_per_second"]
    cm = ours[name]["residual_cm"]
    print(f"{cls.__name__:10s} pySLAMMER {py_rate / 1e3:9.1f} k samples/s, {py_cm:.4f} cm | topple {rate / 1e6:8.2f} M "
          f"samples/s, {cm:.4f} cm | speed ratio {rate / py_rate:.0f}x, displacement difference "
          f"{100.0 * (py_cm - cm) / cm:+.2f} %")
