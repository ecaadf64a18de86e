#!/usr/bin/python3
"""SciPy's Radau (scipy.integrate.solve_ivp(method="Radau")) on the two stiff problems that
tests/test_radau_iia_accuracy.cpp runs with turgor's radauiia, at rtol = atol = 1e-4 .. 1e-8.

Problems (the same equations, initial values, intervals, first steps and references as the test):

  hires  HIRES, 8 equations, t in [0, 321.8122], y(0) = (1, 0, 0, 0, 0, 0, 0, 0.0057), first step
         1e-6. Reference: the Test Set for IVP Solvers (Mazzia & Magherini, Univ. Bari, release 2.4,
         problem HIRES), y(321.8122).
  vdp    Van der Pol with mu = 1e3 in the scaled form of examples/van_der_pol.cpp (Hairer & Wanner
         II, eq. IV.1.5'): y1' = y2, y2' = ((1 - y1^2) y2 - y1) / eps, eps = 1e-6, y(0) = (2, 0),
         t in [0, 2], first step 1e-6. Reference: the Test Set's VDPOL (mu = 1e3 on [0, 2000]),
         rescaled (t / mu, y2 * mu): y(2) = (1.706167732170469, -0.8928097010248125).

Both problems get the analytic Jacobian. Two errors of a run, both absolute, max norm over the
components:
  end      |y(t_end) - ref| against the Test Set's reference (the Test Set's and the usual measure);
  sampled  the largest error of the dense output (the collocation polynomial, sol.sol here,
           TSInterpolate in turgor) at 50 equally spaced times t_k = k t_end / 50, k = 1..50,
           against tests/data/radau_iia_<problem>.txt. That reference is computed here
           (--write-data): SciPy's Radau at rtol = atol = 1e-13, restarted at every t_k so that
           each value is a step value, not an interpolated one; at t_end it holds the Test Set's
           values (the chained run differs from them by 3.5e-14 for hires, 2.0e-13 for vdp).
  band     the geometric mean of the sampled errors of the runs at 0.8, 0.9, 1, 1.1 and 1.25 x tol.
The end error of HIRES jumps by up to 100x between tolerances 25% apart, for SciPy and radauiia
alike (--band prints the single runs); the sampled error varies by up to 4x, and the band mean
less. tests/test_radau_iia_accuracy.cpp checks the band mean against 3x SciPy's.
f-evals: SciPy's nfev (the f calls of Newton and of the error estimate; with an analytic Jacobian
there are no others).

  /usr/bin/python3 bench/radau_vs_scipy.py                  # the table
  /usr/bin/python3 bench/radau_vs_scipy.py --cxx            # + the figures as C++ constants for the test
  /usr/bin/python3 bench/radau_vs_scipy.py --band           # + the single runs of the band
  /usr/bin/python3 bench/radau_vs_scipy.py --write-data tests/data   # recompute the references

(SciPy is not needed by the build or by CI: the test stores these figures.)
"""
import argparse
import os
import sys

import numpy as np
import scipy
from scipy.integrate import solve_ivp

TOLS = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
BAND = [0.8, 0.9, 1.0, 1.1, 1.25]
NSAMPLES = 50
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data")


def hires_f(t, y):
    return np.array([
        -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007,
        1.71 * y[0] - 8.75 * y[1],
        -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4],
        8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3],
        -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6],
        -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6],
        280.0 * y[5] * y[7] - 1.81 * y[6],
        -280.0 * y[5] * y[7] + 1.81 * y[6],
    ])


def hires_jac(t, y):
    J = np.zeros((8, 8))
    J[0, 0], J[0, 1], J[0, 2] = -1.71, 0.43, 8.32
    J[1, 0], J[1, 1] = 1.71, -8.75
    J[2, 2], J[2, 3], J[2, 4] = -10.03, 0.43, 0.035
    J[3, 1], J[3, 2], J[3, 3] = 8.32, 1.71, -1.12
    J[4, 4], J[4, 5], J[4, 6] = -1.745, 0.43, 0.43
    J[5, 3], J[5, 4], J[5, 5], J[5, 6], J[5, 7] = 0.69, 1.71, -0.43 - 280.0 * y[7], 0.69, -280.0 * y[5]
    J[6, 5], J[6, 6], J[6, 7] = 280.0 * y[7], -1.81, 280.0 * y[5]
    J[7, 5], J[7, 6], J[7, 7] = -280.0 * y[7], 1.81, -280.0 * y[5]
    return J


VDP_EPS = 1e-6


def vdp_f(t, y):
    return np.array([y[1], ((1 - y[0] ** 2) * y[1] - y[0]) / VDP_EPS])


def vdp_jac(t, y):
    return np.array([[0.0, 1.0], [(-2 * y[0] * y[1] - 1) / VDP_EPS, (1 - y[0] ** 2) / VDP_EPS]])


PROBLEMS = {
    "hires": dict(f=hires_f, jac=hires_jac, t=(0.0, 321.8122), y0=[1, 0, 0, 0, 0, 0, 0, 0.0057], h0=1e-6,
                  ref=[0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4, 0.1175651343283149e-2,
                       0.2386356198831331e-2, 0.6238968252742796e-2, 0.2849998395185769e-2, 0.2850001604814231e-2]),
    "vdp": dict(f=vdp_f, jac=vdp_jac, t=(0.0, 2.0), y0=[2.0, 0.0], h0=1e-6, ref=[1.706167732170469, -0.8928097010248125]),
}


