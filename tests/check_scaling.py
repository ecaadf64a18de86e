#!/usr/bin/python3
"""Checks bench/scaling.py (the scaling-study driver). Each check works in WORKDIR (in the
build tree), which it empties first.

  check_scaling.py collect SCALING_PY WORKDIR
      --collect on a fabricated study (summary.json files with and without the keys the binary may
      lack, repeats, a meta file, a broken and a foreign summary.json): the CSV's columns exactly,
      the best of the repeats, the efficiencies (strong and weak), the imbalance, empty fields for
      missing keys; and the scene reader without PyYAML.
  check_scaling.py slurm SCALING_PY WORKDIR
      --slurm job scripts (srun and mpiexec launchers): --ntasks / -n, nodes, tasks per node, time,
      partition, account, set-up line, the weak study's grown sizes, submit_all.sh, the meta files;
      nothing run; then --collect of those runs once their summary.json files exist; --dry-run
      writes nothing.
  check_scaling.py local SCALING_PY WORKDIR TURGOR MPIEXEC SCENE
      a real strong and weak study of the fine mode on 1 and 2 ranks (4 x 4 cells, 5 steps): a CSV
      of 2 rows each with the right cells, particles and steps, the plots (or the message saying
      why they were skipped)."""
import csv, json, math, os, shutil, subprocess, sys

COLUMNS = ["mode", "kind", "ranks", "cells", "particles", "steps", "wall_time_s", "time_per_step_s",
           "halo_bytes_per_step", "particles_per_rank_max", "particles_per_rank_mean", "imbalance", "efficiency"]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
    return cond


