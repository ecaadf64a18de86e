#!/usr/bin/python3
"""A run stops cleanly on SIGTERM (stdlib only).

  interrupt_run.py SIGNALS DIR TURGOR ARGS...

Starts TURGOR ARGS... -output_dir DIR and sends SIGTERM; it must end within 30 s with:
  1        one signal after its first progress line: exit status 130 and summary.json saying
           "interrupted" at a time before the requested one;
  2        two signals after its first progress line: a non-zero exit and a summary.json saying
           "interrupted", or "failed" with the reason "Interrupted twice";
  setup:S[:TEXT]
           one signal S seconds after the start (or after the first line that starts with TEXT),
           in the set-up, to TURGOR and its child processes (mpiexec's ranks, as a batch system
           signals every task; mpiexec alone passes it on a second later and kills the ranks a
           second after that): it ends within 8 s of it, exit
           status 130 (under mpiexec, which ends the job itself: non-zero), summary.json
           "interrupted" and no step taken;
  group:T  a batch system's TERM, then KILL: one SIGTERM to the whole process group after the first
           progress line at t >= T (TURGOR may be mpiexec, which passes it on to the ranks and kills
           them a second later), and SIGKILL to the group as soon as summary.json says the run
           writes the interrupt's checkpoint (checkpoint_pending): summary.json "interrupted", and
           the checkpoint it names as the last complete one (checkpoint_last) is there.
"""
import json, os, signal, subprocess, sys, time


def children(pid):
    """The processes whose parent is pid (Linux /proc)."""
    out = []
    for entry in os.listdir("/proc"):
        try:
            if entry.isdigit() and int(open(f"/proc/{entry}/stat").read().rsplit(")", 1)[1].split()[1]) == pid:
                out.append(int(entry))
        except (OSError, ValueError, IndexError):
            pass
    return out


def wait_progress(p, t=None):
    """Until the first progress line (the run is stepping), or the first at a time >= t."""
    for line in p.stdout:
        words = line.split()
        if len(words) > 2 and words[0] == "t" and words[1] == "=" and (t is None or float(words[2]) >= t):
            return
    sys.exit("FAIL: the run ended before the progress line it was to be interrupted at")


def main(argv):
    how, outdir, cmd = argv[1], argv[2], argv[3:] + ["-output_dir", argv[2], "-output_overwrite"]
    group = how.startswith("group:")
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=group)
    start = time.time()
    limit = 30
    if how.startswith("setup:"):
        delay, _, text = how[len("setup:"):].partition(":")
        for line in p.stdout if text else []:  # the set-up has begun
            if line.startswith(text):
                break
        time.sleep(float(delay))
        p.send_signal(signal.SIGTERM)
        for child in children(p.pid):  # under mpiexec, its ranks too, as a batch system signals every task
            os.kill(child, signal.SIGTERM)
        limit = 8
    elif group:
        wait_progress(p, float(how.split(":")[1]))
        os.killpg(p.pid, signal.SIGTERM)
        while p.poll() is None:
            try:
                if "checkpoint_pending" in json.load(open(f"{outdir}/summary.json")):
                    os.killpg(p.pid, signal.SIGKILL)
                    print("killed while the interrupt's checkpoint was written")
                    break
            except (OSError, ValueError):  # not there yet, or being written
                pass
            time.sleep(0.005)
    else:
        wait_progress(p)
        for k in range(int(how)):
            p.send_signal(signal.SIGTERM)
            time.sleep(0.05)
    sent = time.time()
    try:
        rest, _ = p.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        p.kill()
        sys.exit(f"FAIL: still running {limit} s after SIGTERM ({how})")
    try:
        s = json.load(open(f"{outdir}/summary.json"))
    except (OSError, ValueError) as e:
        sys.exit(f"FAIL: no readable summary.json ({e}); exit {p.returncode}:\n{rest}")
    print(f"stopped {time.time() - sent:.2f} s after SIGTERM ({how}; run started {sent - start:.1f} s before), exit {p.returncode}, status {s['status']},"
          f" t_final {s.get('t_final')}, reason: {s.get('reason')}")
    if how == "1":
        if p.returncode != 130 or s["status"] != "interrupted" or not s["t_final"] < s["t_requested"]:
            sys.exit("FAIL: expected exit 130 and an interrupted summary before the requested time")
    elif how == "2":
        if p.returncode == 0 or not (s["status"] == "interrupted" or (s["status"] == "failed" and "Interrupted twice" in s.get("reason", ""))):
            sys.exit("FAIL: expected a non-zero exit with an interrupted summary, or failed with 'Interrupted twice'")
    elif how.startswith("setup:"):
        # mpiexec ends the job it was signalled to stop with its own status (1)
        mpi = os.path.basename(cmd[0]).startswith("mpi")
        if (p.returncode == 0 if mpi else p.returncode != 130) or s["status"] != "interrupted" or s.get("steps", 0) != 0:
            sys.exit(f"FAIL: expected exit 130 (under mpiexec: non-zero) and an interrupted summary without a step:\n{rest}")
    else:
        last = s.get("checkpoint_last", "")
        print(f"last complete checkpoint: {last}; files: {sorted(os.listdir(outdir))}")
        if p.returncode == 0 or s["status"] != "interrupted":
            sys.exit(f"FAIL: expected a non-zero exit and an interrupted summary:\n{rest}")
        if not last or last.endswith(".tmp") or not os.path.isfile(last) or os.path.getsize(last) == 0:
            sys.exit("FAIL: the summary does not name a complete checkpoint that is there")


if __name__ == "__main__":
    main(sys.argv)
