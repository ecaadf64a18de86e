#!/usr/bin/python3
"""The spectrum of a -mode eigen run as a PNG: every argument is a run's output directory (its
eigen.csv and summary.json), or LABEL=DIR.

  examples/plot_spectrum.py out/eigen -o spectrum.png
  examples/plot_spectrum.py relaxed=out/eigen_relaxed reference=out/eigen_reference -o spectrum.png

Left: the lowest modes' angular frequencies omega = sqrt(K phi = omega^2 M phi) [rad/µs] against
the mode number (log scale; filled where the mode is mostly transverse, open where it is mostly
along x: eigen.csv's x_fraction > 0.5), with omega_max (the explicit stability limit's frequency)
as a line. Right: with -eigen_damping (default), the damped eigenvalues s = -zeta omega + i omega_d in the
complex plane. Needs Debian's python3-matplotlib."""
import argparse, csv, json, math, os, sys

import matplotlib
matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt


def read_run(d):
    path = os.path.join(d, "eigen.csv")
    if not os.path.isfile(path):
        sys.exit(f"plot_spectrum.py: {path} not found (is {d} the output directory of a -mode eigen run?)")
    rows = list(csv.DictReader(open(path)))
    if not rows:
        sys.exit(f"plot_spectrum.py: {path} has no modes")
    summary = json.load(open(os.path.join(d, "summary.json")))
    return rows, summary


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="output directory, or LABEL=DIR")
    ap.add_argument("-o", "--output", default="spectrum.png", help="PNG file to write (default spectrum.png)")
    a = ap.parse_args()
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    for k, arg in enumerate(a.runs):
        label, _, d = arg.partition("=") if "=" in arg else (os.path.basename(os.path.normpath(arg)), "", arg)
        rows, s = read_run(d)
        colour = f"C{k}"
        for r in rows:
            lam, x = float(r["eigenvalue"]), float(r["x_fraction"])
            if lam <= 0:
                left.plot(int(r["mode"]), 1e-300, "x", color="red")
                continue
            left.plot(int(r["mode"]), math.sqrt(lam), "o", color=colour, mfc="none" if x > 0.5 else colour)
        left.plot([], [], "o", color=colour, label=f"{label}: {s.get('state', '')} state, {s.get('n_elements', '?')} elements")
        if s.get("omega_max"):
            left.axhline(s["omega_max"], color=colour, ls="--", lw=1, label=f"{label}: omega_max {s['omega_max']:.4g} rad/µs")
        if s.get("damped_real"):
            right.plot(s["damped_real"], s["damped_imag"], "o", color=colour, label=label)
    left.set_yscale("log")
    left.set_xlabel("mode")
    left.set_ylabel("omega [rad/µs]   (period 2 pi / omega [µs])")
    left.set_title("K phi = omega^2 M phi (open: mostly along x)")
    left.legend(fontsize=8)
    right.set_xlabel("Re s [1/µs] (decay)")
    right.set_ylabel("Im s [rad/µs] (damped omega)")
    right.set_title("(K + s C + s^2 M) phi = 0")
    right.axvline(0, color="grey", lw=0.5)
    if right.lines[1:]:
        right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
