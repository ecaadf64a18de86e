#!/usr/bin/python3
"""Check that an XDMF file written by turgor is consistent with its HDF5 data, as ParaView's XDMF
reader needs it: well-formed XML, every HDF DataItem resolves to a dataset of the stated
dimensions, topologies match the geometry, times increase, and positions are finite.

  check_xdmf.py FILE.xmf
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import h5py


def main(path):
    root = ET.parse(path).getroot()
    base = os.path.dirname(path)
    files = {}
    checked = 0
    for grid in root.iter("Grid"):
        if grid.get("CollectionType") != "Temporal":
            continue
        times = [float(g.find("Time").get("Value")) for g in grid.findall("Grid")]
        if not times or any(b <= a for a, b in zip(times, times[1:])):
            sys.exit(f"FAIL: {grid.get('Name')}: times not increasing: {times}")
        for step in grid.findall("Grid"):
            npoints = None
            for item in step.iter("DataItem"):
                fname, dset = item.text.strip().split(":")
                f = files.setdefault(fname, h5py.File(os.path.join(base, fname), "r"))
                if dset not in f:
                    sys.exit(f"FAIL: {fname}:{dset} does not exist")
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                if f[dset].shape != dims:
                    sys.exit(f"FAIL: {fname}:{dset} has shape {f[dset].shape}, the XDMF says {dims}")
                if dset.endswith("/position"):
                    npoints = dims[0]
                    if not all(math.isfinite(v) for v in f[dset][:].ravel()):
                        sys.exit(f"FAIL: {dset} has non-finite positions")
                checked += 1
            topo = step.find("Topology")
            if topo.get("TopologyType") == "Polyvertex" and int(topo.get("NumberOfElements")) != npoints:
                sys.exit("FAIL: Polyvertex count differs from the number of positions")
            if topo.get("TopologyType") == "Polyline":
                conn = files[topo.find("DataItem").text.strip().split(":")[0]][topo.find("DataItem").text.strip().split(":")[1]][:]
                if conn.min() < 0 or conn.max() >= npoints:
                    sys.exit("FAIL: spring connectivity outside the particle range")
    print(f"{path}: {checked} data items consistent with their HDF5 datasets")


if __name__ == "__main__":
    main(sys.argv[1])
