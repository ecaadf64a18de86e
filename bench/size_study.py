#!/usr/bin/python3
"""FE^2 where it pays: the seed's bending bar at growing tissue sizes, fine model against FE^2.

The bar of N x N cells of the same 25 µm cell (N = 16: the seed's; config/bending_bar_N_fine.yaml,
config/bending_bar_N_fe2.yaml), same loads, compared over the same number of bending periods: the
period grows with the bar (about 1.33 N µs), so each size runs to t = 4 N µs (three periods). For
every size the fine run (DOPRI, one rank: the fine mode is not parallel) and FE^2 runs on the coarse
meshes given (--meshes: element:faces, e.g. q1:8,q2:4), the same meshes at every size (the bar's
shape does not change with its size).

Per FE^2 run, against the fine run over the window. Each tip history y(t) is split into its bending
oscillation, the least-squares fit y1 = m + A exp(-a t) cos(w t - phi) (the bar's lowest mode about
its static deflection m), and the rest r = y - y1 (higher modes: the tissue's axial and breathing
modes, excited by the turgor's onset at t = 0, ride on the bending):
  max error        max_t |y - y_fine| / max |y_fine| (bench/study.py's measure, y the tip deflection)
  period error     (T - T_fine) / T_fine, T = 2 pi / w of the fit
  phase error      the fits' phase difference at the end of the window, in degrees
  amplitude error  (A - A_fine) / A_fine of the fits
  offset error     (m - m_fine) / max |y_fine|
  bending error    max_t |y1 - y1_fine| / max |y_fine|: the four above together, the max error of
                   the bending alone
  higher modes     max_t |r - r_fine| / max |y_fine|: what the fitted bending leaves
and the costs: wall time (summary.json) and CPU time of the process (user + sys, from the kernel:
both are reported because this machine is shared), the speed-up fine / FE^2 in each.

Cost model (docs/accuracy-cost.md): fine CPU = c_f x particles x simulated time (DOPRI's step is
set by the cell walls' dashpots, which do not change with the tissue size); FE^2 CPU = c_rve x RVE
solves (material points x function evaluations). Radau IIA's steps per period grow slowly with the
size (the larger bar's higher modes ring with more amplitude): the solves of each mesh are fitted as
N^beta over the sizes run. c_f and c_rve are fitted to the runs here; the model then predicts the
speed-up at other sizes (--predict).

  bench/size_study.py --sizes 16,32,64 --meshes q1:4,q1:8,q2:2,q2:4 --fine 16=DIR --fine 32=DIR ...
  bench/size_study.py --sizes 16 --window 300 --meshes q1:4,q1:8,q1:16,q2:2,q2:4,q2:8 --fine 16=DIR --tag q1q2
  bench/size_study.py --replot --out DIR        # the table and plots again from DIR/size_study.csv
Outputs in --out: size_study.csv, size_speedup.png, size_tips.png (and error_cost.png with --tag).
"""
import argparse, bisect, csv, json, math, os, resource, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study import write_rows  # noqa: E402 (bench/study.py's CSV writer)

COLUMNS = ["size", "run", "element", "mesh", "t_final", "ok", "wall_s", "cpu_s", "steps", "rhs_evals", "jacobian_evals", "rve_solves",
           "n_material_points", "n_particles", "speedup_wall", "speedup_cpu", "max_error", "period_error", "phase_error", "amplitude_error",
           "offset_error", "bending_error", "higher_modes_error", "period", "amplitude", "decay", "time_material_points_s", "time_tangents_s",
           "time_coarse_assembly_s", "time_other_s", "load", "integrator"]


def read_tip(d):
    with open(os.path.join(d, "tip.csv")) as f:
        rows = [(float(r["time"]), float(r["tip_displacement_y"])) for r in csv.DictReader(f)]
    return [t for t, _ in rows], [y for _, y in rows]


def within(t, y, t_end):
    k = bisect.bisect_right(t, t_end + 1e-9)
    return t[:k], y[:k]


def interp(t, y, s):
    """y at time s (linear)."""
    i = min(max(bisect.bisect_left(t, s), 1), len(t) - 1)
    return y[i - 1] + (y[i] - y[i - 1]) * (s - t[i - 1]) / (t[i] - t[i - 1])


