#!/usr/bin/env python3
"""Scaling studies of turgor: strong and weak scaling of the fine and FE^2 modes.

Strong scaling: the same tissue on every rank count of --ranks. Weak scaling: the tissue grows with
the ranks so that the work per rank stays fixed: at R ranks the base size (--size, else the
scene's) is multiplied by R / R0 (R0 the smallest rank count of the list), split into two integer
factors a x b = R / R0 as close to square as possible (a >= b, a along x): fine mode, the tissue's
cells (-tissue_cells_x, -tissue_cells_y); FE^2, the coarse mesh's faces and the box with them
(-coarse_dm_plex_box_faces, -coarse_dm_plex_box_upper: the elements keep their size, and the
material points per rank stay fixed). A rank count that is not a multiple of R0 scales both sides
by sqrt(R / R0), rounded (the work per rank is then only nearly fixed; the CSV's cells tell).

Every run goes into its own output directory OUT/runs/<mode>_<kind>_r<R>_k<i> (i = 1..--repeat),
with a small meta file beside it (OUT/runs/<mode>_<kind>_r<R>_k<i>.json: mode, kind, ranks, repeat,
size, command). Locally each run is

  mpiexec -n R --allow-run-as-root --oversubscribe TURGOR -options_file_yaml SCENE -mode MODE
      -ts_max_steps STEPS -<mode>_snapshots 0 -<mode>_progress_interval 0 -output_overwrite
      -output_dir OUT/runs/NAME [size options] [extra options after --]

and its summary.json is read back. Of --repeat runs the fastest (time per step) is kept.

Outputs in OUT: scaling.csv, one row per (mode, kind, ranks):
  mode, kind, ranks       fine or fe2; strong or weak; MPI ranks (summary.json's mpi_ranks)
  cells                   fine: the tissue's cells (n_cells); FE^2: the coarse elements (n_elements)
  particles               wall + fluid particles (FE^2: those of all RVEs together)
  steps                   time steps taken (summary.json)
  wall_time_s             the time integration's wall time (summary.json)
  time_per_step_s         wall_time_s / steps
  halo_bytes_per_step     ghost exchange volume per step (summary.json; empty if the binary lacks it)
  particles_per_rank_max, particles_per_rank_mean   (summary.json; empty if missing)
  imbalance               particles_per_rank_max / particles_per_rank_mean
  efficiency              relative to the smallest rank count R0 of the (mode, kind) group, on the
                          time per step: strong (R0 T_R0) / (R T_R), weak T_R0 / T_R
and the plots scaling_time_per_step.png and scaling_efficiency.png (matplotlib, Agg backend; skipped
with a message when matplotlib is missing).

On a cluster: --slurm writes one Slurm job script per run (OUT/jobs/NAME.sh) and OUT/submit_all.sh
instead of running; after the jobs have finished, --collect OUT reads the runs' summary.json files
back and writes scaling.csv and the plots without running anything.

Examples:
  bench/scaling.py --mode fine --kind strong --ranks 1,2 --steps 50 --outdir out/scaling_fine
  bench/scaling.py --mode fine --kind weak --ranks 1,2,4 --size 32,32 --outdir out/weak_fine
  bench/scaling.py --mode fe2 --kind strong --ranks 1,2 --size 16,16 --outdir out/scaling_fe2 -- -coarse_partitioner metis
  bench/scaling.py --mode fine --kind strong --ranks 16,32,64,128 --slurm --tasks-per-node 64 \\
      --time 00:30:00 --partition compute --setup 'module load petsc/3.18' --turgor /path/to/turgor --outdir study
  sh study/submit_all.sh            # on the cluster; then, when the jobs are done:
  bench/scaling.py --collect study  # scaling.csv and the plots in study/
"""
import argparse, csv, glob, json, math, os, re, shlex, subprocess, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
COLUMNS = ["mode", "kind", "ranks", "cells", "particles", "steps", "wall_time_s", "time_per_step_s",
           "halo_bytes_per_step", "particles_per_rank_max", "particles_per_rank_mean", "imbalance", "efficiency"]
