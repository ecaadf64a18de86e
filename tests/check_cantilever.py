#!/usr/bin/python3
"""The static cantilever chain of config/polygon_cantilever.yaml against closed forms (stdlib only).

  check_cantilever.py DIR F K_R N L DISCRETE_TOL EB_TOL MOMENT_TOL

DIR holds the run's tip.csv and groups.csv (groups 'root', nodes 0 and 1, and 'tip'); F is the tip
load, K_R the hinge stiffness, N the number of nodes, L the chain's length. Hinge j (nodes 1 .. N-2)
carries M_j = F (N - 1 - j) l0 and turns M_j / K_R, so the linear static deflection of the tip is
F / K_R sum_{k=1}^{N-2} (k l0)^2 (the discrete value); Euler-Bernoulli with EI = K_R l0 gives
F L^3 / (3 EI). The clamp's moment about node 0 is the root group's moment about its centre
(root_mz, centre at l0/2 on the axis) plus the lever of its reaction, and must balance the load's
moment F x_tip (x_tip the deformed tip's abscissa, L - u_x). Each check is relative.
"""
import csv, sys


def main(argv):
    d, F, kr, n, L = argv[1], float(argv[2]), float(argv[3]), int(argv[4]), float(argv[5])
    tol_discrete, tol_eb, tol_moment = map(float, argv[6:9])
    l0 = L / (n - 1)
    discrete = F / kr * sum((k * l0) ** 2 for k in range(1, n - 1))
    eb = F * L**3 / (3 * kr * l0)
    g = list(csv.DictReader(open(f"{d}/groups.csv")))[-1]
    tip = -float(g["tip_uy"])
    x_tip = L + float(g["tip_ux"])
    moment = float(g["root_mz"]) + 0.5 * l0 * float(g["root_fy"])
    e_discrete, e_eb, e_moment = abs(tip - discrete) / discrete, abs(tip - eb) / eb, abs(moment - F * x_tip) / (F * L)
    print(f"static tip deflection {tip:.8g} µm: discrete linear {discrete:.8g} (relative difference {e_discrete:.2e}),"
          f" Euler-Bernoulli {eb:.8g} ({e_eb:.2e}); root moment {moment:.8g} µN µm, F x_tip = {F * x_tip:.8g} ({e_moment:.2e} of F L);"
          f" root reaction {float(g['root_fy']):.8g} µN")
    failed = [w for w, e, t in (("discrete", e_discrete, tol_discrete), ("Euler-Bernoulli", e_eb, tol_eb), ("moment", e_moment, tol_moment)) if not e <= t]
    if failed:
        sys.exit(f"FAIL: {', '.join(failed)} above tolerance")


if __name__ == "__main__":
    main(sys.argv)
