#!/usr/bin/python3
"""A run stops cleanly on SIGTERM (stdlib only).

  interrupt_run.py SIGNALS DIR TURGOR ARGS...

Starts TURGOR ARGS... -output_dir DIR, waits until its first progress line, sends SIGNALS (1 or 2)
SIGTERMs, and requires it to end within 30 s with: one signal, exit status 130 and summary.json
saying "interrupted" at a time before the requested one; two signals, a non-zero exit and a
summary.json saying "interrupted", or "failed" with the reason "Interrupted twice".
"""
import json, signal, subprocess, sys, time


def main(argv):
    count, outdir, cmd = int(argv[1]), argv[2], argv[3:] + ["-output_dir", argv[2], "-output_overwrite"]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    start = time.time()
    for line in p.stdout:  # the first progress line: the run is stepping
        if line.lstrip().startswith("t = "):
            break
    else:
        sys.exit("FAIL: the run ended before its first progress line")
    for k in range(count):
        p.send_signal(signal.SIGTERM)
        time.sleep(0.05)
    sent = time.time()
    try:
        rest, _ = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        sys.exit(f"FAIL: still running 30 s after {count} SIGTERM")
    s = json.load(open(f"{outdir}/summary.json"))
    print(f"stopped {time.time() - sent:.2f} s after {count} SIGTERM (run started {sent - start:.1f} s before), exit {p.returncode}, status {s['status']},"
          f" t_final {s.get('t_final')}, reason: {s.get('reason')}")
    if count == 1:
        if p.returncode != 130 or s["status"] != "interrupted" or not s["t_final"] < s["t_requested"]:
            sys.exit("FAIL: expected exit 130 and an interrupted summary before the requested time")
    else:
        if p.returncode == 0 or not (s["status"] == "interrupted" or (s["status"] == "failed" and "Interrupted twice" in s.get("reason", ""))):
            sys.exit("FAIL: expected a non-zero exit with an interrupted summary, or failed with 'Interrupted twice'")


if __name__ == "__main__":
    main(sys.argv)