DEFAULT_SCENE = {"fine": "config/bending_bar_64_fine.yaml", "fe2": "config/bending_bar_fe2.yaml"}
DEFAULT_STEPS = {"fine": 50, "fe2": 10}
NAME_RE = re.compile(r"^(fine|fe2)_(strong|weak)_r(\d+)(?:_k(\d+))?$")


# ---------------------------------------------------------------------------------------------
# Scenes and sizes

def read_yaml(path):
    """The scene file as nested dicts. PyYAML if present, else a reader for turgor's scene files
    (nested `key: value` mappings by indentation, # comments; values kept as strings)."""
    try:
        import yaml
        with open(path) as f:
            return yaml.safe_load(f) or {}
    except ImportError:
        pass
    root, stack = {}, [(-1, None)]
    stack[0] = (-1, root)
    with open(path) as f:
        for raw in f:
            line = raw.split("#", 1)[0].rstrip()
            if not line.strip() or ":" not in line:
                continue
            indent = len(line) - len(line.lstrip())
            key, _, value = line.strip().partition(":")
            while stack[-1][0] >= indent:
                stack.pop()
            parent = stack[-1][1]
            if value.strip():
                parent[key.strip()] = value.strip()
            else:
                parent[key.strip()] = {}
                stack.append((indent, parent[key.strip()]))
    return root


def pair(value, what, typ=int):
    """'64,64' (or [64, 64] from PyYAML) -> (64, 64)."""
    if isinstance(value, (list, tuple)):
        parts = list(value)
    else:
        parts = str(value).split(",")
    if len(parts) != 2:
        raise SystemExit(f"scaling.py: {what} = {value!r}: expected two values x,y")
    try:
        return tuple(typ(p) for p in parts)
    except ValueError:
        raise SystemExit(f"scaling.py: {what} = {value!r}: expected two numbers x,y")


def scene_size(scene, mode):
    """(size, box) of the scene: fine the cells (x, y), box None; FE^2 the coarse faces and the
    box's (lower, upper). None where the scene cannot be read (a cluster path) or lacks them."""
    if not scene or not os.path.isfile(scene):
        return None, None
    y = read_yaml(scene)
    if mode == "fine":
        t = y.get("tissue") or {}
        if "cells_x" in t and "cells_y" in t:
            return (int(t["cells_x"]), int(t["cells_y"])), None
        return None, None
    c = y.get("coarse") or {}
    faces = pair(c["dm_plex_box_faces"], "coarse dm_plex_box_faces") if "dm_plex_box_faces" in c else (4, 4)
    lower = pair(c.get("dm_plex_box_lower", "0,0"), "coarse dm_plex_box_lower", float)
    upper = pair(c.get("dm_plex_box_upper", "400,400"), "coarse dm_plex_box_upper", float)
    return faces, (lower, upper)


def grow_factors(ranks, base_ranks):
    """(fx, fy): how much each side grows at `ranks` for a weak study starting at `base_ranks`."""
    if ranks % base_ranks == 0:
        f = ranks // base_ranks
        b = max(d for d in range(1, int(math.isqrt(f)) + 1) if f % d == 0)
        return f // b, b
    s = math.sqrt(ranks / base_ranks)
    return s, s


def fmt_num(v):
    return f"{v:.10g}"


def size_options(args, ranks, base_ranks):
    """(turgor options, size tuple) for a run on `ranks`."""
    if args.size_xy is None:
        return [], None
    fx, fy = (1, 1) if args.kind == "strong" else grow_factors(ranks, base_ranks)
    nx, ny = max(1, round(args.size_xy[0] * fx)), max(1, round(args.size_xy[1] * fy))
    if args.mode == "fine":
        return ["-tissue_cells_x", str(nx), "-tissue_cells_y", str(ny)], (nx, ny)
    opts = ["-coarse_dm_plex_box_faces", f"{nx},{ny}"]
    if args.kind == "weak" and args.box is not None:
        # the elements keep their size at the base size: the box grows with the faces
        (x0, y0), (x1, y1) = args.box
        ex, ey = (x1 - x0) / args.size_xy[0], (y1 - y0) / args.size_xy[1]
        opts += ["-coarse_dm_plex_box_upper", f"{fmt_num(x0 + ex * nx)},{fmt_num(y0 + ey * ny)}"]
    return opts, (nx, ny)


