#!/usr/bin/env python3
"""A model of a distributed fine run's parallel efficiency at many ranks, from measured inputs.

  bench/scaling_model.py --one RUN1 --two RUN2 [--particles 1e7] [--ranks 64,128,256,512,1024]
                         [--latency 2e-6] [--bandwidth 12.5e9] [--neighbours 8]

RUN1 and RUN2 are the output directories of the same square tissue on 1 and 2 ranks (e.g. the
64 x 64-cell bending bar, bench/scaling.py's strong study). From them:

  t_eval   seconds per particle and force evaluation on one rank (wall time / (evaluations x particles))
  h_line   halo particles per cell length of cut (the 2-rank run's largest halo over the cut: a
           square tissue of C x C cells split in two halves is cut along C cells)
  checks   full halo checks per step (the 2-rank run's halo_full_checks / steps)
  b_line   bytes a full check receives per cell length of cut (the 2-rank run's halo_check_bytes per
           check, less the ranks' regions, over the cut)

and for N particles on P ranks (square parts of a square tissue with the run's particles per cell):

  compute   t_eval * (N / P) * imbalance                     per evaluation
  halo      4 sqrt(cells / P) h_line halo particles per rank; per evaluation the x and v of each come
            in (32 B) and its force goes out (16 B), in 2 rounds of `neighbours` messages:
            2 * neighbours * latency + 48 B * halo / bandwidth
  check     an allreduce of one number per evaluation: ceil(log2 P) * latency; and `checks` times per
            step a full check: an allgather of the ranks' regions (32 B a rank), the two-sided
            discovery of the neighbours (log2 P latency) and the boxes of the cells near the part's
            4 sqrt(cells / P)-cell boundary from `neighbours` ranks:
            2 log2 P latency + 32 P / bandwidth + neighbours latency + b_line 4 sqrt(cells / P) / bandwidth
            (a run without halo_check_bytes, from before the checks went to the neighbours only:
            an allgather of every cell's box, 40 B * cells / bandwidth + log2 P latency)
  E(P) = (t_eval N / P) / (compute + halo + check), the evaluations per step cancelling except in
  the full checks (counted per evaluation with the run's evaluations per step). The model leaves
  out what two ranks on one machine measure beyond it (shared memory bandwidth and caches, noise):
  the last column scales E(P) by the measured 2-rank efficiency over the model's for 2 ranks.

Assumptions (stated in docs/scaling.md): a network of `latency` per message and `bandwidth` per
rank (defaults: 2 µs and 12.5 GB/s, an InfiniBand HDR link, no overlap of communication and
computation, no gain from shared memory within a node), the per-particle cost of this machine's
core, METIS parts as compact as squares (measured cut 1.02-1.06 x the square bound), the imbalance
`--imbalance` (default 1.03: METIS at 16 parts on the 128 x 128 grid). Prints a markdown table.
"""
import argparse
import json
import math
import os
import sys


def load(d):
    with open(os.path.join(d, "summary.json")) as f:
        return json.load(f)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--one", required=True, help="output directory of the 1-rank run")
    ap.add_argument("--two", required=True, help="output directory of the same tissue on 2 ranks")
    ap.add_argument("--particles", type=float, default=1e7, help="particles of the modelled tissue (default 1e7)")
    ap.add_argument("--ranks", default="64,128,256,512,1024", help="rank counts (default 64,128,256,512,1024)")
    ap.add_argument("--latency", type=float, default=2e-6, help="seconds per message (default 2e-6)")
    ap.add_argument("--bandwidth", type=float, default=12.5e9, help="bytes per second per rank (default 12.5e9)")
    ap.add_argument("--neighbours", type=int, default=8, help="neighbouring ranks of a part (default 8: a square's sides and corners)")
    ap.add_argument("--imbalance", type=float, default=1.03, help="max / mean particles per rank (default 1.03)")
    a = ap.parse_args(argv)

    s1, s2 = load(a.one), load(a.two)
    n1 = s1["n_wall_particles"] + s1["n_fluid_particles"]
    cells1 = s1["n_cells"]
    evals_per_step = s1["rhs_evals"] / s1["steps"]
    t_eval = s1["wall_time_s"] / (s1["rhs_evals"] * n1)
    side = math.sqrt(cells1)  # the measured tissue is C x C cells
    h_line = s2["halo_particles_max"] / side
    checks = s2.get("halo_full_checks", 0) / max(s2["steps"], 1)
    neighbour_checks = "halo_check_bytes" in s2 and s2.get("halo_full_checks", 0) > 0
    b_line = (s2["halo_check_bytes"] / s2["halo_full_checks"] - 32 * s2["mpi_ranks"]) / side if neighbour_checks else 0.0
    per_cell = n1 / cells1
    cells = a.particles / per_cell
    print(f"inputs: t_eval = {t_eval * 1e9:.1f} ns per particle-evaluation ({n1} particles, {s1['rhs_evals']} evaluations, "
          f"{s1['wall_time_s']:.3f} s), {evals_per_step:.2f} evaluations per step, halo {s2['halo_particles_max']} particles over a "
          f"{side:.0f}-cell cut = {h_line:.2f} per cell length, {checks:.3f} full halo checks per step"
          + (f" receiving {b_line:.1f} B per cell length of cut" if neighbour_checks else " (every cell's box gathered)")
          + f", {per_cell:.2f} particles per cell")
    print(f"model: N = {a.particles:.3g} particles ({cells:.3g} cells), latency {a.latency * 1e6:g} µs, bandwidth {a.bandwidth / 1e9:g} GB/s, "
          f"{a.neighbours} neighbours, imbalance {a.imbalance}")
    print()
    def model(P, N, ncells, imbalance):
        comp = t_eval * N / P * imbalance
        halo = 4 * math.sqrt(ncells / P) * h_line if P > 1 else 0.0
        t_halo = (2 * a.neighbours * a.latency + 48 * halo / a.bandwidth) if P > 1 else 0.0
        lg = math.ceil(math.log2(P)) if P > 1 else 0
        if neighbour_checks:
            full = 2 * lg * a.latency + 32 * P / a.bandwidth + a.neighbours * a.latency + b_line * 4 * math.sqrt(ncells / P) / a.bandwidth
        else:
            full = 40 * ncells / a.bandwidth + lg * a.latency
        t_check = (lg * a.latency + checks / evals_per_step * full) if P > 1 else 0.0
        return comp, halo, t_halo, t_check, (t_eval * N / P) / (comp + t_halo + t_check)

    # the measured 2-rank efficiency against the model's for the measured tissue (its imbalance)
    e2 = (s1["wall_time_s"] / s1["steps"]) / (2 * s2["wall_time_s"] / s2["steps"])
    m2 = model(2, n1, cells1, s2.get("load_imbalance", 1.0))[4]
    print(f"measured 2-rank efficiency {e2:.3f}, the model's {m2:.3f}: scale {e2 / m2:.3f}")
    print()
    print("| ranks | particles per rank | halo per rank | compute / evaluation | halo / evaluation | check / evaluation | model | scaled |")
    print("|---|---|---|---|---|---|---|---|")
    for P in [int(r) for r in a.ranks.split(",")]:
        comp, halo, t_halo, t_check, eff = model(P, a.particles, cells, a.imbalance)
        print(f"| {P} | {a.particles / P:.3g} | {halo:.0f} | {comp * 1e6:.0f} µs | {t_halo * 1e6:.1f} µs | {t_check * 1e6:.1f} µs | {eff:.3f} | "
              f"{eff * e2 / m2:.3f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
