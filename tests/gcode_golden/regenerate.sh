#!/usr/bin/env bash
# Regenerates each golden program's LinuxCNC trace (NAME.canon) with
# LinuxCNC's rs274 (2.9), which is not needed to run the tests:
#
#   RS274=/path/to/rs274 bash tests/gcode_golden/regenerate.sh
#
# rs274's tool table is in its machine units, inches: tools.tbl (mm) is
# converted first.
set -euo pipefail
cd "$(dirname "$0")"
rs274=${RS274:-rs274}
inch=$(mktemp)
trap 'rm -f "$inch"' EXIT
awk '/^;/ { next } {
  for (i = 1; i <= NF; i++) {
    if ($i ~ /^;/) { break }
    if ($i ~ /^[DZ]/) { $i = substr($i, 1, 1) (substr($i, 2) / 25.4) }
  }
  print
}' tools.tbl >"$inch"
for program in *.ngc; do
  # rs274 exits 1 even when the program runs; it prints "executing", then
  # the message of an error, on stderr.
  message=$("$rs274" -t "$inch" -g "$program" "${program%.ngc}.canon" 2>&1 </dev/null | sed 's/executing//' || true)
  if [ -n "$message" ]; then
    echo "$program: $message" >&2
    exit 1
  fi
done
