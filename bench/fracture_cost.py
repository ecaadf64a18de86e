#!/usr/bin/python3
"""What the fracture answer costs: the glued traction scene (config/voronoi_traction.yaml,
by default on 64 cells, 200 x 200 µm) pulled apart at several loading speeds (same step rule) and
with several time steps (-fine_dt_safety, same speed). Per run: the raw and smoothed peak of the top
grip's force, the fracture energy dissipated by the glue, the bonds broken and their interface
length, the controls' work, the energy balance's worst residual, steps and wall time. Writes a CSV
and a PNG (peak force and fracture energy against speed and step, with the cost).

  bench/fracture_cost.py [--turgor build/turgor] [--cells 64] [--speeds 0.2,0.1,0.05,0.025]
                         [--dt-safety 0.5,0.25,0.125,0.0625] [--csv fracture_cost.csv] [--png fracture_cost.png]
"""
import argparse, csv, json, math, os, subprocess, sys, tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from check_fracture import smoothed_peak  # noqa: E402  (the tests' measure of the peak)

OPENING = 1.75  # µm each grip moves after its ramp: the 64-cell tissue has separated by then


def run(a, speed, dt_safety, workdir, law="softening", bar_length=None):
    side = 25 * math.sqrt(a.cells)
    grip = 0.1 * side
    ramp = 0.5 / speed
    out = os.path.join(workdir, f"v{speed}_s{dt_safety}_{law}_{bar_length}")
    cmd = [a.turgor, "-options_file_yaml", a.scene, "-tissue_voronoi_cells", str(a.cells), "-tissue_box", f"0,0,{side},{side}",
           "-control_top_box", f"-1,{side - grip},{side + 1},{side + 1}", "-control_bottom_box", f"-1,-1,{side + 1},{grip}",
           "-control_top_velocity", f"0,{speed}", "-control_bottom_velocity", f"0,{-speed}", "-control_top_ramp_time", str(ramp),
           "-control_bottom_ramp_time", str(ramp), "-ts_max_time", str(ramp / 2 + OPENING / speed), "-fine_dt_safety", str(dt_safety),
           "-fine_snapshots", "0", "-fine_progress_interval", "0", "-output_overwrite", "-output_dir", out, "-glue_law", law]
    if bar_length:
        cmd += ["-tissue_bar_length", str(bar_length)]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    s = json.load(open(os.path.join(out, "summary.json")))
    e = list(csv.DictReader(open(os.path.join(out, "energy.csv"))))[-1]
    br = list(csv.DictReader(open(os.path.join(out, "breaks.csv"))))
    raw, smooth = smoothed_peak(out, a.window)
    return {"law": law, "bar_length": bar_length or "scene", "nodes": s["n_nodes"], "speed": speed, "dt_safety": dt_safety, "dt": s["dt_initial"], "steps": s["steps"], "wall_s": s["wall_time_s"],
            "peak_raw": raw, "peak_smoothed": smooth, "fracture_energy": float(e["dissipated_glue"]), "bonds_broken": s["bonds_broken"],
            "broken_length": sum(float(r["length_share"]) for r in br), "work_controls": float(e["work_controls"]),
            "residual_max": s.get("energy_residual_max", float("nan"))}


