#!/usr/bin/python3
"""The homogenised tangent of irregular tissue, measured twice: on a large fine tissue held by grips
(config/voronoi_tangent_fine.yaml: 1 600 glued, turgid Voronoi cells stretched under uniaxial
strain) and by the polygon RVE (config/polygon_rve.yaml, the same cells and physics) over an
ensemble of periodic samples. Prints the turgor prestress, C22 and C12 of both and their
difference.

The fine run: σ_xx = right_fx / H and σ_yy = top_fy / W (groups.csv; every vertical section carries
the right grip's x-force, every horizontal one the top grip's y-force), before the stretch (at the
grips' delay: the held, turgid tissue at F = I) and at the end (held after the stretch); the strain
increment is the least-squares affine fit of the displacements of the nodes in the middle of the
tissue (particles.h5), away from the grips' boundary layers, and C22, C12 solved from both stress
increments with that strain's small ε_xx (an isotropic tangent assumed: C11 = C22). The RVE: D^e at rest by implicit
differentiation (-mode rve, one hold step), K cells, seeds 1..N.

  bench/fine_tangent.py [--turgor build/turgor] [--rve-cells 64] [--rve-seeds 10] [--jobs 2]
                        [--window 0.2] [--keep DIR] [-- extra options of the fine run]
"""
import argparse, concurrent.futures, csv, os, statistics, subprocess, sys, tempfile, time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def fine(a, work):
    out = os.path.join(work, "fine")
    cmd = [a.turgor, "-options_file_yaml", a.fine_scene, "-output_dir", out, "-output_overwrite"] + a.extra
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        sys.exit("fine run failed:\n" + (p.stdout + p.stderr)[-3000:])
    rows = list(csv.DictReader(open(os.path.join(out, "groups.csv"))))
    t = np.array([float(r["time"]) for r in rows])
    fx = np.array([float(r["right_fx"]) for r in rows])
    fy = np.array([float(r["top_fy"]) for r in rows])
    with h5py.File(os.path.join(out, "particles.h5"), "r") as h5:
        ids = h5["static/particle_id"][:, 0]
        order = np.argsort(ids)
        snaps = sorted(k for k in h5 if k.startswith("snapshot_"))
        times = np.array([h5[k].attrs["time"] for k in snaps])
        X = h5[snaps[0]]["position"][:][order]
        pos = {k: h5[k]["position"][:][order] for k in snaps}
    lo, hi = X.min(axis=0), X.max(axis=0)
    W, H = hi[0] - lo[0], hi[1] - lo[1]
    inner = np.all((X > lo + a.window * (hi - lo)) & (X < hi - a.window * (hi - lo)), axis=1)
    return {"t": t, "sxx": fx / H, "syy": fy / W, "times": times, "pos": pos, "snaps": snaps, "X": X, "inner": inner, "wall": wall,
            "nodes": len(ids), "summary": open(os.path.join(out, "summary.json")).read()}


def strain(F, s0, s1):
    """Least-squares affine fit u = A X + b of the displacement from snapshot s0 to s1 on the inner nodes."""
    X = F["X"][F["inner"]]
    U = F["pos"][s1][F["inner"]] - F["pos"][s0][F["inner"]]
    M = np.hstack([X - X.mean(axis=0), np.ones((len(X), 1))])
    A = np.linalg.lstsq(M, U, rcond=None)[0][:2].T  # A[i, j] = du_i / dX_j
    return A[0, 0], A[1, 1], 0.5 * (A[0, 1] + A[1, 0])


def at(F, key, time):
    return float(np.interp(time, F["t"], F[key]))


