#!/usr/bin/env bash
# stand_in.sh LIBRARY OUT_DIR USER...: an empty stand-in for the shared LIBRARY, written to
# OUT_DIR under the same name and soname, that defines as functions (each aborts if called)
# every symbol of LIBRARY that the USER libraries import, so that they load and bind without it.
# For libraries lfcam pulls in but never calls (GDAL and GDCM, through OpenCV's codecs), to keep
# the bundle bundle.sh makes small enough to carry to a lent GPU machine.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: stand_in.sh LIBRARY OUT_DIR USER..." >&2; exit 2; }
library=$1 out=$2
shift 2
name=$(basename "$library")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
nm -D --defined-only "$library" | awk '{print $NF}' | sed 's/@.*//' | sort -u >"$work/defined"
nm -D --undefined-only "$@" 2>/dev/null | awk '{print $NF}' | sed 's/@.*//' | sort -u >"$work/wanted"
comm -12 "$work/defined" "$work/wanted" >"$work/symbols"
{
  echo '#include <stdlib.h>'
  i=0
  while read -r symbol; do
    echo "void f$i(void) __asm__(\"$symbol\");"
    echo "void f$i(void) { abort(); }"
    i=$((i + 1))
  done <"$work/symbols"
} >"$work/stand_in.c"
gcc -shared -fPIC -o "$out/$name" -Wl,-soname,"$name" "$work/stand_in.c"
echo "stand_in: $name with $(wc -l <"$work/symbols") symbols"
