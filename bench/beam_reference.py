#!/usr/bin/python3
"""Closed forms for turgor's eigen analysis of a plane-strain beam (-mode eigen, -fe2_static_eigen_monitor):
natural frequencies of a clamped-free beam (Timoshenko and Euler-Bernoulli) and the self-weight
buckling load of a clamped-free column (Greenhill), numpy only.

A beam L x H in plane strain (the 2D model: per unit thickness), E, nu, density rho: E' = E / (1 - nu^2),
G = E / (2 (1 + nu)), A = H, I = H^3 / 12, shear coefficient kappa = 10 (1 + nu') / (12 + 11 nu') with
nu' = nu / (1 - nu) (the plane-strain beam is the plane-stress one with E', nu'; the same reading as
bench/cantilever_reference.py).

  Timoshenko: kappa G A (w'' - psi') + rho A omega^2 w = 0,  E' I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0,
    w = psi = 0 at x = 0, psi' = 0 and w' - psi = 0 at x = L: the frequencies are the zeros of the
    2 x 2 determinant of the transfer matrix exp(A(omega) L) (by scaling and squaring of its Taylor
    series), found by a scan and bisection.
  Euler-Bernoulli: omega_n = (beta_n L)^2 sqrt(E' I / (rho A)) / L^2, beta_n L = 1.8751, 4.6941, 7.8548.
  Greenhill (a column clamped at x = 0, free at x = L, under its own weight q = rho g H per length
    toward the clamp): (q L)_cr = 7.83734 E' I / L^2, i.e. g_cr = 7.83734 E' H^2 / (12 rho L^3)
    (Timoshenko & Gere, Theory of Elastic Stability, §2.10; inextensible, without shear).

  beam_reference.py frequencies [--L 400 --H 20 --E 1 --nu 0.3 --rho 1]
  beam_reference.py buckling [--L 400 --H 10 ...]
  beam_reference.py --table frequencies --turgor build/turgor --meshes 40,2 80,4 160,8 320,16
  beam_reference.py --table buckling --turgor build/turgor --meshes 80,2 160,4 320,8 640,16
"""
import argparse, json, math, os, subprocess, sys, time

import numpy as np

BETA_L = (1.875104068711961, 4.694091132974175, 7.854757438237613)
GREENHILL = 7.83734


def section(L, H, E, nu, rho):
    Ep, nup, G = E / (1 - nu * nu), nu / (1 - nu), E / (2 * (1 + nu))
    return dict(Ep=Ep, G=G, kappa=10 * (1 + nup) / (12 + 11 * nup), A=H, I=H**3 / 12, rho=rho, L=L)


def expm(A):
    """exp(A) by scaling and squaring of the Taylor series (A is 4 x 4 and well scaled here)."""
    n = np.linalg.norm(A, 1)
    k = max(0, int(math.ceil(math.log2(n))) + 1) if n > 0 else 0
    B, E, T = A / 2**k, np.eye(len(A)), np.eye(len(A))
    for j in range(1, 30):
        T = T @ B / j
        E = E + T
    for _ in range(k):
        E = E @ E
    return E


def timoshenko_frequencies(L, H, E, nu, rho, n=3):
    s = section(L, H, E, nu, rho)
    kGA, EI = s["kappa"] * s["G"] * s["A"], s["Ep"] * s["I"]

    def det(w):
        M = np.zeros((4, 4))  # y = [w, psi, w', psi']
        M[0, 2] = M[1, 3] = M[2, 3] = 1
        M[2, 0] = -rho * s["A"] * w * w / kGA
        M[3, 1] = (kGA - rho * s["I"] * w * w) / EI
        M[3, 2] = -kGA / EI
        P = expm(M * L)
        return P[3, 2] * (P[2, 3] - P[1, 3]) - P[3, 3] * (P[2, 2] - P[1, 2])

    w1 = euler_bernoulli_frequencies(L, H, E, nu, rho, 1)[0]
    grid = np.linspace(0.05 * w1, 1.2 * (BETA_L[-1] / BETA_L[0]) ** 2 * w1 * max(1, n / 3) ** 2, 6000 * n)
    d = [det(w) for w in grid]
    roots = []
    for i in range(len(grid) - 1):
        if d[i] * d[i + 1] < 0:
            a, b, fa = grid[i], grid[i + 1], d[i]
            for _ in range(100):
                m = 0.5 * (a + b)
                fm = det(m)
                if fa * fm <= 0:
                    b = m
                else:
                    a, fa = m, fm
            roots.append(0.5 * (a + b))
            if len(roots) == n:
                break
    return roots


def euler_bernoulli_frequencies(L, H, E, nu, rho, n=3):
    s = section(L, H, E, nu, rho)
    return [bl * bl * math.sqrt(s["Ep"] * s["I"] / (rho * s["A"])) / L**2 for bl in BETA_L[:n]]


def greenhill_body_force(L, H, E, nu, rho):
    """g_cr: the body force (acceleration) along the axis at which the column buckles."""
    s = section(L, H, E, nu, rho)
    return GREENHILL * s["Ep"] * s["I"] / (rho * s["A"] * L**3)