def rve(a, cells, seed, work):
    out = os.path.join(work, f"rve_K{cells}_s{seed}")
    cmd = [a.turgor, "-options_file_yaml", a.rve_scene, "-prve_cells", str(cells), "-prve_seed", str(seed), "-path_type", "hold", "-path_steps", "1",
           "-path_t_final", "1", "-output_dir", out, "-output_overwrite"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return None
    r = next(csv.DictReader(open(os.path.join(out, "rve.csv"))))
    return {"prestress": 0.5 * (float(r["s11"]) + float(r["s22"])), "C22": float(r["De22_22"]), "C12": float(r["De11_22"]),
            "C11": float(r["De11_11"])}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default=os.path.join(HERE, "..", "build", "turgor"))
    ap.add_argument("--fine-scene", default=os.path.join(HERE, "..", "config", "voronoi_tangent_fine.yaml"))
    ap.add_argument("--rve-scene", default=os.path.join(HERE, "..", "config", "polygon_rve.yaml"))
    ap.add_argument("--rve-cells", type=int, default=64)
    ap.add_argument("--rve-seeds", type=int, default=10)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--window", type=float, default=0.2, help="the strain is fitted on nodes farther than this fraction of the size from every side")
    ap.add_argument("--stretch-start", type=float, default=25, help="the grips' delay [µs]: the state before the stretch")
    ap.add_argument("--keep", help="keep the runs' outputs in this folder")
    ap.add_argument("extra", nargs="*", help="further options of the fine run (after --)")
    a = ap.parse_args()
    work_ctx = tempfile.TemporaryDirectory() if not a.keep else None
    work = a.keep or work_ctx.name
    os.makedirs(work, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        fut_fine = pool.submit(fine, a, work)
        rves = [r for r in pool.map(lambda s: rve(a, a.rve_cells, s, work), range(1, a.rve_seeds + 1)) if r]
        F = fut_fine.result()
    t0, t1 = a.stretch_start, F["t"][-1]
    s0 = F["snaps"][int(np.argmin(abs(F["times"] - t0)))]
    print(f"fine tissue: {F['nodes']} nodes, {F['inner'].sum()} in the fitting window, {F['wall']:.0f} s")
    print("settling (the stresses' last snapshots, N/m):")
    for s in F["snaps"]:
        ts = float(F["times"][F["snaps"].index(s)])
        if ts >= t0:
            exx, eyy, exy = strain(F, s0, s)
            print(f"  t = {ts:5.1f} µs: sxx {at(F, 'sxx', ts):+.5f} syy {at(F, 'syy', ts):+.5f}  strain from t = {t0:g}: "
                  f"exx {exx:+.3e} eyy {eyy:+.3e} exy {exy:+.3e}")
    exx, eyy, exy = strain(F, s0, F["snaps"][-1])
    d_sxx, d_syy = at(F, "sxx", t1) - at(F, "sxx", t0), at(F, "syy", t1) - at(F, "syy", t0)
    # the interior does not reach Δε_xx = 0 exactly (the grips hold the boundary, a boundary layer
    # contracts): with an isotropic tangent (C11 = C22: the RVEs have it to 0.1 %),
    #   Δσ_yy = C22 Δε_yy + C12 Δε_xx,  Δσ_xx = C12 Δε_yy + C22 Δε_xx
    det = eyy * eyy - exx * exx
    C22, C12 = (d_syy * eyy - d_sxx * exx) / det, (d_sxx * eyy - d_syy * exx) / det
    fine_vals = {"prestress": 0.5 * (at(F, "sxx", t0) + at(F, "syy", t0)), "C22": C22, "C12": C12}
    print(f"fine: Δε_yy {eyy:.4e}, Δε_xx {exx:.2e} ({exx / eyy:+.1%} of it), Δσ_yy {d_syy:.5f}, Δσ_xx {d_sxx:.5f} N/m; "
          f"Δσ / Δε_yy alone: C22 {d_syy / eyy:.5g}, C12 {d_sxx / eyy:.5g}; with Δε_xx (isotropic): C22 {C22:.5g}, C12 {C12:.5g}")
    print(f"\n| quantity | fine, 1 tissue | RVE, K = {a.rve_cells} ({len(rves)} seeds) | fine - RVE |")
    print("|---|---|---|---|")
    for q in ["prestress", "C22", "C12"]:
        v = [r[q] for r in rves]
        m, sd = statistics.mean(v), statistics.stdev(v) if len(v) > 1 else float("nan")
        print(f"| {q} | {fine_vals[q]:.5g} | {m:.5g} ± {sd:.2g} | {(fine_vals[q] - m) / abs(m):+.1%} |")


if __name__ == "__main__":
    main()
