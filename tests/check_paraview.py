#!/usr/bin/env pvpython
"""Open turgor's XDMF output in ParaView itself (pvpython, no window) and check what a user gets.

  pvpython check_paraview.py fine RUN_DIR [--reader XDMFReader]
  pvpython check_paraview.py fe2  RUN_DIR [--reader XDMFReader]
  pvpython check_paraview.py polygons RUN_DIR [--reader XDMFReader]   (see check_polygons)
  pvpython check_paraview.py modes RUN_DIR [--reader XDMFReader]      (see check_modes: -mode eigen's modes.xmf)

RUN_DIR holds summary.json and particles.xmf (fine) or coarse.xmf (fe2). The file is opened with
ParaView's default reader for .xmf (OpenDataFile; the reader it picked is printed), or the one named
by --reader (XDMFReader: the legacy reader). At the last time step the data are fetched to the client
(servermanager.Fetch) and checked:

  fine  two blocks: the particles, one vertex cell per particle, and the wall springs, one
        two-point line per spring; point arrays velocity (3 components, z = 0, floating point) and
        kind, cell, fixed (1 component, integer types; kind counts the wall and fluid particles of
        summary.json); the tip particle (the wall particle nearest the middle of the right side of
        the initial bounding box, as the run chooses it) moved vertically by summary.json's
        tip_displacement_final (and tip.csv's last row), to 1e-6 relative.
  fe2   one block of summary.json's n_elements quadrilaterals; point arrays displacement and
        velocity (3 components, z = 0), cell arrays stress (a 9-component tensor, xx, xy, 0 / xy,
        yy, 0 / 0, 0, 0, equal to stress_xx, stress_yy, stress_xy), density (> 0), acoustic_min_det
        (finite, > 0: the bending bar stays elliptic); WarpByVector with
        the displacement moves the tip vertex (nearest the middle of the right side) by summary.json's
        tip_displacement_final to 1e-6 relative, and the clamped left side not at all.

Exits non-zero with a line starting FAIL on the first failed check.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkDataObject

RTOL = 1e-6
VTK_VERTEX, VTK_POLY_VERTEX, VTK_LINE, VTK_POLY_LINE, VTK_POLYGON, VTK_QUAD = 1, 2, 3, 4, 7, 9


def fail(msg):
    print(f"FAIL: {msg}", flush=True)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def close(a, b, rtol=RTOL):
    return abs(a - b) <= rtol * max(abs(a), abs(b), 1e-300)


def leaves(data):
    """The datasets of a (possibly composite) data object, in order."""
    if not data.IsA("vtkCompositeDataSet"):
        return [data]
    out, it = [], data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        out.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return out


def fetch(proxy, t):
    """The data of `proxy` at time t on the client; fails if it is not that time's data."""
    # Fetch updates its own reduction filter without a time (the reader then answers with its first
    # step, or all of them): ForceTime asks the pipeline above for t
    forced = simple.ForceTime(Input=proxy, ForcedTime=t, IgnorePipelineTime=1)
    data = sm.Fetch(forced)
    simple.Delete(forced)
    dt = data.GetInformation().Get(vtkDataObject.DATA_TIME_STEP())  # (the blocks' own keys are stale)
    check(dt is not None and close(dt, t, 1e-12), f"fetched the data of time {dt}, asked for t = {t}")
    return leaves(data)


def array(block, assoc, name, ncomp, integer):
    attrs = block.GetPointData() if assoc == "point" else block.GetCellData()
    a = attrs.GetArray(name)
    n = block.GetNumberOfPoints() if assoc == "point" else block.GetNumberOfCells()
    check(a is not None, f"no {assoc} array '{name}' (have: {[attrs.GetArrayName(i) for i in range(attrs.GetNumberOfArrays())]})")
    check(a.GetNumberOfComponents() == ncomp, f"{assoc} array '{name}' has {a.GetNumberOfComponents()} components, expected {ncomp}")
    check(a.GetNumberOfTuples() == n, f"{assoc} array '{name}' has {a.GetNumberOfTuples()} tuples for {n} {assoc}s")
    v = vtk_to_numpy(a)
    kind = "integer" if integer else "floating point"
    check((v.dtype.kind in "iu") == bool(integer) and (integer or v.dtype.kind == "f"),
          f"{assoc} array '{name}' is {a.GetDataTypeAsString()}, expected {kind}")
    check(bool(np.isfinite(v).all()), f"{assoc} array '{name}' has non-finite values")
    return v.reshape(n, ncomp) if ncomp > 1 else v.reshape(n)


