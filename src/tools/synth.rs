//! Synthesis and place-and-route for iCE40 HX8K (ct256) with yosys and
//! nextpnr, and the figures they report.

use std::path::Path;
use std::process::Command;

use super::{read_text, run, work_dir, ToolError};

/// The iCE40 device and package every figure refers to.
pub const DEVICE: &str = "iCE40 HX8K (ct256)";

/// Resource and timing figures of one placed-and-routed design.
#[derive(Clone, Debug, PartialEq)]
pub struct SynthFigures {
    /// `SB_LUT4` cells after synthesis.
    pub lut4: u32,
    /// Flip-flops (`SB_DFF*` cells) after synthesis.
    pub dff: u32,
    /// `SB_CARRY` cells after synthesis.
    pub carry: u32,
    /// `SB_RAM40_4K` block RAMs.
    pub ram: u32,
    /// Logic cells used after placement (`ICESTORM_LC`).
    pub logic_cells: u32,
    /// Achieved Fmax of `clock` for each seed, in MHz, in seed order.
    pub fmax_mhz: Vec<f64>,
}

impl SynthFigures {
    /// The median Fmax over the seeds.
    pub fn median_fmax(&self) -> f64 {
        median(&self.fmax_mhz)
    }
}

/// The median of `values` (0 for none).
pub(crate) fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(|a, b| a.total_cmp(b));
    let n = sorted.len();
    if n == 0 {
        0.0
    } else if n % 2 == 1 {
        sorted[n / 2]
    } else {
        (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0
    }
}

/// The iCE40 HX8K's logic cells.
pub const DEVICE_LOGIC_CELLS: u32 = 7680;

/// User IO of the HX8K in the ct256 package.
pub const PACKAGE_IO: usize = 206;

/// A top with more port bits than [`PACKAGE_IO`] cannot be placed as it is
/// (nextpnr gives every top-level port bit a pin). It is measured inside
/// this wrapper instead: its input bits come from a shift register loaded
/// from one pin, its output bits are XOR-folded into one registered pin, so
/// that none of its logic is optimized away.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PinWrapper {
    /// Input bits of the wrapped top (without the clock): the shift
    /// register's length.
    pub input_bits: usize,
    /// Output bits folded.
    pub output_bits: usize,
}

impl PinWrapper {
    /// The wrapper a top with `ports` needs (clocked by `clock`), if it has
    /// more port bits than the package has pins.
    pub fn needed(ports: &[crate::export::Port], clock: &str) -> Option<Self> {
        use crate::export::PortDirection;
        let bits = |dir: PortDirection| -> usize {
            ports
                .iter()
                .filter(|p| p.direction == dir && p.name != clock)
                .map(|p| p.width)
                .sum()
        };
        let (input_bits, output_bits) = (bits(PortDirection::Input), bits(PortDirection::Output));
        (input_bits + output_bits + 1 > PACKAGE_IO).then_some(Self {
            input_bits,
            output_bits,
        })
    }

    /// Flip-flops the wrapper adds (the shift register and the output pin),
    /// subtracted from the DFF and logic-cell figures (each sits alone in a
    /// logic cell, or with the last LUT of the fold).
    pub fn flip_flops(&self) -> u32 {
        self.input_bits as u32 + 1
    }

    /// LUT4s of the XOR fold (a tree of 4-input XORs): included in the
    /// LUT4 and logic-cell figures.
    pub fn fold_lut4(&self) -> u32 {
        (self.output_bits.saturating_sub(1) as u32).div_ceil(3)
    }

    /// The wrapper module `<top>__pins` around `top` with `ports`.
    pub fn verilog(&self, top: &str, ports: &[crate::export::Port], clock: &str) -> String {
        use crate::export::PortDirection;
        let mut connections = vec![format!(".{clock}(clock)")];
        let (mut at_in, mut at_out) = (0, 0);
        for p in ports.iter().filter(|p| p.name != clock) {
            let (bus, at) = match p.direction {
                PortDirection::Output => ("folded", &mut at_out),
                _ => ("shift_in", &mut at_in),
            };
            connections.push(format!(".{}({bus}[{}:{}])", p.name, *at + p.width - 1, *at));
            *at += p.width;
        }
        format!(
            "module {top}__pins(input wire clock, input wire pin_in, output reg pin_out);\n\
             \x20 reg [{in_top}:0] shift_in = 0;\n\
             \x20 wire [{out_top}:0] folded;\n\
             \x20 always @(posedge clock) begin\n\
             \x20   shift_in <= {{shift_in[{in_below}:0], pin_in}};\n\
             \x20   pin_out <= ^folded;\n\
             \x20 end\n\
             \x20 {top} uut ({});\n\
             endmodule\n",
            connections.join(", "),
            in_top = self.input_bits - 1,
            in_below = self.input_bits.saturating_sub(2),
            out_top = self.output_bits - 1,
        )
    }
}

