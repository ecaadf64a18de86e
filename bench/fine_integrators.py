#!/usr/bin/python3
"""Work-precision of the adaptive explicit integrators on the fine bending bar: DOPRI (rk 5dp, the
bar's default, 15 state vectors) and the low-storage pair lsrk (RK4(3)5[3S*], 4 state vectors).

Each integrator runs config/bending_bar_fine.yaml to --t-final at rtol = atol = tol for every tol,
and once more at --ref-tol as the reference (DOPRI; the lsrk reference is run too and their
difference printed, so the reference's own error is known). Error of a run: max over the tip.csv
sample times (interpolated by TS at equally spaced times) of |y - y_ref| / max |y_ref|, y the
vertical tip displacement. Cost: wall time, steps, rejected steps and right-hand side evaluations
(interpolation's included) from summary.json. Runs are interleaved (for each tolerance, every
integrator in turn), one at a time.

    bench/fine_integrators.py                                 # 20 µs, tol 1e-2 .. 1e-7
    bench/fine_integrators.py --t-final 5 --tols 1e-3 1e-5   # quick
    bench/fine_integrators.py --integrators dopri lsrk lsrk_basic

Prints a table and writes fine_integrators.csv in --out.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INTEGRATORS = {  # name -> turgor options
    "dopri": ["-ts_type", "rk", "-ts_rk_type", "5dp"],
    "dopri_dsp": ["-ts_type", "rk", "-ts_rk_type", "5dp", "-ts_adapt_type", "dsp"],
    "lsrk": ["-ts_type", "lsrk"],
    "lsrk_basic": ["-ts_type", "lsrk", "-ts_adapt_type", "basic"],
}


def run(args, name, tol):
    out = os.path.join(args.out, f"{name}_{tol:g}")
    cmd = [args.binary, "-options_file_yaml", os.path.join(ROOT, "config", "bending_bar_fine.yaml"), "-ts_max_time", str(args.t_final),
           "-ts_rtol", str(tol), "-ts_atol", str(tol), "-fine_snapshots", "0", "-fine_progress_interval", "0", "-output_overwrite",
           "-output_dir", out] + INTEGRATORS[name]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "tip.csv")) as f:
        rows = list(csv.DictReader(f))
    tip = [(float(r["time"]), float(r["tip_displacement_y"])) for r in rows]
    return s, tip


def error(tip, ref):
    scale = max(abs(y) for _, y in ref)
    if len(tip) != len(ref) or any(abs(a[0] - b[0]) > 1e-9 * max(1, abs(b[0])) for a, b in zip(tip, ref)):
        sys.exit("tip.csv sample times differ between runs")
    return max(abs(a[1] - b[1]) for a, b in zip(tip, ref)) / scale


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "turgor"))
    ap.add_argument("--integrators", nargs="+", default=["dopri", "lsrk"], choices=sorted(INTEGRATORS))
    ap.add_argument("--tols", type=float, nargs="+", default=[1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7])
    ap.add_argument("--ref-tol", type=float, default=1e-10)
    ap.add_argument("--t-final", type=float, default=20.0, help="µs")
    ap.add_argument("--out", default="fine_integrators_runs")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    _, ref = run(args, "dopri", args.ref_tol)
    _, ref_ls = run(args, "lsrk", args.ref_tol)
    print(f"reference: dopri at tol {args.ref_tol:g}; lsrk at the same tolerance differs from it by {error(ref_ls, ref):.2e} (relative, max over samples)")
    rows = []
    print(f"{'integrator':>11} {'tol':>7} {'error':>9} {'error/tol':>9} {'steps':>7} {'rejected':>8} {'evaluations':>11} {'wall [s]':>8}")
    for tol in args.tols:
        for name in args.integrators:
            s, tip = run(args, name, tol)
            e = error(tip, ref)
            rows.append(dict(integrator=name, tol=tol, error=e, steps=s["steps"], rejected=s["rejected_steps"], rhs_evals=s["rhs_evals"],
                             wall_s=round(s["wall_time_s"], 3), t_final=args.t_final))
            print(f"{name:>11} {tol:>7.0e} {e:>9.2e} {e / tol:>9.2f} {s['steps']:>7} {s['rejected_steps']:>8} {s['rhs_evals']:>11} {s['wall_time_s']:>8.2f}")
    with open(os.path.join(args.out, "fine_integrators.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
