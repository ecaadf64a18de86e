#!/usr/bin/python3
"""Independent reference for turgor's static cantilever (-mode fe2_static, config/cantilever_static.yaml).

Linear-elastic plane-strain Q1 or Q2 elements (--element), assembled and solved here with numpy
alone (no turgor, no PETSc), on the same structured mesh: a beam L x H on nx x ny quadrilaterals,
clamped at x = 0 (both displacement components of every node there), loaded by a body force rho g.
Q2's nodes are a (2 nx + 1) x (2 ny + 1) grid and its shape functions products of the 1D quadratic
Lagrange polynomials on -1, 0, 1 (written out here, independently of turgor's PetscFE tabulation).
Two rules:

  full  the whole stress at the full Gauss points (Q1: 2 x 2, Q2: 3 x 3);
  sri   selective reduced integration as turgor does it: the deviatoric part at the full Gauss
        points, the pressure part tr(sigma)/2 at fewer (Q1: the centre, weight 4; Q2: the 2 x 2
        Gauss points), i.e. in Voigt form D_vol = (lambda + mu) m m^T with m = [1, 1, 0] there and
        D - D_vol at the full points.

Prints the tip deflection (vertical displacement of the vertex at (L, H/2)) and Timoshenko's for
plane strain: q L^4 / (8 E' I) + q L^2 / (2 kappa G A), E' = E / (1 - nu^2), G = mu, q = rho g H,
I = H^3 / 12, A = H, kappa = 10 (1 + nu') / (12 + 11 nu') with nu' = nu / (1 - nu) (the plane-strain
beam is the plane-stress one with E', nu').

  cantilever_reference.py --faces 16,4 --rule sri --g=-1e-8
  cantilever_reference.py --faces 8,2 --element q2 --rule sri --g=-1e-8
  cantilever_reference.py --faces 16,4 --rule full --g=-1e-8 --check DIR --rtol 1e-4
        compare DIR/summary.json (a turgor -mode fe2_static run of the same beam) with the reference
  cantilever_reference.py --faces 8,2 --element q2 [--skin EA] --axial --g=1e-8 --check DIR
        the body force along the beam (-body_force g,0): the tip's horizontal displacement
        (tip_displacement_x_final); --skin: a membrane of axial stiffness EA on the top and bottom
        faces (-coarse_skin_stiffness EA)
  cantilever_reference.py --table --turgor build/turgor [--g=-1e-7] [--meshes 8,2 16,4 32,8 64,16] [--element q2]
        run turgor on each mesh with both rules and print the docs/benchmarks.md table
"""
import argparse, json, math, os, subprocess, sys, time

import numpy as np

G = 1.0 / math.sqrt(3.0)
GAUSS = [(-G, -G), (G, -G), (G, G), (-G, G)]
XI = [(-1, -1), (1, -1), (1, 1), (-1, 1)]  # counter-clockwise vertices


def gradients(X, xi, eta):
    """dN_a/dX (4 x 2) and det J at (xi, eta) for vertex coordinates X (4 x 2)."""
    dNr = np.array([[0.25 * a * (1 + b * eta), 0.25 * b * (1 + a * xi)] for a, b in XI])
    J = X.T @ dNr  # J_ij = dX_i / dxi_j
    return dNr @ np.linalg.inv(J), np.linalg.det(J)


def bmatrix(dN):
    B = np.zeros((3, 8))
    for a in range(4):
        B[0, 2 * a] = dN[a, 0]
        B[1, 2 * a + 1] = dN[a, 1]
        B[2, 2 * a] = dN[a, 1]
        B[2, 2 * a + 1] = dN[a, 0]
    return B


