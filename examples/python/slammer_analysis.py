#!/usr/bin/env python3
"""SLAMMER-style rigid-block (Newmark) analysis of every record in a folder with topple.

For each record and each critical acceleration ky (g), the one-way (down-slope) sliding displacement of a rigid
block, for the record as given ("normal") and inverted, and their mean, as SLAMMER's rigid-block analysis reports
it. On level ground with friction mu the yield acceleration is mu g, so ky = mu here.

Usage: python examples/python/slammer_analysis.py OUT_DIR [--records DIR] [--ky 0.05 0.1 0.2] [--max-records N]
Records default to ../shared/records/slammer beside the clone (SLAMMER's sample records) when it exists, else three
synthetic motions (topple.synth). Prints a table and writes OUT_DIR/slammer_displacements.png and
OUT_DIR/slammer_history.png (headless: matplotlib's Agg backend).
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

import topple  # noqa: E402
import topple.plot  # noqa: E402

DEFAULT_RECORDS = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "records" / "slammer"


def load_motions(folder, max_records):
    if folder is not None and folder.is_dir():
        files = sorted(p for p in folder.iterdir() if p.suffix.lower() in (".csv", ".at2", ".txt")
                       and p.name != "gm_summary.csv")
        motions = []
        for path in files[:max_records]:
            try:
                motions.append((path.stem, topple.read(str(path))))
            except topple.InputError as err:
                print(f"skipped {path.name}: {err}")
        if motions:
            return motions
    print("no record folder: using synthetic motions (topple.synth)")
    return [(f"synthetic seed {s}", topple.synth(pga_g=0.4, freq_hz=f, duration_s=20.0, seed=s))
            for s, f in ((1, 1.5), (2, 3.0), (3, 6.0))][:max_records]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("--records", type=pathlib.Path, default=DEFAULT_RECORDS)
    parser.add_argument("--ky", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.2, 0.3])
    parser.add_argument("--max-records", type=int, default=1000)
    args = parser.parse_args()
    args.out_dir.mkdir(parents=True, exist_ok=True)

    motions = load_motions(args.records, args.max_records)
    print(f"{'record':<34} {'PGA g':>6} {'ky g':>5} {'normal cm':>10} {'inverse cm':>10} {'mean cm':>9}")
    table = {}
    for name, motion in motions:
        rows = []
        for ky in args.ky:
            normal = topple.slide(motion, mu=ky, mode="one-way", history=False).max_abs_displacement_m
            inverse = topple.slide(motion.inverted(), mu=ky, mode="one-way", history=False).max_abs_displacement_m
            rows.append((normal, inverse))
            print(f"{name[:34]:<34} {motion.pga_g:6.3f} {ky:5.2f} {100 * normal:10.3f} {100 * inverse:10.3f} "
                  f"{50 * (normal + inverse):9.3f}")
        table[name] = (motion, np.array(rows))

    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 5.5), layout="constrained")
    ax = fig.subplots()
    for name, (motion, rows) in table.items():
        mean_cm = 50.0 * rows.sum(axis=1)
        ky_ratio = np.array(args.ky) / motion.pga_g
        keep = mean_cm > 0
        ax.plot(ky_ratio[keep], mean_cm[keep], marker="o", lw=0.8, label=name[:28])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ky / PGA")
    ax.set_ylabel("mean rigid-block displacement (cm)")
    ax.set_title("Rigid-block (one-way) displacements, topple")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize="x-small", ncol=2)
    fig.savefig(args.out_dir / "slammer_displacements.png", dpi=110)

    name, (motion, _) = next(iter(table.items()))
    result = topple.slide(motion, mu=args.ky[len(args.ky) // 2], mode="one-way")
    topple.plot.sliding(motion, result).savefig(args.out_dir / "slammer_history.png", dpi=110)
    print(f"figures written to {args.out_dir}/slammer_displacements.png and slammer_history.png")


if __name__ == "__main__":
    main()