def points(block):
    x = vtk_to_numpy(block.GetPoints().GetData()).reshape(-1, 3)
    check(bool(np.isfinite(x).all()), "non-finite point coordinates")
    return x


def cells_of(block):
    """(cell types, point ids per cell) of an unstructured grid."""
    types, ids = [], []
    for c in range(block.GetNumberOfCells()):
        cell = block.GetCell(c)
        types.append(cell.GetCellType())
        ids.append([cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())])
    return types, ids


def open_reader(path, reader):
    path = os.path.abspath(path)  # Xdmf3 resolves the HDF5 file wrongly from a bare file name
    check(os.path.exists(path), f"{path} does not exist")
    r = simple.OpenDataFile(path) if reader is None else getattr(simple, reader)(FileNames=[path])
    check(r is not None, f"ParaView has no reader for {path}")
    print(f"{path}: reader {r.GetXMLName()}{' (the default for .xmf)' if reader is None else ''}")
    times = list(r.TimestepValues) if r.TimestepValues else []
    check(len(times) >= 2, f"{len(times)} time steps; the runs checked write at least 2")
    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = times[-1]
    return r, times


def check_times(times, summary):
    check(len(times) == summary["snapshots"], f"{len(times)} time steps, summary.json says {summary['snapshots']} snapshots")
    check(close(times[-1], summary["t_final"], 1e-12), f"last time step {times[-1]}, t_final {summary['t_final']}")


def check_fine(run, reader):
    summary = json.load(open(os.path.join(run, "summary.json")))
    n_wall, n_fluid, n_springs = summary["n_wall_particles"], summary["n_fluid_particles"], summary["n_springs"]
    n = n_wall + n_fluid
    r, times = open_reader(os.path.join(run, "particles.xmf"), reader)
    check_times(times, summary)
    first, last = fetch(r, times[0]), fetch(r, times[-1])
    check(len(last) == 2, f"{len(last)} blocks at the last time step, expected 2 (particles, walls)")
    parts, walls = last
    for name, b in (("particles", parts), ("walls", walls)):
        check(b.GetNumberOfPoints() == n, f"{name}: {b.GetNumberOfPoints()} points, summary.json has {n} particles")
        vel = array(b, "point", "velocity", 3, False)
        check(bool((vel[:, 2] == 0).all()), f"{name}: velocity has a non-zero z component")
        kind = array(b, "point", "kind", 1, True)
        check(int((kind == 0).sum()) == n_wall and int((kind == 1).sum()) == n_fluid,
              f"{name}: kind counts {int((kind == 0).sum())} wall, {int((kind == 1).sum())} fluid; summary.json {n_wall}, {n_fluid}")
        cell = array(b, "point", "cell", 1, True)
        check(bool(((cell >= 0) == (kind == 1)).all()), f"{name}: cell is not >= 0 exactly for the fluid particles")
        fixed = array(b, "point", "fixed", 1, True)
        check(bool(((fixed == 0) | (fixed == 1)).all()) and int(fixed.sum()) > 0, f"{name}: fixed is not a 0/1 flag with clamped particles")
        check(bool((points(b)[:, 2] == 0).all()), f"{name}: points off the plane z = 0")
    types, ids = cells_of(parts)
    check(len(types) == n, f"particles: {len(types)} cells for {n} particles (each particle must be a cell)")
    check(set(types) <= {VTK_VERTEX, VTK_POLY_VERTEX}, f"particles: cell types {sorted(set(types))}, expected vertex cells")
    check(sorted(i for c in ids for i in c) == list(range(n)) and all(len(c) == 1 for c in ids), "particles: the cells are not one per particle")
    types, ids = cells_of(walls)
    check(len(types) == n_springs, f"walls: {len(types)} cells, summary.json has {n_springs} springs")
    check(set(types) <= {VTK_LINE, VTK_POLY_LINE} and all(len(c) == 2 for c in ids), "walls: cells are not two-point lines")
    check(all(kind[i] == 0 for c in ids for i in c), "walls: a spring ends at a fluid particle")

    # the tip as the run chooses it: the wall particle nearest the middle of the right side of the
    # initial bounding box; its vertical displacement at the final time
    x0 = points(first[0])
    kind0 = array(first[0], "point", "kind", 1, True)
    px, py = x0[:, 0].max(), 0.5 * (x0[:, 1].min() + x0[:, 1].max())
    d2 = [(x0[i, 0] - px) ** 2 + (x0[i, 1] - py) ** 2 if kind0[i] == 0 else math.inf for i in range(n)]
    tip = min(range(n), key=lambda i: d2[i])
    uy = points(parts)[tip, 1] - x0[tip, 1]
    want = summary["tip_displacement_final"]
    rows = list(csv.DictReader(open(os.path.join(run, "tip.csv"))))
    check(close(float(rows[-1]["time"]), times[-1], 1e-12), "tip.csv's last row is not at the last time step")
    print(f"  tip particle {tip} at ({x0[tip, 0]:g}, {x0[tip, 1]:g}) µm: uy = {uy:.12g} µm; summary.json {want:.12g} (relative difference "
          f"{abs(uy - want) / abs(want):.1e}), tip.csv {float(rows[-1]['tip_displacement_y']):.12g}")
    check(close(uy, want), f"tip displacement {uy!r} differs from summary.json's {want!r} (relative {abs(uy - want) / abs(want):.2g})")
    check(close(uy, float(rows[-1]["tip_displacement_y"])), "tip displacement differs from tip.csv's last row")
    print(f"  OK: {n} particle vertex cells, {n_springs} spring lines, {len(times)} time steps, arrays velocity(3) kind cell fixed (integer)")


