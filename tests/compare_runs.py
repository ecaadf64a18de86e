#!/usr/bin/python3
"""Compare two turgor runs' outputs (stdlib only, so CI needs no extra packages).

  compare_runs.py tip A_DIR B_DIR TOL        tip.csv histories agree within TOL (absolute, µm; a static
                                             run's rows are load factors instead of times)
  compare_runs.py tiprel A_DIR REF_DIR TOL   max |tip_a - tip_ref| <= TOL * max |tip_ref|
  compare_runs.py positive DIR KEY           summary.json[KEY] > 0
  compare_runs.py final A_DIR B_DIR RELTOL   final tip displacements agree within RELTOL (relative)
  compare_runs.py keys DIR KEY...            summary.json has the keys, with finite values
  compare_runs.py invariants DIR RELTOL      rve.csv: trace and determinant of sigma stay constant
                                             (a rigid rotation must only rotate the stress)
  compare_runs.py numbers A B RELTOL         two files of whitespace-separated numbers agree
                                             (|a - b| <= RELTOL * max |b|, per line)
  compare_runs.py identical A_DIR B_DIR KEY...  tip.csv byte for byte, and summary.json[KEY] equal
  compare_runs.py samefiles A_DIR B_DIR FILE...  the files are byte for byte the same in both runs
                                             (a restarted run's energy.csv, groups.csv, breaks.csv)
  compare_runs.py increasing DIR             tip.csv's times strictly increase (no row written twice)
  compare_runs.py freefall DIR G TOL         the tip falls freely: |tip(t) + G t^2 / 2| <= TOL (µm)
  compare_runs.py settling DIR RELTOL        a damped oscillation about a rest state: the tip's range
                                             shrinks from third to third of the history, and the
                                             thirds' means agree within RELTOL of their size
  compare_runs.py csvrel A_DIR B_DIR FILE RELTOL   every column of FILE agrees within RELTOL of its largest value
  compare_runs.py samerows A_DIR B_DIR FILE COL...  FILE has the same rows (by those columns) in any order
  compare_runs.py samekey A_DIR B_DIR KEY RELTOL  summary.json[KEY] of the two runs agree within RELTOL (relative)
  compare_runs.py between DIR KEY LO HI      LO <= summary.json[KEY] <= HI
  compare_runs.py equals DIR KEY VALUE       summary.json[KEY] is VALUE (a word, or a list of words joined by commas)
  compare_runs.py contains DIR KEY TEXT...   every TEXT is one of the entries of the list summary.json[KEY]
  compare_runs.py notmore A_DIR B_DIR KEY RELTOL  summary.json[KEY] of A is at most (1 + RELTOL) x B's (strictly
                                             less when RELTOL < 0)
  compare_runs.py csvrow A_CSV ROW_A B_CSV ROW_B RELTOL  row ROW_A of A_CSV and row ROW_B of B_CSV agree in every
                                             column but the first (time), each within RELTOL of the row's
                                             largest |value| (a static equilibrium against a settled dynamic run)
  compare_runs.py pathtangent DIR RELTOL      rve.csv: the stress change from row 0 to row 1 is the row-0
                                             tangent's prediction, D^e [d11, d22, 2 d12] + l s + s l^T - tr(l) s
                                             (its Truesdell rate; l = dF F^-1), within RELTOL of |change|
  compare_runs.py stresspath FE2_DIR RVE_DIR H11 RELTOL
                                             a homogeneous -mode fe2_static stretch (-coarse_boundary_gradient
                                             H11,0,0,0) against -mode rve on the same uniaxial path: tip.csv's
                                             mean stress equals rve.csv's at every common strain below the
                                             localisation (within RELTOL of the largest |stress|), and the
                                             localisation's increment holds the path's first fall of s11
  compare_runs.py column CSV NAME ROW EXPECTED RELTOL [BASE_ROW]
                                             CSV[ROW][NAME] (minus CSV[BASE_ROW][NAME]) is EXPECTED
                                             within RELTOL (relative); ROW -1 is the last row
"""
import csv, json, math, sys


def tip(d):
    """(time, tip) rows; a static run's tip.csv has the load factor where a time run has the time."""
    with open(f"{d}/tip.csv") as f:
        return [(float(r["time"] if "time" in r else r["load_factor"]), float(r["tip_displacement_y"])) for r in csv.DictReader(f)]