def fit_bending(t, y):
    """Least squares y ~ m + A exp(-a t) cos(w t - phi): a scan over w (1 to 8 periods in the
    window) and a (decay), linear in (m, A cos phi, A sin phi) for each, then scipy's
    least_squares from the best. Returns m, A, a, w, phi and the residual r = y - fit."""
    import numpy as np
    from scipy.optimize import least_squares
    t, y = np.asarray(t), np.asarray(y)
    span = t[-1] - t[0]

    def linear(w, a):
        e = np.exp(-a * t)
        M = np.column_stack([np.ones_like(t), e * np.cos(w * t), e * np.sin(w * t)])
        c, *_ = np.linalg.lstsq(M, y, rcond=None)
        return c, np.sum((M @ c - y) ** 2)

    best = None
    for w in np.linspace(2 * np.pi / span, 16 * np.pi / span, 400):
        for a in np.linspace(0, 2.0 / span, 9):
            c, res = linear(w, a)
            if best is None or res < best[0]:
                best = (res, w, a, c)
    _, w, a, c = best
    A0, phi0 = np.hypot(c[1], c[2]), np.arctan2(c[2], c[1])
    f = lambda p: p[0] + p[1] * np.exp(-p[2] * t) * np.cos(p[3] * t - p[4]) - y
    p = least_squares(f, [c[0], A0, a, w, phi0], x_scale="jac").x
    m, A, a, w, phi = p
    if A < 0:
        A, phi = -A, phi + np.pi
    return m, A, a, w, phi, y - (m + A * np.exp(-a * t) * np.cos(w * t - phi))


def compare(run, fine):
    """The error measures of a run (t, y) against the fine run (t, y), on the run's samples (the
    fine history interpolated linearly at them)."""
    import numpy as np
    (t, y), (tf, yf) = run, fine
    keep = [k for k, s in enumerate(t) if tf[0] <= s <= tf[-1]]
    t, y = [t[k] for k in keep], [y[k] for k in keep]
    yi = [interp(tf, yf, s) for s in t]
    scale = max(abs(v) for v in yf)
    err = max(abs(v - w) for v, w in zip(y, yi)) / scale
    m, A, a, w, phi, r = fit_bending(t, y)
    mf, Af, af, wf, phif, rf = fit_bending(t, yi)
    dphase = ((w - wf) * t[-1] - (phi - phif) + np.pi) % (2 * np.pi) - np.pi
    y1, y1f = np.asarray(y) - r, np.asarray(yi) - rf
    return dict(max_error=err, period_error=wf / w - 1, phase_error=np.degrees(dphase), amplitude_error=A / Af - 1, offset_error=(m - mf) / scale,
                bending_error=float(np.max(np.abs(y1 - y1f))) / scale, higher_modes_error=float(np.max(np.abs(r - rf))) / scale, period=2 * np.pi / w,
                amplitude=A, decay=a)


