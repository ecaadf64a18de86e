#!/usr/bin/env python3
"""Memory per particle of a fine run: the slope of the largest rank's maximum resident set between
two sizes of the bending bar (the target: below 400 B a particle per rank, halo included).

Each case runs `-ts_max_steps 5` (the set-up and the run's steady state: the lists, the integrator's
work vectors) under `/usr/bin/time -f %M` on every rank; the particles of the largest rank are
summary.json's particles_per_rank_max plus halo_particles_max. The slope removes what does not
grow with the tissue (libraries, MPI and PETSc start-up). Repeats are averaged: the resident set of
one rank moves by about 1 MB from run to run on the 2-core VM of docs/scaling.md.

    bench/memory.py --ranks 1 2 --ts verlet rk --repeats 3
    bench/memory.py --sizes 32 64 --extra "-ts_rk_type 3bs"    # any further turgor options

Prints one row per (integrator, ranks) and writes memory.csv in --out.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_case(args, ts, ranks, size, rep):
    out = os.path.join(args.out, f"{ts}_np{ranks}_{size}_{rep}")
    os.makedirs(out, exist_ok=True)
    for f in os.listdir(out):
        if f.startswith("maxrss_kb."):
            os.remove(os.path.join(out, f))
    turgor = [args.binary, "-options_file_yaml", os.path.join(ROOT, "config", f"bending_bar_{size}_fine.yaml"), "-ts_type", ts, "-ts_max_steps", "5",
              "-fine_snapshots", "0", "-fine_progress_interval", "0", "-output_overwrite", "-output_dir", out] + args.extra.split()
    # each rank's figure into its own file (mpiexec may drop a rank's last stderr line at exit)
    rank_cmd = f"exec /usr/bin/time -f %M -o {out}/maxrss_kb.$OMPI_COMM_WORLD_RANK " + " ".join(turgor)
    cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), "sh", "-c", rank_cmd]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    rss = []
    for f in sorted(os.listdir(out)):
        if f.startswith("maxrss_kb."):
            with open(os.path.join(out, f)) as g:
                rss += [int(x) for x in re.findall(r"^(\d+)$", g.read(), re.M)]
    if len(rss) != ranks:
        sys.exit(f"expected {ranks} resident-set figures, got {rss}: {' '.join(cmd)}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    particles = s["n_wall_particles"] + s["n_fluid_particles"] if ranks == 1 else s["particles_per_rank_max"] + s["halo_particles_max"]
    return max(rss) * 1024.0, particles


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "turgor"))
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--ts", nargs="+", default=["verlet", "rk"], help="-ts_type values")
    ap.add_argument("--sizes", type=int, nargs=2, default=[32, 64], help="the two bars (cells per side; config/bending_bar_<n>_fine.yaml)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--extra", default="", help="further turgor options, one string")
    ap.add_argument("--out", default="memory_runs")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    print(f"{'integrator':>10} {'ranks':>5} {'particles (small, large)':>26} {'B per particle':>15}  repeats (B)")
    for ts in args.ts:
        for ranks in args.ranks:
            slopes = []
            for rep in range(args.repeats):
                (r0, p0), (r1, p1) = (run_case(args, ts, ranks, size, rep) for size in args.sizes)
                slopes.append((r1 - r0) / (p1 - p0))
            mean = sum(slopes) / len(slopes)
            rows.append(dict(integrator=ts, ranks=ranks, particles_small=p0, particles_large=p1, bytes_per_particle=round(mean, 1),
                             repeats=" ".join(f"{b:.0f}" for b in slopes)))
            print(f"{ts:>10} {ranks:>5} {p0:>12} {p1:>13} {mean:>15.0f}  {rows[-1]['repeats']}")
    with open(os.path.join(args.out, "memory.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