def run(script, *args, expect_rc=0):
    p = subprocess.run([sys.executable, script, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != expect_rc:
        sys.exit(f"FAIL: scaling.py {' '.join(args)} exited {p.returncode} (expected {expect_rc}):\n{p.stdout}")
    return p.stdout


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return os.path.abspath(path)


def fake_run(rundir, summary=None, meta=None, raw=None):
    os.makedirs(rundir, exist_ok=True)
    with open(os.path.join(rundir, "summary.json"), "w") as f:
        f.write(raw if raw is not None else json.dumps(summary))
    if meta is not None:
        with open(rundir.rstrip("/") + ".json", "w") as f:
            json.dump(meta, f)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


def close(text, value, rel=1e-9):
    try:
        return abs(float(text) - value) <= rel * abs(value)
    except ValueError:
        return False


def fine(ranks, steps, wall, **extra):
    s = {"mode": "fine", "status": "completed", "steps": steps, "wall_time_s": wall, "mpi_ranks": ranks,
         "n_wall_particles": 65, "n_fluid_particles": 256, "n_cells": 16}
    s.update(extra)
    return s


def check_collect(script, work):
    runs = os.path.join(work, "study", "runs")
    # strong: the best of two repeats on 1 rank (1.0 s/step), 0.6 s/step on 2, 0.4 s/step on 4
    fake_run(f"{runs}/fine_strong_r1_k1", fine(1, 10, 10.0))
    fake_run(f"{runs}/fine_strong_r1_k2", fine(1, 10, 12.0))
    fake_run(f"{runs}/fine_strong_r2_k1", fine(2, 10, 6.0, particles_per_rank_max=170, particles_per_rank_mean=160.5,
                                               halo_bytes_per_step=4096))
    fake_run(f"{runs}/fine_strong_r4_k1", fine(4, 8, 3.2, particles_per_rank_max=90, particles_per_rank_mean=80.25,
                                               halo_bytes_per_step=6144.5))
    # weak FE^2: 0.5 s/step on 1 rank, 0.625 on 2 (a directory name that tells nothing: its meta file does)
    fe2 = {"mode": "fe2", "status": "completed", "n_elements": 16, "n_material_points": 80, "n_wall_particles": 240,
           "n_fluid_particles": 1280, "time_material_points_s": 1.0}
    fake_run(f"{runs}/fe2_weak_r1", dict(fe2, mpi_ranks=1, steps=4, wall_time_s=2.0))
    fake_run(f"{runs}/job_1234", dict(fe2, mpi_ranks=2, steps=4, wall_time_s=2.5, n_elements=32, n_wall_particles=480,
                                      n_fluid_particles=2560), meta={"mode": "fe2", "kind": "weak", "ranks": 2})
    fake_run(f"{runs}/fine_strong_r8_k1", raw='{"mode": "fine", "steps": 10, ')  # a run killed while writing
    fake_run(f"{work}/study/other/summary.json_dir", fine(1, 1, 1.0))              # no meta, no telling name
    fake_run(f"{runs}/fine_strong_r16_k1", fine(16, 0, 0.1, status="failed"))       # a failed run: skipped
    out = run(script, "--collect", os.path.join(work, "study"), "--outdir", os.path.join(work, "collected"))
    check("unreadable" in out and "fine_strong_r8_k1" in out, "a broken summary.json is not reported")
    check("neither a meta file" in out, "a run of unknown mode/kind is not reported")
    check("the run failed" in out, "a failed run is not reported")
    header, rows = read_csv(os.path.join(work, "collected", "scaling.csv"))
    check(header == COLUMNS, f"CSV columns {header}, expected {COLUMNS}")
    got = [(r["mode"], r["kind"], r["ranks"]) for r in rows]
    want = [("fe2", "weak", "1"), ("fe2", "weak", "2"), ("fine", "strong", "1"), ("fine", "strong", "2"), ("fine", "strong", "4")]
    if not check(got == want, f"CSV rows {got}, expected {want}"):
        return
    r = {(x["mode"], x["kind"], int(x["ranks"])): x for x in rows}
    expect = {  # (cells, particles, steps, wall, time per step, halo, pmax, pmean, imbalance, efficiency)
        ("fine", "strong", 1): ("16", "321", "10", 10.0, 1.0, "", "", "", "", 1.0),
        ("fine", "strong", 2): ("16", "321", "10", 6.0, 0.6, 4096, 170, 160.5, 170 / 160.5, 1.0 / (2 * 0.6)),
        ("fine", "strong", 4): ("16", "321", "8", 3.2, 0.4, 6144.5, 90, 80.25, 90 / 80.25, 1.0 / (4 * 0.4)),
        ("fe2", "weak", 1): ("16", "1520", "4", 2.0, 0.5, "", "", "", "", 1.0),
        ("fe2", "weak", 2): ("32", "3040", "4", 2.5, 0.625, "", "", "", "", 0.8),
    }
    names = ["cells", "particles", "steps", "wall_time_s", "time_per_step_s", "halo_bytes_per_step",
             "particles_per_rank_max", "particles_per_rank_mean", "imbalance", "efficiency"]
    for key, values in expect.items():
        for name, v in zip(names, values):
            ok = r[key][name] == v if isinstance(v, str) else close(r[key][name], v)
            check(ok, f"{key} {name} = {r[key][name]!r}, expected {v!r}")
    # the scene reader without PyYAML gives what PyYAML would
    sys.modules["yaml"] = None
    sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
    import scaling
    repo = os.path.dirname(os.path.dirname(os.path.abspath(script)))
    faces, box = scaling.scene_size(os.path.join(repo, "config", "bending_bar_64_fe2.yaml"), "fe2")
    check(faces == (4, 4) and box == ((0.0, 0.0), (1600.0, 1600.0)), f"bending_bar_64_fe2.yaml read as {faces}, {box}")
    cells, _ = scaling.scene_size(os.path.join(repo, "config", "bending_bar_64_fine.yaml"), "fine")
    check(cells == (64, 64), f"bending_bar_64_fine.yaml read as {cells} cells")
    check([scaling.grow_factors(r, 1) for r in (1, 2, 4, 6, 8, 16)] == [(1, 1), (2, 1), (2, 2), (3, 2), (4, 2), (4, 4)],
          "weak scaling's growth factors")
    print(f"collect: {len(rows)} rows, columns and efficiencies as expected")


def slurm_file(work, name):
    with open(os.path.join(work, "jobs", name + ".sh")) as f:
        return f.read()


def check_slurm(script, work, scene_dir):
    a = os.path.join(work, "a")
    run(script, "--slurm", "--mode", "fine", "--kind", "strong", "--ranks", "1,2,8", "--tasks-per-node", "4",
        "--time", "00:10:00", "--partition", "short", "--account", "plants", "--setup", "module load petsc/3.18",
        "--turgor", "/opt/turgor/bin/turgor", "--scene", os.path.join(scene_dir, "bending_bar_64_fine.yaml"),
        "--steps", "7", "--outdir", a)
    j = slurm_file(a, "fine_strong_r8_k1")
    for line in ("#SBATCH --ntasks=8\n", "#SBATCH --nodes=2\n", "#SBATCH --ntasks-per-node=4\n", "#SBATCH --time=00:10:00\n",
                 "#SBATCH --partition=short\n", "#SBATCH --account=plants\n", "module load petsc/3.18\n",
                 "srun --ntasks=8 /opt/turgor/bin/turgor ", "-ts_max_steps 7 ", f"-output_dir {a}/runs/fine_strong_r8_k1"):
        check(line in j, f"fine_strong_r8_k1.sh lacks {line!r}")
    check("-tissue_cells_x 64 -tissue_cells_y 64" in j, "the strong study's job does not keep the scene's 64 x 64 cells")
    j1 = slurm_file(a, "fine_strong_r1_k1")
    check("#SBATCH --ntasks=1\n" in j1 and "#SBATCH --nodes=1\n" in j1 and "#SBATCH --ntasks-per-node=1\n" in j1
          and "srun --ntasks=1 " in j1, "fine_strong_r1_k1.sh: not one task on one node")
    with open(os.path.join(a, "submit_all.sh")) as f:
        sub = f.read()
    check(sub.count("sbatch ") == 3 and "fine_strong_r2_k1.sh" in sub, "submit_all.sh does not submit the 3 jobs")
    with open(os.path.join(a, "runs", "fine_strong_r2_k1.json")) as f:
        meta = json.load(f)
    check(meta.get("ranks") == 2 and meta.get("mode") == "fine" and meta.get("kind") == "strong", f"meta file {meta}")
    check(not any(n == "summary.json" for _, _, fs in os.walk(a) for n in fs), "--slurm ran something")

    b = os.path.join(work, "b")
    run(script, "--slurm", "--launcher", "mpiexec", "--mode", "fe2", "--kind", "weak", "--ranks", "2,4", "--repeat", "2",
        "--scene", os.path.join(scene_dir, "bending_bar_fe2.yaml"), "--turgor", "turgor", "--outdir", b,
        "--", "-coarse_partitioner", "metis")
    names = sorted(os.listdir(os.path.join(b, "jobs")))
    check(names == ["fe2_weak_r2_k1.sh", "fe2_weak_r2_k2.sh", "fe2_weak_r4_k1.sh", "fe2_weak_r4_k2.sh"], f"job scripts {names}")
    j2, j4 = slurm_file(b, "fe2_weak_r2_k2"), slurm_file(b, "fe2_weak_r4_k1")
    check("mpiexec -n 2 turgor " in j2 and "#SBATCH --ntasks=2\n" in j2, "fe2_weak_r2_k2.sh: not mpiexec -n 2")
    check("mpiexec -n 4 turgor " in j4 and "#SBATCH --ntasks=4\n" in j4, "fe2_weak_r4_k1.sh: not mpiexec -n 4")
    check("--ntasks-per-node" not in j4 and "--nodes" not in j4 and "--partition" not in j4, "options not asked for are set")
    check("-coarse_dm_plex_box_faces 4,4 -coarse_dm_plex_box_upper 400,400" in j2, "the weak study's base mesh on 2 ranks")
    check("-coarse_dm_plex_box_faces 8,4 -coarse_dm_plex_box_upper 800,400" in j4, "the weak study's mesh does not grow to 8 x 4 on 4 ranks")
    check(j4.rstrip().endswith("-coarse_partitioner metis"), "the extra options after -- are not passed")
    # the jobs ran (fabricated): --collect reads them back through the meta files and directory names
    for r, k, wall in ((2, 1, 3.0), (2, 2, 2.0), (4, 1, 2.5), (4, 2, 4.0)):
        fake_run(os.path.join(b, "runs", f"fe2_weak_r{r}_k{k}"),
                 {"mode": "fe2", "mpi_ranks": r, "steps": 10, "wall_time_s": wall, "n_elements": 8 * r,
                  "n_wall_particles": 120 * r, "n_fluid_particles": 640 * r})
    run(script, "--collect", b)
    _, rows = read_csv(os.path.join(b, "scaling.csv"))
    check([(x["ranks"], x["cells"], x["wall_time_s"]) for x in rows] == [("2", "16", "2"), ("4", "32", "2.5")],
          f"collected Slurm study {rows}")
    check(len(rows) == 2 and close(rows[1]["efficiency"], 0.8), "weak efficiency of the collected Slurm study")

    c = os.path.join(work, "c")
    out = run(script, "--dry-run", "--ranks", "1,3", "--size", "4,4", "--turgor", "/x/turgor", "--outdir", c)
    check("mpiexec -n 3 --allow-run-as-root --oversubscribe /x/turgor " in out, "--dry-run does not print the run on 3 ranks")
    out = run(script, "--dry-run", "--slurm", "--ranks", "5", "--turgor", "/x/turgor", "--outdir", c)
    check("#SBATCH --ntasks=5" in out, "--dry-run --slurm does not print the job")
    check(not os.path.exists(c), "--dry-run wrote files")
    run(script, "--kind", "weak", "--scene", "none", "--ranks", "0,1", expect_rc=2)
    print("slurm: job scripts, submit_all.sh, meta files and their collection as expected")


def check_local(script, work, turgor, mpiexec, scene):
    for kind, cells in (("strong", ["16", "16"]), ("weak", ["16", "32"])):
        out_dir = os.path.join(work, kind)
        out = run(script, "--turgor", turgor, "--mpiexec", mpiexec, "--mode", "fine", "--kind", kind, "--ranks", "1,2",
                  "--scene", scene, "--size", "4,4", "--steps", "5", "--outdir", out_dir)
        print(out)
        header, rows = read_csv(os.path.join(out_dir, "scaling.csv"))
        check(header == COLUMNS, f"{kind}: CSV columns {header}")
        if not check(len(rows) == 2, f"{kind}: {len(rows)} rows, expected 2"):
            continue
        check([x["ranks"] for x in rows] == ["1", "2"], f"{kind}: ranks {[x['ranks'] for x in rows]}")
        check([x["cells"] for x in rows] == cells, f"{kind}: cells {[x['cells'] for x in rows]}, expected {cells}")
        check([x["steps"] for x in rows] == ["5", "5"], f"{kind}: steps {[x['steps'] for x in rows]}")
        check(rows[0]["particles"] == "321", f"{kind}: {rows[0]['particles']} particles on 4 x 4 cells, expected 321")
        check(rows[0]["efficiency"] == "1", f"{kind}: efficiency {rows[0]['efficiency']} at the base rank count")
        t = [float(x["time_per_step_s"]) for x in rows]
        e = float(rows[1]["efficiency"])
        check(all(v > 0 for v in t) and math.isfinite(e) and e > 0, f"{kind}: times per step {t}, efficiency {e}")
        try:
            import matplotlib  # noqa: F401
            for png in ("scaling_time_per_step.png", "scaling_efficiency.png"):
                p = os.path.join(out_dir, png)
                with open(p, "rb") as f:
                    check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"{p} is not a PNG file")
        except ImportError:
            check("plots skipped" in out, "no plots and no message saying why")
        except OSError as err:
            check(False, f"{kind}: plot missing ({err})")
    print("local: strong and weak studies on 1 and 2 ranks as expected")


def main():
    if len(sys.argv) < 4 or sys.argv[1] not in ("collect", "slurm", "local"):
        sys.exit(__doc__)
    what, script, work = sys.argv[1], sys.argv[2], fresh(sys.argv[3])
    if what == "collect":
        check_collect(script, work)
    elif what == "slurm":
        check_slurm(script, work, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(script))), "config"))
    else:
        if len(sys.argv) != 7:
            sys.exit(__doc__)
        check_local(script, work, *sys.argv[4:7])
    if failures:
        sys.exit("FAIL:\n  " + "\n  ".join(failures))


if __name__ == "__main__":
    main()