# ---------------------------------------------------------------------------------------------
# Runs

def run_name(mode, kind, ranks, rep):
    return f"{mode}_{kind}_r{ranks}_k{rep}"


def turgor_args(args, rundir, ranks, base_ranks):
    m = args.mode
    opts, size = size_options(args, ranks, base_ranks)
    cmd = [args.turgor]
    if args.scene:
        cmd += ["-options_file_yaml", args.scene]
    # -mode after the scene file: the command line's mode wins over a `mode:` key in the file
    cmd += ["-mode", m, "-ts_max_steps", str(args.steps), f"-{m}_snapshots", "0", f"-{m}_progress_interval", "0",
            "-output_overwrite", "-output_dir", rundir] + opts + args.extra
    return cmd, size


def planned_runs(args):
    base = min(args.ranks)
    runs = []
    # rounds of every rank count (1, 2, 1, 2, ...) rather than each count's repeats in a row: a shared
    # machine's slow spells then touch every rank count alike
    for k in range(1, args.repeat + 1):
        for r in args.ranks:
            name = run_name(args.mode, args.kind, r, k)
            rundir = os.path.join(args.runs_dir, name)
            tcmd, size = turgor_args(args, rundir, r, base)
            runs.append(dict(name=name, rundir=rundir, ranks=r, repeat=k, size=size, turgor_cmd=tcmd))
    return runs


def write_meta(args, run, command):
    meta = dict(mode=args.mode, kind=args.kind, ranks=run["ranks"], repeat=run["repeat"],
                size=list(run["size"]) if run["size"] else None, steps=args.steps, scene=args.scene, command=command)
    with open(run["rundir"] + ".json", "w") as f:
        json.dump(meta, f, indent=1)
        f.write("\n")


def run_local(args, runs):
    mpiexec = shlex.split(args.mpiexec)
    flags = shlex.split(args.mpi_flags if args.mpi_flags is not None else "--allow-run-as-root --oversubscribe")
    failed = []
    for run in runs:
        cmd = mpiexec + ["-n", str(run["ranks"])] + flags + run["turgor_cmd"]
        line = shlex.join(cmd)
        if args.dry_run:
            print(line)
            continue
        os.makedirs(args.runs_dir, exist_ok=True)
        write_meta(args, run, line)
        stale = os.path.join(run["rundir"], "summary.json")
        if os.path.exists(stale):  # an earlier run's: a run that fails early must not be read as this one
            os.remove(stale)
        log = run["rundir"] + ".log"
        t0 = time.time()
        try:
            with open(log, "w") as f:
                rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=args.timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
        except OSError as e:
            rc = f"cannot start ({e})"
        dt = time.time() - t0
        if rc != 0:
            failed.append(run["name"])
            print(f"  {run['name']}: FAILED ({rc}) after {dt:.1f} s; see {log}", file=sys.stderr)
        else:
            print(f"  {run['name']}: {dt:.1f} s", flush=True)
    return failed


SLURM_TEMPLATE = """#!/bin/bash
# turgor scaling study (bench/scaling.py): {mode} {kind}, {ranks} ranks, repeat {repeat}
#SBATCH --job-name=turgor_{name}
{sbatch}#SBATCH --output={rundir}.out
set -e
{setup}
mkdir -p {runs_dir}
{launch}
"""


