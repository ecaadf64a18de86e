#!/usr/bin/python3
"""The RVE size of irregular tissue: the polygon RVE (config/polygon_rve.yaml: glued, turgid Voronoi
cells) at rest for K cells and several seeds; per K the mean and standard deviation of its
homogenised tangent (C11, C22, C12, C33 = D^e 11,11, 22,22, 11,22, 12,12) and of its turgor
prestress (the mean of sigma11 and sigma22), and the smallest K whose mean is within 2 % of the
largest K's and whose standard deviation is below 5 % of its mean. Writes a CSV of every run and
prints a Markdown table.

  bench/prve_ensemble.py [--turgor build/turgor] [--cells 4,16,64] [--seeds 10] [--jobs 1] [--csv prve_ensemble.csv]
                         [-- extra turgor options]
"""
import argparse, concurrent.futures, csv, math, os, statistics, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
QUANTITIES = [("C11", "De11_11"), ("C22", "De22_22"), ("C12", "De11_22"), ("C33", "De12_12")]


def run(a, cells, seed, workdir):
    out = os.path.join(workdir, f"K{cells}_s{seed}")
    cmd = [a.turgor, "-options_file_yaml", a.scene, "-prve_cells", str(cells), "-prve_seed", str(seed), "-path_type", "hold", "-path_steps", "1",
           "-path_t_final", "1", "-output_dir", out, "-output_overwrite"] + a.extra
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        return {"cells": cells, "seed": seed, "ok": 0, "wall_s": wall, "error": (p.stdout + p.stderr).strip().splitlines()[-1:]}
    row = next(csv.DictReader(open(os.path.join(out, "rve.csv"))))
    r = {"cells": cells, "seed": seed, "ok": int(row["ok"]), "wall_s": wall, "prestress": 0.5 * (float(row["s11"]) + float(row["s22"]))}
    for name, col in QUANTITIES:
        r[name] = float(row[col])
    return r


def summary(rows, cells):
    good = [r for r in rows if r["cells"] == cells and r["ok"]]
    s = {"cells": cells, "runs": len(good), "wall_s": statistics.mean(r["wall_s"] for r in good) if good else float("nan")}
    for q in [n for n, _ in QUANTITIES] + ["prestress"]:
        v = [r[q] for r in good]
        s[q] = (statistics.mean(v), statistics.stdev(v) if len(v) > 1 else float("nan")) if v else (float("nan"), float("nan"))
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default=os.path.join(HERE, "..", "build", "turgor"))
    ap.add_argument("--scene", default=os.path.join(HERE, "..", "config", "polygon_rve.yaml"))
    ap.add_argument("--cells", default="4,16,64")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--csv", default="prve_ensemble.csv")
    ap.add_argument("extra", nargs="*", help="further turgor options (after --)")
    a = ap.parse_args()
    Ks = [int(k) for k in a.cells.split(",")]
    with tempfile.TemporaryDirectory() as work, concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        rows = list(pool.map(lambda ks: run(a, ks[0], ks[1], work), [(K, s) for K in Ks for s in range(1, a.seeds + 1)]))
    keys = ["cells", "seed", "ok", "wall_s", "prestress"] + [n for n, _ in QUANTITIES]
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        if not r["ok"]:
            print(f"K = {r['cells']}, seed {r['seed']}: failed {r.get('error', '')}", file=sys.stderr)
    S = [summary(rows, K) for K in Ks]
    ref = S[-1]
    names = [n for n, _ in QUANTITIES] + ["prestress"]
    print("| K | runs | " + " | ".join(f"{n} mean ± sd" for n in names) + " | s per RVE |")
    print("|---|---|" + "---|" * len(names) + "---|")
    for s in S:
        print(f"| {s['cells']} | {s['runs']} | " + " | ".join(f"{s[n][0]:.4g} ± {s[n][1]:.2g}" for n in names) + f" | {s['wall_s']:.1f} |")
    for n in names:
        ok = [s["cells"] for s in S if abs(s[n][0] - ref[n][0]) <= 0.02 * abs(ref[n][0]) and s[n][1] <= 0.05 * abs(s[n][0])]
        print(f"{n}: converged (mean within 2 % of K = {ref['cells']}'s, sd below 5 %) from K = {ok[0] if ok else 'none of these'}")


if __name__ == "__main__":
    main()
