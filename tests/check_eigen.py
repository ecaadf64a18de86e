#!/usr/bin/python3
"""Checks of -mode eigen and the stability monitors against closed forms and other runs. Each
subcommand reads run directories (summary.json, eigen.csv, tip.csv, stability.csv) and exits
non-zero with a line starting FAIL when a measurement is off.

  check_eigen.py summary DIR                       the keys others rely on, lowest first, periods = 2 pi / omega,
                                                   residual norms < 1e-8
  check_eigen.py cantilever DIR... [--tol 0.01]    the first three bending frequencies (x share < 0.5) of meshes
                                                   refined by 2 converge to Timoshenko's (bench/beam_reference.py)
                                                   at order >= 1.5, the finest within tol
  check_eigen.py period EIGEN FE2 [--tol 0.01]     the lowest period predicts the FE^2 run's tip oscillation period
                                                   (mean of the up-crossings of tip - mean in tip.csv)
  check_eigen.py dopri EIGEN FE2_DOPRI             the DOPRI run's mean accepted step t/steps times omega_max lies in
                                                   DP5's real stability interval (3.3066) and within [0.8, 1.05] of the
                                                   limit along the highest mode's damped eigenvalue (dt_limit_dopri)
  check_eigen.py buckling DIR --g G [--tol 0.03]   the monitor's zero crossing (load factor x G) against Greenhill's
                                                   self-weight buckling body force of the column
  check_eigen.py agree DIR DIR [--rtol 1e-9]       the same eigenvalues (and omega_max) on two runs (1 and 2 ranks, a
                                                   snapshot and the relaxed state)
  check_eigen.py monitor FE2 EIGEN [--rtol 1e-9]   the monitor's first check (the initial state) gives EIGEN's lowest
                                                   eigenvalues
  check_eigen.py buckled EIGEN MONITOR [--rtol]    EIGEN (a state past buckling) has exactly one negative eigenvalue,
                                                   MONITOR's (a monitored load path) lowest one at its last level
"""
import argparse, csv, json, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import beam_reference as beam  # noqa: E402


def fail(msg):
    sys.exit(f"FAIL: {msg}")


def summary(d):
    s = json.load(open(os.path.join(d, "summary.json")))
    if s.get("status") != "completed":
        fail(f"{d}: status {s.get('status')}: {s.get('reason', '')}")
    return s


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def check_summary(a):
    s = summary(a.dirs[0])
    for k in ("mode", "eigenvalues", "frequencies", "periods", "omega_max", "residual_norms"):
        if k not in s:
            fail(f"summary.json has no {k}")
    if s["mode"] != "eigen":
        fail(f"mode {s['mode']}")
    ev = s["eigenvalues"]
    if ev != sorted(ev):
        fail(f"eigenvalues not lowest first: {ev}")
    for lam, f, T in zip(ev, s["frequencies"], s["periods"]):
        w = math.sqrt(lam)
        if rel(f, w / (2 * math.pi)) > 1e-12 or rel(T, 2 * math.pi / w) > 1e-12:
            fail(f"frequency {f} / period {T} do not follow from omega^2 = {lam}")
    if max(s["residual_norms"]) >= 1e-8:
        fail(f"residual norms {s['residual_norms']} not all below 1e-8")
    rows = list(csv.DictReader(open(os.path.join(a.dirs[0], "eigen.csv"))))
    if [float(r["eigenvalue"]) for r in rows] != ev:
        fail("eigen.csv and summary.json differ")
    print(f"ok: {len(ev)} modes, periods {', '.join(f'{T:.6g}' for T in s['periods'])} µs, omega_max {s['omega_max']:.6g} rad/µs, "
          f"residuals <= {max(s['residual_norms']):.1e}")


