#!/usr/bin/python3
"""A glued, turgid Voronoi tissue pulled apart under uniaxial strain, cell by cell: the fine
counterpart of the polygon RVE's tension path (bench/prve_ensemble.py --tension). The tissue of
config/voronoi_tangent_fine.yaml (the polygon RVE's cells and physics) scaled to --cells cells of
25 µm, held by its four grips (the sides hold x, top and bottom move y), inflated by its turgor
for 25 µs, then stretched in y at 0.01 µm/µs per grip to --strain. Prints, against the nominal
strain (the grips' separation over the height): the first bond that breaks, the first fall of the
top grip's stress sigma_yy = top_fy / W by more than --drop of the tension reached so far (a crack
that runs), and the peak of sigma_yy.

  bench/fine_tension.py [--turgor build/turgor] [--cells 256] [--seed 1] [--strain 0.03] [--drop 0.05]
                        [--keep DIR | --analyse DIR] [-- extra turgor options]

--analyse DIR reads the outputs of an earlier run (--keep DIR) instead of running.
"""
import argparse, csv, math, os, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
SPEED = 0.01  # µm/µs per grip
DELAY = 25.0  # µs: the turgor settles first


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default=os.path.join(HERE, "..", "build", "turgor"))
    ap.add_argument("--scene", default=os.path.join(HERE, "..", "config", "voronoi_tangent_fine.yaml"))
    ap.add_argument("--cells", type=int, default=256)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--strain", type=float, default=0.03)
    ap.add_argument("--drop", type=float, default=0.05)
    ap.add_argument("--keep", help="keep the run's outputs here")
    ap.add_argument("--analyse", help="only read an earlier run's outputs from here (the same --cells)")
    ap.add_argument("extra", nargs="*", help="further turgor options (after --)")
    a = ap.parse_args()
    L = 25.0 * math.sqrt(a.cells)  # µm: a square of cells of 25 µm
    g = 12.5  # µm: the grips' depth
    stretch = a.strain * L / (2 * SPEED)  # µs per grip
    with tempfile.TemporaryDirectory() as tmp:
        out = a.analyse or a.keep or os.path.join(tmp, "fine")
        cmd = [a.turgor, "-options_file_yaml", a.scene, "-tissue_voronoi_cells", str(a.cells), "-tissue_seed", str(a.seed),
               "-tissue_box", f"0,0,{L},{L}", "-control_left_box", f"-1,-1,{g},{L + 1}", "-control_right_box", f"{L - g},-1,{L + 1},{L + 1}",
               "-control_bottom_box", f"{g},-1,{L - g},{g}", "-control_top_box", f"{g},{L - g},{L - g},{L + 1}", "-control_bottom_duration",
               repr(stretch), "-control_top_duration", repr(stretch), "-ts_max_time", repr(DELAY + stretch), "-fine_snapshots", "0",
               "-fine_tip_samples", str(int(4 * stretch)), "-fine_progress_interval", "0", "-output_dir", out, "-output_overwrite"] + a.extra
        t0 = time.time()
        if not a.analyse:
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit("fine run failed:\n" + (p.stdout + p.stderr)[-3000:])
        wall = time.time() - t0
        rows = list(csv.DictReader(open(os.path.join(out, "groups.csv"))))
        breaks = list(csv.DictReader(open(os.path.join(out, "breaks.csv"))))
    strain = lambda t: max(t - DELAY, 0.0) * 2 * SPEED / L
    eps = [(float(r["top_uy"]) - float(r["bottom_uy"])) / L for r in rows]
    syy = [float(r["top_fy"]) / L for r in rows]
    i_peak = max(range(len(syy)), key=lambda i: syy[i])
    first_break = strain(float(breaks[0]["time"])) if breaks else float("nan")
    drop, top = float("nan"), -math.inf  # the first fall below the tension reached so far (in tension, once stretching)
    for e, s in zip(eps, syy):
        if e > 0 and top > 0 and s < (1 - a.drop) * top:
            drop = e
            break
        top = max(top, s) if e > 0 else top
    print(f"{a.cells} cells ({L:g} µm square), seed {a.seed}, to a strain of {a.strain:g}: {len(breaks)} bonds broken" + ("" if a.analyse else f", {wall:.0f} s"))
    print(f"  prestress sigma_yy at rest {syy[0]:.4g} N/m")
    print(f"  first bond broken at strain {100 * first_break:.3f} %")
    print(f"  first fall of sigma_yy by more than {100 * a.drop:g} % at strain {100 * drop:.3f} %")
    print(f"  peak sigma_yy {syy[i_peak]:.4g} N/m at strain {100 * eps[i_peak]:.3f} %")


if __name__ == "__main__":
    main()
