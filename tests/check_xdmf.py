#!/usr/bin/python3
"""Check that an XDMF file written by turgor is consistent with its HDF5 data, as ParaView's XDMF
readers (the default Xdmf3 readers and the legacy one) need it: well-formed XML; every HDF DataItem
resolves to a dataset of the stated dimensions, number type and precision; times increase; each
topology has its connectivity (a Polyvertex too: without it Xdmf3 builds no cells), within the
points, one cell per point for a Polyvertex; the geometry is finite; vector attributes have 3
components, tensors 9 (Tensor6: 6), scalars 1, as many tuples as their centre (points or cells); and
units are stated (an Information element on the Domain, Name="unit" on the geometry and on every
floating-point attribute).

  check_xdmf.py FILE.xmf
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy

COMPONENTS = {"Scalar": 1, "Vector": 3, "Tensor": 9, "Tensor6": 6}
CONNECTED = {"Polyvertex": 1, "Polyline": None, "Triangle": 3, "Quadrilateral": 4, "Polygon": None, "Mixed": None}


def fail(msg):
    sys.exit(f"FAIL: {msg}")


class Checker:
    def __init__(self, path):
        self.base = os.path.dirname(path)
        self.files = {}
        self.checked = 0

    def data(self, item, where):
        """The dataset of a DataItem, checked against its Dimensions, NumberType and Precision."""
        if item is None:
            fail(f"{where}: no DataItem")
        if item.get("Format") != "HDF":
            fail(f"{where}: DataItem format {item.get('Format')}, turgor writes HDF")
        fname, dset = item.text.strip().split(":")
        if fname not in self.files:
            if not os.path.exists(os.path.join(self.base, fname)):
                fail(f"{where}: {fname} does not exist")
            self.files[fname] = h5py.File(os.path.join(self.base, fname), "r")
        f = self.files[fname]
        if dset not in f:
            fail(f"{where}: {fname}:{dset} does not exist")
        d = f[dset]
        dims = tuple(int(x) for x in item.get("Dimensions").split())
        if d.shape != dims:
            fail(f"{where}: {fname}:{dset} has shape {d.shape}, the XDMF says {dims}")
        ntype, prec = item.get("NumberType", "Float"), int(item.get("Precision", "4"))
        kind = {"Int": "i", "UInt": "u", "Float": "f", "Char": "i", "UChar": "u"}.get(ntype)
        if kind is None or d.dtype.kind != kind or d.dtype.itemsize != prec:
            fail(f"{where}: {fname}:{dset} is {d.dtype}, the XDMF says {ntype} of {prec} bytes")
        self.checked += 1
        return d[()]

    @staticmethod
    def unit(elem, where):
        u = [i.get("Value") for i in elem.findall("Information") if i.get("Name") == "unit"]
        if not u or not u[0]:
            fail(f"{where}: no <Information Name=\"unit\">")

    def step(self, g):
        name = g.get("Name")
        geo = g.find("Geometry")
        if geo is None:
            fail(f"{name}: no Geometry")
        gtype = geo.get("GeometryType", "XYZ")
        x = self.data(geo.find("DataItem"), f"{name} geometry")
        if gtype not in ("XY", "XYZ") or x.ndim != 2 or x.shape[1] != len(gtype):
            fail(f"{name}: geometry {gtype} with data of shape {x.shape}")
        if not all(math.isfinite(v) for v in x.ravel()):
            fail(f"{name}: non-finite positions")
        self.unit(geo, f"{name} geometry")
        npoints = x.shape[0]

        topo = g.find("Topology")
        ttype, ncells = topo.get("TopologyType"), int(topo.get("NumberOfElements"))
        if ttype not in CONNECTED:
            fail(f"{name}: topology {ttype}, turgor writes {sorted(CONNECTED)}")
        conn = self.data(topo.find("DataItem"), f"{name} topology {ttype}")
        if ttype == "Mixed":  # per cell: the type code (3: Polygon), the number of points, the points
            flat, k, cells, points = conn.ravel(), 0, 0, []
            while k < flat.size:
                if flat[k] != 3 or k + 1 >= flat.size:
                    fail(f"{name}: Mixed connectivity: cell {cells} has type code {flat[k]}, turgor writes polygons (3) with their point counts")
                m = int(flat[k + 1])
                points.extend(flat[k + 2 : k + 2 + m])
                k, cells = k + 2 + m, cells + 1
            if k != flat.size or cells != ncells:
                fail(f"{name}: Mixed connectivity of {flat.size} integers holds {cells} cells, the XDMF says {ncells}")
            conn = numpy.array(points, dtype=int)
        else:
            per = CONNECTED[ttype] or int(topo.get("NodesPerElement", "0"))
            if conn.size != ncells * per or (conn.ndim == 2 and conn.shape[0] != ncells):
                fail(f"{name}: {ttype} connectivity of shape {conn.shape} for {ncells} cells of {per} points")
        if conn.size and (conn.min() < 0 or conn.max() >= npoints):
            fail(f"{name}: {ttype} connectivity outside the {npoints} points")
        if ttype == "Polyvertex" and sorted(conn.ravel()) != list(range(npoints)):
            fail(f"{name}: the Polyvertex is not one cell per point")

        for a in g.findall("Attribute"):
            where = f"{name} attribute {a.get('Name')}"
            atype, center = a.get("AttributeType", "Scalar"), a.get("Center", "Node")
            v = self.data(a.find("DataItem"), where)
            n = {"Node": npoints, "Cell": ncells}.get(center)
            if n is None or atype not in COMPONENTS:
                fail(f"{where}: {atype} centred on {center}")
            ncomp = v.size // n if n and v.size % n == 0 and v.shape[0] == n else None
            if ncomp != COMPONENTS[atype]:
                fail(f"{where}: {atype} data of shape {v.shape} for {n} {center.lower()}s (needs {COMPONENTS[atype]} components)")
            if v.dtype.kind == "f":
                if not all(math.isfinite(t) for t in v.ravel()):
                    fail(f"{where}: non-finite values")
                self.unit(a, where)


def main(path):
    root = ET.parse(path).getroot()
    domain = root.find("Domain")
    if domain is None or not [i for i in domain.findall("Information") if i.get("Name") == "units" and i.get("Value")]:
        fail("no <Information Name=\"units\"> on the Domain")
    c = Checker(path)
    collections = [g for g in domain.findall("Grid") if g.get("CollectionType") == "Temporal"]
    if not collections:
        fail("no temporal collection")
    for grid in collections:
        steps = grid.findall("Grid")
        times = [float(g.find("Time").get("Value")) for g in steps]
        if not times or any(b <= a for a, b in zip(times, times[1:])):
            fail(f"{grid.get('Name')}: times not increasing: {times}")
        for g in steps:
            c.step(g)
    print(f"{path}: {c.checked} data items consistent with their HDF5 datasets")


if __name__ == "__main__":
    main(sys.argv[1])