def slurm_jobs(args, runs):
    jobs_dir = os.path.join(args.outdir, "jobs")
    scripts = []
    for run in runs:
        r = run["ranks"]
        sb = []
        if args.nodes:
            sb.append(f"--nodes={args.nodes}")
        elif args.tasks_per_node:
            sb.append(f"--nodes={-(-r // args.tasks_per_node)}")
        sb.append(f"--ntasks={r}")
        if args.tasks_per_node:
            sb.append(f"--ntasks-per-node={min(r, args.tasks_per_node)}")
        sb.append(f"--time={args.time}")
        if args.partition:
            sb.append(f"--partition={args.partition}")
        if args.account:
            sb.append(f"--account={args.account}")
        if args.exclusive:
            sb.append("--exclusive")
        if args.launcher == "srun":
            launch = ["srun", f"--ntasks={r}"] + run["turgor_cmd"]
        else:
            flags = shlex.split(args.mpi_flags) if args.mpi_flags else []
            launch = shlex.split(args.mpiexec) + ["-n", str(r)] + flags + run["turgor_cmd"]
        text = SLURM_TEMPLATE.format(mode=args.mode, kind=args.kind, ranks=r, repeat=run["repeat"], name=run["name"],
                                     sbatch="".join(f"#SBATCH {s}\n" for s in sb), rundir=shlex.quote(run["rundir"]),
                                     setup=args.setup or "# (no set-up: --setup 'module load ...')",
                                     runs_dir=shlex.quote(args.runs_dir), launch=shlex.join(launch))
        path = os.path.join(jobs_dir, run["name"] + ".sh")
        scripts.append(path)
        if args.dry_run:
            print(f"# {path}\n{text}")
            continue
        os.makedirs(jobs_dir, exist_ok=True)
        os.makedirs(args.runs_dir, exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        os.chmod(path, 0o755)
        write_meta(args, run, shlex.join(launch))
    submit = os.path.join(args.outdir, "submit_all.sh")
    text = "#!/bin/sh\n# Submits every job of this scaling study; then: bench/scaling.py --collect " + \
           shlex.quote(args.outdir) + "\nset -e\n" + "".join(f"sbatch {shlex.quote(s)}\n" for s in scripts)
    if args.dry_run:
        print(f"# {submit}\n{text}")
        return
    with open(submit, "w") as f:
        f.write(text)
    os.chmod(submit, 0o755)
    print(f"{len(scripts)} job scripts in {jobs_dir}; submit them with: sh {submit}\n"
          f"then collect the results with: {sys.argv[0]} --collect {args.outdir}")


# ---------------------------------------------------------------------------------------------
# Collecting results

def num(d, key):
    v = d.get(key)
    if isinstance(v, bool) or v is None:
        return math.nan
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def read_run(summary_path):
    """One run's row (without efficiency), or None with a warning."""
    rundir = os.path.dirname(summary_path)
    name = os.path.basename(os.path.normpath(rundir))
    try:
        with open(summary_path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        print(f"warning: {summary_path}: unreadable ({e}); skipped", file=sys.stderr)
        return None
    meta = {}
    if os.path.isfile(rundir.rstrip("/") + ".json"):
        try:
            with open(rundir.rstrip("/") + ".json") as f:
                meta = json.load(f)
        except (OSError, ValueError) as e:
            print(f"warning: {rundir}.json: unreadable ({e}); using the directory name", file=sys.stderr)
    m = NAME_RE.match(name)
    mode = meta.get("mode") or (m.group(1) if m else s.get("mode"))
    kind = meta.get("kind") or (m.group(2) if m else None)
    if mode not in ("fine", "fe2") or kind not in ("strong", "weak"):
        print(f"warning: {rundir}: neither a meta file nor a directory name <mode>_<kind>_r<ranks> tells the "
              f"mode and kind; skipped", file=sys.stderr)
        return None
    if s.get("mode") and s["mode"] != mode:
        print(f"warning: {rundir}: summary.json says mode {s['mode']}, the study {mode}", file=sys.stderr)
    status = s.get("status", "completed")
    if status == "failed":
        print(f"warning: {rundir}: the run failed (summary.json status 'failed'); skipped", file=sys.stderr)
        return None
    if status not in ("completed", "stopped"):  # interrupted (a signal, a job's time limit): its steps were timed all the same
        print(f"warning: {rundir}: status {status!r}; its {s.get('steps')} steps are used", file=sys.stderr)
    asked = meta.get("ranks", int(m.group(3)) if m else None)
    ranks = s.get("mpi_ranks", asked)
    if asked is not None and ranks != asked:
        print(f"warning: {rundir}: ran on {ranks} ranks, {asked} were asked for", file=sys.stderr)
    if ranks is None:
        print(f"warning: {rundir}: no rank count; skipped", file=sys.stderr)
        return None
    steps, wall = num(s, "steps"), num(s, "wall_time_s")
    pmax, pmean = num(s, "particles_per_rank_max"), num(s, "particles_per_rank_mean")
    cells = num(s, "n_cells") if mode == "fine" or "n_cells" in s else num(s, "n_elements")
    return dict(mode=mode, kind=kind, ranks=int(ranks), cells=cells,
                particles=num(s, "n_wall_particles") + num(s, "n_fluid_particles"), steps=steps, wall_time_s=wall,
                time_per_step_s=wall / steps if steps > 0 else math.nan,
                halo_bytes_per_step=num(s, "halo_bytes_per_step"), particles_per_rank_max=pmax,
                particles_per_rank_mean=pmean, imbalance=pmax / pmean if pmean > 0 else math.nan,
                efficiency=math.nan, _dir=rundir)


def summaries_under(directory):
    return sorted(glob.glob(os.path.join(directory, "**", "summary.json"), recursive=True))


def collect(paths):
    """The study's rows from the runs' summary.json files `paths`: the fastest of each (mode, kind,
    ranks), efficiencies relative to the smallest rank count of each (mode, kind)."""
    best = {}
    for p in paths:
        row = read_run(p)
        if row is None:
            continue
        key = (row["mode"], row["kind"], row["ranks"])
        old = best.get(key)
        if old is None or (row["time_per_step_s"] < old["time_per_step_s"]) or math.isnan(old["time_per_step_s"]):
            best[key] = row
    rows = [best[k] for k in sorted(best, key=lambda k: (k[0], ["strong", "weak"].index(k[1]), k[2]))]
    for mode, kind in sorted({(r["mode"], r["kind"]) for r in rows}):
        group = [r for r in rows if r["mode"] == mode and r["kind"] == kind]
        ref = group[0]  # the smallest rank count
        for r in group:
            if kind == "strong":
                r["efficiency"] = ref["ranks"] * ref["time_per_step_s"] / (r["ranks"] * r["time_per_step_s"])
                if r["cells"] != ref["cells"] and not (math.isnan(r["cells"]) and math.isnan(ref["cells"])):
                    print(f"warning: {mode} strong: {r['ranks']} ranks ran {r['cells']:g} cells, "
                          f"{ref['ranks']} ranks {ref['cells']:g}", file=sys.stderr)
            else:
                r["efficiency"] = ref["time_per_step_s"] / r["time_per_step_s"]
    return rows, len(paths)


def cell(v):
    if isinstance(v, str):
        return v
    if isinstance(v, int):
        return str(v)
    if v is None or math.isnan(v):
        return ""
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return f"{v:.10g}"


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([cell(r[c]) for c in COLUMNS])


def plot(rows, outdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        print(f"matplotlib is not available ({e}): plots skipped (scaling.csv is written)")
        return []
    files = []
    groups = sorted({(r["mode"], r["kind"]) for r in rows})
    for what, ylabel, fname in (("time_per_step_s", "wall time per step [s]", "scaling_time_per_step.png"),
                                ("efficiency", "parallel efficiency", "scaling_efficiency.png")):
        fig, ax = plt.subplots(figsize=(6, 4.2))
        for mode, kind in groups:
            g = [r for r in rows if (r["mode"], r["kind"]) == (mode, kind) and not math.isnan(r[what])]
            if not g:
                continue
            ax.plot([r["ranks"] for r in g], [r[what] for r in g], "o-", label=f"{mode} {kind}")
            if what == "time_per_step_s" and kind == "strong":
                r0 = g[0]
                ax.plot([r["ranks"] for r in g], [r0["time_per_step_s"] * r0["ranks"] / r["ranks"] for r in g],
                        ":", color="grey", label=f"ideal ({mode} strong)")
        if what == "efficiency":
            ax.axhline(1.0, color="grey", ls=":", lw=1)
            ax.set_ylim(bottom=0)
        else:
            ax.set_yscale("log")
        ax.set_xscale("log", base=2)
        ranks = sorted({r["ranks"] for r in rows})
        ax.set_xticks(ranks)
        ax.set_xticklabels([str(r) for r in ranks])
        ax.set_xlabel("MPI ranks")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        fig.tight_layout()
        path = os.path.join(outdir, fname)
        fig.savefig(path, dpi=120)
        plt.close(fig)
        files.append(path)
    return files


def report(rows, outdir, npaths):
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, "scaling.csv")
    write_csv(rows, path)
    print(f"{len(rows)} rows from {npaths} summary.json files")
    print(f"{'mode':5s} {'kind':6s} {'ranks':>5s} {'cells':>8s} {'particles':>10s} {'s/step':>10s} {'imbal.':>7s} {'eff.':>6s}")
    for r in rows:
        print(f"{r['mode']:5s} {r['kind']:6s} {r['ranks']:5d} {cell(r['cells']):>8s} {cell(r['particles']):>10s} "
              f"{r['time_per_step_s']:10.4g} {r['imbalance']:7.4f} {r['efficiency']:6.3f}")
    files = [path] + plot(rows, outdir)
    print("Outputs: " + ", ".join(files))


# ---------------------------------------------------------------------------------------------

def ranks_list(text):
    try:
        r = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a comma list of rank counts, e.g. 1,2,4")
    if not r or min(r) < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: rank counts must be >= 1")
    return sorted(set(r))


def parse(argv):
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(prog="scaling.py", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 usage="%(prog)s [options] [-- extra turgor options]")
    g = ap.add_argument_group("the study")
    g.add_argument("--mode", choices=("fine", "fe2"), default="fine", help="turgor's mode (default fine)")
    g.add_argument("--kind", choices=("strong", "weak"), default="strong",
                   help="strong: the same tissue on every rank count; weak: the tissue grows with the ranks (default strong)")
    g.add_argument("--ranks", type=ranks_list, default=[1, 2, 4], help="comma list of MPI rank counts (default 1,2,4)")
    g.add_argument("--scene", help="scene file (-options_file_yaml); default config/bending_bar_64_fine.yaml (fine), "
                                   "config/bending_bar_fe2.yaml (fe2); 'none' for turgor's defaults")
    g.add_argument("--size", help="NX,NY: the tissue's cells (fine) or the coarse mesh's faces (fe2) for a strong study, "
                                  "or at the smallest rank count of a weak one (default: the scene's)")
    g.add_argument("--steps", type=int, help="time steps per run, -ts_max_steps (default 50 fine, 10 fe2)")
    g.add_argument("--repeat", type=int, default=1, help="runs per rank count; the fastest is kept (default 1)")
    g.add_argument("--outdir", help="directory of the study: runs/, jobs/, scaling.csv, plots (default out/scaling_<mode>_<kind>; "
                                    "with --collect: the collected directory)")
    g.add_argument("--turgor", default=os.environ.get("TURGOR", os.path.join(REPO, "build", "turgor")),
                   help="the turgor executable (default $TURGOR, else build/turgor of this repository)")
    g.add_argument("--dry-run", action="store_true", help="print the commands (or the job scripts with --slurm); run and write nothing")
    g = ap.add_argument_group("running locally")
    g.add_argument("--mpiexec", default="mpiexec", help="the MPI launcher (default mpiexec)")
    g.add_argument("--mpi-flags", help="flags after `-n R` (default locally '--allow-run-as-root --oversubscribe', "
                                       "in job scripts with --launcher mpiexec none)")
    g.add_argument("--timeout", type=float, help="seconds per run before it is killed (default none)")
    g = ap.add_argument_group("clusters")
    g.add_argument("--slurm", action="store_true", help="write one Slurm job script per run (OUT/jobs/) and OUT/submit_all.sh instead of running")
    g.add_argument("--nodes", type=int, help="nodes per job (default ceil(ranks / --tasks-per-node) when that is given, else Slurm's choice)")
    g.add_argument("--tasks-per-node", type=int, help="MPI ranks per node (#SBATCH --ntasks-per-node)")
    g.add_argument("--time", default="01:00:00", help="time limit per job (default 01:00:00)")
    g.add_argument("--partition", help="Slurm partition (optional)")
    g.add_argument("--account", help="Slurm account (optional)")
    g.add_argument("--exclusive", action="store_true", help="#SBATCH --exclusive (nodes not shared with other jobs)")
    g.add_argument("--setup", help="shell line(s) run before turgor in each job, e.g. 'module load petsc/3.18 openmpi' "
                                   "or 'export LD_LIBRARY_PATH=...'")
    g.add_argument("--launcher", choices=("srun", "mpiexec"), default="srun", help="launcher in the job scripts (default srun)")
    g.add_argument("--collect", metavar="DIR", help="read the summary.json files under DIR (runs of this script, local or Slurm) "
                                                     "and write scaling.csv and the plots; runs nothing")
    args = ap.parse_args(argv)
    args.extra = extra
    if args.repeat < 1:
        ap.error("--repeat must be >= 1")
    if args.collect:
        return args
    if args.steps is None:
        args.steps = DEFAULT_STEPS[args.mode]
    if args.steps < 1:
        ap.error("--steps must be >= 1")
    if args.scene is None:
        args.scene = os.path.join(REPO, DEFAULT_SCENE[args.mode])
    elif args.scene.lower() == "none":
        args.scene = None
    if args.scene and os.path.exists(args.scene):
        args.scene = os.path.abspath(args.scene)
    if "/" in args.turgor:
        args.turgor = os.path.abspath(args.turgor)
    args.outdir = os.path.abspath(args.outdir or os.path.join("out", f"scaling_{args.mode}_{args.kind}"))
    args.runs_dir = os.path.join(args.outdir, "runs")
    scene_xy, args.box = scene_size(args.scene, args.mode)
    if args.mode == "fe2" and args.box is None and args.scene is None:
        args.box = ((0.0, 0.0), (400.0, 400.0))  # turgor's default coarse box
    args.size_xy = pair(args.size, "--size") if args.size else scene_xy
    if args.size_xy is None and args.scene is None:
        args.size_xy = (16, 16) if args.mode == "fine" else (4, 4)  # turgor's defaults
    if args.size_xy is not None and min(args.size_xy) < 1:
        ap.error("--size: both sides must be >= 1")
    if args.kind == "weak" and args.size_xy is None:
        ap.error(f"a weak study needs the base size: --size NX,NY (the scene {args.scene} cannot be read here or has no size)")
    return args


def main(argv=None):
    args = parse(sys.argv[1:] if argv is None else argv)
    if args.collect:
        if not os.path.isdir(args.collect):
            sys.exit(f"scaling.py: --collect {args.collect}: not a directory")
        rows, n = collect(summaries_under(args.collect))
        if not rows:
            sys.exit(f"scaling.py: no run's summary.json under {args.collect}")
        report(rows, args.outdir or args.collect, n)
        return 0
    runs = planned_runs(args)
    if args.slurm:
        slurm_jobs(args, runs)
        return 0
    if not args.dry_run and not os.access(args.turgor, os.X_OK):
        sys.exit(f"scaling.py: --turgor {args.turgor}: not an executable (build turgor, or give its path)")
    print(f"{args.mode} {args.kind} scaling, ranks {','.join(map(str, args.ranks))}, {args.steps} steps, "
          f"{len(runs)} runs into {args.runs_dir}", flush=True)
    failed = run_local(args, runs)
    if args.dry_run:
        return 0
    # this study's runs only (not those of an earlier study in the same directory)
    rows, n = collect([p for p in (os.path.join(r["rundir"], "summary.json") for r in runs) if os.path.isfile(p)])
    if rows:
        report(rows, args.outdir, n)
    if failed:
        print(f"scaling.py: {len(failed)} runs failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0 if rows else 1


if __name__ == "__main__":
    sys.exit(main())
