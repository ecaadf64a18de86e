#!/usr/bin/python3
"""Tip displacement against time for one or more turgor runs, like TW 562 Figure 3 (fine scale vs
FE^2): every argument is a run's output directory (its tip.csv), or LABEL=DIR to name the curve.

  examples/plot_tip.py out/bending_bar_fine fe2=out/bending_bar_fe2 -o docs/figures/tip.png

Needs Debian's python3-matplotlib. The second panel shows each run's difference from the first one
where their sample times coincide (turgor samples tip.csv at equally spaced times by TS
interpolation, so runs with the same -*_tip_samples and final time line up)."""
import argparse, csv, os, sys

import matplotlib
matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt


def read_tip(run_dir):
    path = os.path.join(run_dir, "tip.csv")
    if not os.path.isfile(path):
        sys.exit(f"plot_tip.py: {path} not found (is {run_dir} a turgor output directory?)")
    t, y = [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            t.append(float(row["time"]))
            y.append(float(row["tip_displacement_y"]))
    if not t:
        sys.exit(f"plot_tip.py: {path} has no samples")
    return t, y


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directory, or LABEL=DIR")
    ap.add_argument("-o", "--output", default="tip.png", help="PNG file to write (default tip.png)")
    ap.add_argument("--title", default="Bending bar: tip displacement")
    a = ap.parse_args()

    curves = []
    for arg in a.runs:
        label, _, d = arg.partition("=") if "=" in arg else (os.path.basename(os.path.normpath(arg)), "", arg)
        curves.append((label, *read_tip(d)))

    fig, axes = plt.subplots(2 if len(curves) > 1 else 1, 1, sharex=True, figsize=(7, 6 if len(curves) > 1 else 4), squeeze=False)
    top = axes[0][0]
    for label, t, y in curves:
        top.plot(t, y, label=label, lw=1.2)
    top.set_ylabel("tip displacement y [µm]")
    top.set_title(a.title)
    top.grid(alpha=0.3)
    top.legend()
    if len(curves) > 1:
        bottom = axes[1][0]
        ref_label, t0, y0 = curves[0]
        ref = dict(zip((round(x, 9) for x in t0), y0))
        for label, t, y in curves[1:]:
            pairs = [(x, v - ref[round(x, 9)]) for x, v in zip(t, y) if round(x, 9) in ref]
            if not pairs:
                print(f"plot_tip.py: {label} shares no sample times with {ref_label}; no difference drawn", file=sys.stderr)
                continue
            bottom.plot([p[0] for p in pairs], [p[1] for p in pairs], label=f"{label} − {ref_label}", lw=1.0)
        bottom.set_ylabel("difference [µm]")
        bottom.grid(alpha=0.3)
        bottom.legend()
    axes[-1][0].set_xlabel("time [µs]")
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(a.output)), exist_ok=True)
    fig.savefig(a.output, dpi=120)
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
