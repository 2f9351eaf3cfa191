#!/usr/bin/env python3
"""Rocking and overturning of a few household objects under one record, at several shaking levels, with topple.

Usage: python examples/python/rocking_objects.py OUT_DIR [--record FILE] [--pga 0.2 0.4 0.8]
The record defaults to ../shared/records/Rinaldi228.AT2 beside the clone when it exists, else a synthetic motion.
Prints a table (uplift threshold a/h in g, max |theta| / alpha, overturned) and writes OUT_DIR/rocking_objects.png
(max |theta|/alpha per object and PGA) and OUT_DIR/rocking_history.png (headless: matplotlib's Agg backend).
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import topple  # noqa: E402
import topple.plot  # noqa: E402

DEFAULT_RECORD = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "records" / "Rinaldi228.AT2"

# Dimensions in metres.
OBJECTS = {
    "vase (cylinder 8 x 40 cm)": topple.Cylinder(diameter=0.08, height=0.40),
    "speaker (block 15 x 60 cm)": topple.Block(width=0.15, height=0.60),
    "book (block 3 x 24 cm)": topple.Block(width=0.03, height=0.24),
    "bottle (cylinder 7 x 30 cm)": topple.Cylinder(diameter=0.07, height=0.30),
    "cabinet (block 45 x 180 cm)": topple.Block(width=0.45, height=1.80),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("--record", type=pathlib.Path, default=DEFAULT_RECORD)
    parser.add_argument("--pga", type=float, nargs="+", default=[0.2, 0.4, 0.8])
    args = parser.parse_args()
    args.out_dir.mkdir(parents=True, exist_ok=True)

    if args.record.is_file():
        motion = topple.read(str(args.record))
    else:
        print("no record: using a synthetic motion (topple.synth, 2 Hz, seed 1)")
        motion = topple.synth(pga_g=0.4, freq_hz=2.0, duration_s=20.0, seed=1)
    print(f"motion: {motion}")
    print(f"{'object':<30} {'a/h':>6} {'PGA g':>6} {'max th/alpha':>12} {'overturned':>10}")
    ratios = np.zeros((len(OBJECTS), len(args.pga)))
    for i, (name, body) in enumerate(OBJECTS.items()):
        for j, pga in enumerate(args.pga):
            r = topple.rock(motion.scaled_to_pga(pga), body, history=False)
            ratios[i, j] = min(r.max_rotation_over_alpha, np.pi / 2 / r.alpha_rad)
            print(f"{name:<30} {body.a_m / body.h_m:6.3f} {pga:6.2f} {r.max_rotation_over_alpha:12.4g} "
                  f"{'yes' if r.overturned else 'no':>10}")

    fig = Figure(figsize=(9, 5), layout="constrained")
    ax = fig.subplots()
    width = 0.8 / len(args.pga)
    x = np.arange(len(OBJECTS))
    for j, pga in enumerate(args.pga):
        ax.bar(x + (j - (len(args.pga) - 1) / 2) * width, ratios[:, j], width, label=f"PGA {pga:g} g")
    ax.axhline(1.0, color="tab:red", ls="--", lw=1, label="|theta| = alpha")
    ax.set_xticks(x, [n.split(" (")[0] for n in OBJECTS], rotation=0)
    ax.set_yscale("symlog", linthresh=0.01)
    ax.set_ylabel("max |theta| / alpha (capped at the fall)")
    ax.set_title(f"Rocking of household objects: {motion.name or 'synthetic motion'}")
    ax.legend(fontsize="small")
    fig.savefig(args.out_dir / "rocking_objects.png", dpi=110)

    name, body = next(iter(OBJECTS.items()))
    scaled = motion.scaled_to_pga(args.pga[len(args.pga) // 2])
    topple.plot.rocking(scaled, topple.rock(scaled, body)).savefig(args.out_dir / "rocking_history.png", dpi=110)
    print(f"figures written to {args.out_dir}/rocking_objects.png and rocking_history.png")


if __name__ == "__main__":
    main()