NH = lambda E, nu: ["-material", "neo_hookean", "-nh_mu", repr(E / (2 * (1 + nu))), "-nh_lambda", repr(E * nu / ((1 + nu) * (1 - 2 * nu))), "-nh_viscosity", "0"]


def run(cmd, out):
    t = time.time()
    subprocess.run(cmd + ["-output_dir", out, "-output_overwrite"], check=True, stdout=subprocess.DEVNULL)
    return json.load(open(os.path.join(out, "summary.json"))), time.time() - t


def table_frequencies(a):
    ref = timoshenko_frequencies(a.L, a.H, a.E, a.nu, a.rho)
    print(f"Timoshenko omega_1..3 = {', '.join(f'{w:.6e}' for w in ref)} rad/µs (Euler-Bernoulli "
          f"{', '.join(f'{w:.6e}' for w in euler_bernoulli_frequencies(a.L, a.H, a.E, a.nu, a.rho))})\n")
    print("| mesh | omega_1 | omega_2 | omega_3 (bending) | vs Timoshenko | iterations | wall time |")
    print("|---|---|---|---|---|---|---|")
    rows = []
    for m in a.meshes:
        s, wall = run([a.turgor, "-mode", "eigen", "-eigen_state", "reference"] + NH(a.E, a.nu) +
                      ["-nh_density", repr(a.rho), "-coarse_dm_plex_simplex", "0", "-coarse_dm_plex_box_faces", m, "-coarse_dm_plex_box_upper",
                       f"{a.L},{a.H}", "-eigen_modes", "5", "-eigen_mode_shapes", "0"], f"beam_reference_{m.replace(',', 'x')}")
        w = [o for o, x in zip(s["omegas"], s["x_fractions"]) if x < 0.5][:3]
        rows.append(w)
        err = ", ".join(f"{(wi - r) / r:+.3%}" for wi, r in zip(w, ref))
        print(f"| {m.replace(',', ' × ')} | {w[0]:.6e} | {w[1]:.6e} | {w[2]:.6e} | {err} | {s['iterations']} | {wall:.2f} s |")
    for k in range(3):
        p = [math.log2(abs(rows[i][k] - rows[i + 1][k]) / abs(rows[i + 1][k] - rows[i + 2][k])) for i in range(len(rows) - 2)]
        print(f"mode {k + 1}: observed orders {', '.join(f'{x:.2f}' for x in p)}")


def table_buckling(a):
    g = greenhill_body_force(a.L, a.H, a.E, a.nu, a.rho)
    print(f"Greenhill g_cr = {g:.6e} µm/µs^2; body force {2 * g:.6e} in {a.load_steps} load steps\n")
    print("| mesh | crossing (load factor) | g_cr | vs Greenhill | wall time |")
    print("|---|---|---|---|---|")
    for m in a.meshes:
        s, wall = run([a.turgor, "-mode", "fe2_static"] + NH(a.E, a.nu) +
                      ["-nh_density", repr(a.rho), "-coarse_dm_plex_simplex", "0", "-coarse_dm_plex_box_faces", m, "-coarse_dm_plex_box_upper",
                       f"{a.L},{a.H}", "-body_force", f"{-2 * g!r},0", "-fe2_static_load_steps", str(a.load_steps), "-fe2_static_eigen_monitor", "1",
                       "-fe2_static_snapshots", "0"], f"beam_reference_col_{m.replace(',', 'x')}")
        gc = s["stability_crossing"] * 2 * g
        print(f"| {m.replace(',', ' × ')} | {s['stability_crossing']:.6f} | {gc:.6e} | {(gc - g) / g:+.2%} | {wall:.2f} s |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("what", choices=["frequencies", "buckling"])
    p.add_argument("--L", type=float, default=400.0)
    p.add_argument("--H", type=float, default=None, help="default 20 (frequencies), 10 (buckling)")
    p.add_argument("--E", type=float, default=1.0)
    p.add_argument("--nu", type=float, default=0.3)
    p.add_argument("--rho", type=float, default=1.0)
    p.add_argument("--table", action="store_true", help="run turgor on --meshes and print the docs/benchmarks.md table")
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--meshes", nargs="+", default=None)
    p.add_argument("--load-steps", type=int, default=4)
    a = p.parse_args()
    if a.H is None:
        a.H = 20.0 if a.what == "frequencies" else 10.0
    if a.table:
        a.meshes = a.meshes or (["40,2", "80,4", "160,8", "320,16"] if a.what == "frequencies" else ["80,2", "160,4", "320,8", "640,16"])
        (table_frequencies if a.what == "frequencies" else table_buckling)(a)
    elif a.what == "frequencies":
        print("Timoshenko     ", " ".join(f"{w:.10e}" for w in timoshenko_frequencies(a.L, a.H, a.E, a.nu, a.rho)))
        print("Euler-Bernoulli", " ".join(f"{w:.10e}" for w in euler_bernoulli_frequencies(a.L, a.H, a.E, a.nu, a.rho)))
    else:
        print(f"g_cr = {greenhill_body_force(a.L, a.H, a.E, a.nu, a.rho):.10e}")


if __name__ == "__main__":
    main()