def check_fe2(run, reader):
    summary = json.load(open(os.path.join(run, "summary.json")))
    r, times = open_reader(os.path.join(run, "coarse.xmf"), reader)
    check_times(times, summary)
    blocks = fetch(r, times[-1])
    check(len(blocks) == 1, f"{len(blocks)} blocks at the last time step, expected 1")
    (mesh,) = blocks
    nc = summary["n_elements"]
    types, ids = cells_of(mesh)
    check(len(types) == nc and set(types) == {VTK_QUAD}, f"{len(types)} cells of types {sorted(set(types))}, expected {nc} quadrilaterals")
    used = sorted({i for c in ids for i in c})
    check(used == list(range(mesh.GetNumberOfPoints())), "the quadrilaterals do not use every vertex exactly as numbered")
    disp = array(mesh, "point", "displacement", 3, False)
    vel = array(mesh, "point", "velocity", 3, False)
    check(bool((disp[:, 2] == 0).all() and (vel[:, 2] == 0).all()), "displacement or velocity has a non-zero z component")
    s = array(mesh, "cell", "stress", 9, False)
    sxx, syy, sxy = (array(mesh, "cell", f"stress_{c}", 1, False) for c in ("xx", "yy", "xy"))
    check(bool((s[:, 0] == sxx).all() and (s[:, 4] == syy).all() and (s[:, 1] == sxy).all() and (s[:, 3] == sxy).all()),
          "stress tensor (row-major 3 x 3) differs from stress_xx, stress_yy, stress_xy")
    check(bool((s[:, [2, 5, 6, 7, 8]] == 0).all()), "stress tensor has non-zero z components")
    check(bool((abs(sxx) + abs(syy)).max() > 0), "the stress is zero everywhere at the last time step")
    rho = array(mesh, "cell", "density", 1, False)
    check(bool((rho > 0).all()), "density not positive")
    ac = array(mesh, "cell", "acoustic_min_det", 1, False)
    check(bool(np.isfinite(ac).all() and (ac > 0).all()), f"acoustic_min_det not finite and positive (elliptic) everywhere: {ac.min()}..{ac.max()}")
    mt = mesh.GetCellData().GetTensors()
    if reader is None:
        check(mt is not None and mt.GetName() == "stress", "stress is not the active cell tensor")

    # (before this check, Warp By Vector would abort on a 2-component displacement)
    warp = simple.WarpByVector(Input=r, Vectors=["POINTS", "displacement"])
    blocks = fetch(warp, times[-1])
    check(len(blocks) == 1, f"{len(blocks)} blocks after WarpByVector, expected 1")
    x0, x1 = points(mesh), points(blocks[0])
    check(x1.shape == x0.shape, "WarpByVector changed the number of points")
    check(bool((abs(x1 - x0 - disp) <= 1e-12 * (1 + abs(x0))).all()), "WarpByVector did not move the points by the displacement")
    px, py = x0[:, 0].max(), 0.5 * (x0[:, 1].min() + x0[:, 1].max())
    tip = min(range(len(x0)), key=lambda i: math.hypot(x0[i, 0] - px, x0[i, 1] - py))
    uy = x1[tip, 1] - x0[tip, 1]
    want = summary["tip_displacement_final"]
    print(f"  tip vertex {tip} at ({x0[tip, 0]:g}, {x0[tip, 1]:g}) µm: warped uy = {uy:.12g} µm; summary.json {want:.12g} (relative difference "
          f"{abs(uy - want) / abs(want):.1e})")
    check(close(uy, want), f"tip displacement after WarpByVector {uy!r} differs from summary.json's {want!r} (relative {abs(uy - want) / abs(want):.2g})")
    left = x0[:, 0] == x0[:, 0].min()
    check(bool((x1[left] == x0[left]).all()), "WarpByVector moved the clamped left side")
    print(f"  OK: {nc} quadrilaterals, {len(x0)} vertices, {len(times)} time steps, arrays displacement(3) velocity(3) stress(9) "
          f"stress_xx/yy/xy density; stress range [{s[:, 0].min():.4g}, {s[:, 0].max():.4g}] N/m (xx)")


