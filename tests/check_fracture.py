#!/usr/bin/python3
"""Checks on the fracture outputs of a fine run with glue (stdlib only).

  check_fracture.py bonds DIR
      bonds_created = bonds_intact + bonds_broken (summary.json), as many rows in breaks.csv as
      bonds_broken, every bond id once, some bonds broken
  check_fracture.py peaks WINDOW TOL DIR1 DIR2 DIR3
      the quasi-static limit: the peak of the top grip's force (groups.csv top_fy against top_uy),
      smoothed by a running mean over WINDOW µm of displacement (the raw force rings with the
      tissue's vibrations), for three runs at decreasing speeds: the two slowest within TOL
  check_fracture.py energy DIR TOL
      the energy balance closes: summary energy_residual_max and every row's residual_relative in
      energy.csv within TOL, with work done by the controls and bonds broken
  check_fracture.py weaker WINDOW RATIO NOTCHED PLAIN
      the notched specimen's smoothed peak force is below RATIO x the plain one's
  check_fracture.py notch DIR X Y RADIUS N
      the crack starts at the notch: the first N breaks lie within RADIUS µm of its tip (X, Y)
"""
import csv, json, math, sys


def breaks(d):
    return list(csv.DictReader(open(f"{d}/breaks.csv")))


def smoothed_peak(d, window):
    rows = list(csv.DictReader(open(f"{d}/groups.csv")))
    u = [float(r["top_uy"]) for r in rows]
    f = [float(r["top_fy"]) for r in rows]
    n = 400
    grid = [u[-1] * k / (n - 1) for k in range(n)]
    fi, j = [], 0
    for g in grid:  # linear interpolation on the increasing displacement
        while j + 2 < len(u) and u[j + 1] < g:
            j += 1
        a, b = u[j], u[j + 1]
        fi.append(f[j] + (f[j + 1] - f[j]) * ((g - a) / (b - a) if b > a else 0))
    k = max(1, int(window / (grid[1] - grid[0])))
    means = [sum(fi[i : i + k]) / k for i in range(len(fi) - k + 1)]
    return max(f), max(means)


def main(argv):
    if argv[1] == "bonds":
        s, b = json.load(open(f"{argv[2]}/summary.json")), breaks(argv[2])
        ids = {r["bond"] for r in b}
        print(f"bonds: {s['bonds_created']} created = {s['bonds_intact']} intact + {s['bonds_broken']} broken; breaks.csv {len(b)} rows, {len(ids)} bonds")
        if s["bonds_created"] != s["bonds_intact"] + s["bonds_broken"] or len(b) != s["bonds_broken"] or len(ids) != len(b) or not b:
            sys.exit("FAIL: bonds lost, counted twice, or none broken")
    elif argv[1] == "peaks":
        window, tol, dirs = float(argv[2]), float(argv[3]), argv[4:7]
        peaks = [smoothed_peak(d, window) for d in dirs]
        change = abs(peaks[2][1] - peaks[1][1]) / peaks[2][1]
        print("peak force (raw, smoothed over %g µm): %s; the two slowest differ by %.2e" % (window, ", ".join("%.4g, %.4g" % p for p in peaks), change))
        if not change <= tol:
            sys.exit(f"FAIL: the smoothed peak does not converge within {tol}")
    elif argv[1] == "energy":
        s, tol = json.load(open(f"{argv[2]}/summary.json")), float(argv[3])
        rows = list(csv.DictReader(open(f"{argv[2]}/energy.csv")))
        worst = max(abs(float(r["residual_relative"])) for r in rows)
        last = rows[-1]
        print(f"energy: {len(rows)} rows to t = {float(last['time']):.4g} µs, work of the controls {float(last['work_controls']):.6g}, residual {float(last['residual']):.4g}"
              f" ({float(last['residual_relative']):.2e}); largest |residual| / external work {worst:.2e} (summary {s['energy_residual_max']:.2e}); {s.get('bonds_broken', 0)} bonds broken")
        if not (worst <= tol and s["energy_residual_max"] <= tol and float(last["work_controls"]) > 0):
            sys.exit(f"FAIL: the energy balance does not close within {tol}")
    elif argv[1] == "weaker":
        window, ratio = float(argv[2]), float(argv[3])
        a, b = smoothed_peak(argv[4], window)[1], smoothed_peak(argv[5], window)[1]
        print(f"smoothed peak force: notched {a:.5g}, plain {b:.5g} (ratio {a / b:.3f})")
        if not a < ratio * b:
            sys.exit(f"FAIL: the notch does not weaken the specimen below {ratio} of its strength")
    elif argv[1] == "notch":
        x, y, radius, n = float(argv[3]), float(argv[4]), float(argv[5]), int(argv[6])
        b = sorted(breaks(argv[2]), key=lambda r: float(r["time"]))[:n]
        d = [math.hypot(float(r["x"]) - x, float(r["y"]) - y) for r in b]
        print(f"the first {len(b)} breaks lie {min(d):.3g} .. {max(d):.3g} µm from the notch tip ({x}, {y}), from t = {float(b[0]['time']):.4g} µs")
        if len(b) < n or max(d) > radius:
            sys.exit(f"FAIL: the crack does not start within {radius} µm of the notch tip")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