def main(argv):
    mode = argv[1]
    if mode == "tip":
        a, b, tol = tip(argv[2]), tip(argv[3]), float(argv[4])
        if len(a) != len(b):
            sys.exit(f"FAIL: {len(a)} vs {len(b)} samples")
        err = max(abs(x[1] - y[1]) for x, y in zip(a, b))
        terr = max(abs(x[0] - y[0]) for x, y in zip(a, b))
        print(f"{len(a)} samples, max |tip_a - tip_b| = {err:.3e} µm, max time difference {terr:.3e}")
        if err > tol or terr > 1e-12:
            sys.exit(f"FAIL: difference above {tol}")
    elif mode == "tiprel":
        a, b, tol = tip(argv[2]), tip(argv[3]), float(argv[4])
        if len(a) != len(b):
            sys.exit(f"FAIL: {len(a)} vs {len(b)} samples")
        scale = max(abs(y[1]) for y in b)
        err = max(abs(x[1] - y[1]) for x, y in zip(a, b)) / scale
        print(f"{len(a)} samples: max |tip - reference| = {err:.3e} of max |reference| = {scale:.4g} µm")
        if not err <= tol:
            sys.exit(f"FAIL: above {tol}")
    elif mode == "positive":
        s = json.load(open(f"{argv[2]}/summary.json"))
        print(f"{argv[3]} = {s[argv[3]]}")
        if not s[argv[3]] > 0:
            sys.exit(f"FAIL: {argv[3]} is not positive")
    elif mode == "final":
        a = json.load(open(f"{argv[2]}/summary.json"))["tip_displacement_final"]
        b = json.load(open(f"{argv[3]}/summary.json"))["tip_displacement_final"]
        rel = abs(a - b) / max(abs(b), 1e-300)
        print(f"final tip displacement {a:.10g} vs {b:.10g} µm, relative difference {rel:.3e}")
        if not rel <= float(argv[4]):
            sys.exit(f"FAIL: relative difference above {argv[4]}")
    elif mode == "keys":
        s = json.load(open(f"{argv[2]}/summary.json"))
        for k in argv[3:]:
            if k not in s:
                sys.exit(f"FAIL: summary.json lacks '{k}'")
            v = s[k]
            if isinstance(v, float) and not math.isfinite(v):
                sys.exit(f"FAIL: summary.json '{k}' = {v}")
        print(f"summary.json has {len(argv) - 3} required keys: {json.dumps({k: s[k] for k in argv[3:]})}")
    elif mode == "invariants":
        rows = list(csv.DictReader(open(f"{argv[2]}/rve.csv")))
        tr = [float(r["s11"]) + float(r["s22"]) for r in rows]
        de = [float(r["s11"]) * float(r["s22"]) - float(r["s12"]) * float(r["s21"]) for r in rows]
        dt = max(abs(t - tr[0]) for t in tr) / abs(tr[0])
        dd = max(abs(d - de[0]) for d in de) / abs(de[0])
        angle = math.degrees(math.atan2(float(rows[-1]["F21"]), float(rows[-1]["F11"])))
        print(f"{len(rows)} states up to {angle:.1f} degrees: trace varies by {dt:.2e}, determinant by {dd:.2e} (relative)")
        if not (dt <= float(argv[3]) and dd <= float(argv[3])):
            sys.exit(f"FAIL: stress invariants change under a rigid rotation (tolerance {argv[3]})")
    elif mode == "numbers":
        la = [list(map(float, l.split())) for l in open(argv[2]) if l.strip()]
        lb = [list(map(float, l.split())) for l in open(argv[3]) if l.strip()]
        if [len(x) for x in la] != [len(x) for x in lb]:
            sys.exit("FAIL: the files have different shapes")
        worst = 0.0
        for x, y in zip(la, lb):
            scale = max(abs(v) for v in y) or 1.0
            worst = max(worst, max(abs(p - q) for p, q in zip(x, y)) / scale)
        print(f"{len(la)} lines, largest difference {worst:.3e} of the line's largest entry")
        if not worst <= float(argv[4]):
            sys.exit(f"FAIL: above {argv[4]}")
    elif mode == "identical":
        ta, tb = open(f"{argv[2]}/tip.csv", "rb").read(), open(f"{argv[3]}/tip.csv", "rb").read()
        if ta != tb:
            worst = max((abs(x[1] - y[1]) for x, y in zip(tip(argv[2]), tip(argv[3]))), default=math.inf)
            sys.exit(f"FAIL: tip.csv differs (largest tip difference {worst:.3e} µm)")
        sa, sb = json.load(open(f"{argv[2]}/summary.json")), json.load(open(f"{argv[3]}/summary.json"))
        for k in argv[4:]:
            if sa[k] != sb[k]:
                sys.exit(f"FAIL: summary.json '{k}': {sa[k]} vs {sb[k]}")
        print(f"tip.csv identical ({len(ta)} bytes); equal: {json.dumps({k: sa[k] for k in argv[4:]})}")
    elif mode == "samefiles":
        for name in argv[4:]:
            fa, fb = open(f"{argv[2]}/{name}", "rb").read(), open(f"{argv[3]}/{name}", "rb").read()
            if fa != fb:
                la, lb = fa.splitlines(), fb.splitlines()
                first = next((k for k, (x, y) in enumerate(zip(la, lb)) if x != y), min(len(la), len(lb)))
                sys.exit(f"FAIL: {name} differs from line {first + 1} ({len(la)} vs {len(lb)} lines)")
        print(f"identical: {' '.join(argv[4:])}")
    elif mode == "increasing":
        times = [t for t, _ in tip(argv[2])]
        bad = [k for k in range(1, len(times)) if not times[k] > times[k - 1]]
        if bad:
            sys.exit(f"FAIL: tip.csv row {bad[0] + 1} at t = {times[bad[0]]} does not follow t = {times[bad[0] - 1]}")
        print(f"{len(times)} rows, times increasing from {times[0]} to {times[-1]}")
    elif mode == "freefall":
        g, tol = float(argv[3]), float(argv[4])
        err = max(abs(y + 0.5 * g * t * t) for t, y in tip(argv[2]))
        print(f"max |tip + g t^2/2| = {err:.3e} µm (g = {g})")
        if not err <= tol:
            sys.exit(f"FAIL: not a free fall within {tol} µm")
    elif mode == "settling":
        y = [v for _, v in tip(argv[2])]
        n = len(y) // 3
        thirds = [y[:n], y[n : 2 * n], y[2 * n :]]
        ranges = [max(p) - min(p) for p in thirds]
        means = [sum(p) / len(p) for p in thirds]
        spread = (max(means) - min(means)) / max(abs(m) for m in means)
        print(f"range by thirds {['%.4g' % r for r in ranges]} µm, means {['%.6g' % m for m in means]} µm (spread {spread:.2e})")
        if not (ranges[0] > ranges[1] > ranges[2]):
            sys.exit("FAIL: the oscillation does not decay")
        if not spread <= float(argv[3]):
            sys.exit(f"FAIL: the mean moves by more than {argv[3]}")
    elif mode == "csvrel":
        # every column of FILE in both runs: max |a - b| over the rows, relative to the column's
        # largest |b| (absolute where the column is all zero)
        ra = list(csv.reader(open(f"{argv[2]}/{argv[4]}")))
        rb = list(csv.reader(open(f"{argv[3]}/{argv[4]}")))
        tol = float(argv[5])
        if ra[0] != rb[0] or len(ra) != len(rb):
            sys.exit(f"FAIL: {argv[4]}: columns or row counts differ ({len(ra)} vs {len(rb)} rows)")
        worst, where = 0.0, ""
        for c, name in enumerate(rb[0]):
            a, b = [float(r[c]) for r in ra[1:]], [float(r[c]) for r in rb[1:]]
            scale = max((abs(v) for v in b), default=0.0) or 1.0
            err = max((abs(x - y) for x, y in zip(a, b)), default=0.0) / scale
            if err > worst:
                worst, where = err, name
        print(f"{argv[4]}: {len(rb) - 1} rows, {len(rb[0])} columns, largest relative difference {worst:.3e} ({where or 'none'})")
        if not worst <= tol:
            sys.exit(f"FAIL: above {tol}")
    elif mode == "samerows":
        # the same rows of FILE in both runs by the given columns, in any order (a distributed run
        # gathers its ranks' rows rank by rank)
        cols = argv[5:]
        ra = sorted(tuple(r[c] for c in cols) for r in csv.DictReader(open(f"{argv[2]}/{argv[4]}")))
        rb = sorted(tuple(r[c] for c in cols) for r in csv.DictReader(open(f"{argv[3]}/{argv[4]}")))
        print(f"{argv[4]}: {len(ra)} and {len(rb)} rows, compared by {' '.join(cols)}")
        if ra != rb:
            sys.exit(f"FAIL: the rows differ ({len(set(ra) ^ set(rb))} not in both)")
    elif mode == "samekey":
        a, b = json.load(open(f"{argv[2]}/summary.json"))[argv[4]], json.load(open(f"{argv[3]}/summary.json"))[argv[4]]
        rel = abs(a - b) / max(abs(b), 1e-300)
        print(f"{argv[4]}: {a:.10g} vs {b:.10g}, relative difference {rel:.3e}")
        if not rel <= float(argv[5]):
            sys.exit(f"FAIL: relative difference above {argv[5]}")
    elif mode == "between":
        v, lo, hi = json.load(open(f"{argv[2]}/summary.json"))[argv[3]], float(argv[4]), float(argv[5])
        print(f"{argv[3]} = {v} (expected {lo:g} .. {hi:g})")
        if not lo <= v <= hi:
            sys.exit(f"FAIL: {argv[3]} outside {lo:g} .. {hi:g}")
    elif mode == "equals":
        v = json.load(open(f"{argv[2]}/summary.json")).get(argv[3])
        got = ",".join(str(x) for x in v) if isinstance(v, list) else str(v)
        print(f"{argv[3]} = {got!r} (expected {argv[4]!r})")
        if got != argv[4]:
            sys.exit(f"FAIL: {argv[3]} is {got!r}, not {argv[4]!r}")
    elif mode == "contains":
        v = json.load(open(f"{argv[2]}/summary.json")).get(argv[3], [])
        print(f"{argv[3]} = {v}")
        missing = [t for t in argv[4:] if t not in v]
        if missing:
            sys.exit(f"FAIL: {argv[3]} lacks {missing}")
    elif mode == "notmore":
        a, b = json.load(open(f"{argv[2]}/summary.json"))[argv[4]], json.load(open(f"{argv[3]}/summary.json"))[argv[4]]
        tol = float(argv[5])
        print(f"{argv[4]}: {a} ({argv[2]}) vs {b} ({argv[3]})")
        if not (a <= (1 + tol) * b if tol >= 0 else a < b):
            sys.exit(f"FAIL: {argv[4]} of {argv[2]} is {'not less than' if tol < 0 else 'more than (1 + ' + argv[5] + ') x'} {argv[3]}'s")
    elif mode == "column":
        rows = list(csv.DictReader(open(argv[2])))
        name, row, expected, tol = argv[3], int(argv[4]), float(argv[5]), float(argv[6])
        value = float(rows[row][name]) - (float(rows[int(argv[7])][name]) if len(argv) > 7 else 0.0)
        err = abs(value - expected) / abs(expected)
        print(f"{argv[2]}: {name}[{row}]{' - ' + name + '[' + argv[7] + ']' if len(argv) > 7 else ''} = {value:.8g}, expected {expected:.8g} (relative error {err:.2e})")
        if not err <= tol:
            sys.exit(f"FAIL: above {tol}")
    elif mode == "csvrow":
        ra, rb = list(csv.reader(open(argv[2]))), list(csv.reader(open(argv[4])))
        if ra[0] != rb[0]:
            sys.exit(f"FAIL: the columns differ: {ra[0]} vs {rb[0]}")
        a, b, tol = ra[1:][int(argv[3])], rb[1:][int(argv[5])], float(argv[6])
        scale = max(abs(float(v)) for v in b[1:]) or 1.0
        worst, where = max((abs(float(x) - float(y)), name) for x, y, name in zip(a[1:], b[1:], ra[0][1:]))
        print(f"{argv[2]} row {argv[3]} (t = {a[0]}) against {argv[4]} row {argv[5]} (t = {b[0]}): largest difference {worst:.3e} "
              f"({where}), {worst / scale:.3e} of the row's largest value {scale:.6g}")
        if not worst <= tol * scale:
            sys.exit(f"FAIL: above {tol}")
    elif mode == "stresspath":
        fe2 = list(csv.DictReader(open(f"{argv[2]}/tip.csv")))
        path = list(csv.DictReader(open(f"{argv[3]}/rve.csv")))
        h11, tol = float(argv[4]), float(argv[5])
        loc = json.load(open(f"{argv[2]}/summary.json"))["localisation_load_factor"]
        by_strain = {round((float(r["F11"]) - 1) * 1e9): r for r in path if int(r["ok"])}
        worst, scale, common = 0.0, 0.0, 0
        for r in fe2:
            lam = float(r["load_factor"])
            q = by_strain.get(round(lam * h11 * 1e9))
            if q is None or (loc >= 0 and lam >= loc - 1e-12):
                continue
            common += 1
            for c in ("11", "22", "12"):
                worst = max(worst, abs(float(r[f"mean_s{c}"]) - float(q[f"s{c}"])))
                scale = max(scale, abs(float(q[f"s{c}"])))
        s11 = [(float(r["F11"]) - 1, float(r["s11"])) for r in path if int(r["ok"])]
        fall = next((e1 for (e0, a), (e1, b) in zip(s11, s11[1:]) if b < a), None)
        levels = [float(r["load_factor"]) * h11 for r in fe2]
        print(f"{common} common strains below the localisation: largest stress difference {worst:.3e}, {worst / max(scale, 1e-300):.2e} of "
              f"{scale:.4g}; the path's stress first falls at strain {fall}, fe2_static localised at {loc * h11 if loc >= 0 else None}")
        if common < 2 or not worst <= tol * scale:
            sys.exit(f"FAIL: fewer than 2 common strains, or a difference above {tol}")
        if fall is None or loc < 0:
            sys.exit("FAIL: no fall on the path, or no localisation in fe2_static")
        before = max(e for e in levels if e < loc * h11 - 1e-12)
        if not before < fall <= loc * h11 + 1e-12:
            sys.exit(f"FAIL: the path falls at {fall}, outside the localised increment ({before}, {loc * h11}]")
    elif mode == "pathtangent":
        r0, r1 = list(csv.DictReader(open(f"{argv[2]}/rve.csv")))[:2]
        g = lambda r, k: float(r[k])
        F0 = [[g(r0, "F11"), g(r0, "F12")], [g(r0, "F21"), g(r0, "F22")]]
        det = F0[0][0] * F0[1][1] - F0[0][1] * F0[1][0]
        Fi = [[F0[1][1] / det, -F0[0][1] / det], [-F0[1][0] / det, F0[0][0] / det]]
        dF = [[g(r1, f"F{i}{j}") - g(r0, f"F{i}{j}") for j in (1, 2)] for i in (1, 2)]
        l = [[sum(dF[i][k] * Fi[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
        s = [[g(r0, "s11"), g(r0, "s12")], [g(r0, "s21"), g(r0, "s22")]]
        d = [l[0][0], l[1][1], l[0][1] + l[1][0]]  # d11, d22, 2 d12
        tr = l[0][0] + l[1][1]
        pred, meas = [], []
        for row, (i, j) in zip(("11", "22", "12"), ((0, 0), (1, 1), (0, 1))):
            De = sum(g(r0, f"De{row}_{c}") * d[k] for k, c in enumerate(("11", "22", "12")))
            rot = sum(l[i][k] * s[k][j] + s[i][k] * l[j][k] for k in range(2)) - tr * s[i][j]
            pred.append(De + rot)
            meas.append(g(r1, f"s{i + 1}{j + 1}") - g(r0, f"s{i + 1}{j + 1}"))
        scale = max(abs(m) for m in meas)
        err = max(abs(p - m) for p, m in zip(pred, meas)) / scale
        print(f"stress change (11, 22, 12) {[f'{m:.6g}' for m in meas]}, tangent's prediction {[f'{p:.6g}' for p in pred]}: {err:.2e} of the largest")
        if not err <= float(argv[3]):
            sys.exit(f"FAIL: above {argv[3]}")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
