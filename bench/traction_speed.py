#!/usr/bin/python3
"""Speed of a polygonal-tissue scene (default: the 400-cell glued traction scene):
turgor runs it for a fixed number of steps with -log_view, and this prints node-steps per second
(solve stage only, and the whole process) and the cost of each force term in ns per node-step,
from the -log_view events Tg_<term>. Compare with the L-hyphen seed code's 1.05e7 node-steps/s on
its own 390-cell traction scene (the target is 3e7).

  bench/traction_speed.py [--turgor build/turgor] [--scene config/voronoi_traction.yaml] [--steps 3000] [--repeats 3]
"""
import argparse, json, os, re, subprocess, tempfile, time


def run(turgor, scene, steps, extra):
    with tempfile.TemporaryDirectory() as d:
        log = os.path.join(d, "log.txt")
        cmd = [turgor, "-options_file_yaml", scene, "-ts_max_steps", str(steps), "-fine_snapshots", "0", "-fine_energy", "0",
               "-fine_progress_interval", "0", "-output_dir", os.path.join(d, "out"), "-log_view", ":" + log] + extra
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        text = open(log).read()
        summary = json.load(open(os.path.join(d, "out", "summary.json")))
    stage = float(re.search(r"^\s*\d+:\s+fine solve:\s+([\d.e+-]+)", text, re.M).group(1))
    events = {m.group(1): (int(m.group(2)), float(m.group(3))) for m in re.finditer(r"^(Tg\w+)\s+(\d+) [\d.]+ ([\d.e+-]+)", text, re.M)}
    return wall, stage, events, summary


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--scene", default="config/voronoi_traction.yaml")
    p.add_argument("--steps", type=int, default=3000)
    p.add_argument("--repeats", type=int, default=3, help="runs; the fastest solve stage counts (the machine is shared)")
    p.add_argument("extra", nargs="*", help="more turgor options (after --)")
    a = p.parse_args()
    best = None
    for _ in range(a.repeats):
        r = run(a.turgor, a.scene, a.steps, a.extra)
        if best is None or r[1] < best[1]:
            best = r
    wall, stage, events, s = best
    nodes, steps = s["n_nodes"], s["steps"]
    ns = nodes * steps
    print(f"{a.scene}: {s['n_cells']} cells, {nodes} nodes, {s.get('bonds_created', 0)} bonds, {steps} steps ({s['ts_type']}), physics {','.join(s['physics'])}")
    print(f"solve stage {stage:.3f} s: {ns / stage:.3e} node-steps/s ({1e9 * stage / ns:.1f} ns per node-step); whole process {wall:.2f} s: {ns / wall:.3e} node-steps/s")
    print(f"{'event':<16} {'count':>6} {'time s':>8} {'ns/node-step':>13} {'share':>6}")
    for name, (count, t) in sorted(events.items(), key=lambda kv: -kv[1][1]):
        if name in ("TgOutput", "TgVoronoi") or t == 0:
            continue
        print(f"{name:<16} {count:>6} {t:>8.3f} {1e9 * t / (count * nodes):>13.2f} {t / stage:>6.1%}")
    print(f"seed code 1.05e7 node-steps/s: x{ns / stage / 1.05e7:.2f}; target 3e7: x{ns / stage / 3e7:.2f}")


if __name__ == "__main__":
    main()
