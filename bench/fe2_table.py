#!/usr/bin/python3
"""The seed's Table 1 for turgor: the bending bar at full fine scale (DOPRI) and with FE^2 for each
coarse integrator at rtol = atol = 1e-3, run side by side on this machine; prints a Markdown table
with the seed's numbers beside ours and the FE^2 - fine tip difference.

  bench/fe2_table.py [--turgor build/turgor] [--out out/table1] [--reuse-fine DIR] [--integrators ...]
"""
import argparse, csv, json, os, subprocess, sys, time

SEED = {  # TW 562 Table 1 (2010 hardware)
    "fine DOPRI": (1911794, None, 318630, "6h18m"),
    "rk 5dp": (11024, None, 1448, "1h39m"),
    "radau5": (507, 60, 66, "9m"),
    "bdf": (1652, 25, 1484, "17m"),
    "am": (9506, None, 5112, "1h37m"),
}
INTEGRATORS = {
    "rk 5dp": ["-ts_type", "rk", "-ts_rk_type", "5dp"],
    "radau5": ["-ts_type", "radauiia"],
    "bdf": ["-ts_type", "bdf"],
    "bdf3": ["-ts_type", "bdf", "-ts_bdf_order", "3"],
    "arkimex": ["-ts_type", "arkimex"],
    "am": ["-ts_type", "am"],
}


def run(cmd, out):
    t0 = time.time()
    subprocess.run(cmd + ["-output_dir", out, "-output_overwrite"], check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(f"{out}/summary.json"))
    s["elapsed"] = time.time() - t0
    return s


def tip(d):
    with open(f"{d}/tip.csv") as f:
        return [(float(r["time"]), float(r["tip_displacement_y"])) for r in csv.DictReader(f)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default="build/turgor")
    ap.add_argument("--out", default="out/table1")
    ap.add_argument("--reuse-fine", help="an existing fine run's output directory")
    ap.add_argument("--integrators", nargs="*", default=list(INTEGRATORS))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    fine_dir = a.reuse_fine or f"{a.out}/fine"
    if a.reuse_fine:
        fine = json.load(open(f"{fine_dir}/summary.json"))
    else:
        print("running the fine DOPRI bending bar ...", file=sys.stderr)
        fine = run([a.turgor, "-options_file_yaml", "config/bending_bar_fine.yaml", "-fine_snapshots", "0", "-fine_progress_interval", "0"], fine_dir)
    ref = tip(fine_dir)
    scale = max(abs(v) for _, v in ref)
    rows = [("fine DOPRI", fine, None)]
    for name in a.integrators:
        print(f"running FE^2 with {name} ...", file=sys.stderr)
        d = f"{a.out}/fe2_{name.replace(' ', '_')}"
        s = run([a.turgor, "-options_file_yaml", "config/bending_bar_fe2.yaml", "-fe2_snapshots", "0", "-fe2_progress_interval", "0"] + INTEGRATORS[name], d)
        c = tip(d)
        early = max(abs(x[1] - y[1]) for x, y in zip(c, ref) if x[0] <= 30) / scale
        whole = max(abs(x[1] - y[1]) for x, y in zip(c, ref)) / scale
        rows.append((name, s, (early, whole)))
    print(f"| run | f-evals (seed) | Jacobian evals (seed) | accepted steps (seed) | rejected | wall time (seed) | speed-up vs fine | tip vs fine, t <= 30 µs / whole run |")
    print("|---|---|---|---|---|---|---|---|")
    for name, s, diff in rows:
        key = "fine DOPRI" if name == "fine DOPRI" else ("bdf" if name.startswith("bdf") else name)
        sd = SEED.get(key, (None, None, None, "-"))
        fmt = lambda v: "-" if v is None else f"{v:,}".replace(",", " ")
        jac = s.get("jacobian_evals")
        label = f"FE2 {name}" + (f" ({s['ts_type']})" if s['ts_type'] != name else "") if diff else f"fine {s['ts_type']}"
        print(f"| {label} | {fmt(s['rhs_evals'])} ({fmt(sd[0])}) | {fmt(jac) if diff else '-'} ({fmt(sd[1])}) | {fmt(s['steps'])} ({fmt(sd[2])}) | {s['rejected_steps']} | {s['wall_time_s']:.1f} s ({sd[3]}) | "
              f"{fine['wall_time_s'] / s['wall_time_s']:.1f}x | {'-' if not diff else f'{diff[0]:.1%} / {diff[1]:.1%}'} |")
    print(f"\nfine final tip {fine['tip_displacement_final']:.5g} µm; max |tip| {scale:.4g} µm; "
          f"fine run {fine['t_final']:g} µs with {fine['n_wall_particles']} + {fine['n_fluid_particles']} particles")


if __name__ == "__main__":
    main()
