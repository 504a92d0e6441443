#!/usr/bin/env bash
# Vector runner: compiles an exported module with its generated testbench
# (<module>_tb.v) and runs it on a vector file, in Icarus or in Verilator.
#
#   testbench/run_vectors.sh icarus|verilator RTL.v TB.v VECTORS.hex BUILD_DIR
#
# The testbench prints "PASS cycles=N" or the first
# "MISMATCH cycle=N signal=S expected=X got=Y". The vector files come from
# the Rust simulation (motion_hdl::tools::cosim); one line per clock cycle:
# the inputs in port order, then the expected outputs, all in hex.
set -euo pipefail
if [ $# -ne 5 ]; then
  echo "usage: $0 icarus|verilator RTL.v TB.v VECTORS.hex BUILD_DIR" >&2
  exit 2
fi
simulator=$1 rtl=$2 tb=$3 vectors=$4 build=$5
top=$(basename "$tb" .v)
mkdir -p "$build"
case "$simulator" in
  icarus)
    # The exported RTL carries no `timescale (the user's project sets it);
    # only the testbench does, which -Wtimescale would report.
    iverilog -g2012 -Wall -Wno-timescale -s "$top" -o "$build/$top.vvp" "$rtl" "$tb"
    vvp -n "$build/$top.vvp" +vectors="$vectors"
    ;;
  verilator)
    # The RTL is linted separately with -Wall; the testbench is plain
    # simulation code, so lint warnings are not fatal here. Every build
    # compiles the same Verilator runtime (about 10 s of g++); with ccache
    # (tests/run.sh installs it) only the first build of a run does.
    if command -v ccache >/dev/null 2>&1; then
      export OBJCACHE=ccache
    fi
    # The model runs a few thousand clocks once: g++ at -O0 builds it
    # faster than make's default -Os saves in running it.
    verilator --binary -Wno-fatal -Wno-lint -Wno-style -O1 \
      -MAKEFLAGS "OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0" \
      --top-module "$top" -Mdir "$build/obj" -o "V$top" "$rtl" "$tb" >"$build/verilator.log" 2>&1 \
      || { cat "$build/verilator.log"; exit 1; }
    "$build/obj/V$top" +vectors="$vectors"
    ;;
  *)
    echo "unknown simulator: $simulator (icarus or verilator)" >&2
    exit 2
    ;;
esac
