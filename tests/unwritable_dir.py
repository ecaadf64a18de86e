#!/usr/bin/python3
"""A run into an output directory that exists but cannot be written (stdlib only).

  unwritable_dir.py DIR REGEX command [args...]

Makes DIR an empty directory nobody can write into (chattr +i, which stops root too; chmod 555 for
another user), runs expect_error.py REGEX command... -output_dir DIR (a clear error, no crash), and
makes DIR writable again. Exit 77 (the test is skipped) where neither works (root without the
capability to set the immutable flag).
"""
import os, shutil, subprocess, sys


def writable(d):
    probe = os.path.join(d, ".probe")
    try:
        open(probe, "w").close()
        os.remove(probe)
        return True
    except OSError:
        return False


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    d, regex, cmd = os.path.abspath(argv[1]), argv[2], argv[3:]
    subprocess.run(["chattr", "-i", d], stderr=subprocess.DEVNULL)
    if os.path.isdir(d):
        os.chmod(d, 0o755)
        shutil.rmtree(d)
    os.makedirs(d)
    try:
        if subprocess.run(["chattr", "+i", d], stderr=subprocess.DEVNULL).returncode != 0:
            os.chmod(d, 0o555)
        if writable(d):
            print("SKIP: cannot make a directory unwritable here (no chattr +i, and chmod does not stop this user)")
            sys.exit(77)
        here = os.path.dirname(os.path.abspath(__file__))
        rc = subprocess.run([sys.executable, os.path.join(here, "expect_error.py"), regex] + cmd + ["-output_dir", d]).returncode
        if not os.listdir(d) == []:
            sys.exit(f"FAIL: {d} was written")
        sys.exit(rc)
    finally:
        subprocess.run(["chattr", "-i", d], stderr=subprocess.DEVNULL)
        os.chmod(d, 0o755)


if __name__ == "__main__":
    main(sys.argv)
