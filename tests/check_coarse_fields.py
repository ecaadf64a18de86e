#!/usr/bin/python3
"""Compare the coarse fields (coarse.h5) of two FE^2 runs of the same scene on different numbers of
ranks. Each rank writes its own vertices and elements, so the files' vertex and element orders depend
on the distribution: vertices are matched by their reference coordinates and elements by their
vertices' coordinates. Checks that both files hold the same mesh (every vertex and element once,
the connectivity naming existing vertices, counter-clockwise quadrilaterals of positive area), the
same snapshots (count and times), and at matched vertices and elements the same displacement,
velocity, stress and density within RTOL of each dataset's largest value; and that each file's
density is its own reference density times reference area over current area (rho0 A0 / A) up to a
common factor rho0, which ties the vertex and element arrays of the file together.

  check_coarse_fields.py RUN_DIR REF_DIR [RTOL]
"""
import os
import sys

import h5py
import numpy


def fail(msg):
    sys.exit(f"FAIL: {msg}")


def area(xy):  # shoelace over each element's four vertices, xy: (n, 4, 2)
    x, y = xy[:, :, 0], xy[:, :, 1]
    return 0.5 * numpy.sum(x * numpy.roll(y, -1, axis=1) - numpy.roll(x, -1, axis=1) * y, axis=1)


class Fields:
    def __init__(self, d):
        self.f = h5py.File(os.path.join(d, "coarse.h5"), "r")
        self.xy = numpy.array(self.f["/mesh/vertices"])
        self.cells = numpy.array(self.f["/mesh/cells"]).reshape(-1, 4)
        n = len(self.xy)
        if self.cells.min() < 0 or self.cells.max() >= n:
            fail(f"{d}: the connectivity names vertices outside 0..{n - 1}")
        self.vkey = [tuple(numpy.round(p, 9)) for p in self.xy]
        if len(set(self.vkey)) != n:
            fail(f"{d}: a vertex is written twice")
        used = numpy.zeros(n, bool)
        used[self.cells.ravel()] = True
        if not used.all():
            fail(f"{d}: {int((~used).sum())} vertices belong to no element")
        a0 = area(self.xy[self.cells])
        if (a0 <= 0).any():
            fail(f"{d}: {int((a0 <= 0).sum())} elements are not counter-clockwise")
        self.a0 = a0
        self.ckey = [tuple(sorted(self.vkey[v] for v in c)) for c in self.cells]
        if len(set(self.ckey)) != len(self.cells):
            fail(f"{d}: an element is written twice")
        self.snaps = sorted(k for k in self.f if k.startswith("snapshot_"))

    def time(self, s):
        return float(self.f[s].attrs["time"])

    def data(self, s, name):
        return numpy.array(self.f[s][name])


def main():
    if len(sys.argv) < 3:
        fail(__doc__)
    run, ref = Fields(sys.argv[1]), Fields(sys.argv[2])
    rtol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-10
    if sorted(run.vkey) != sorted(ref.vkey):
        fail("the two files hold different vertices")
    if sorted(run.ckey) != sorted(ref.ckey):
        fail("the two files hold different elements")
    vmap = {k: i for i, k in enumerate(ref.vkey)}
    cmap = {k: i for i, k in enumerate(ref.ckey)}
    vperm = numpy.array([vmap[k] for k in run.vkey])  # run vertex -> ref vertex
    cperm = numpy.array([cmap[k] for k in run.ckey])
    if len(run.snaps) != len(ref.snaps) or not run.snaps:
        fail(f"{len(run.snaps)} snapshots against {len(ref.snaps)}")
    worst = 0.0
    for s in run.snaps:
        if run.time(s) != ref.time(s):
            fail(f"{s}: time {run.time(s)} against {ref.time(s)}")
        for name, perm in (("displacement", vperm), ("velocity", vperm), ("stress", cperm), ("density", cperm)):
            a, b = run.data(s, name), ref.data(s, name)[perm]
            scale = max(float(numpy.abs(b).max()), 1e-300)
            err = float(numpy.abs(a - b).max()) / scale
            worst = max(worst, err)
            if not err <= rtol:
                fail(f"{s}/{name}: differs by {err:.3g} of its largest value (tolerance {rtol:g})")
        for f in (run, ref):  # density = rho0 A0 / A: one rho0 over all elements
            u = f.data(s, "displacement")[:, :2]
            ratio = f.data(s, "density") * area((f.xy + u)[f.cells]) / f.a0
            if not numpy.allclose(ratio, ratio[0], rtol=1e-12, atol=0):
                fail(f"{s}: density is not rho0 A0 / A with one rho0 (spread {ratio.min():.17g} .. {ratio.max():.17g})")
    print(f"{len(run.snaps)} snapshots, {len(run.xy)} vertices, {len(run.cells)} elements matched; largest difference {worst:.2e} "
          f"of each field's largest value (tolerance {rtol:g}); density = rho0 A0 / A in both")


if __name__ == "__main__":
    main()
