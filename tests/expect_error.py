#!/usr/bin/python3
"""Bad input must end the run cleanly: a non-zero exit status, a message matching REGEX (naming the
option or file and the value), never a crash (a signal, a sanitizer report) or a silent success,
and an output directory that does not lie: empty or absent, or holding a summary.json whose status
is "failed" (the run's -output_dir, the last one on the command line; removed before the run).
A hang is caught by ctest's TIMEOUT.

  expect_error.py REGEX command [args...]
"""
import json, os, re, shutil, subprocess, sys

CRASH = re.compile(r"Segmentation|Caught signal|core dumped|SIGSEGV|SIGFPE|SIGABRT|AddressSanitizer|runtime error:|terminate called")


def output_dir(cmd):
    dirs = [cmd[i + 1] for i in range(len(cmd) - 1) if cmd[i] == "-output_dir"]
    return dirs[-1] if dirs else None


def check_output_dir(d):
    """'' when d is consistent after a failed run, else what is wrong."""
    if not d or not os.path.isdir(d):
        return ""
    files = sorted(os.listdir(d))
    if not files:
        return ""
    if "summary.json" not in files:
        return f"{d} holds {files} but no summary.json saying the run failed"
    try:
        status = json.load(open(os.path.join(d, "summary.json"))).get("status")
    except (OSError, ValueError) as e:
        return f"{d}/summary.json is not readable JSON ({e})"
    if status != "failed":
        return f'{d}/summary.json has status "{status}", not "failed"'
    return ""


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    regex, cmd = argv[1], argv[2:]
    d = output_dir(cmd)
    # only a directory of the build tree (relative) is cleared: never a path the case points elsewhere
    if d and not os.path.isabs(d) and os.path.isdir(d):
        shutil.rmtree(d)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    out, rc = p.stdout, p.returncode
    if rc == 0:
        sys.exit(f"FAIL: expected an error, the command succeeded:\n{out}")
    if rc < 0 or rc >= 128 or CRASH.search(out):
        sys.exit(f"FAIL: crashed (exit {rc}) instead of reporting an error:\n{out}")
    match = re.search(regex, out)
    if not match:
        sys.exit(f"FAIL: the error message does not match /{regex}/:\n{out}")
    wrong = check_output_dir(d) if d and not os.path.isabs(d) else ""
    if wrong:
        sys.exit(f"FAIL: the output directory is inconsistent: {wrong}\n{out}")
    line = next((l for l in out.splitlines() if re.search(regex, l)), match.group(0))
    print(f"ok (exit {rc}): {line.strip()}")


if __name__ == "__main__":
    main(sys.argv)