def check_cantilever(a):
    ref = beam.timoshenko_frequencies(a.L, a.H, a.E, a.nu, a.rho)
    rows = []
    for d in a.dirs:
        s = summary(d)
        w = [o for o, x in zip(s["omegas"], s["x_fractions"]) if x < 0.5][:3]
        if len(w) < 3:
            fail(f"{d}: fewer than three bending modes among {s['x_fractions']}")
        rows.append(w)
        print(f"  {d}: {s['n_elements']} elements, bending omega {', '.join(f'{x:.8e}' for x in w)}; vs Timoshenko "
              f"{', '.join(f'{(x - r) / r:+.3%}' for x, r in zip(w, ref))}")
    for k in range(3):
        errs = [abs(r[k] - ref[k]) / ref[k] for r in rows]
        if errs[-1] > a.tol:
            fail(f"mode {k + 1} on the finest mesh is {errs[-1]:.3%} from Timoshenko's {ref[k]:.6e} (tolerance {a.tol:.1%})")
        orders = [math.log2(abs(rows[i][k] - rows[i + 1][k]) / abs(rows[i + 1][k] - rows[i + 2][k])) for i in range(len(rows) - 2)]
        print(f"  mode {k + 1}: observed orders {', '.join(f'{p:.2f}' for p in orders)}")
        if k == 0 and not all(p >= 1.5 for p in orders):
            fail(f"mode 1 converges at orders {orders}, expected about 2")
    print(f"ok: first three bending frequencies within {a.tol:.0%} of Timoshenko's on the finest mesh")


def tip_period(d):
    t, y = [], []
    for r in csv.DictReader(open(os.path.join(d, "tip.csv"))):
        t.append(float(r["time"]))
        y.append(float(r["tip_displacement_y"]))
    m = sum(y) / len(y)
    up = [t[i] - (y[i] - m) * (t[i + 1] - t[i]) / (y[i + 1] - y[i]) for i in range(len(t) - 1) if y[i] - m < 0 <= y[i + 1] - m]
    if len(up) < 3:
        fail(f"{d}/tip.csv: {len(up)} oscillations, too few to measure a period")
    return (up[-1] - up[0]) / (len(up) - 1), len(up) - 1


def check_period(a):
    s = summary(a.dirs[0])
    T, n = tip_period(a.dirs[1])
    Te = s["periods"][0]
    print(f"  lowest mode at the {s['state']} state: period {Te:.6f} µs; FE^2 tip: {T:.6f} µs over {n} periods; difference {(Te - T) / T:+.3%}")
    if rel(Te, T) > a.tol:
        fail(f"period {Te} vs measured {T}: {rel(Te, T):.2%} > {a.tol:.0%}")
    print(f"ok: within {a.tol:.0%}")


def check_dopri(a):
    e, r = summary(a.dirs[0]), summary(a.dirs[1])
    dt = r["t_final"] / r["steps"]
    w, lim = e["omega_max"], e["dt_limit_dopri"]
    print(f"  DOPRI: {r['steps']} steps to {r['t_final']} µs, mean accepted dt {dt:.5f} µs; omega_max {w:.6f} rad/µs: dt omega_max = {dt * w:.4f} "
          f"(real interval 3.3066); limit along the damped highest mode (zeta {e['damping_ratio_omega_max']:.4f}) {lim:.5f} µs, dt / limit = {dt / lim:.3f}")
    if not dt * w <= 3.3066:
        fail(f"dt omega_max = {dt * w} outside DP5's real stability interval")
    if not 0.8 <= dt / lim <= 1.05:
        fail(f"the mean accepted step is {dt / lim:.3f} of the predicted stability limit (expected 0.8-1.05: stability-limited steps)")
    print("ok")


def check_buckling(a):
    s = json.load(open(os.path.join(a.dirs[0], "summary.json")))
    if not s.get("stability_lost"):
        fail(f"no loss of stability found (lowest eigenvalue last {s.get('eigen_monitor_lowest')})")
    g = s["stability_crossing"] * a.g
    ref = beam.greenhill_body_force(a.L, a.H, a.E, a.nu, a.rho)
    print(f"  crossing at load factor {s['stability_crossing']:.6f} (between {s['stability_crossing_bracket']}): g_cr = {g:.6e}; Greenhill "
          f"{ref:.6e}: {(g - ref) / ref:+.2%}")
    if rel(g, ref) > a.tol:
        fail(f"{rel(g, ref):.2%} from Greenhill's critical load (tolerance {a.tol:.0%})")
    print("ok")


