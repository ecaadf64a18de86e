#!/usr/bin/python3
"""Compare the snapshots of two fine runs of the same scene (particles.h5, particles.xmf), dataset by
dataset: the tables are written in id order whatever the ranks, so a run on several ranks writes
what a run on one writes.

  check_snapshots.py RUN_DIR REF_DIR [--rtol R] [--extra NAME...]

Both files have the same datasets (but for snapshot fields named by --extra that RUN_DIR has and
REF_DIR lacks: a distributed run's "rank"), of the same shape and type; integer datasets (the
connectivity, kinds, ids) are equal; real ones equal bit for bit, or with --rtol within R of the
dataset's largest value (a distributed run sums its forces in another order); the snapshot times are
equal. Without --extra the XDMF files are the same text. Each file is also checked to be in id
order: /static/particle_id is 0..N-1, the bar, cell and segment ids strictly increase, and the
connectivity names particles 0..N-1.
"""
import argparse
import os
import sys

import h5py
import numpy


def fail(msg):
    sys.exit(f"FAIL: {msg}")


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def check_order(f, path):
    s = f["static"]
    n = s["particle_id"].shape[0]
    if not numpy.array_equal(s["particle_id"][()].ravel(), numpy.arange(n)):
        fail(f"{path}: /static/particle_id is not 0..{n - 1}")
    for name in s:
        if name in ("bar_id", "cell_id") or name.endswith("_id") and name != "particle_id":
            ids = s[name][()].ravel()
            if len(ids) > 1 and not numpy.all(ids[1:] > ids[:-1]):
                fail(f"{path}: /static/{name} does not increase")
    for name in ("springs", "vertices"):
        c = s[name][()]
        if c.size and (c.min() < 0 or c.max() >= n):
            fail(f"{path}: /static/{name} names particles outside 0..{n - 1}")
    return n


def main():
    p = argparse.ArgumentParser()
    p.add_argument("run")
    p.add_argument("ref")
    p.add_argument("--rtol", type=float, default=0.0)
    p.add_argument("--extra", nargs="*", default=[])
    a = p.parse_args()
    fa, fb = (h5py.File(os.path.join(d, "particles.h5"), "r") for d in (a.run, a.ref))
    n = check_order(fa, a.run)
    check_order(fb, a.ref)
    da, db = datasets(fa), datasets(fb)
    extra = {k for k in set(da) - set(db) if k.split("/")[-1] in a.extra}
    if set(da) - extra != set(db):
        fail(f"datasets only in {a.run}: {sorted(set(da) - set(db) - extra)}, only in {a.ref}: {sorted(set(db) - set(da))}")
    compared, worst = 0, 0.0
    for name in sorted(db):
        x, y = da[name], db[name]
        if x.shape != y.shape or x.dtype != y.dtype:
            fail(f"{name}: {x.shape} {x.dtype} in {a.run}, {y.shape} {y.dtype} in {a.ref}")
        u, v = x[()], y[()]
        if y.dtype.kind in "iu" or a.rtol == 0:
            if not numpy.array_equal(u, v):
                k = numpy.argwhere(u != v)[0]
                fail(f"{name}: differs first at {tuple(k)}: {u[tuple(k)]} in {a.run}, {v[tuple(k)]} in {a.ref}")
        else:
            scale = float(numpy.max(numpy.abs(v))) if v.size else 0.0
            d = float(numpy.max(numpy.abs(u - v))) if v.size else 0.0
            if not d <= a.rtol * scale:
                fail(f"{name}: differs by {d:.3g}, more than {a.rtol:g} x {scale:.3g}")
            worst = max(worst, d / scale if scale else 0.0)
        compared += 1
    groups = sorted(g for g in fb if g.startswith("snapshot_"))
    if sorted(g for g in fa if g.startswith("snapshot_")) != groups or len(groups) < 2:
        fail(f"snapshot groups differ or fewer than 2: {groups}")
    for g in groups:
        if fa[g].attrs["time"] != fb[g].attrs["time"]:
            fail(f"{g}: time {fa[g].attrs['time']} in {a.run}, {fb[g].attrs['time']} in {a.ref}")
    if not a.extra:
        xa, xb = (open(os.path.join(d, "particles.xmf")).read() for d in (a.run, a.ref))
        if xa != xb:
            fail("particles.xmf differs")
    print(f"OK: {compared} datasets of {len(groups)} snapshots ({n} particles) agree" + (f", reals within {worst:.2g} of their largest" if a.rtol else " exactly")
          + (f"; {len(extra)} further datasets {sorted({e.split('/')[-1] for e in extra})} in {a.run}" if extra else ""))


if __name__ == "__main__":
    main()
