#!/usr/bin/python3
"""What accuracy costs in time: work-precision studies of turgor's FE^2 bending bar.

Integration error: every coarse integrator at every tolerance rtol = atol = tol, against a
tight-tolerance radauiia run of the same model (--ref-tol). The RVEs' Psi-tc tolerance follows the
coarse one (min(1e-9, 1e-4 tol)), so that their residual noise stays below the error measured. Modelling error: FE^2
with RVEs of k x k cells on n x n coarse meshes, relaxed and Cauchy-Born, against the full fine-scale
run (--fine DIR, or run here with --run-fine).

Error of a run: max over the tip.csv sample times of |y(t) - y_ref(t)| / max |y_ref|, y the vertical
tip displacement. turgor samples tip.csv at equally spaced times by TS interpolation
(-fe2_tip_samples), so every run is compared at the same >= 100 times, whatever steps it took.

Outputs in --out: study.csv (one row per run) and PNG plots: work_precision.png (error vs wall
time), error_vs_tol.png, cost_breakdown.png and, with --modelling, modelling.png.

  bench/study.py                       # the full integration study (tolerances 1e-1 .. 1e-6)
  bench/study.py --modelling --fine out/bending_bar_fine   # + RVE size / mesh / Cauchy-Born
  bench/study.py --quick               # small: 20 µs, tolerances 1e-2 .. 1e-4 (the ctest)
"""
import argparse, bisect, csv, json, math, os, subprocess, sys, time

INTEGRATORS = {  # name -> turgor options
    "dopri": ["-ts_type", "rk", "-ts_rk_type", "5dp"],
    "bdf": ["-ts_type", "bdf"],
    "arkimex": ["-ts_type", "arkimex"],
    "radauiia": ["-ts_type", "radauiia"],
    "am": ["-ts_type", "am"],
}
SAMPLE_SPACING = 0.3  # µs: the fine run's tip.csv spacing (1000 samples over 300 µs)
COLUMNS = ["study", "integrator", "tol", "mesh", "rve_cells", "relax", "t_final", "ok", "wall_s",
           "rhs_evals", "jacobian_evals", "steps", "rejected", "rve_solves", "rve_tangent_solves",
           "psi_iterations", "time_material_points_s", "time_tangents_s", "time_other_s",
           "error_vs_reference", "error_vs_fine", "note"]


def psi_options(tol):
    """The RVE's Psi-tc tolerance follows the coarse one: at most the scene's 1e-9, and 1e-4 x tol
    below that, so that the RVEs' residual noise stays far below the integration error measured."""
    psi = min(1e-9, 1e-4 * tol)
    return ["-rve_psi_atol", f"{psi:g}", "-rve_psi_steptol", f"{psi:g}"]


def read_tip(d):
    with open(os.path.join(d, "tip.csv")) as f:
        return {round(float(r["time"]), 6): float(r["tip_displacement_y"]) for r in csv.DictReader(f)}


def error(run, ref):
    """max |y - y_ref| / max |y_ref| over the run's sample times within the reference's range: at
    the same times where both have them (runs of one study share them), else with the reference
    interpolated linearly (the fine run, sampled every 0.3 µs: 1e-4 of the amplitude at most)."""
    scale = max(abs(v) for v in ref.values()) or 1.0
    common = [t for t in run if t in ref]
    if len(common) >= 100:
        return max(abs(run[t] - ref[t]) for t in common) / scale
    rt = sorted(ref)
    errs = []
    for t in sorted(run):
        if t < rt[0] or t > rt[-1]:
            continue
        i = bisect.bisect_left(rt, t)
        if rt[i] == t:
            y = ref[t]
        else:
            t0, t1 = rt[i - 1], rt[i]
            y = ref[t0] + (ref[t1] - ref[t0]) * (t - t0) / (t1 - t0)
        errs.append(abs(run[t] - y))
    return max(errs) / scale if len(errs) >= 100 else None


