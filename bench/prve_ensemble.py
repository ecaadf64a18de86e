#!/usr/bin/python3
"""The RVE size of irregular tissue: the polygon RVE (config/polygon_rve.yaml: glued, turgid Voronoi
cells) at rest for K cells and several seeds; per K the mean and standard deviation of its
homogenised tangent (C11, C22, C12, C33 = D^e 11,11, 22,22, 11,22, 12,12) and of its turgor
prestress (the mean of sigma11 and sigma22), and the smallest K whose mean is within 2 % of the
largest K's and whose standard deviation is below 5 % of its mean. Writes a CSV of every run and
prints a Markdown table.

With --tension E each RVE is instead stretched along the scene's uniaxial-strain path (F11 = 1 + eps,
F22 = 1) to eps = E in steps of --tension-step, and the table gives, per K, the peak sigma11, the
strain at the peak and the strain at which the RVE first gives way: the first step at which sigma11
falls (the relaxed RVE jumped to another equilibrium: a crack across the period) or the first of
three failed relaxations in a row (Newton creeping along a mode that has lost its stiffness). A
single failed relaxation is a stall at a kink of a force law (a bond at its peak): it is skipped.
The path ends there (-path_stop_after_failures 3: past it every relaxation fails, each at the cost of
a full one).

  bench/prve_ensemble.py [--turgor build/turgor] [--cells 4,16,64] [--seeds 10] [--jobs 1] [--csv prve_ensemble.csv]
                         [--tension 0.015 [--tension-step 2.5e-5]] [-- extra turgor options]
"""
import argparse, concurrent.futures, csv, math, os, statistics, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
QUANTITIES = [("C11", "De11_11"), ("C22", "De22_22"), ("C12", "De11_22"), ("C33", "De12_12")]


def path_options(a):
    if not a.tension:
        return ["-path_type", "hold", "-path_steps", "1", "-path_t_final", "1"]
    rate = 1e-3  # 1/µs: the time is a parameter of the path only (a static RVE)
    steps = int(math.ceil(a.tension / a.tension_step))
    return ["-path_type", "uniaxial", "-path_rate", str(rate), "-path_t_final", repr(steps * a.tension_step / rate), "-path_steps", str(steps),
            "-path_tangents", "0", "-path_allow_failures", "-path_stop_after_failures", "3"]


def peak(rows):
    """Peak sigma11 along the path, its strain, and the strain at which the RVE first gives way (nan: not on this path)."""
    good = [(float(r["F11"]) - 1, float(r["s11"])) for r in rows if int(r["ok"])]
    e_peak, s_peak = max(good, key=lambda es: es[1])
    fall = next((e1 for (e0, s0), (e1, s1) in zip(good, good[1:]) if s1 < s0), float("inf"))
    ok = [int(r["ok"]) for r in rows]
    run3 = next((float(rows[i]["F11"]) - 1 for i in range(len(rows) - 2) if not any(ok[i:i + 3])), float("inf"))
    gives = min(fall, run3)
    return {"peak": s_peak, "peak_strain": e_peak, "gives_way_strain": gives if gives < float("inf") else float("nan"), "failures": ok.count(0)}


def run(a, cells, seed, workdir):
    out = os.path.join(workdir, f"K{cells}_s{seed}")
    cmd = [a.turgor, "-options_file_yaml", a.scene, "-prve_cells", str(cells), "-prve_seed", str(seed), "-output_dir", out, "-output_overwrite"]
    cmd += path_options(a) + a.extra
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        return {"cells": cells, "seed": seed, "ok": 0, "wall_s": wall, "error": (p.stdout + p.stderr).strip().splitlines()[-1:]}
    if a.tension:
        return {"cells": cells, "seed": seed, "ok": 1, "wall_s": wall, **peak(list(csv.DictReader(open(os.path.join(out, "rve.csv")))))}
    row = next(csv.DictReader(open(os.path.join(out, "rve.csv"))))
    r = {"cells": cells, "seed": seed, "ok": int(row["ok"]), "wall_s": wall, "prestress": 0.5 * (float(row["s11"]) + float(row["s22"]))}
    for name, col in QUANTITIES:
        r[name] = float(row[col])
    return r


def summary(rows, cells, names):
    good = [r for r in rows if r["cells"] == cells and r["ok"]]
    s = {"cells": cells, "runs": len(good), "wall_s": statistics.mean(r["wall_s"] for r in good) if good else float("nan")}
    for q in names:
        v = [r[q] for r in good if not math.isnan(r[q])]  # nan: the RVE did not give way on the path
        s[q] = (statistics.mean(v), statistics.stdev(v) if len(v) > 1 else float("nan"), len(v)) if v else (float("nan"), float("nan"), 0)
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default=os.path.join(HERE, "..", "build", "turgor"))
    ap.add_argument("--scene", default=os.path.join(HERE, "..", "config", "polygon_rve.yaml"))
    ap.add_argument("--cells", default="4,16,64")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--csv", default="prve_ensemble.csv")
    ap.add_argument("--tension", type=float, default=0, help="stretch to this strain and report the peak stress (0: the tangent at rest)")
    ap.add_argument("--tension-step", type=float, default=2.5e-5, help="strain increment of the tension path")
    ap.add_argument("extra", nargs="*", help="further turgor options (after --)")
    a = ap.parse_args()
    Ks = [int(k) for k in a.cells.split(",")]
    with tempfile.TemporaryDirectory() as work, concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        rows = list(pool.map(lambda ks: run(a, ks[0], ks[1], work), [(K, s) for K in Ks for s in range(1, a.seeds + 1)]))
    names = ["peak", "peak_strain", "gives_way_strain"] if a.tension else [n for n, _ in QUANTITIES] + ["prestress"]
    keys = ["cells", "seed", "ok", "wall_s"] + names + (["failures"] if a.tension else [])
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        if not r["ok"]:
            print(f"K = {r['cells']}, seed {r['seed']}: failed {r.get('error', '')}", file=sys.stderr)
    S = [summary(rows, K, names) for K in Ks]
    ref = S[-1]
    print("| K | runs | " + " | ".join(f"{n} mean ± sd" for n in names) + " | s per RVE |")
    print("|---|---|" + "---|" * len(names) + "---|")
    for s in S:
        cell = lambda q: f"{q[0]:.4g} ± {q[1]:.2g}" + (f" ({q[2]} of {s['runs']})" if q[2] < s["runs"] else "")
        print(f"| {s['cells']} | {s['runs']} | " + " | ".join(cell(s[n]) for n in names) + f" | {s['wall_s']:.1f} |")
    for n in names:
        ok = [s["cells"] for s in S if abs(s[n][0] - ref[n][0]) <= 0.02 * abs(ref[n][0]) and s[n][1] <= 0.05 * abs(s[n][0])]
        print(f"{n}: converged (mean within 2 % of K = {ref['cells']}'s, sd below 5 %) from K = {ok[0] if ok else 'none of these'}")


if __name__ == "__main__":
    main()