def tip_deflection(nx, ny, L, H, mu, lam, rho, g, rule, c=1, skin=0.0):
    if ny % 2:
        sys.exit("cantilever_reference.py: ny must be even (the tip vertex is at (L, H/2))")
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    m = np.array([1.0, 1.0, 0.0])
    Dvol = (lam + mu) * np.outer(m, m)
    node = lambda i, j: i * (ny + 1) + j  # column by column: a narrow band
    n = (nx + 1) * (ny + 1)
    K = np.zeros((2 * n, 2 * n))
    f = np.zeros(2 * n)
    for i in range(nx):
        for j in range(ny):
            verts = [node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]
            X = np.array([[(i + di) * L / nx, (j + dj) * H / ny] for di, dj in [(0, 0), (1, 0), (1, 1), (0, 1)]])
            Ke = np.zeros((8, 8))
            fe = np.zeros(8)
            for xi, eta in GAUSS:
                dN, det = gradients(X, xi, eta)
                B = bmatrix(dN)
                Ke += B.T @ (D if rule == "full" else D - Dvol) @ B * det
                N = [0.25 * (1 + a * xi) * (1 + b * eta) for a, b in XI]
                for a in range(4):
                    fe[2 * a + c] += rho * g * N[a] * det  # exact for the bilinear N det J of a parallelogram
            if rule == "sri":
                dN, det = gradients(X, 0.0, 0.0)
                B = bmatrix(dN)
                Ke += B.T @ Dvol @ B * 4 * det
            dofs = [2 * v + d for v in verts for d in range(2)]
            K[np.ix_(dofs, dofs)] += Ke
            f[dofs] += fe
    for j in (0, ny):  # a membrane of axial stiffness skin along the bottom and top faces (linear: t = e_x)
        for i in range(nx):
            for a, b, k in [(i, i, 1), (i, i + 1, -1), (i + 1, i, -1), (i + 1, i + 1, 1)]:
                K[2 * node(a, j), 2 * node(b, j)] += k * skin / (L / nx)
    free = np.array([d for d in range(2 * n) if d // 2 // (ny + 1) != 0])  # not on x = 0
    u = np.zeros(2 * n)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
    return u[2 * node(nx, ny // 2) + c]


def quadratic(t):
    """The 1D quadratic Lagrange polynomials on the nodes -1, 0, 1 at t, and their derivatives."""
    return (np.array([0.5 * t * (t - 1), 1 - t * t, 0.5 * t * (t + 1)]), np.array([t - 0.5, -2 * t, t + 0.5]))


def tip_deflection_q2(nx, ny, L, H, mu, lam, rho, g, rule, c=1, skin=0.0):
    """The same beam on biquadratic 9-node elements: nodes on the (2 nx + 1) x (2 ny + 1) grid."""
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    m = np.array([1.0, 1.0, 0.0])
    Dvol = (lam + mu) * np.outer(m, m)
    nyn = 2 * ny + 1
    node = lambda i, j: i * nyn + j  # grid node (i, j), column by column
    n = (2 * nx + 1) * nyn
    K = np.zeros((2 * n, 2 * n))
    f = np.zeros(2 * n)
    t3, w3 = np.polynomial.legendre.leggauss(3)
    t2, w2 = np.polynomial.legendre.leggauss(2)
    hx, hy = L / nx, H / ny  # a rectangle: dX/dxi = diag(hx / 2, hy / 2)
    det = hx * hy / 4

    def bmat(xi, eta):
        (Nx, dNx), (Ny, dNy) = quadratic(xi), quadratic(eta)
        B = np.zeros((3, 18))
        N = np.zeros(9)
        for a in range(3):
            for b in range(3):
                k = 3 * a + b  # local node (a along x, b along y)
                gx, gy = dNx[a] * Ny[b] * 2 / hx, Nx[a] * dNy[b] * 2 / hy
                B[0, 2 * k], B[1, 2 * k + 1], B[2, 2 * k], B[2, 2 * k + 1] = gx, gy, gy, gx
                N[k] = Nx[a] * Ny[b]
        return B, N

    for i in range(nx):
        for j in range(ny):
            nodes = [node(2 * i + a, 2 * j + b) for a in range(3) for b in range(3)]
            Ke = np.zeros((18, 18))
            fe = np.zeros(18)
            for xi, wx in zip(t3, w3):
                for eta, wy in zip(t3, w3):
                    B, N = bmat(xi, eta)
                    Ke += B.T @ (D if rule == "full" else D - Dvol) @ B * wx * wy * det
                    fe[c::2] += rho * g * N * wx * wy * det
            if rule == "sri":
                for xi, wx in zip(t2, w2):
                    for eta, wy in zip(t2, w2):
                        B, _ = bmat(xi, eta)
                        Ke += B.T @ Dvol @ B * wx * wy * det
            dofs = [2 * v + d for v in nodes for d in range(2)]
            K[np.ix_(dofs, dofs)] += Ke
            f[dofs] += fe
    for j in (0, 2 * ny):  # the membrane along the faces: 3-node edges, dN/dxi = xi - 1/2, -2 xi, xi + 1/2, |dX/dxi| = hx / 2
        for i in range(nx):
            for xi, wx in zip(t3, w3):
                dN = [xi - 0.5, -2 * xi, xi + 0.5]
                for a in range(3):
                    for b in range(3):
                        K[2 * node(2 * i + a, j), 2 * node(2 * i + b, j)] += wx * skin / (hx / 2) * dN[a] * dN[b]
    free = np.array([d for d in range(2 * n) if d // 2 // nyn != 0])  # not on x = 0
    u = np.zeros(2 * n)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
    return u[2 * node(2 * nx, ny) + c]


def timoshenko(L, H, mu, lam, rho, g):
    E = mu * (3 * lam + 2 * mu) / (lam + mu)
    nu = lam / (2 * (lam + mu))
    Ep, nup = E / (1 - nu * nu), nu / (1 - nu)
    q, I, kappa = rho * g * H, H**3 / 12, 10 * (1 + nup) / (12 + 11 * nup)
    return q * L**4 / (8 * Ep * I) + q * L**2 / (2 * kappa * mu * H)


def turgor_run(turgor, nx, ny, rule, a, out):
    cmd = [turgor, "-mode", "fe2_static", "-material", "neo_hookean", "-nh_mu", repr(a.mu), "-nh_lambda", repr(a.lam), "-nh_density", repr(a.density),
           "-nh_viscosity", "0", "-coarse_dm_plex_simplex", "0", "-coarse_dm_plex_box_faces", f"{nx},{ny}", "-coarse_dm_plex_box_upper", f"{a.L},{a.H}",
           "-coarse_dirichlet_values", "4", "-coarse_element", a.element, "-coarse_quadrature", rule, "-body_force", f"0,{a.g!r}", "-fe2_static_load_steps", str(a.load_steps),
           "-fe2_static_snapshots", "0", "-output_dir", out, "-output_overwrite"]
    t = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - t
    return json.load(open(os.path.join(out, "summary.json"))), wall


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--faces", default="16,4", help="nx,ny")
    p.add_argument("--L", type=float, default=400.0)
    p.add_argument("--H", type=float, default=100.0)
    p.add_argument("--E", type=float, default=1.0)
    p.add_argument("--nu", type=float, default=0.3)
    p.add_argument("--density", type=float, default=1.0, help="rho0 (-nh_density)")
    p.add_argument("--g", type=float, default=-1e-8, help="vertical body force (acceleration, -body_force 0,g)")
    p.add_argument("--rule", choices=["sri", "full", "both"], default="both")
    p.add_argument("--element", choices=["q1", "q2"], default="q1")
    p.add_argument("--skin", type=float, default=0.0, help="a membrane of this axial stiffness EA along the top and bottom faces (-coarse_skin_stiffness)")
    p.add_argument("--axial", action="store_true", help="the body force along the beam (-body_force g,0); the tip's horizontal displacement")
    p.add_argument("--check", metavar="DIR", help="compare DIR/summary.json's tip_displacement_final")
    p.add_argument("--rtol", type=float, default=1e-4)
    p.add_argument("--table", action="store_true")
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--meshes", nargs="+", default=["8,2", "16,4", "32,8", "64,16"])
    p.add_argument("--load-steps", type=int, default=1)
    p.add_argument("--out", default="cantilever_runs")
    a = p.parse_args()
    a.mu = a.E / (2 * (1 + a.nu))
    a.lam = a.E * a.nu / ((1 + a.nu) * (1 - 2 * a.nu))
    theory = -timoshenko(a.L, a.H, a.mu, a.lam, a.density, -a.g)
    rules = ["sri", "full"] if a.rule == "both" else [a.rule]
    deflection = tip_deflection_q2 if a.element == "q2" else tip_deflection
    if a.table:
        print(f"Cantilever {a.L:g} x {a.H:g}, plane strain, E = {a.E:g}, nu = {a.nu:g} (mu = {a.mu!r}, lambda = {a.lam!r}), rho g = {a.density * a.g:g}; "
              f"Timoshenko {theory:.6g} (deflection / length {abs(theory) / a.L:.2g})\n")
        print(f"element {a.element}\n")
        print("| mesh | rule | tip (turgor, neo-Hookean) | tip (numpy, linear) | turgor vs numpy | turgor vs Timoshenko | Newton iterations | wall time |")
        print("|---|---|---|---|---|---|---|---|")
        tips = {rule: [] for rule in rules}
        for mesh in a.meshes:
            nx, ny = map(int, mesh.split(","))
            for rule in rules:
                ref = deflection(nx, ny, a.L, a.H, a.mu, a.lam, a.density, a.g, rule)
                s, wall = turgor_run(a.turgor, nx, ny, rule, a, os.path.join(a.out, f"{a.element}_{rule}_{nx}x{ny}"))
                tip = s["tip_displacement_final"]
                tips[rule].append(tip)
                print(f"| {nx} × {ny} | {rule} | {tip:.7g} | {ref:.7g} | {(tip - ref) / ref:+.1e} | {100 * (tip - theory) / theory:+.2f}% | "
                      f"{s['snes_its']} | {wall:.2f} s ({s['wall_time_s']:.3f} s solve) |")
        # the meshes halve h: observed order and Richardson's limit from the three finest
        for rule in rules:
            d = tips[rule]
            if len(d) >= 3 and (d[-3] - d[-2]) * (d[-2] - d[-1]) > 0:
                order = math.log2((d[-3] - d[-2]) / (d[-2] - d[-1]))
                limit = d[-1] + (d[-1] - d[-2]) / (2**order - 1)
                print(f"\n{rule}: observed order {order:.2f} on the three finest meshes, extrapolated limit {limit:.7g} "
                      f"({100 * (limit - theory) / theory:+.2f}% from Timoshenko)")
        return
    nx, ny = map(int, a.faces.split(","))
    c, key = (0, "tip_displacement_x_final") if a.axial else (1, "tip_displacement_final")
    if a.axial and a.table:
        sys.exit("cantilever_reference.py: --table is for the bending load")
    for rule in rules:
        ref = deflection(nx, ny, a.L, a.H, a.mu, a.lam, a.density, a.g, rule, c, a.skin)
        if a.axial:  # the bar's 1D limit, E' L^2 / 2 (the clamp's lateral restraint stiffens it near x = 0)
            E = a.mu * (3 * a.lam + 2 * a.mu) / (a.lam + a.mu)
            bar = a.density * a.g * a.L**2 / (2 * E / (1 - (a.lam / (2 * (a.lam + a.mu)))**2))
            print(f"{a.element} {rule}: {nx} x {ny} elements, tip extension {ref:.10g} (the 1D bar's {bar:.6g}, {100 * (ref - bar) / bar:+.2f}%)")
        else:
            print(f"{a.element} {rule}: {nx} x {ny} elements, tip deflection {ref:.10g} (Timoshenko {theory:.6g}, {100 * (ref - theory) / theory:+.2f}%)")
        if a.check:
            s = json.load(open(os.path.join(a.check, "summary.json")))
            if s.get("quadrature") != rule or s.get("element", "q1") != a.element or s.get("n_elements") != nx * ny or s.get("status") != "completed":
                sys.exit(f"FAIL: {a.check} is not a completed {a.element} {rule} run on {nx} x {ny} elements: {s.get('status')}, {s.get('element')}, "
                         f"{s.get('quadrature')}, {s.get('n_elements')}")
            tip = s[key]
            rel = abs(tip - ref) / abs(ref)
            print(f"turgor ({a.check}): {tip:.10g}, relative difference {rel:.2e} (tolerance {a.rtol:g})")
            if not rel <= a.rtol:
                sys.exit(f"FAIL: turgor's tip deflection differs from the reference by {rel:.2e}")


if __name__ == "__main__":
    main()
