#!/usr/bin/python3
"""Checkpoint files for the restart tests (stdlib only).

  checkpoint_helper.py first DIR DEST       copy DIR's earliest checkpoint_<step>.h5 to DEST (a restart
                                            from a checkpoint written at -checkpoint_interval, not the end)
  checkpoint_helper.py count DIR N          DIR holds exactly N checkpoint_<step>.h5 files, the last of them the
                                            same bytes as DIR/checkpoint.h5 (-checkpoint_keep N)
  checkpoint_helper.py truncate SRC DEST    copy the first half of SRC to DEST (a checkpoint cut short,
                                            as a full disk or a killed copy leaves it)
  checkpoint_helper.py damage SRC DEST DATASET
                                            DEST is SRC with one byte of DATASET's stored values changed
                                            in the file (a bad disk block: HDF5's Fletcher32 finds it)
  checkpoint_helper.py edit SRC DEST DATASET INDEX VALUE
                                            DEST is SRC with DATASET's value INDEX (flat) set to VALUE by
                                            HDF5 (h5py), which rewrites the chunk's Fletcher32: turgor's own
                                            checksum attribute finds it
  checkpoint_helper.py forge SRC DEST DATASET INDEX VALUE
                                            the same, and the dataset's checksum attribute made to match
                                            (a deliberate edit: the values' checks must find it)
  checkpoint_helper.py attribute SRC DEST NAME VALUE
                                            DEST is SRC with the root attribute NAME (an integer) set to VALUE
"""
import glob, os, shutil, struct, sys


def main(argv):
    if len(argv) >= 5 and argv[1] == "damage":
        return damaged(argv)
    if len(argv) >= 6 and argv[1] in ("edit", "forge", "attribute"):
        return edited(argv)
    if len(argv) != 4:
        sys.exit(__doc__)
    mode, src, dest = argv[1:]
    if mode == "first":
        files = sorted(glob.glob(os.path.join(src, "checkpoint_*.h5")))
        if len(files) < 2:
            sys.exit(f"FAIL: {src} holds {len(files)} checkpoint_<step>.h5 files, expected one at an interval and one at the end")
        shutil.copyfile(files[0], dest)
        print(f"{files[0]} -> {dest}")
    elif mode == "count":
        files = sorted(glob.glob(os.path.join(src, "checkpoint_*.h5")))
        if len(files) != int(dest):
            sys.exit(f"FAIL: {src} holds {len(files)} checkpoint_<step>.h5 files, expected {dest}")
        if open(files[-1], "rb").read() != open(os.path.join(src, "checkpoint.h5"), "rb").read():
            sys.exit(f"FAIL: {files[-1]} is not the latest checkpoint, checkpoint.h5")
        print(f"{src}: {len(files)} checkpoints kept, {os.path.basename(files[0])} to {os.path.basename(files[-1])}")
    elif mode == "truncate":
        data = open(src, "rb").read()
        open(dest, "wb").write(data[: len(data) // 2])
        print(f"{src}: {len(data)} bytes, {dest}: {len(data) // 2}")
    else:
        sys.exit(__doc__)


MASK = (1 << 64) - 1


def mix(x):
    """SplitMix64's finaliser, as turgor's checksum (src/io/checkpoint_file.cpp) uses it"""
    x = (x + 0x9E3779B97F4A7C15) & MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK
    return x ^ (x >> 31)


def checksum(values):
    """turgor's checksum of a dataset: the sum of mix(mix(k) ^ word_k) over its values (64-bit words)"""
    import numpy
    flat = numpy.ascontiguousarray(values).reshape(-1)
    words = flat.view(numpy.uint64) if flat.dtype.itemsize == 8 else flat.astype(numpy.uint64)
    return sum(mix(mix(k) ^ int(w)) for k, w in enumerate(words)) & MASK


def edited(argv):
    import h5py, numpy
    mode, src, dest = argv[1:4]
    shutil.copyfile(src, dest)
    with h5py.File(dest, "r+") as f:
        if mode == "attribute":
            f.attrs.modify(argv[4], numpy.int64(int(argv[5])))
            print(f"{dest}: attribute {argv[4]} = {argv[5]}")
            return
        d = f[argv[4]]
        v = d[...]
        v.reshape(-1)[int(argv[5])] = float(argv[6])
        d[...] = v
        if mode == "forge":
            d.attrs.modify("checksum", numpy.uint64(checksum(v)))
        print(f"{dest}: {argv[4]}[{argv[5]}] = {argv[6]}{' (checksum matched)' if mode == 'forge' else ''}")


def damaged(argv):
    import h5py
    src, dest, name = argv[2:5]
    shutil.copyfile(src, dest)
    with h5py.File(dest, "r") as f:
        d = f[name]
        info = d.id.get_chunk_info(0) if d.chunks else None
        offset = info.byte_offset + info.size // 2 if info else d.id.get_offset() + d.id.get_storage_size() // 2
    with open(dest, "r+b") as f:
        f.seek(offset)
        b = f.read(1)
        f.seek(offset)
        f.write(bytes([b[0] ^ 0x5A]))
    print(f"{dest}: byte {offset} of {name} changed")


if __name__ == "__main__":
    main(sys.argv)