def sample_times(p):
    return p["t"][1] * np.arange(1, NSAMPLES + 1) / NSAMPLES


def compute_reference(p):
    """SciPy's Radau at rtol = atol = 1e-13 from sample time to sample time (restarted at each)."""
    y, t0, rows = np.array(p["y0"], dtype=float), p["t"][0], []
    for t in sample_times(p):
        s = solve_ivp(p["f"], (t0, t), y, method="Radau", rtol=1e-13, atol=1e-13, jac=p["jac"])
        if s.status != 0:
            sys.exit("reference: solve_ivp failed: " + s.message)
        y, t0 = s.y[:, -1], t
        rows.append(y.copy())
    rows = np.array(rows)
    diff = float(np.max(np.abs(rows[-1] - np.array(p["ref"]))))
    rows[-1] = p["ref"]
    return rows, diff


def write_reference(name, p, rows, diff, directory):
    path = os.path.join(directory, f"radau_iia_{name}.txt")
    with open(path, "w") as f:
        f.write(f"# {name}: reference at t_k = k t_end / {NSAMPLES}, written by bench/radau_vs_scipy.py --write-data\n")
        f.write(f"# (SciPy {scipy.__version__} Radau, rtol = atol = 1e-13, restarted at every t_k; the last line is the\n")
        f.write(f"# Test Set's reference, from which the chained run differs by {diff:.1e} in the max norm)\n")
        f.write("# t y_1 .. y_n\n")
        for t, y in zip(sample_times(p), rows):
            f.write(" ".join(f"{v:.17g}" for v in [t, *y]) + "\n")
    return path


def read_reference(name, p):
    rows = np.loadtxt(os.path.join(DATA, f"radau_iia_{name}.txt"), comments="#")
    if rows.shape != (NSAMPLES, len(p["y0"]) + 1) or abs(rows[-1, 0] - p["t"][1]) > 1e-12 * p["t"][1]:
        sys.exit(f"tests/data/radau_iia_{name}.txt does not match the problem: rerun with --write-data tests/data")
    return rows[:, 1:]


def run(p, tol, ref_rows):
    sol = solve_ivp(p["f"], p["t"], p["y0"], method="Radau", rtol=tol, atol=tol, jac=p["jac"], first_step=p["h0"], dense_output=True)
    if sol.status != 0:
        sys.exit("solve_ivp failed: " + sol.message)
    end = float(np.max(np.abs(sol.y[:, -1] - np.array(p["ref"]))))
    Y = sol.sol(sample_times(p)).T
    Y[-1] = sol.y[:, -1]
    sampled = float(np.max(np.abs(Y - ref_rows)))
    return end, sampled, sol.nfev, sol.njev, sol.nlu, len(sol.t) - 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cxx", action="store_true", help="also print the figures as C++ constants")
    ap.add_argument("--band", action="store_true", help="also the errors at 0.8, 0.9, 1.1 and 1.25 x tol")
    ap.add_argument("--write-data", metavar="DIR", help="recompute the references and write them to DIR")
    ap.add_argument("--problem", choices=list(PROBLEMS), action="append", help="only these (default: all)")
    a = ap.parse_args()
    names = a.problem or list(PROBLEMS)
    print(f"SciPy {scipy.__version__}, NumPy {np.__version__}, Python {sys.version.split()[0]}")
    figures = {}
    for name in names:
        p = PROBLEMS[name]
        if a.write_data:
            rows, diff = compute_reference(p)
            print(f"wrote {write_reference(name, p, rows, diff, a.write_data)} (chained run vs Test Set at t_end: {diff:.1e})")
        ref_rows = read_reference(name, p)
        print(f"\n{name}: t in [{p['t'][0]}, {p['t'][1]}], first step {p['h0']:g}")
        print(f"  {'tol':>6}  {'end error':>9}  {'sampled':>9}  {'band':>9}  {'f-evals':>7}  {'Jacobians':>9}  {'LU':>5}  {'steps':>5}")
        figures[name] = []
        for tol in TOLS:
            end, sampled, nfev, njev, nlu, steps = run(p, tol, ref_rows)
            others = {f: (end, sampled) if f == 1.0 else run(p, tol * f, ref_rows)[:2] for f in BAND}
            band = float(np.exp(np.mean(np.log([s for _, s in others.values()]))))
            figures[name].append((tol, end, sampled, band, nfev))
            print(f"  {tol:6.0e}  {end:9.3e}  {sampled:9.3e}  {band:9.3e}  {nfev:7d}  {njev:9d}  {nlu:5d}  {steps:5d}")
            if a.band:
                print(f"          x {', '.join(f'{f:g}' for f in BAND)}: end " + " ".join(f"{e:.2e}" for e, _ in others.values()) +
                      "; sampled " + " ".join(f"{s:.2e}" for _, s in others.values()))
    if a.cxx:
        print(f"\n/* bench/radau_vs_scipy.py --cxx, SciPy {scipy.__version__}: tol, error at t_end, sampled error, band mean, f-evals */")
        for name, rows in figures.items():
            print(f"const ScipyFigure kScipy_{name}[] = {{")
            for tol, end, sampled, band, nfev in rows:
                print(f"  {{{tol:.0e}, {end:.3e}, {sampled:.3e}, {band:.3e}, {nfev}}},")
            print("};")


if __name__ == "__main__":
    main()