def write_rows(path, columns, rows):
    """rows (dicts) as CSV with these columns, empty where a row has no value."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k, "")) for k in columns})


class Study:
    def __init__(self, a):
        self.a = a
        self.rows = []
        os.makedirs(a.out, exist_ok=True)

    def run(self, name, extra, t_final):
        """One turgor run into out/runs/name; returns (summary dict or None, directory, message)."""
        d = os.path.join(self.a.out, "runs", name)
        os.makedirs(d, exist_ok=True)
        samples = max(100, int(round(t_final / SAMPLE_SPACING)))
        cmd = [self.a.turgor, "-options_file_yaml", self.a.scene, "-ts_max_time", f"{t_final:g}",
               "-fe2_tip_samples", str(samples), "-fe2_snapshots", "0", "-fe2_progress_interval", "0",
               "-output_dir", d, "-output_overwrite"] + extra
        with open(os.path.join(d, "command.txt"), "w") as f:
            f.write(" ".join(cmd) + "\n")
        t0 = time.time()
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        with open(os.path.join(d, "log.txt"), "w") as f:
            f.write(p.stdout)
        if p.returncode != 0:
            why = next((l.split("ERROR:", 1)[1].strip() for l in p.stdout.splitlines() if "ERROR:" in l and "---" not in l), "exit code %d" % p.returncode)
            print(f"  {name}: FAILED ({why}) after {time.time() - t0:.1f} s", file=sys.stderr)
            return None, d, why
        with open(os.path.join(d, "summary.json")) as f:
            s = json.load(f)
        print(f"  {name}: {s['wall_time_s']:.2f} s, {s['steps']} steps, {s['rhs_evals']} f-evals", file=sys.stderr)
        return s, d, ""

    def record(self, study, integrator, tol, mesh, cells, relax, t_final, s, d, why, ref=None, fine=None):
        row = dict(study=study, integrator=integrator, tol=tol, mesh=mesh, rve_cells=cells, relax=relax,
                   t_final=t_final, ok=int(s is not None), note=why)
        if s:
            row.update(wall_s=s["wall_time_s"], rhs_evals=s["rhs_evals"], jacobian_evals=s["jacobian_evals"],
                       steps=s["steps"], rejected=s["rejected_steps"], rve_solves=s.get("rve_solves", 0),
                       rve_tangent_solves=s.get("rve_tangent_solves", 0), psi_iterations=s.get("psi_tc_iterations", 0),
                       time_material_points_s=s.get("time_material_points_s", ""), time_tangents_s=s.get("time_tangents_s", ""),
                       time_other_s=s.get("time_integrator_and_linear_algebra_s", ""))
            tip = read_tip(d)
            if ref is not None:
                row["error_vs_reference"] = error(tip, ref)
            if fine is not None:
                row["error_vs_fine"] = error(tip, fine)
        self.rows.append(row)
        self.write_csv()

    def write_csv(self):
        write_rows(os.path.join(self.a.out, "study.csv"), COLUMNS, self.rows)

    def integration(self):
        a = self.a
        print(f"reference: radauiia at rtol = atol = {a.ref_tol:g} to {a.t_final:g} µs", file=sys.stderr)
        tight = ["-ts_type", "radauiia", "-ts_rtol", f"{a.ref_tol:g}", "-ts_atol", f"{a.ref_tol:g}"] + psi_options(a.ref_tol)
        s, d, why = self.run("reference", tight, a.t_final)
        if s is None:
            sys.exit(f"study.py: the reference run failed: {why}")
        ref = read_tip(d)
        fine = self.fine_tip()
        self.record("reference", "radauiia", a.ref_tol, a.mesh, 1, "relaxed", a.t_final, s, d, why, None, fine)
        for integ in a.integrators:
            for tol in a.tols:
                s, d, why = self.run(f"{integ}_tol{tol:g}", INTEGRATORS[integ] + ["-ts_rtol", f"{tol:g}", "-ts_atol", f"{tol:g}"] + psi_options(tol), a.t_final)
                self.record("integration", integ, tol, a.mesh, 1, "relaxed", a.t_final, s, d, why, ref, fine)

    def fine_tip(self):
        a = self.a
        if a.run_fine and not a.fine:
            a.fine = os.path.join(a.out, "runs", "fine")
            print("running the full fine-scale bending bar (DOPRI) ...", file=sys.stderr)
            subprocess.run([a.turgor, "-options_file_yaml", "config/bending_bar_fine.yaml", "-ts_max_time", f"{a.t_final:g}",
                            "-fine_tip_samples", str(max(100, int(round(a.t_final / SAMPLE_SPACING)))),
                            "-fine_snapshots", "0", "-fine_progress_interval", "0", "-output_dir", a.fine, "-output_overwrite"],
                           check=True, stdout=subprocess.DEVNULL)
        return read_tip(a.fine) if a.fine else None

    def load(self):
        """Rows of an earlier study.csv in --out (to add runs to it, or to redraw its plots)."""
        path = os.path.join(self.a.out, "study.csv")
        if not os.path.isfile(path):
            return
        num = {"tol": float, "mesh": int, "rve_cells": int, "t_final": float, "ok": int, "wall_s": float,
               "error_vs_reference": float, "error_vs_fine": float}
        with open(path) as f:
            for r in csv.DictReader(f):
                if r.get("integrator") == "radau5":  # the TS type's name before it became radauiia
                    r["integrator"] = "radauiia"
                self.rows.append({k: (num[k](v) if k in num and v != "" else (None if v == "" else v)) for k, v in r.items()})

    def modelling(self):
        a = self.a
        fine = self.fine_tip()
        if fine is None:
            sys.exit("study.py: --modelling needs the fine run (--fine DIR or --run-fine)")
        tm = a.modelling_t_final
        for cells in a.rve_cells:
            for mesh in a.meshes:
                if cells * cells * mesh * mesh > a.max_rve_cells_total:
                    print(f"  skipping mesh {mesh}² with {cells}×{cells}-cell RVEs (--max-rve-cells-total)", file=sys.stderr)
                    continue
                for relax in (["relaxed", "cauchy_born"] if cells == 1 else ["relaxed"]):
                    name = f"model_mesh{mesh}_rve{cells}_{relax}"
                    extra = ["-ts_type", "radauiia", "-coarse_dm_plex_box_faces", f"{mesh},{mesh}", "-rve_cells", str(cells), "-rve_relax", relax]
                    s, d, why = self.run(name, extra, tm)
                    self.record("modelling", "radauiia", 1e-3, mesh, cells, relax, tm, s, d, why, None, fine)

    def plots(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        integ = [r for r in self.rows if r["study"] == "integration" and r["ok"] and r.get("error_vs_reference")]
        if integ:
            self.integration_plots(plt, integ)
        model = [r for r in self.rows if r["study"] == "modelling" and r["ok"] and r.get("error_vs_fine")]
        if model:
            self.modelling_plot(plt, model)

    def integration_plots(self, plt, integ):
        out = self.a.out
        names = [n for n in INTEGRATORS if any(r["integrator"] == n for r in integ)]
        label = {"dopri": "DOPRI (rk 5dp)", "bdf": "BDF (PETSc)", "arkimex": "ARKIMEX 3", "radauiia": "Radau IIA", "am": "Adams–Moulton"}
        # work-precision: error vs wall time
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for n in names:
            rs = sorted((r for r in integ if r["integrator"] == n), key=lambda r: -r["tol"])
            ax.loglog([r["wall_s"] for r in rs], [r["error_vs_reference"] for r in rs], "o-", label=label[n])
            for r in rs:
                ax.annotate(f"{r['tol']:g}", (r["wall_s"], r["error_vs_reference"]), fontsize=6, xytext=(3, 3), textcoords="offset points")
        fine = [r for r in self.rows if r.get("error_vs_fine")]
        ax.set_xlabel("wall time [s] (one core)")
        ax.set_ylabel("max |y_tip − y_ref| / max |y_ref|")
        ax.set_title(f"Work–precision, FE² bending bar to {self.a.t_final:g} µs")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "work_precision.png"), dpi=120)
        plt.close(fig)
        # tolerance honoured?
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        tols = sorted({r["tol"] for r in integ})
        for n in names:
            rs = sorted((r for r in integ if r["integrator"] == n), key=lambda r: r["tol"])
            ax.loglog([r["tol"] for r in rs], [r["error_vs_reference"] for r in rs], "o-", label=label[n])
        if tols:
            ax.loglog(tols, tols, "k--", lw=0.8, label="error = tol")
            ax.loglog(tols, [10 * t for t in tols], "k:", lw=0.8, label="10 × tol")
        ax.set_xlabel("rtol = atol")
        ax.set_ylabel("relative tip error vs reference")
        ax.set_title("Is the tolerance honoured?")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "error_vs_tol.png"), dpi=120)
        plt.close(fig)
        # cost breakdown at the tolerance nearest 1e-3
        if integ:
            t3 = min(tols, key=lambda t: abs(math.log10(t) + 3))
            rs = [r for n in names for r in integ if r["integrator"] == n and r["tol"] == t3]
            fig, ax = plt.subplots(figsize=(6.5, 4.0))
            x = range(len(rs))
            parts = [("time_material_points_s", "RVE solves (stress)"), ("time_tangents_s", "RVE tangents"),
                     ("time_other_s", "integrator + linear algebra")]
            bottom = [0.0] * len(rs)
            for key, lab in parts:
                v = [float(r.get(key) or 0) for r in rs]
                ax.bar(x, v, bottom=bottom, label=lab)
                bottom = [b + w for b, w in zip(bottom, v)]
            ax.set_xticks(list(x))
            ax.set_xticklabels([label[r["integrator"]] for r in rs], fontsize=8)
            ax.set_ylabel("wall time [s]")
            ax.set_title(f"Where the time goes (tol = {t3:g})")
            ax.legend(fontsize=8)
            fig.tight_layout()
            fig.savefig(os.path.join(out, "cost_breakdown.png"), dpi=120)
            plt.close(fig)

    def modelling_plot(self, plt, model):
        """Error against the fine run vs wall time, one line per RVE size (and Cauchy-Born)."""
        out = self.a.out
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for cells in sorted({r["rve_cells"] for r in model}):
            for relax in ("relaxed", "cauchy_born"):
                rs = sorted((r for r in model if r["rve_cells"] == cells and r["relax"] == relax), key=lambda r: r["mesh"])
                if not rs:
                    continue
                ax.loglog([r["wall_s"] for r in rs], [r["error_vs_fine"] for r in rs], "o-" if relax == "relaxed" else "s--",
                          label=f"RVE {cells}×{cells}" + (", Cauchy–Born" if relax != "relaxed" else ""))
                for r in rs:
                    ax.annotate(f"{r['mesh']}²", (r["wall_s"], r["error_vs_fine"]), fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_xlabel("wall time [s] (one core)")
        ax.set_ylabel("max |y_FE² − y_fine| / max |y_fine|")
        ax.set_title(f"Modelling error vs cost (to {self.a.modelling_t_final:g} µs; labels: coarse mesh)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "modelling.png"), dpi=120)
        plt.close(fig)

    def report(self):
        print("| study | integrator | tol | mesh | RVE | relax | wall [s] | f-evals | Jac | steps | rej | error vs ref | error vs fine |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in self.rows:
            f = lambda k, fmt: ("—" if r.get(k) in (None, "") else fmt.format(r[k]))
            print(f"| {r['study']} | {r['integrator']} | {r['tol']:g} | {r['mesh']}² | {r['rve_cells']}² | {r['relax']} | {f('wall_s', '{:.2f}')} | "
                  f"{f('rhs_evals', '{}')} | {f('jacobian_evals', '{}')} | {f('steps', '{}')} | {f('rejected', '{}')} | "
                  f"{f('error_vs_reference', '{:.2e}')} | {f('error_vs_fine', '{:.2e}')} |" + ("" if r["ok"] else f" failed: {r['note']}"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default="build/turgor")
    ap.add_argument("--scene", default="config/bending_bar_fe2.yaml")
    ap.add_argument("--out", default="out/study")
    ap.add_argument("--integrators", default=",".join(INTEGRATORS), help="comma list of " + ", ".join(INTEGRATORS))
    ap.add_argument("--tols", default="1e-1,1e-2,1e-3,1e-4,1e-5,1e-6")
    ap.add_argument("--t-final", type=float, default=300.0, help="µs")
    ap.add_argument("--ref-tol", type=float, default=1e-8)
    ap.add_argument("--mesh", type=int, default=4, help="coarse mesh of the integration study (the scene's)")
    ap.add_argument("--fine", help="output directory of a full fine run (its tip.csv) for errors against the fine model")
    ap.add_argument("--run-fine", action="store_true", help="run the fine model here if --fine is not given")
    ap.add_argument("--modelling", action="store_true", help="also the RVE-size / mesh / Cauchy-Born study")
    ap.add_argument("--meshes", default="4,8,16")
    ap.add_argument("--rve-cells", default="1,2,3")
    ap.add_argument("--modelling-t-final", type=float, default=300.0, help="µs")
    ap.add_argument("--max-rve-cells-total", type=int, default=1024,
                    help="skip modelling runs with more RVE cells per material point x elements (mesh² × cells²) than this")
    ap.add_argument("--no-integration", action="store_true", help="skip the tolerance sweep")
    ap.add_argument("--append", action="store_true", help="add to the study.csv already in --out")
    ap.add_argument("--replot", action="store_true", help="only redraw the plots and table from --out/study.csv")
    ap.add_argument("--quick", action="store_true", help="20 µs, tolerances 1e-2,1e-3,1e-4, reference 1e-7 (about a minute)")
    a = ap.parse_args()
    if a.quick:
        a.t_final, a.tols, a.ref_tol = 30.0, "1e-2,1e-3,1e-4", 1e-7
    a.integrators = [s for s in a.integrators.split(",") if s]
    bad = [s for s in a.integrators if s not in INTEGRATORS]
    if bad:
        sys.exit(f"study.py: unknown integrator(s) {bad}; known: {list(INTEGRATORS)}")
    a.tols = [float(t) for t in a.tols.split(",")]
    a.meshes = [int(m) for m in a.meshes.split(",")]
    a.rve_cells = [int(c) for c in a.rve_cells.split(",")]
    if not os.access(a.turgor, os.X_OK):
        sys.exit(f"study.py: {a.turgor} is not an executable (build first, or pass --turgor)")
    st = Study(a)
    t0 = time.time()
    if a.append or a.replot:
        st.load()
    if a.replot:
        st.plots()
        st.report()
        return
    if not a.no_integration:
        st.integration()
    if a.modelling:
        st.modelling()
    st.plots()
    st.report()
    print(f"study.py: {len(st.rows)} runs in {time.time() - t0:.0f} s; {a.out}/study.csv and plots", file=sys.stderr)


if __name__ == "__main__":
    main()
