#!/usr/bin/env python3
"""Side-by-side: pySLAMMER's rigid-block analysis vs topple's one-way sliding, same record, same ky, one run.

Usage: scripts/bench-venv.sh && .venv-bench/bin/python bench/compare_pyslammer.py [build/release]

The record is the first 20,000 samples of Kocaeli 1999 ATS-090 (../shared/records/slammer), as in bench_sliding.
topple's figure comes from its Google Benchmark program (BM_OneWaySliding/20: ky = 20 % of PGA); pySLAMMER's from
timing RigidAnalysis on the same samples with the same ky (best of 5 runs).
"""
import json
import subprocess
import time

import pyslammer

from kocaeli_record import build_dir, load

build = build_dir()
accel_g, dt, ky_g = load()

gm = pyslammer.GroundMotion(accel_g, dt, "Kocaeli_1999_ATS-090")
best = float("inf")
for _ in range(5):
    start = time.perf_counter()
    result = pyslammer.RigidAnalysis(ky_g, gm)
    best = min(best, time.perf_counter() - start)
py_rate = len(accel_g) / best
py_disp_cm = 100.0 * result.max_sliding_disp

out = subprocess.run([str(build / "bench" / "bench_sliding"), "--benchmark_filter=BM_OneWaySliding/20$",
                      "--benchmark_format=json", "--benchmark_min_time=0.5"],
                     check=True, capture_output=True, text=True).stdout
bench = json.loads(out)["benchmarks"][0]
topple_rate = bench["items_per_second"]
topple_disp_cm = bench["residual_cm"]

print(f"record: Kocaeli 1999 ATS-090, {len(accel_g)} samples, dt = {dt} s; ky = {ky_g:.5f} g (20 % of PGA), one-way")
print(f"pySLAMMER {pyslammer.__version__ if hasattr(pyslammer, '__version__') else ''}: "
      f"{py_rate / 1e6:8.3f} M samples/s, displacement {py_disp_cm:.4f} cm")
print(f"topple:     {topple_rate / 1e6:8.1f} M samples/s, displacement {topple_disp_cm:.4f} cm")
print(f"speed ratio topple / pySLAMMER: {topple_rate / py_rate:.0f}x; "
      f"displacement difference {100.0 * (py_disp_cm - topple_disp_cm) / topple_disp_cm:+.2f} %")