class SizeStudy:
    def __init__(self, a):
        self.a = a
        self.rows = []
        os.makedirs(a.out, exist_ok=True)

    def run(self, name, cmd):
        """One turgor run into out/runs/name (kept if --reuse and complete): summary, dir, CPU time."""
        d = os.path.join(self.a.out, "runs", name)
        os.makedirs(d, exist_ok=True)
        cmd = cmd + ["-output_dir", d, "-output_overwrite"]
        done = os.path.join(d, "cpu_s.txt")
        same = lambda c: c.split(" -output_dir ")[0]  # a run copied from another --out is the same run
        if self.a.reuse and os.path.isfile(done) and same(open(os.path.join(d, "command.txt")).read().strip()) == same(" ".join(cmd)):
            s = json.load(open(os.path.join(d, "summary.json")))
            return s, d, float(open(done).read().split()[0]), float(open(done).read().split()[1])
        with open(os.path.join(d, "command.txt"), "w") as f:
            f.write(" ".join(cmd) + "\n")
        load = os.getloadavg()[0]
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        with open(os.path.join(d, "log.txt"), "w") as f:
            f.write(p.stdout)
        if p.returncode != 0:
            print(f"  {name}: FAILED (exit {p.returncode}); {d}/log.txt", file=sys.stderr)
            return None, d, cpu, load
        with open(done, "w") as f:
            f.write(f"{cpu} {load}\n")
        s = json.load(open(os.path.join(d, "summary.json")))
        print(f"  {name}: {s['wall_time_s']:.1f} s wall, {cpu:.1f} s CPU, {s['steps']} steps (load {load:.1f})", file=sys.stderr)
        return s, d, cpu, load

    def fine(self, n):
        """The fine run of size n: given (--fine n=DIR, its CPU time from DIR/cpu_s.txt or a
        /usr/bin/time -v file DIR.time) or run here."""
        a = self.a
        given = dict(x.split("=", 1) for x in a.fine)
        if str(n) in given:
            d = given[str(n)]
            s = json.load(open(os.path.join(d, "summary.json")))
            cpu, load = float("nan"), float("nan")
            if os.path.isfile(os.path.join(d, "cpu_s.txt")):
                cpu, load = map(float, open(os.path.join(d, "cpu_s.txt")).read().split()[:2])
            elif os.path.isfile(d.rstrip("/") + ".time"):
                tv = open(d.rstrip("/") + ".time").read()
                grab = lambda key: float(tv.split(key)[1].split("\n")[0].strip())
                cpu = grab("User time (seconds):") + grab("System time (seconds):")
            return s, d, cpu, load
        scene = os.path.join(a.config, "bending_bar_fine.yaml" if n == 16 else f"bending_bar_{n}_fine.yaml")
        return self.run(f"fine{n}", [a.turgor, "-options_file_yaml", scene, "-ts_max_time", f"{4 * n:g}", "-fine_snapshots", "0",
                                     "-fine_progress_interval", "0"])

    def study(self):
        a = self.a
        for n in a.sizes:
            window = a.window or 4.0 * n
            print(f"size {n} x {n}: window {window:g} µs", file=sys.stderr)
            sf, df, cf, lf = self.fine(n)
            if sf is None:
                continue
            fine = within(*read_tip(df), window)
            nf = sf["n_wall_particles"] + sf["n_fluid_particles"]
            self.rows.append(dict(size=n, run="fine", element="", mesh="", t_final=sf["t_final"], ok=1, wall_s=sf["wall_time_s"], cpu_s=cf,
                                  steps=sf["steps"], rhs_evals=sf["rhs_evals"], n_particles=nf, load=lf, integrator=sf.get("ts_type", "rk"),
                                  **compare(fine, fine)))
            wall_f = sf["wall_time_s"] * window / sf["t_final"]  # the fine run's cost over the window (it may run longer)
            cpu_f = cf * window / sf["t_final"]
            scene = os.path.join(a.config, "bending_bar_fe2.yaml" if n == 16 else f"bending_bar_{n}_fe2.yaml")
            for spec in a.meshes:
                element, faces = spec.split(":")
                name = f"fe2_{n}_{element}_{faces}" + (f"_{a.tag}" if a.tag else "")
                cmd = [a.turgor, "-options_file_yaml", scene, "-coarse_element", element, "-coarse_dm_plex_box_faces", f"{faces},{faces}",
                       "-coarse_dm_plex_box_upper", f"{25 * n},{25 * n}", "-ts_max_time", f"{window:g}", "-fe2_tip_samples", "1000",
                       "-fe2_snapshots", "0", "-fe2_progress_interval", "0"] + a.extra
                s, d, cpu, load = self.run(name, cmd)
                row = dict(size=n, run="fe2", element=element, mesh=int(faces), t_final=window, ok=int(s is not None), cpu_s=cpu, load=load)
                if s:
                    row.update(wall_s=s["wall_time_s"], steps=s["steps"], rhs_evals=s["rhs_evals"], jacobian_evals=s["jacobian_evals"],
                               rve_solves=s["rve_solves"], n_material_points=s["n_material_points"], speedup_wall=wall_f / s["wall_time_s"],
                               speedup_cpu=cpu_f / cpu if cpu > 0 else float("nan"),
                               time_material_points_s=s.get("time_material_points_s"), time_tangents_s=s.get("time_tangents_s"),
                               time_coarse_assembly_s=s.get("time_coarse_assembly_s"), time_other_s=s.get("time_integrator_and_linear_algebra_s"),
                               **compare(read_tip(d), fine))
                self.rows.append(row)
                self.write_csv()
        self.write_csv()

    def write_csv(self):
        write_rows(os.path.join(self.a.out, "size_study.csv"), COLUMNS, self.rows)

    def load(self):
        num = lambda v: float(v) if v not in ("", None) else None
        with open(os.path.join(self.a.out, "size_study.csv")) as f:
            for r in csv.DictReader(f):
                self.rows.append({k: (v if k in ("run", "element", "integrator") else num(v)) for k, v in r.items()})
        for r in self.rows:
            r["size"] = int(r["size"])
            if r["mesh"] is not None:
                r["mesh"] = int(r["mesh"])

    @staticmethod
    def solves_at(rs, n):
        """RVE solves of one FE^2 mesh at size n: the largest size's count times (n / N)^beta, beta the
        slope of log(solves) against log(N) over the sizes run (0 with one size): the steps per
        period grow with the bar, whose higher modes ring with more amplitude and less damping."""
        rs = sorted(rs, key=lambda r: r["size"])
        beta = 0.0
        if len(rs) >= 2:
            x = [math.log(r["size"]) for r in rs]
            y = [math.log(r["rve_solves"]) for r in rs]
            mx, my = sum(x) / len(x), sum(y) / len(y)
            beta = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
        return rs[-1]["rve_solves"] * (n / rs[-1]["size"]) ** beta, beta

    def model(self):
        """c_f [CPU s per particle per µs simulated] and c_rve [CPU s per RVE solve], least squares
        through the origin over the runs."""
        fine = [r for r in self.rows if r["run"] == "fine" and r.get("cpu_s") and r["cpu_s"] == r["cpu_s"]]
        fe2 = [r for r in self.rows if r["run"] == "fe2" and r.get("ok") and r.get("rve_solves") and r.get("cpu_s")]
        cf = sum(r["cpu_s"] for r in fine) / sum(r["n_particles"] * r["t_final"] for r in fine) if fine else float("nan")
        crve = sum(r["cpu_s"] for r in fe2) / sum(r["rve_solves"] for r in fe2) if fe2 else float("nan")
        return cf, crve

    def report(self):
        cf, crve = self.model()
        print("| cells | run | wall [s] | CPU [s] | speed-up (wall / CPU) | steps | f-evals | RVE solves | max error | period error | phase error "
              "| amplitude error | offset error | bending error | higher modes |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        f = lambda v, fmt: "—" if v is None or v != v else fmt.format(v)
        times = lambda v: f(v, "{:.0f}×" if v is not None and v >= 9.5 else "{:.2g}×")  # below 10: two digits (0.26×, not 0×)
        for r in self.rows:
            pct = lambda k, fmt: f(None if r.get(k) is None else 100 * r[k], fmt)
            ts = {"rk": "DOPRI", "": "DOPRI", None: "DOPRI"}.get(r.get("integrator"), r.get("integrator"))  # older CSVs: DOPRI
            label = f"fine ({ts}, 1 rank)" if r["run"] == "fine" else f"FE² {r['element'].upper()} {r['mesh']}×{r['mesh']}"
            print(f"| {r['size']}² | {label} | {f(r.get('wall_s'), '{:.1f}')} | {f(r.get('cpu_s'), '{:.1f}')} | "
                  f"{'—' if r['run'] == 'fine' else times(r.get('speedup_wall')) + ' / ' + times(r.get('speedup_cpu'))} | "
                  f"{f(r.get('steps'), '{:.0f}')} | {f(r.get('rhs_evals'), '{:.0f}')} | {f(r.get('rve_solves'), '{:.0f}')} | "
                  f"{'—' if r['run'] == 'fine' else pct('max_error', '{:.1f}%')} | "
                  f"{f(r.get('period'), '{:.2f} µs') if r['run'] == 'fine' else pct('period_error', '{:+.2f}%')} | "
                  f"{'—' if r['run'] == 'fine' else f(r.get('phase_error'), '{:+.0f}°')} | "
                  f"{f(r.get('amplitude'), '{:.2f} µm') if r['run'] == 'fine' else pct('amplitude_error', '{:+.1f}%')} | "
                  f"{'—' if r['run'] == 'fine' else pct('offset_error', '{:+.1f}%')} | "
                  f"{'—' if r['run'] == 'fine' else pct('bending_error', '{:.1f}%')} | "
                  f"{'—' if r['run'] == 'fine' else pct('higher_modes_error', '{:.1f}%')} |")
        print(f"\ncost model: fine CPU = {cf:.3e} s x particles x µs simulated; FE² CPU = {crve:.3e} s x RVE solves")
        for n in self.a.predict:
            particles = 16 * n * n + (n + 1) ** 2 + 2 * n * (n + 1)  # 16 fluid per cell, the corners, one midpoint per wall
            fe2 = [r for r in self.rows if r["run"] == "fe2" and r.get("ok") and r.get("rve_solves")]
            for r in sorted({(r["element"], r["mesh"]) for r in fe2}):
                solves, beta = self.solves_at([x for x in fe2 if (x["element"], x["mesh"]) == r], n)
                print(f"predicted at {n}²: fine {cf * particles * 4 * n:.0f} s CPU, FE² {r[0]} {r[1]}² {crve * solves:.1f} s (RVE solves ∝ N^{beta:.2f}), "
                      f"speed-up {cf * particles * 4 * n / (crve * solves):.0f}×")

    def plots(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        a = self.a
        cf, crve = self.model()
        fe2 = [r for r in self.rows if r["run"] == "fe2" and r.get("ok") and r.get("speedup_cpu")]
        fine = {r["size"]: r for r in self.rows if r["run"] == "fine"}
        if len(fine) > 1:
            fig, ax = plt.subplots(figsize=(6.5, 4.5))
            for key in sorted({(r["element"], r["mesh"]) for r in fe2}):
                rs = sorted((r for r in fe2 if (r["element"], r["mesh"]) == key), key=lambda r: r["size"])
                cells = [r["size"] ** 2 for r in rs]
                line, = ax.loglog(cells, [r["speedup_cpu"] for r in rs], "o-", label=f"FE² {key[0].upper()} {key[1]}×{key[1]} (CPU)")
                ax.loglog(cells, [r["speedup_wall"] for r in rs], "x:", color=line.get_color(), alpha=0.6)
                for r in rs:
                    ax.annotate(f"{100 * r['max_error']:.0f}% / {100 * r['bending_error']:.1f}%", (r["size"] ** 2, r["speedup_cpu"]), fontsize=7, xytext=(4, -10),
                                textcoords="offset points")
                # the cost model: fine ∝ particles x time, FE^2 ∝ RVE solves (∝ N^beta, fitted)
                ns = [16 * 2**k for k in range(0, 5)]
                part = [16 * n * n + (n + 1) ** 2 + 2 * n * (n + 1) for n in ns]
                ax.loglog([n * n for n in ns], [cf * p * 4 * n / (crve * self.solves_at(rs, n)[0]) for n, p in zip(ns, part)], "--",
                          color=line.get_color(), lw=0.8)
            ax.axhline(200, color="k", lw=0.6, ls="-.")
            ax.annotate("200×", (256, 200), fontsize=8, xytext=(2, 3), textcoords="offset points")
            ax.set_xlabel("cells in the tissue (N × N)")
            ax.set_ylabel("speed-up of FE² over the fine run")
            ax.set_title("Speed-up vs tissue size (3 bending periods; labels: max tip error / bending error)\nsolid: CPU time, dotted: wall, "
                         "dashed: cost model", fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(a.out, "size_speedup.png"), dpi=120)
            plt.close(fig)
            # tip histories, fine vs FE^2, one panel per size
            fig, axs = plt.subplots(1, len(fine), figsize=(4 * len(fine), 3.3))
            for ax, n in zip(axs if len(fine) > 1 else [axs], sorted(fine)):
                d = fine[n].get("dir") or os.path.join(a.out, "runs", f"fine{n}")
                given = dict(x.split("=", 1) for x in a.fine)
                d = given.get(str(n), d)
                if os.path.isfile(os.path.join(d, "tip.csv")):
                    t, y = within(*read_tip(d), 4.0 * n)
                    ax.plot(t, y, "k-", lw=1.2, label="fine")
                for r in sorted((r for r in fe2 if r["size"] == n), key=lambda r: (r["element"], r["mesh"])):
                    dr = os.path.join(a.out, "runs", f"fe2_{n}_{r['element']}_{r['mesh']}" + (f"_{a.tag}" if a.tag else ""))
                    if os.path.isfile(os.path.join(dr, "tip.csv")):
                        t, y = read_tip(dr)
                        ax.plot(t, y, lw=0.8, label=f"{r['element'].upper()} {r['mesh']}²")
                ax.set_title(f"{n} × {n} cells", fontsize=9)
                ax.set_xlabel("t [µs]")
                ax.grid(alpha=0.3)
            (axs[0] if len(fine) > 1 else axs).set_ylabel("tip deflection [µm]")
            (axs[0] if len(fine) > 1 else axs).legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(a.out, "size_tips.png"), dpi=120)
            plt.close(fig)
        if a.tag:  # error per cost at one size, Q1 against Q2
            fig, ax = plt.subplots(figsize=(6.5, 4.5))
            for el, mk in (("q1", "o-"), ("q2", "s-")):
                rs = sorted((r for r in fe2 if r["element"] == el), key=lambda r: r["mesh"])
                if not rs:
                    continue
                ax.loglog([r["cpu_s"] for r in rs], [r["max_error"] for r in rs], mk, label=f"{el.upper()} (max error)")
                ax.loglog([r["cpu_s"] for r in rs], [r["bending_error"] for r in rs], mk.replace("-", ":"), alpha=0.6,
                          label=f"{el.upper()} (bending error)")
                for r in rs:
                    ax.annotate(f"{r['mesh']}²", (r["cpu_s"], r["max_error"]), fontsize=7, xytext=(3, 3), textcoords="offset points")
            ax.set_xlabel("CPU time [s]")
            ax.set_ylabel("tip error against the fine bar")
            ax.set_title(f"Q1 and Q2 on the {a.sizes[0]}² bar, error per cost (to {a.window or 4 * a.sizes[0]:g} µs)", fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(a.out, "error_cost.png"), dpi=120)
            plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--turgor", default="build/turgor")
    ap.add_argument("--config", default="config")
    ap.add_argument("--out", default="out/size_study")
    ap.add_argument("--sizes", default="16,32,64")
    ap.add_argument("--meshes", default="q1:4,q1:8,q2:2,q2:4", help="element:faces,...")
    ap.add_argument("--fine", action="append", default=[], metavar="N=DIR", help="an existing fine run of size N (else it is run here); its CPU time from DIR/cpu_s.txt or the /usr/bin/time -v file DIR.time, prorated to the window if it ran longer")
    ap.add_argument("--window", type=float, default=0, help="µs (default 4 N: three periods)")
    ap.add_argument("--tag", default="", help="a name for the runs of this study (and the error-per-cost plot)")
    ap.add_argument("--extra", default="", help="more turgor options for the FE^2 runs (one string)")
    ap.add_argument("--predict", default="128", help="sizes to predict with the cost model")
    ap.add_argument("--reuse", action="store_true", help="keep completed runs with the same command")
    ap.add_argument("--replot", action="store_true")
    ap.add_argument("--check-max-error", type=float, default=0, help="exit 1 if an FE^2 run failed or its max error is above this (the ctest)")
    a = ap.parse_args()
    a.sizes = [int(s) for s in a.sizes.split(",")]
    a.meshes = [m for m in a.meshes.split(",") if m]
    a.extra = a.extra.split()
    a.predict = [int(s) for s in a.predict.split(",") if s]
    st = SizeStudy(a)
    if a.replot:
        st.load()
    else:
        if not os.access(a.turgor, os.X_OK):
            sys.exit(f"size_study.py: {a.turgor} is not an executable (build first, or pass --turgor)")
        st.study()
    st.report()
    st.plots()
    if a.check_max_error > 0:
        bad = [r for r in st.rows if r["run"] == "fe2" and (not r.get("ok") or not r.get("max_error", 1e9) <= a.check_max_error)]
        for r in bad:
            print(f"FAIL: FE^2 {r['element']} {r['mesh']}² at {r['size']}²: " + ("failed" if not r.get("ok") else f"max error {r['max_error']:.3f}") +
                  f" (limit {a.check_max_error:g})", file=sys.stderr)
        if bad:
            sys.exit(1)
        print(f"size_study.py: every FE^2 run within a max error of {a.check_max_error:g}")


if __name__ == "__main__":
    main()
