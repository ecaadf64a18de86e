#!/usr/bin/python3
"""Checks on groups.csv of a fine run with load controls (stdlib only).

  check_groups.py balance CSV A B T0 T1 TOL
      force balance through the tissue: over the rows with T0 <= time <= T1, the mean of A_fy + B_fy
      is within TOL of the mean |A_fy| (the reactions of two groups that hold the tissue between
      them, e.g. a lid and a floor, once the tissue is at rest)
  check_groups.py agree CSV1 CSV2 COLUMN T0 T1 TOL
      two runs' COLUMN agree: max |c1 - c2| over the rows with T0 <= time <= T1 (same sample times)
      is within TOL of max |c2|
"""
import csv, sys


def rows(path, t0, t1):
    return [r for r in csv.DictReader(open(path)) if t0 <= float(r["time"]) <= t1]


def main(argv):
    if argv[1] == "balance":
        rs = rows(argv[2], float(argv[5]), float(argv[6]))
        a, b = argv[3], argv[4]
        net = sum(float(r[f"{a}_fy"]) + float(r[f"{b}_fy"]) for r in rs) / len(rs)
        scale = sum(abs(float(r[f"{a}_fy"])) for r in rs) / len(rs)
        print(f"{len(rs)} samples in [{argv[5]}, {argv[6]}] µs: mean {a}_fy = {-scale:.6g} µN, mean {a}_fy + {b}_fy = {net:.4g} µN ({abs(net) / scale:.2e} of it)")
        if not (scale > 0 and abs(net) <= float(argv[7]) * scale):
            sys.exit(f"FAIL: the reactions do not balance within {argv[7]}")
    elif argv[1] == "agree":
        t0, t1, col = float(argv[5]), float(argv[6]), argv[4]
        r1, r2 = rows(argv[2], t0, t1), rows(argv[3], t0, t1)
        if len(r1) != len(r2) or any(abs(float(x["time"]) - float(y["time"])) > 1e-9 for x, y in zip(r1, r2)):
            sys.exit("FAIL: the runs were not sampled at the same times")
        diff = max(abs(float(x[col]) - float(y[col])) for x, y in zip(r1, r2))
        scale = max(abs(float(y[col])) for y in r2)
        print(f"{len(r1)} samples in [{t0}, {t1}] µs: max |{col} difference| = {diff:.4g}, {diff / scale:.2e} of max |{col}| = {scale:.6g}")
        if not diff <= float(argv[7]) * scale:
            sys.exit(f"FAIL: above {argv[7]}")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
