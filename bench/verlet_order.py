#!/usr/bin/python3
"""Order of velocity Verlet on the stiff-walls hard case (config/hard/fine_stiff_walls.yaml): the
scene is run with Verlet at a fixed step of 0.5, 0.25, 0.125 and 0.0625 x its stability limit
(-fine_dt_safety) and with DOPRI at rtol = atol = 1e-11 as the reference; each run's error is
max |tip(t) - tip_ref(t)| / max |tip_ref| over the 1001 tip.csv samples, and each halving of the step
should divide it by 4 (second order). A force that jumps where particles cross a line gives about 2
(first order) instead.

  bench/verlet_order.py [--turgor build/turgor] [--out DIR] [--safety 0.5 0.25 0.125 0.0625] [--ts verlet|basicsymplectic]
                        [-- more turgor options]

--ts: turgor's kick-drift-kick `verlet` or PETSc's `basicsymplectic` (the default, as first measured);
with `verlet`, `-- -fine_predict_velocity` gives the dashpots the velocity predicted to the step's end.
"""
import argparse, csv, os, subprocess, sys, tempfile, time

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "config", "hard", "fine_stiff_walls.yaml")


def tip(d):
    with open(os.path.join(d, "tip.csv")) as f:
        return [(float(r["time"]), float(r["tip_displacement_y"])) for r in csv.DictReader(f)]


def run(turgor, out, opts):
    t0 = time.perf_counter()
    subprocess.run([turgor, "-options_file_yaml", SCENE, "-output_dir", out, "-output_overwrite"] + opts, check=True, capture_output=True, text=True)
    return time.perf_counter() - t0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--out", default=None, help="keep the runs here (default: a temporary directory)")
    p.add_argument("--safety", type=float, nargs="+", default=[0.5, 0.25, 0.125, 0.0625])
    p.add_argument("--ref-tol", type=float, default=1e-11)
    p.add_argument("--ts", default="basicsymplectic", choices=["basicsymplectic", "verlet"])
    p.add_argument("extra", nargs="*", help="more turgor options for every run (after --)")
    a = p.parse_args()
    tmp = None if a.out else tempfile.TemporaryDirectory()
    out = a.out or tmp.name
    os.makedirs(out, exist_ok=True)
    ref_extra = [o for o in a.extra if o != "-fine_predict_velocity"]  # DOPRI: no drift velocity
    w = run(a.turgor, os.path.join(out, "ref"), ["-ts_rtol", f"{a.ref_tol:g}", "-ts_atol", f"{a.ref_tol:g}"] + ref_extra)
    ref = tip(os.path.join(out, "ref"))
    scale = max(abs(y) for _, y in ref)
    print(f"reference: DOPRI at rtol = atol = {a.ref_tol:g} ({w:.1f} s), max |tip| = {scale:.6g} µm")
    errors = []
    for s in a.safety:
        d = os.path.join(out, f"verlet_{s:g}")
        w = run(a.turgor, d, ["-ts_type", a.ts, "-fine_dt_safety", f"{s:g}"] + a.extra)
        y = tip(d)
        if len(y) != len(ref):
            sys.exit(f"FAIL: {len(y)} samples against {len(ref)}")
        err = max(abs(u[1] - v[1]) for u, v in zip(y, ref)) / scale
        ratio = f"{errors[-1] / err:.2f}" if errors else "-"
        errors.append(err)
        print(f"Verlet at {s:g} x its limit: error {err:.3e} of max |tip| ({w:.1f} s), ratio to the previous step {ratio}")


if __name__ == "__main__":
    main()
