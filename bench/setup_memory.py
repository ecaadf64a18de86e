#!/usr/bin/env python3
"""The set-up's peak memory per rank on 2 ranks against 1: a tissue generated (or read) in parts
under -fine_partitioner ranges, against METIS (every rank generates the whole tissue) and one rank
(the target: the larger rank's peak at most 0.6 of the 1-rank peak).

For each tissue size three runs of 2 steps (TS verlet): one rank, two ranks dealt by METIS, two ranks
in parts; summary.json's peak_rss_setup_bytes (the largest rank's resident set at the end of the
set-up), the halo (halo_particles_max: the space order's ranges against METIS's parts, a measure
of the cut) and the wall time of each run.

  --tissue square      the bending bar of N x N cells (config/bending_bar_64_fine.yaml)
  --tissue voronoi     N Voronoi cells of 25 µm in a square, the glued Voronoi bar's physics
                       (config/voronoi_bar_fine.yaml)
  --tissue node_file   N square cells of 23.95 µm at a 25 µm pitch, 40 nodes each, written to a node
                       file in a shuffled order (its numbering in no spatial order), the same physics

    bench/setup_memory.py --tissue voronoi --sizes 10000 40000
    bench/setup_memory.py --tissue square --sizes 256 512

Prints one row per size and writes setup_memory.csv in --out.
"""
import argparse
import csv
import json
import math
import os
import random
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write_squares(path, n):
    """n x n square cells, 40 nodes each (10 a side), in a shuffled order"""
    pitch, side, k = 25.0, 23.95, 10
    cells = [(i, j) for j in range(n) for i in range(n)]
    random.Random(1).shuffle(cells)
    with open(path, "w") as f:
        f.write(f"# {n} x {n} square cells of {side} um at a pitch of {pitch} um, {4 * k} nodes each (bench/setup_memory.py)\n")
        for c, (i, j) in enumerate(cells):
            x0, y0 = i * pitch, j * pitch
            pts = [(x0 + side * t / k, y0) for t in range(k)] + [(x0 + side, y0 + side * t / k) for t in range(k)]
            pts += [(x0 + side - side * t / k, y0 + side) for t in range(k)] + [(x0, y0 + side - side * t / k) for t in range(k)]
            for x, y in pts:
                f.write(f"{x!r} {y!r} {c}\n")


def scene(args, size):
    if args.tissue == "square":
        return ["-options_file_yaml", os.path.join(ROOT, "config", "bending_bar_64_fine.yaml"), "-tissue_cells_x", str(size), "-tissue_cells_y", str(size)]
    voronoi = ["-options_file_yaml", os.path.join(ROOT, "config", "voronoi_bar_fine.yaml")]
    if args.tissue == "voronoi":
        L = round(25 * math.sqrt(size))
        return voronoi + ["-tissue_voronoi_cells", str(size), "-tissue_box", f"0,0,{L},{L}"]
    n = round(math.sqrt(size))
    path = os.path.join(args.out, f"squares_{n}.nodes")
    if not os.path.exists(path):
        write_squares(path, n)
    return voronoi + ["-tissue_type", "node_file", "-tissue_node_file", path]


def run(args, size, case):
    out = os.path.join(args.out, f"{args.tissue}_{size}_{case}")
    ranks = 1 if case == "one" else 2
    cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), args.binary] + scene(args, size)
    cmd += ["-ts_type", "verlet", "-ts_max_steps", "2", "-fine_snapshots", "0", "-fine_progress_interval", "0", "-output_overwrite", "-output_dir", out]
    if case == "parts":
        cmd += ["-fine_partitioner", "ranges"]
    t0 = time.time()
    p = subprocess.run(cmd + args.extra.split(), capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    s = json.load(open(os.path.join(out, "summary.json")))
    if case == "parts" and not s.get("setup_in_parts"):
        sys.exit(f"{out}: the tissue was not built in parts")
    return s, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tissue", choices=["square", "voronoi", "node_file"], default="voronoi")
    ap.add_argument("--sizes", type=int, nargs="+", default=[10000, 40000], help="cells (square: cells a side)")
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "turgor"))
    ap.add_argument("--out", default="out/setup_memory")
    ap.add_argument("--extra", default="", help="further turgor options (one string)")
    ap.add_argument("--check", action="store_true", help="exit 1 unless both 2-rank runs own every particle of the 1-rank run once (the ctest)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    print(f"{'size':>8} {'particles':>10} {'1 rank MB':>10} {'METIS MB':>9} {'ratio':>6} {'parts MB':>9} {'ratio':>6} {'halo METIS/parts':>17} {'wall 1/METIS/parts s':>21}")
    for size in args.sizes:
        r = {case: run(args, size, case) for case in ("one", "metis", "parts")}
        one, metis, parts = (r[c][0]["peak_rss_setup_bytes"] / 1e6 for c in ("one", "metis", "parts"))
        row = dict(tissue=args.tissue, size=size, particles=r["one"][0]["particles_per_rank_max"], one_mb=one, metis_mb=metis, parts_mb=parts,
                   metis_ratio=metis / one, parts_ratio=parts / one, halo_metis=r["metis"][0]["halo_particles_max"], halo_parts=r["parts"][0]["halo_particles_max"],
                   wall_one=r["one"][1], wall_metis=r["metis"][1], wall_parts=r["parts"][1])
        rows.append(row)
        if args.check:
            for c in ("metis", "parts"):
                owned = round(2 * r[c][0]["particles_per_rank_mean"])
                if owned != row["particles"] or r[c][0]["halo_particles_max"] <= 0:
                    sys.exit(f"FAIL: {args.tissue} {size}, {c}: {owned} particles owned on 2 ranks (1 rank: {row['particles']}), halo {r[c][0]['halo_particles_max']}")
        print(f"{size:>8} {row['particles']:>10} {one:>10.0f} {metis:>9.0f} {row['metis_ratio']:>6.3f} {parts:>9.0f} {row['parts_ratio']:>6.3f} "
              f"{row['halo_metis']:>8}/{row['halo_parts']:<8} {row['wall_one']:>6.1f}/{row['wall_metis']:.1f}/{row['wall_parts']:.1f}")
    with open(os.path.join(args.out, "setup_memory.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
