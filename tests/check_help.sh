#!/bin/sh
# -help lists the options of every part of a mode and touches no file: run it on an output
# directory holding a foreign file (with -output_overwrite, which would clear turgor's files) and
# check that the directory is unchanged and each expected option is listed.
#   check_help.sh TURGOR MODE OPTION...
set -u
turgor=$1 mode=$2
shift 2
dir=help_${mode}_$$ # per process: two checks of one mode may run at once
rm -rf "$dir" && mkdir -p "$dir" && echo keep > "$dir/foreign" && echo '{}' > "$dir/summary.json"
out=$("$turgor" -mode "$mode" -help -output_dir "$dir" -output_overwrite 2>&1) || { printf 'FAIL: -help exited with an error:\n%s\n' "$out"; exit 1; }
[ "$(ls "$dir" | tr '\n' ' ')" = "foreign summary.json " ] && [ "$(cat "$dir/summary.json")" = "{}" ] || { echo "FAIL: -help changed $dir: $(ls "$dir")"; exit 1; }
for o in "$@"; do
  printf '%s\n' "$out" | grep -q -- "^ *$o[ <:]" || { echo "FAIL: -help does not list $o"; exit 1; }
done
rm -rf "$dir"
echo "ok: -mode $mode -help lists $# options and leaves its output directory as it was"
