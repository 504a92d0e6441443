# What every board's build.sh shares: its options, the check that the tools
# and sources are there, and the figures printed at the end. Sourced by
# boards/<board>/build.sh after it has set:
#   top       the top module (and the stem of its pin file and bitstream)
#   install   the pip line that installs its tools
#   device    the device named in the utilisation printout
# A board folder needs this file beside it (and rtl-out/ for the SPI
# adapter) when copied elsewhere.

# Reads the options into `seed` (nextpnr's arguments): --seed N, or none.
# Anything else, or --seed without its number, is a usage error (exit 2).
parse_options() {
    seed=()
    while [ $# -gt 0 ]; do
        if [ "$1" != --seed ] || [ $# -lt 2 ]; then
            echo "usage: $0 [--seed N]" >&2
            exit 2
        fi
        seed=(--seed "$2")
        shift 2
    done
}

# Fails naming the first of the given commands that is not installed, and
# the pip line that installs them.
require_tools() {
    local tool
    for tool in "$@" python3; do
        if ! command -v "$tool" >/dev/null 2>&1; then
            echo "error: '$tool' not found. Install the tools with:" >&2
            echo "  $install" >&2
            exit 1
        fi
    done
}

# Fails naming the first of the given files that is missing.
require_files() {
    local f
    for f in "$@"; do
        [ -f "$f" ] || { echo "error: $PWD/$f is missing" >&2; exit 1; }
    done
}

# Prints the build's time, its utilisation and Fmax from build/report.json
# and build/nextpnr.log; fails when a clock misses its constraint or
# nextpnr timed no path at all.
print_figures() {
    local elapsed=$1
    python3 - build/report.json build/nextpnr.log "$elapsed" "$device" <<'PY'
import json, re, sys
report = json.load(open(sys.argv[1]))
log = open(sys.argv[2]).read()
elapsed = int(sys.argv[3])
print(f"== done in {elapsed // 60} min {elapsed % 60} s")
print(f"utilisation ({sys.argv[4]}):")
for bel, u in sorted(report["utilization"].items()):
    if not u["used"]:
        continue
    share = f"{100 * u['used'] / u['available']:5.1f} %" if u["available"] else ""
    print(f"  {bel:16s} {u['used']:6d} / {u['available']:6d}  {share}")
ok = bool(report["fmax"])
if not ok:
    print("  nextpnr timed no path (no Fmax in build/report.json): the clock is not confirmed")
for clock, f in report["fmax"].items():
    passed = f["achieved"] >= f["constraint"]
    ok = ok and passed
    print(f"  Fmax {clock}: {f['achieved']:.2f} MHz (target {f['constraint']:.2f} MHz) "
          + ("PASS" if passed else "FAIL"))
hold = re.search(r"(\d+) Hold/min time violations", log)
if hold:
    print(f"  nextpnr reports {hold.group(1)} hold/min-time violations: see build/nextpnr.log")
if not ok:
    print("timing FAILED: see build/nextpnr.log (try another --seed)")
    sys.exit(1)
PY
}