def polygon_area(x, ids):
    return 0.5 * sum(x[ids[k], 0] * x[ids[(k + 1) % len(ids)], 1] - x[ids[(k + 1) % len(ids)], 0] * x[ids[k], 1] for k in range(len(ids)))


def check_polygons(run, reader, gas_p0=None):
    """A polygonal tissue: a third block of summary.json's n_cells closed polygons (VTK polygon cells
    through the particles' points), cell arrays cell_id (integer, 0..n-1 in order) and area_ratio equal to the
    polygon's area from the points at the last time step over its area at the first; the walls
    block has a bar_strain cell array (and an axial_force cell array of the same sign where the run
    wrote one), the particles a 3-component force; with --gas-p0 P0, a pressure cell array equal to
    P0 / area_ratio (the gas law). Open cells (plates, walls) are not in the cells block."""
    summary = json.load(open(os.path.join(run, "summary.json")))
    r, times = open_reader(os.path.join(run, "particles.xmf"), reader)
    check_times(times, summary)
    first, last = fetch(r, times[0]), fetch(r, times[-1])
    bonded = "bonds_created" in summary
    check(len(last) == (4 if bonded else 3), f"{len(last)} blocks at the last time step, expected {4 if bonded else 3} (particles, walls, cells{', bonds' if bonded else ''})")
    cells, walls = last[2], last[1]
    nc = summary.get("n_closed_cells", summary["n_cells"])
    types, ids = cells_of(cells)
    check(len(types) == nc and set(types) == {VTK_POLYGON}, f"cells: {len(types)} cells of types {sorted(set(types))}, expected {nc} polygons")
    cid = array(cells, "cell", "cell_id", 1, True)
    # every cell once, in cell-id order whatever the ranks
    check(list(cid) == list(range(nc)), f"cell_id is {list(cid)}")
    ratio = array(cells, "cell", "area_ratio", 1, False)
    x0, x1 = points(first[2]), points(cells)
    want = [polygon_area(x1, c) / polygon_area(x0, c) for c in ids]
    check(all(polygon_area(x0, c) > 0 for c in ids), "a polygon is not counter-clockwise at t = 0")
    check(all(close(a, b, 1e-12) for a, b in zip(ratio, want)), f"area_ratio {list(ratio)} differs from the points' areas {want}")
    check(max(abs(a - 1) for a in ratio) > 1e-3, "no cell changed its area: the test does not test area_ratio")
    strain = array(walls, "cell", "bar_strain", 1, False)
    check(len(strain) == summary["n_bars"], "bar_strain is not one value per bar")
    extra = ""
    if walls.GetCellData().GetArray("axial_force") is not None:
        force = array(walls, "cell", "axial_force", 1, False)
        check(len(force) == len(strain) and all((f > 0) == (e > 0) for f, e in zip(force, strain) if abs(e) > 1e-12),
              "axial_force is not one value per bar, of the sign of the bar's strain")
        nf = array(last[0], "point", "force", 3, False)
        check(len(nf) == summary["n_nodes"] and all(abs(v[2]) == 0 for v in nf), "force: not a 3-component vector (z = 0) per particle")
        extra += f", axial forces {min(force):.4g} .. {max(force):.4g} µN, node forces up to {max(abs(v[0]) + abs(v[1]) for v in nf):.4g} µN"
    if bonded:  # the glue bonds: one line per bond, intact = 1 for the bonds still intact at the end
        bonds = last[3]
        btypes, _ = cells_of(bonds)
        intact = array(bonds, "cell", "intact", 1, False)
        check(len(btypes) == summary["bonds_created"] and set(btypes) <= {VTK_LINE, VTK_POLY_LINE}, f"bonds: {len(btypes)} cells, expected {summary['bonds_created']} lines")
        check(int(sum(intact)) == summary["bonds_intact"], f"bonds: {int(sum(intact))} intact in the last snapshot, summary says {summary['bonds_intact']}")
        extra += f", {len(btypes)} bonds ({int(sum(intact))} intact)"
    if gas_p0 is not None:
        p = array(cells, "cell", "pressure", 1, False)
        check(all(close(a * q, gas_p0, 1e-9) for a, q in zip(ratio, p)), "pressure is not p0 / area_ratio (the gas law)")
        extra += f", pressure {min(p):.6g} .. {max(p):.6g} N/m = p0 A0/A"
    print(f"  OK: {nc} polygons with {[len(c) for c in ids][:8]}... nodes, area_ratio {[round(float(a), 6) for a in ratio][:8]}..., {len(strain)} bar strains{extra}")


