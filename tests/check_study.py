#!/usr/bin/python3
"""Checks a quick work-precision study (bench/study.py --quick): the outputs exist and are PNG
images, every integrator finished at every tolerance, and each integrator's error against the
tight reference falls as the tolerance tightens.

  tests/check_study.py OUT_DIR INTEGRATOR..."""
import csv, os, sys


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, integrators = sys.argv[1], sys.argv[2:]
    failures = []
    for name in ("study.csv", "work_precision.png", "error_vs_tol.png", "cost_breakdown.png"):
        path = os.path.join(out, name)
        if not os.path.isfile(path) or os.path.getsize(path) == 0:
            failures.append(f"missing output {path}")
        elif name.endswith(".png"):
            with open(path, "rb") as f:
                if f.read(8) != b"\x89PNG\r\n\x1a\n":
                    failures.append(f"{path} is not a PNG file")
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    with open(os.path.join(out, "study.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["study"] == "integration"]
    for integ in integrators:
        rs = sorted((r for r in rows if r["integrator"] == integ), key=lambda r: -float(r["tol"]))
        if len(rs) < 3:
            failures.append(f"{integ}: {len(rs)} runs, expected at least 3 tolerances")
            continue
        bad = [r["tol"] for r in rs if r["ok"] != "1" or not r["error_vs_reference"]]
        if bad:
            failures.append(f"{integ}: no result at tol {', '.join(bad)}")
            continue
        errs = [float(r["error_vs_reference"]) for r in rs]
        print(f"{integ:8s} tol " + "  ".join(f"{float(r['tol']):.0e}: {e:.2e}" for r, e in zip(rs, errs)))
        if any(b >= a for a, b in zip(errs, errs[1:])):
            failures.append(f"{integ}: the error does not fall as the tolerance tightens ({errs})")
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    print("study outputs present; the error falls with the tolerance for " + ", ".join(integrators))


if __name__ == "__main__":
    main()
