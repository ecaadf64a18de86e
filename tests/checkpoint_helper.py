#!/usr/bin/python3
"""Checkpoint files for the restart tests (stdlib only).

  checkpoint_helper.py first DIR DEST       copy DIR's earliest checkpoint_<step>.h5 to DEST (a restart
                                            from a checkpoint written at -checkpoint_interval, not the end)
  checkpoint_helper.py truncate SRC DEST    copy the first half of SRC to DEST (a checkpoint cut short,
                                            as a full disk or a killed copy leaves it)
"""
import glob, os, shutil, sys


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    mode, src, dest = argv[1:]
    if mode == "first":
        files = sorted(glob.glob(os.path.join(src, "checkpoint_*.h5")))
        if len(files) < 2:
            sys.exit(f"FAIL: {src} holds {len(files)} checkpoint_<step>.h5 files, expected one at an interval and one at the end")
        shutil.copyfile(files[0], dest)
        print(f"{files[0]} -> {dest}")
    elif mode == "truncate":
        data = open(src, "rb").read()
        open(dest, "wb").write(data[: len(data) // 2])
        print(f"{src}: {len(data)} bytes, {dest}: {len(data) // 2}")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
