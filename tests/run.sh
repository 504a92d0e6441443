#!/usr/bin/env bash
# The whole motion-hdl test suite, on a fresh machine: installs the FPGA
# tools it needs (Debian, as root) or stops with the exact install line,
# checks the format and the lints, then runs every test of the workspace
# (with cargo-nextest; the crates have no doctests, and `cargo test
# --workspace` runs the same tests one binary at a time). `.ci/run` calls
# this script. gcc compiles the
# generated C register headers in the register-map tests; g++ builds the
# Verilator models of the compiled simulation backend; ccache keeps the
# cross-simulation's Verilator builds from compiling Verilator's runtime
# again for every module. yosys-smtbmc (in Debian's yosys package) and
# the z3 solver run the formal proofs (Debian's boolector, 1.5, is too old
# for yosys-smtbmc).
set -euo pipefail
cd "$(dirname "$0")/.."

tools=(yosys yosys-smtbmc z3 iverilog vvp verilator nextpnr-ice40 gcc g++ ccache)
missing=()
for tool in "${tools[@]}"; do
  command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
done
if [ ${#missing[@]} -gt 0 ]; then
  install_line="apt-get install -y yosys z3 iverilog verilator nextpnr-ice40 gcc g++ ccache"
  if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing missing FPGA tools: ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $install_line -qq
  else
    echo "missing FPGA tools: ${missing[*]}" >&2
    echo "install them with: sudo $install_line" >&2
    exit 1
  fi
fi
for tool in "${tools[@]}"; do
  command -v "$tool" >/dev/null 2>&1 || { echo "still missing after install: $tool" >&2; exit 1; }
done

# Cross-simulation builds testbenches with `verilator --binary` (Verilator 5).
verilator_major=$(verilator --version | sed -n 's/^Verilator \([0-9]*\)\..*/\1/p')
if [ "${verilator_major:-0}" -lt 5 ]; then
  echo "Verilator 5 or newer is needed (found: $(verilator --version))." >&2
  echo "Debian 12 ships 5.006: apt-get install -y verilator" >&2
  exit 1
fi

# FuseSoC, from PyPI: a tooling test lists the cores and runs one lint and
# one sim target through it.
if ! command -v fusesoc >/dev/null 2>&1; then
  echo "installing fusesoc"
  if ! python3 -m pip install --quiet fusesoc==2.4.3; then
    echo "install FuseSoC with: pip install fusesoc==2.4.3" >&2
    exit 1
  fi
  # Under pyenv, a new script's shim appears only after a rehash.
  if command -v pyenv >/dev/null 2>&1; then
    pyenv rehash
  fi
  if ! command -v fusesoc >/dev/null 2>&1; then
    echo "fusesoc is installed but not on PATH: add pip's scripts folder (python3 -m site --user-base)/bin" >&2
    exit 1
  fi
fi

# cargo-nextest runs every test of the five binaries in one pool, the
# longest first (.config/nextest.toml). It is on every machine of the
# project's kind; elsewhere it is built from crates.io once.
if ! cargo nextest --version >/dev/null 2>&1; then
  echo "installing cargo-nextest"
  cargo install --locked cargo-nextest
fi
# Formatting and lints before the tests. The project-wide clippy waivers,
# each with its reason, are in Cargo.toml's [workspace.lints.clippy].
for component in rustfmt clippy; do
  if ! cargo "${component/rustfmt/fmt}" --version >/dev/null 2>&1; then
    echo "installing the $component component"
    rustup component add "$component"
  fi
done
cargo fmt --all --check
# clippy checks in a target folder of its own, beside the tests' build:
# much of that build is rustc's single-threaded front end on the large
# crate, so the two share the 2 cores and the lints cost little wall time.
# The tests run only after clippy has passed.
clippy_log=$(mktemp)
CARGO_TARGET_DIR=target/clippy cargo clippy --workspace --all-targets -- -D warnings >"$clippy_log" 2>&1 &
clippy_pid=$!
if ! cargo nextest run --workspace --no-run; then
  wait "$clippy_pid" || true
  exit 1
fi
if ! wait "$clippy_pid"; then
  cat "$clippy_log"
  echo "clippy found warnings (run: cargo clippy --workspace --all-targets -- -D warnings)" >&2
  exit 1
fi
rm -f "$clippy_log"

cargo nextest run --workspace