def check_agree(a):
    s1, s2 = summary(a.dirs[0]), summary(a.dirs[1])
    worst = max(rel(x, y) for x, y in zip(s1["eigenvalues"], s2["eigenvalues"]))
    if len(s1["eigenvalues"]) != len(s2["eigenvalues"]) or worst > a.rtol:
        fail(f"eigenvalues differ by {worst:.2e} (> {a.rtol:.0e}): {s1['eigenvalues']} vs {s2['eigenvalues']}")
    if "omega_max" in s1 and "omega_max" in s2 and rel(s1["omega_max"], s2["omega_max"]) > a.rtol:
        fail(f"omega_max {s1['omega_max']} vs {s2['omega_max']}")
    for key in ("damped_real", "damped_imag"):  # the damped modes, where both runs have them
        if key in s1 or key in s2:
            x, y = s1.get(key, []), s2.get(key, [])
            # a real part is a small difference of large terms: compared to the eigenvalue's magnitude
            scale = [max(abs(complex(r, i)), 1e-300) for r, i in zip(s1.get("damped_real", []), s1.get("damped_imag", []))]
            off = max((abs(u - v) / m for u, v, m in zip(x, y, scale)), default=0.0)
            if len(x) != len(y) or off > a.rtol:
                fail(f"{key} differ by {off:.2e} of |s| (> {a.rtol:.0e}): {x} vs {y}")
    for s, d in ((s1, a.dirs[0]), (s2, a.dirs[1])):
        if max(s["residual_norms"]) >= 1e-8:
            fail(f"{d}: residual norms {s['residual_norms']}")
    print(f"ok: {len(s1['eigenvalues'])} eigenvalues agree to {worst:.1e} ({s1['mpi_ranks']} and {s2['mpi_ranks']} ranks), residuals < 1e-8")


def check_monitor(a):
    rows = list(csv.DictReader(open(os.path.join(a.dirs[0], "stability.csv"))))
    e = summary(a.dirs[1])
    first = [float(rows[0][f"lambda_{k + 1}"]) for k in range(len(e["eigenvalues"])) if f"lambda_{k + 1}" in rows[0]]
    worst = max(rel(x, y) for x, y in zip(first, e["eigenvalues"]))
    print(f"  monitor at {rows[0]['time']}: {first}; eigen: {e['eigenvalues'][:len(first)]}: {worst:.1e}")
    if worst > a.rtol:
        fail(f"the monitor's first check differs from -mode eigen by {worst:.2e}")
    print(f"ok: {len(rows)} checks, the first agrees to {worst:.1e}")


def check_buckled(a):
    e = summary(a.dirs[0])
    rows = list(csv.DictReader(open(os.path.join(a.dirs[1], "stability.csv"))))
    ev, last = e["eigenvalues"], float(rows[-1]["lambda_1"])
    print(f"  eigenvalues {ev}; positive_definite {e['positive_definite']}; the monitor at load factor {rows[-1]['load_factor']}: {last}")
    if not (ev[0] < 0 < ev[1]) or e["positive_definite"]:
        fail("expected exactly one negative eigenvalue")
    if rel(ev[0], last) > a.rtol:
        fail(f"the negative eigenvalue {ev[0]} differs from the monitor's {last} by {rel(ev[0], last):.2e}")
    print(f"ok: one negative eigenvalue, as the monitor's to {rel(ev[0], last):.1e}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("what", choices=["summary", "cantilever", "period", "dopri", "buckling", "agree", "monitor", "buckled"])
    p.add_argument("dirs", nargs="+")
    p.add_argument("--tol", type=float, default=None)
    p.add_argument("--rtol", type=float, default=1e-9)
    p.add_argument("--g", type=float, default=None, help="buckling: the body force of load factor 1")
    p.add_argument("--L", type=float, default=400.0)
    p.add_argument("--H", type=float, default=None)
    p.add_argument("--E", type=float, default=1.0)
    p.add_argument("--nu", type=float, default=0.3)
    p.add_argument("--rho", type=float, default=1.0)
    a = p.parse_args()
    a.H = a.H or (10.0 if a.what == "buckling" else 20.0)
    a.tol = a.tol or {"cantilever": 0.01, "period": 0.01, "buckling": 0.03}.get(a.what, 0)
    globals()["check_" + a.what](a)


if __name__ == "__main__":
    main()