/// [`synthesize`] for a top with `ports`: inside a [`PinWrapper`] when it
/// has more port bits than the package has pins (the wrapper's flip-flops
/// are then subtracted from DFF and logic cells).
pub fn synthesize_top(
    rtl: &Path,
    top: &str,
    ports: &[crate::export::Port],
    seeds: &[u64],
    target_mhz: f64,
) -> Result<(SynthFigures, Option<PinWrapper>), ToolError> {
    let Some(wrapper) = PinWrapper::needed(ports, "clock") else {
        return Ok((synthesize(rtl, top, seeds, target_mhz)?, None));
    };
    let dir = work_dir("pins")?;
    let wrapped = dir.path().join(format!("{top}__pins.v"));
    let source = read_text(rtl)?;
    let text = format!("{source}\n{}", wrapper.verilog(top, ports, "clock"));
    std::fs::write(&wrapped, text).map_err(|source| ToolError::Io {
        context: format!("writing {}", wrapped.display()),
        source,
    })?;
    let mut figures = synthesize(&wrapped, &format!("{top}__pins"), seeds, target_mhz)?;
    figures.dff -= wrapper.flip_flops();
    figures.logic_cells -= wrapper.flip_flops();
    Ok((figures, Some(wrapper)))
}

/// Synthesizes `rtl` (top module `top`) with `synth_ice40 -dffe_min_ce_use
/// 4` (an enable shared by fewer than 4 flip-flops goes into their LUTs
/// rather than onto the clock enable, which the 8 cells of a tile share: at
/// 93 % of an HX8K, the controller with machine I/O, the default packing left
/// nextpnr without a legal placement on some seeds), then places and
/// routes it once per seed with nextpnr, aiming at `target_mhz`. Missing the
/// target is not an error: the achieved Fmax is the figure.
pub fn synthesize(
    rtl: &Path,
    top: &str,
    seeds: &[u64],
    target_mhz: f64,
) -> Result<SynthFigures, ToolError> {
    let dir = work_dir("synth")?;
    let netlist = dir.path().join("netlist.json");
    let mut figures = map_ice40(rtl, top, &netlist)?;
    place(dir.path(), &netlist, None, seeds, target_mhz, &mut figures)?;
    Ok(figures)
}

/// Like [`synthesize`] for a design that may not fit: one yosys run, then
/// only nextpnr's packer first. A design with more logic cells than
/// [`DEVICE_LOGIC_CELLS`] is not placed: its figures have the logic cells
/// it would need and no Fmax.
pub fn synthesize_if_it_fits(
    rtl: &Path,
    top: &str,
    seeds: &[u64],
    target_mhz: f64,
) -> Result<SynthFigures, ToolError> {
    place_if_it_fits(&[rtl], top, None, seeds, target_mhz, DEVICE_LOGIC_CELLS)
}

/// A board design (`sources`, top module `top`) placed with its pin file
/// `pcf` at `target_mhz` and `seed`, after the packer says it needs at
/// most `place_up_to` logic cells; like [`synthesize_if_it_fits`]
/// otherwise (one only packed has no Fmax). A nearly full HX8K can take
/// nextpnr longer than [`super::TOOL_TIME_LIMIT`] to place.
pub fn place_board_up_to(
    sources: &[&Path],
    top: &str,
    pcf: &Path,
    seed: u64,
    target_mhz: f64,
    place_up_to: u32,
) -> Result<SynthFigures, ToolError> {
    place_if_it_fits(sources, top, Some(pcf), &[seed], target_mhz, place_up_to)
}

/// One yosys run, nextpnr's packer, then (if it needs at most
/// `place_up_to` logic cells) one placement per seed, with the pin file
/// `pcf` if there is one.
fn place_if_it_fits(
    sources: &[&Path],
    top: &str,
    pcf: Option<&Path>,
    seeds: &[u64],
    target_mhz: f64,
    place_up_to: u32,
) -> Result<SynthFigures, ToolError> {
    let dir = work_dir("synth")?;
    let netlist = dir.path().join("netlist.json");
    let report = dir.path().join("report-pack.json");
    let mut figures = map_ice40_sources(sources, top, &netlist)?;
    run(nextpnr(&netlist, &report, pcf).arg("--pack-only"), false)?;
    figures.logic_cells = read_nextpnr_utilization(&report)?;
    if figures.logic_cells <= place_up_to.min(DEVICE_LOGIC_CELLS) {
        place(dir.path(), &netlist, pcf, seeds, target_mhz, &mut figures)?;
    }
    Ok(figures)
}

