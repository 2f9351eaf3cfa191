#!/usr/bin/env python3
"""Python-call overhead of topple.slide, and topple from Python side by side with pySLAMMER.

Usage:  scripts/python-venv.sh && scripts/bench-venv.sh && cmake --build --preset release --target bench_sliding
        .venv-py/bin/python bench/python_overhead.py [build/release]

1. Overhead. topple.slide(history=False) from Python on the first 20,000 samples of Kocaeli 1999 ATS-090
   (../shared/records/slammer; the record of bench_sliding), two-way, mu = 0.40 PGA/g, against the C++ benchmark
   BM_TwoWaySliding/40 on the same record: time per call, best of several repeats.
2. pySLAMMER. Its own sample records (pyslammer.sample_ground_motions(), SLAMMER's set), rigid block, one-way,
   ky = 20 % of each record's PGA, record as given: displacement and time of pySLAMMER's RigidAnalysis against
   topple.slide(mode="one-way", mu=ky). pySLAMMER runs in .venv-bench (scripts/bench-venv.sh) through a subprocess
   when it is not importable here; the records come back from it as arrays, so both programs see the same samples.
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import timeit

import numpy as np

import topple

root = pathlib.Path(__file__).resolve().parents[1]
build = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "build" / "release"


def best_seconds(fn, number):
    return min(timeit.repeat(fn, number=number, repeat=7)) / number


def overhead():
    record = root.parent / "shared" / "records" / "slammer" / "Kocaeli_1999_ATS-090.csv"
    if not record.is_file():
        print(f"overhead: {record} absent (../shared); skipped")
        return
    full = topple.read(str(record))
    motion = topple.GroundMotion(np.ascontiguousarray(full.accel_m_s2[:20000]), full.dt_s, units="m/s2")
    mu = 0.40 * motion.pga_m_s2 / topple.STANDARD_GRAVITY
    py_summary = best_seconds(lambda: topple.slide(motion, mu=mu, history=False), 200)
    py_history = best_seconds(lambda: topple.slide(motion, mu=mu), 50)
    py_json = best_seconds(lambda: topple.slide(motion, mu=mu, history=False).json(), 200)
    tiny = topple.GroundMotion(np.array([0.0, 0.01, 0.0]), 0.01)
    py_call = best_seconds(lambda: topple.slide(tiny, mu=0.3, history=False), 20000)
    accel = np.ascontiguousarray(full.accel_m_s2[:20000])
    py_make = best_seconds(lambda: topple.GroundMotion(accel, 0.005, units="m/s2"), 500)
    out = subprocess.run([str(build / "bench" / "bench_sliding"), "--benchmark_filter=BM_TwoWaySliding/40$",
                          "--benchmark_format=json", "--benchmark_min_time=0.5"],
                         check=True, capture_output=True, text=True).stdout
    b = json.loads(out)["benchmarks"][0]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    cpp = b["cpu_time"] * scale
    print(f"record: Kocaeli 1999 ATS-090, {len(motion)} samples, two-way, mu = {mu:.5f} (0.40 PGA/g)")
    print(f"C++ BM_TwoWaySliding/40:               {cpp * 1e6:9.1f} us per call")
    print(f"topple.slide(history=False):           {py_summary * 1e6:9.1f} us per call "
          f"(overhead {1e6 * (py_summary - cpp):+.1f} us, {100 * (py_summary - cpp) / cpp:+.1f} %)")
    print(f"topple.slide on a 3-sample motion:     {py_call * 1e6:9.2f} us per call (the fixed cost of a call)")
    print(f"topple.slide(history=False).json():    {py_json * 1e6:9.1f} us per call")
    print(f"topple.slide() with history arrays:    {py_history * 1e6:9.1f} us per call")
    print(f"topple.GroundMotion(20,000 float64):   {py_make * 1e6:9.1f} us (one copy of the samples)")


PYSLAMMER_RUNNER = r"""
import sys, time
import numpy as np
import pyslammer
out = {}
for name in sorted(pyslammer.sample_ground_motions()):
    gm = pyslammer.load_sample_ground_motion(name)
    accel = np.asarray(gm.accel, dtype=np.float64)
    ky = 0.2 * float(np.max(np.abs(accel)))
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        result = pyslammer.RigidAnalysis(ky, gm)
        best = min(best, time.perf_counter() - start)
    out[name + "__accel_g"] = accel
    out[name + "__meta"] = np.array([float(gm.dt), ky, float(result.max_sliding_disp), best])
np.savez(sys.argv[1], **out)
"""


def pyslammer_side_by_side():
    with tempfile.TemporaryDirectory() as tmp:
        npz = pathlib.Path(tmp) / "pyslammer.npz"
        try:
            import pyslammer  # noqa: F401
            python = sys.executable
        except ImportError:
            python = str(root / ".venv-bench" / "bin" / "python")
            if not pathlib.Path(python).is_file():
                print("pySLAMMER: not installed here nor in .venv-bench (scripts/bench-venv.sh); skipped")
                return
        subprocess.run([python, "-c", PYSLAMMER_RUNNER, str(npz)], check=True)
        data = np.load(npz)
        names = sorted({k.split("__")[0] for k in data.files})
        print(f"\npySLAMMER sample records, rigid block, one-way, ky = 20 % PGA, record as given")
        print(f"{'record':<32} {'npts':>6} {'pySLAMMER cm':>13} {'topple cm':>11} {'diff %':>8} "
              f"{'pySLAMMER ms':>13} {'topple ms':>10} {'ratio':>7}")
        total_py = total_tp = 0.0
        worst = 0.0
        for name in names:
            accel = data[name + "__accel_g"]
            dt, ky, py_disp, py_s = data[name + "__meta"]
            motion = topple.GroundMotion(accel, float(dt), units="g", g=9.80665)
            tp_s = best_seconds(lambda: topple.slide(motion, mu=ky, mode="one-way", history=False), 20)
            tp_disp = topple.slide(motion, mu=ky, mode="one-way", history=False).max_abs_displacement_m
            diff = 100.0 * (py_disp - tp_disp) / tp_disp if tp_disp > 0 else 0.0
            worst = max(worst, abs(diff))
            total_py += py_s
            total_tp += tp_s
            print(f"{name[:32]:<32} {len(accel):6d} {100 * py_disp:13.4f} {100 * tp_disp:11.4f} {diff:+8.3f} "
                  f"{1e3 * py_s:13.2f} {1e3 * tp_s:10.4f} {py_s / tp_s:7.0f}x")
        print(f"all {len(names)} records: pySLAMMER {total_py:.3f} s, topple from Python {1e3 * total_tp:.2f} ms: "
              f"{total_py / total_tp:.0f}x; largest displacement difference {worst:.3f} %")


if __name__ == "__main__":
    overhead()
    pyslammer_side_by_side()