def plot(rows, a, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    base = [r for r in rows if r["law"] == "softening" and r["bar_length"] == "scene"]
    for panel, (key, fixed, label) in enumerate([("speed", a.base_dt_safety, "loading speed [µm/µs]"), ("dt", a.base_speed, "time step [µs]")]):
        sel = sorted((r for r in base if (r["dt_safety"] == fixed if key == "speed" else r["speed"] == fixed)), key=lambda r: r[key])
        x = [r[key] for r in sel]
        p = ax[panel]
        p.semilogx(x, [r["peak_smoothed"] for r in sel], "o-", label="smoothed peak force [µN]")
        p.semilogx(x, [r["peak_raw"] for r in sel], "s--", label="raw peak force [µN]")
        q = p.twinx()
        q.semilogx(x, [r["fracture_energy"] for r in sel], "^-", color="C2", label="fracture energy [µN µm]")
        for r in sel:
            p.annotate(f"{r['wall_s']:.0f} s", (r[key], r["peak_smoothed"]), textcoords="offset points", xytext=(0, 6), fontsize=8)
        p.set_ylim(0, 1.15 * max(r["peak_raw"] for r in sel))  # from zero: the spread is read against the value
        q.set_ylim(0, 1.3 * max(r["fracture_energy"] for r in sel))
        p.set_xticks(x)
        p.set_xticklabels([f"{v:.3g}" for v in x], fontsize=8)
        p.minorticks_off()
        p.set_xlabel(label)
        p.set_ylabel("force [µN]")
        q.set_ylabel("fracture energy [µN µm]", color="C2")
        p.legend(loc="lower left", fontsize=8)
        p.set_title(f"{a.cells} cells, " + (f"dt_safety {fixed}" if key == "speed" else f"{fixed} µm/µs") + " (labels: wall time)", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=90)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--scene", default="config/voronoi_traction.yaml")
    p.add_argument("--cells", type=int, default=64)
    p.add_argument("--speeds", default="0.2,0.1,0.05,0.025")
    p.add_argument("--dt-safety", default="0.5,0.25,0.125,0.0625")
    p.add_argument("--base-speed", type=float, default=0.2, help="the speed of the time-step series")
    p.add_argument("--base-dt-safety", type=float, default=0.125, help="the step rule of the speed series")
    p.add_argument("--laws", default="", help="glue laws of a node-spacing series (e.g. softening,strength), at the base speed and step")
    p.add_argument("--bar-lengths", default="5,2.5,1.25", help="-tissue_bar_length of the spacing series [µm]")
    p.add_argument("--window", type=float, default=0.3, help="µm of displacement the smoothed peak averages over")
    p.add_argument("--replot", metavar="CSV", help="plot the rows of an earlier run's CSV instead of running")
    p.add_argument("--csv", default="fracture_cost.csv")
    p.add_argument("--png", default="fracture_cost.png")
    a = p.parse_args()
    if a.replot:
        rows = list(csv.DictReader(open(a.replot)))
        for r in rows:
            for k, v in r.items():
                try:
                    r[k] = float(v)
                except ValueError:
                    pass
            r.setdefault("law", "softening")
            r.setdefault("bar_length", "scene")
        plot(rows, a, a.png)
        print(f"wrote {a.png}")
        return
    cases = [(float(v), a.base_dt_safety, "softening", None) for v in a.speeds.split(",") if v]
    cases += [(a.base_speed, float(s), "softening", None) for s in a.dt_safety.split(",") if s and (a.base_speed, float(s), "softening", None) not in cases]
    cases += [(a.base_speed, a.base_dt_safety, law, float(b)) for law in a.laws.split(",") if law for b in a.bar_lengths.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for v, s, law, bar in cases:
            rows.append(run(a, v, s, d, law, bar))
            r = rows[-1]
            print(f"{law:<9} bars {r['bar_length']:<5} ({r['nodes']} nodes) speed {v:<6} dt_safety {s:<7} dt {r['dt']:.3e}: {r['steps']:>7} steps {r['wall_s']:7.1f} s, peak {r['peak_raw']:.4g} raw "
                  f"{r['peak_smoothed']:.4g} smoothed, fracture energy {r['fracture_energy']:.4g} ({r['bonds_broken']} bonds, "
                  f"{r['broken_length']:.4g} µm), work {r['work_controls']:.4g}, residual {r['residual_max']:.1e}", flush=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    if any(r["law"] == "softening" and r["bar_length"] == "scene" for r in rows):
        plot(rows, a, a.png)
    print(f"wrote {a.csv}, {a.png}")


if __name__ == "__main__":
    main()
