#!/usr/bin/python3
"""Speed of the glued traction scenes: turgor runs each for a fixed number of steps with -log_view,
and this prints node-steps per second (solve stage only, and the whole process) and the cost of each
force term in ns per node-step, from the -log_view events Tg_<term>. Two scenes by default, one after
the other:
  seed_shaped  the L-hyphen seed code's own traction example in shape: 400 Voronoi cells with bars as
               long as the cell walls allow (about 5.8 nodes a cell, 2 310 nodes), glue on every
               interface, grips top and bottom, velocity Verlet, one rank (config/voronoi_traction.yaml
               -tissue_bar_length 100); the seed code runs its own at 7.67e6 node-steps/s on this
               machine class, one thread: the target is 3x, 2.3e7;
  traction     config/voronoi_traction.yaml as it is: bars of 2.5 µm, 15 861 nodes.

  bench/traction_speed.py [--turgor build/turgor] [--scenes seed_shaped,traction] [--steps N] [--repeats 3] [-- more options]
"""
import argparse, json, os, re, statistics, subprocess, tempfile, time


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


SEED_CODE = 7.67e6  # node-steps/s of the L-hyphen code on its own traction example, one thread
SCENES = {  # name: (scene file, options, default steps)
    "seed_shaped": ("config/voronoi_traction.yaml", ["-tissue_bar_length", "100"], 10000),
    "traction": ("config/voronoi_traction.yaml", [], 3000),
}


def report(name, runs):
    """The fastest run in detail; with several, every run's rate and their median beside it (on a
    shared machine the fastest is the least disturbed, the spread says how much the rest were)."""
    wall, stage, events, s = best = min(runs, key=lambda r: r[1])
    nodes, steps = s["n_nodes"], s["steps"]
    ns = nodes * steps
    print(f"{name}: {s['n_cells']} cells, {nodes} nodes ({nodes / s['n_cells']:.2f} a cell), {s.get('bonds_created', 0)} bonds, {steps} steps ({s['ts_type']}), physics {','.join(s['physics'])}")
    if len(runs) > 1:
        rates = sorted(ns / r[1] for r in runs)
        print(f"the {len(runs)} runs: {' '.join(f'{x:.3e}' for x in rates)} node-steps/s (median {statistics.median(rates):.3e}); the fastest in detail:")
    print(f"solve stage {stage:.3f} s: {ns / stage:.3e} node-steps/s ({1e9 * stage / ns:.1f} ns per node-step); whole process {wall:.2f} s: {ns / wall:.3e} node-steps/s")
    print(f"{'event':<16} {'count':>6} {'time s':>8} {'ns/node-step':>13} {'share':>6}")
    for ev, (count, t) in sorted(events.items(), key=lambda kv: -kv[1][1]):
        if ev in ("TgOutput", "TgVoronoi") or t == 0:
            continue
        print(f"{ev:<16} {count:>6} {t:>8.3f} {1e9 * t / (count * nodes):>13.2f} {t / stage:>6.1%}")
    print(f"against the seed code's {SEED_CODE:.3g} node-steps/s: x{ns / stage / SEED_CODE:.2f} (target x3: {3 * SEED_CODE:.3g})")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--turgor", default="build/turgor")
    p.add_argument("--scenes", default="seed_shaped,traction", help="comma-separated: " + ", ".join(SCENES))
    p.add_argument("--scene", help="another scene file instead (its own options after --)")
    p.add_argument("--steps", type=int, help="steps per run (default: 10 000 seed_shaped, 3 000 traction)")
    p.add_argument("--repeats", type=int, default=3, help="runs; the fastest solve stage counts (the machine is shared), every run's rate and the median are printed")
    p.add_argument("extra", nargs="*", help="more turgor options (after --)")
    a = p.parse_args()
    if a.scene:
        todo = [(a.scene, (a.scene, [], 3000))]
    else:
        names = a.scenes.split(",")
        for n in names:
            if n not in SCENES:
                p.error(f"--scenes: unknown scene {n!r} (known: {', '.join(SCENES)})")
        todo = [(n, SCENES[n]) for n in names]
    for name, (scene, options, steps) in todo:
        report(name, [run(a.turgor, scene, a.steps or steps, options + a.extra) for _ in range(a.repeats)])


if __name__ == "__main__":
    main()