/// Places and routes `netlist` once per seed (reports in `dir`), with the
/// pin file `pcf` if there is one, adding each Fmax and the logic cells to
/// `figures`.
fn place(
    dir: &Path,
    netlist: &Path,
    pcf: Option<&Path>,
    seeds: &[u64],
    target_mhz: f64,
    figures: &mut SynthFigures,
) -> Result<(), ToolError> {
    for seed in seeds {
        let report = dir.join(format!("report-{seed}.json"));
        run(
            nextpnr(netlist, &report, pcf)
                .arg("--freq")
                .arg(format!("{target_mhz}"))
                .arg("--seed")
                .arg(seed.to_string()),
            false,
        )?;
        let (fmax, cells) = read_nextpnr_report(&report)?;
        figures.fmax_mhz.push(fmax);
        figures.logic_cells = cells;
    }
    Ok(())
}

/// yosys `synth_ice40` of `rtl` into `netlist`: the cell counts (no logic
/// cells or Fmax yet).
fn map_ice40(rtl: &Path, top: &str, netlist: &Path) -> Result<SynthFigures, ToolError> {
    map_ice40_sources(&[rtl], top, netlist)
}

/// [`map_ice40`] of several source files.
fn map_ice40_sources(
    sources: &[&Path],
    top: &str,
    netlist: &Path,
) -> Result<SynthFigures, ToolError> {
    let sources: Vec<String> = sources.iter().map(|p| p.display().to_string()).collect();
    let yosys_log = run(
        Command::new("yosys").arg("-p").arg(format!(
            "read_verilog {}; synth_ice40 -dffe_min_ce_use 4 -top {top} -json {}; stat",
            sources.join(" "),
            netlist.display()
        )),
        false,
    )?;
    let cells = final_stat(&yosys_log);
    let count = |prefix: &str| -> u32 {
        cells
            .iter()
            .filter(|(name, _)| name.starts_with(prefix))
            .map(|(_, n)| n)
            .sum()
    };
    Ok(SynthFigures {
        lut4: count("SB_LUT4"),
        dff: count("SB_DFF"),
        carry: count("SB_CARRY"),
        ram: count("SB_RAM40_4K"),
        logic_cells: 0,
        fmax_mhz: Vec::new(),
    })
}

/// nextpnr-ice40 on the HX8K, writing its JSON report: IO placed by the
/// pin file `pcf` if there is one, any other IO unconstrained.
fn nextpnr(netlist: &Path, report: &Path, pcf: Option<&Path>) -> Command {
    let mut command = Command::new("nextpnr-ice40");
    command
        .args([
            "--hx8k",
            "--package",
            "ct256",
            "--pcf-allow-unconstrained",
            "--timing-allow-fail",
            "--quiet",
        ])
        .arg("--json")
        .arg(netlist)
        .arg("--report")
        .arg(report);
    if let Some(pcf) = pcf {
        command.arg("--pcf").arg(pcf);
    }
    command
}

/// Cell counts of the last `stat` block in a yosys log: `(cell type, count)`.
pub fn final_stat(log: &str) -> Vec<(String, u32)> {
    let start = log.rfind("Number of cells:").unwrap_or(0);
    log[start..]
        .lines()
        .skip(1)
        .map_while(|line| {
            let mut words = line.split_whitespace();
            match (words.next(), words.next(), words.next()) {
                (Some(name), Some(count), None) => {
                    count.parse().ok().map(|n| (name.to_string(), n))
                }
                _ => None,
            }
        })
        .collect()
}

fn read_nextpnr_json(path: &Path) -> Result<serde_json::Value, ToolError> {
    let text = read_text(path)?;
    serde_json::from_str(&text).map_err(|e| nextpnr_parse_error(&e.to_string()))
}

fn nextpnr_parse_error(detail: &str) -> ToolError {
    ToolError::Parse {
        tool: "nextpnr-ice40".into(),
        detail: detail.into(),
    }
}

fn utilization(json: &serde_json::Value) -> Result<u32, ToolError> {
    json["utilization"]["ICESTORM_LC"]["used"]
        .as_u64()
        .map(|cells| cells as u32)
        .ok_or_else(|| nextpnr_parse_error("no ICESTORM_LC utilization in the report"))
}

fn read_nextpnr_utilization(path: &Path) -> Result<u32, ToolError> {
    utilization(&read_nextpnr_json(path)?)
}

fn read_nextpnr_report(path: &Path) -> Result<(f64, u32), ToolError> {
    let json = read_nextpnr_json(path)?;
    let fmax =
        slowest_fmax(&json).ok_or_else(|| nextpnr_parse_error("no achieved Fmax in the report"))?;
    Ok((fmax, utilization(&json)?))
}

/// The achieved Fmax of the slowest clock in a nextpnr (iCE40, ECP5 or Gowin)
/// `--report` file, in MHz.
pub(crate) fn slowest_fmax(json: &serde_json::Value) -> Option<f64> {
    json["fmax"].as_object().and_then(|clocks| {
        clocks
            .values()
            .filter_map(|c| c["achieved"].as_f64())
            .reduce(f64::min)
    })
}