def check_modes(run, reader):
    """-mode eigen's modes.xmf: one time step per mode (time = the mode number, as many as
    summary.json's eigenvalues), each one block of n_elements quadrilaterals with the point arrays
    mode (3 components, z = 0, largest vertex displacement 1, 0 on the clamped left side) and
    displacement (the analysed state, the same at every step); Warp By Vector with the mode moves the
    points by it; two modes differ (the file is not one mode repeated)."""
    summary = json.load(open(os.path.join(run, "summary.json")))
    r, times = open_reader(os.path.join(run, "modes.xmf"), reader)
    n = len(summary["eigenvalues"])
    check([round(t) for t in times] == list(range(1, n + 1)), f"times {times}, expected the mode numbers 1..{n}")
    shapes, state = [], None
    for t in times:
        (mesh,) = fetch(r, t)
        types, _ = cells_of(mesh)
        check(len(types) == summary["n_elements"] and set(types) == {VTK_QUAD}, f"mode {t}: {len(types)} cells, expected {summary['n_elements']} quadrilaterals")
        m = array(mesh, "point", "mode", 3, False)
        d = array(mesh, "point", "displacement", 3, False)
        check(bool((m[:, 2] == 0).all()), f"mode {t} has a z component")
        big = float(np.sqrt((m**2).sum(axis=1)).max())
        check(close(big, 1.0, 1e-12), f"mode {t}: largest vertex displacement {big}, expected 1")
        x0 = points(mesh)
        left = x0[:, 0] == x0[:, 0].min()
        check(bool((m[left] == 0).all()), f"mode {t} moves the clamped left side")
        check(state is None or bool((d == state).all()), f"mode {t}: the state's displacement differs from mode 1's")
        state = d
        shapes.append(m)
    warp = simple.WarpByVector(Input=r, Vectors=["POINTS", "mode"])
    (w,) = fetch(warp, times[0])
    check(bool((abs(points(w) - points(fetch(r, times[0])[0]) - shapes[0]) <= 1e-12).all()), "WarpByVector did not move the points by mode 1")
    check(n < 2 or float(abs(shapes[0] - shapes[1]).max()) > 1e-3, "modes 1 and 2 are the same")
    print(f"  OK: {n} modes on {summary['n_elements']} quadrilaterals, each normalised to 1 µm, clamped side at rest; Warp By Vector moves by the mode")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mode", choices=["fine", "fe2", "polygons", "modes"])
    p.add_argument("run", help="the run's output directory")
    p.add_argument("--reader", help="a ParaView reader to use instead of the default (e.g. XDMFReader)")
    p.add_argument("--gas-p0", type=float, help="polygons: the cells follow the gas law with this p0 [N/m]")
    a = p.parse_args()
    if a.mode == "polygons":
        check_polygons(a.run, a.reader, a.gas_p0)
    else:
        {"fine": check_fine, "fe2": check_fe2, "modes": check_modes}[a.mode](a.run, a.reader)


if __name__ == "__main__":
    main()
