#!/usr/bin/python3
"""Cost per node-step of the polygonal-cell forces (bars, hinges, contact, velocity Verlet) from about
1e3 to 1e6 nodes: bench_polygon_forces on square patches of jittered hexagons (6 nodes each), every
patch compressed with the same edge speed (0.1 µm/µs) so that its nodes see the same motion, and
run for the same 400 steps (after 40 of warm-up), so that every size is timed over the same
physical history (neighbour rebuilds and contacts per node alike). Prints ns of CPU per node-step
per size and the spread about the median (the target: flat within 25%).

  bench/node_cost_flatness.py [--bench build/bench/bench_polygon_forces] [--repeats 3]
"""
import argparse, re, statistics, subprocess

SIZES = [(13, 13, 400), (41, 41, 400), (129, 129, 400), (408, 408, 400)]  # ~1.0e3, 1.0e4, 1.0e5, 1.0e6 nodes


def run(bench, nx, ny, steps):
    out = subprocess.run([bench, "-cells_x", str(nx), "-cells_y", str(ny), "-steps", str(steps), "-edge_speed", "0.1"],
                         capture_output=True, text=True, check=True).stdout
    nodes = int(re.search(r"(\d+) nodes", out).group(1))
    ns = float(re.search(r"([\d.]+) ns CPU per node-step", out).group(1))
    cand = re.search(r"contact: (\d+) candidates, (\d+) near", out)
    return nodes, ns, out, cand


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bench", default="build/bench/bench_polygon_forces")
    p.add_argument("--repeats", type=int, default=5, help="runs per size; the fastest counts (the machine is shared)")
    a = p.parse_args()
    rows = []
    for nx, ny, steps in SIZES:
        best = None
        for _ in range(a.repeats):
            nodes, ns, out, cand = run(a.bench, nx, ny, steps)
            if best is None or ns < best[1]:
                best = (nodes, ns, cand)
        rows.append((nx * ny, steps) + best)
    med = statistics.median(r[3] for r in rows)
    print(f"{'cells':>8} {'nodes':>9} {'steps':>6} {'ns/node-step':>13} {'vs median':>10} {'candidates/node':>16} {'near/node':>10}")
    for cells, steps, nodes, ns, cand in rows:
        c, n = (int(cand.group(1)) / nodes, int(cand.group(2)) / nodes) if cand else (0, 0)
        print(f"{cells:>8} {nodes:>9} {steps:>6} {ns:>13.1f} {100 * (ns / med - 1):>+9.1f}% {c:>16.2f} {n:>10.2f}")
    spread = max(abs(r[3] / med - 1) for r in rows)
    print(f"largest deviation from the median: {100 * spread:.1f}% ({'within' if spread <= 0.25 else 'outside'} 25%)")


if __name__ == "__main__":
    main()
