//! `scaling-report.md`: the motion controller's size and Fmax on iCE40 HX8K
//! at K = 1, 3 and 6 axes (#19), from configurations that are synthesized
//! in a work folder, not exported, and the seed card (`seed_board.v`)
//! placed with each controller build (#35). A design that does not fit is
//! packed only: its logic cells are what it would need.

use std::path::{Path, PathBuf};

use super::report::{module_row, verilog_digest};
use super::synth::{
    place_board_up_to, synthesize_if_it_fits, SynthFigures, DEVICE, DEVICE_LOGIC_CELLS,
};
use super::{read_text, repo_root, work_dir, ToolError};
use crate::blocks::motion_controller::registers::BuildOptions;
use crate::blocks::motion_controller::{
    MotionController3NoProbe, MotionController3NoSoftLimits, MotionController3UniformServo,
};
use crate::export::catalog::controller_scaling;
use crate::export::module_verilog;

/// The seed card's board clock, and the seed its figures are placed with.
pub const SEED_CARD_MHZ: f64 = 48.0;
/// See [`SEED_CARD_MHZ`].
pub const SEED_CARD_SEED: u64 = 1;
/// The share of the HX8K's logic cells the seed card may use, in percent.
pub const SEED_CARD_BUDGET_PERCENT: u32 = 85;
/// The controller instance's module in `seed_board.v` (the card's own
/// build; its placement test places the card with it).
pub const SEED_CARD_CONTROLLER: &str = "motion_controller_servo";

/// One controller build on the seed card.
pub struct SeedCardRow {
    /// The controller's module name.
    pub build: &'static str,
    /// Its build options.
    pub options: BuildOptions,
    /// It is exported (in `rtl-out`); else generated for this table.
    pub exported: bool,
    /// The whole card's figures (no Fmax when over the card's budget).
    pub figures: SynthFigures,
    /// [`seed_card_digest`] of the files it was placed from.
    pub digest: String,
}

/// The digest ([`verilog_digest`]) of the seed card's sources as placed:
/// the board top with `build` in place of its controller, the pin file,
/// `host_links` and the controller's Verilog, in that order. A committed
/// row with today's digest measured today's files (yosys and nextpnr, with
/// one seed, are deterministic).
pub fn seed_card_digest(top: &str, pcf: &str, links: &str, controller: &str) -> String {
    verilog_digest([top, pcf, links, controller].concat().as_bytes())
}

/// The seed card's board folder.
const SEED_CARD_BOARD: &str = "boards/ice40-hx8k-breakout";

/// The card's sources besides its top and controller: the pin file and
/// `host_links`.
fn seed_card_fixed_sources() -> (PathBuf, PathBuf) {
    let root = repo_root();
    (
        root.join(SEED_CARD_BOARD).join("seed_board.pcf"),
        root.join("rtl-out/host_links.v"),
    )
}

/// [`seed_card_digest`] of the card placed with `top` (its text) and the
/// controller in `controller`.
fn placed_card_digest(top: &str, controller: &Path) -> Result<String, ToolError> {
    let (pcf, links) = seed_card_fixed_sources();
    Ok(seed_card_digest(
        top,
        &read_text(&pcf)?,
        &read_text(&links)?,
        &read_text(controller)?,
    ))
}

/// The seed card's top (`seed_board.v`) with `build` in place of its own
/// controller.
pub fn seed_card_top(build: &str) -> Result<String, ToolError> {
    let card = read_text(&repo_root().join(SEED_CARD_BOARD).join("seed_board.v"))?;
    let instance = format!("{SEED_CARD_CONTROLLER} controller (");
    if !card.contains(&instance) {
        return Err(ToolError::Parse {
            tool: "seed_board.v".into(),
            detail: format!("no `{instance}` to put each build in"),
        });
    }
    Ok(card.replace(&instance, &format!("{build} controller (")))
}

/// [`seed_card_digest`] of the card with the exported `build`, from today's
/// files.
pub fn exported_seed_card_digest(build: &str) -> Result<String, ToolError> {
    placed_card_digest(
        &seed_card_top(build)?,
        &repo_root().join(format!("rtl-out/{build}.v")),
    )
}

/// The seed card (`boards/ice40-hx8k-breakout/seed_board.v` with its pin
/// file and `host_links`) placed with each controller build in place of
/// its own, at [`SEED_CARD_MHZ`] and [`SEED_CARD_SEED`]. The exported
/// builds are read from `rtl-out` (run `export` first); the build with both
/// uniform generators and analog outputs, and `motion_controller` without
/// the probe and without the soft limits, are generated here.
pub fn measure_seed_card() -> Result<Vec<SeedCardRow>, ToolError> {
    let root = repo_root();
    let (pcf, links) = seed_card_fixed_sources();
    let dir = work_dir("seed-card")?;
    let full = MotionController3UniformServo::BUILD;
    let full_path = dir.path().join(format!("{}.v", full.module_name()));
    write_verilog(
        &full_path,
        full.module_name(),
        &mut MotionController3UniformServo::default(),
    )?;
    let no_probe = MotionController3NoProbe::BUILD;
    let no_probe_path = dir.path().join(format!("{}.v", no_probe.module_name()));
    write_verilog(
        &no_probe_path,
        no_probe.module_name(),
        &mut MotionController3NoProbe::default(),
    )?;
    let no_soft = MotionController3NoSoftLimits::BUILD;
    let no_soft_path = dir.path().join(format!("{}.v", no_soft.module_name()));
    write_verilog(
        &no_soft_path,
        no_soft.module_name(),
        &mut MotionController3NoSoftLimits::default(),
    )?;
    let builds: [(BuildOptions, Option<PathBuf>); 6] = [
        (BuildOptions::MOTION_CONTROLLER_DDA, None),
        (BuildOptions::MOTION_CONTROLLER_SERVO, None),
        (BuildOptions::MOTION_CONTROLLER, None),
        (no_probe, Some(no_probe_path)),
        (no_soft, Some(no_soft_path)),
        (full, Some(full_path)),
    ];
    builds
        .into_iter()
        .map(|(options, generated)| {
            let build = options.module_name();
            let top = dir.path().join(format!("seed_board_{build}.v"));
            let top_text = seed_card_top(build)?;
            write_text(&top, &top_text)?;
            let exported = generated.is_none();
            let controller = generated.unwrap_or_else(|| root.join(format!("rtl-out/{build}.v")));
            let digest = placed_card_digest(&top_text, &controller)?;
            // A build over the card's budget is only packed: it is not
            // the card's, and placing a nearly full HX8K can outlast the
            // tools' time limit.
            let figures = place_board_up_to(
                &[&top, &links, &controller],
                "seed_board",
                &pcf,
                SEED_CARD_SEED,
                SEED_CARD_MHZ,
                DEVICE_LOGIC_CELLS * SEED_CARD_BUDGET_PERCENT / 100,
            )?;
            Ok(SeedCardRow {
                build,
                options,
                exported,
                figures,
                digest,
            })
        })
        .collect()
}

/// One configuration's row.
pub struct ScalingRow {
    /// K.
    pub axes: usize,
    /// What the tools measured (no Fmax when it does not fit).
    pub figures: SynthFigures,
}

/// Synthesizes every configuration of [`controller_scaling`]; one that
/// packs into the HX8K is placed once per seed at `target_mhz`.
pub fn measure(seeds: &[u64], target_mhz: f64) -> Result<Vec<ScalingRow>, ToolError> {
    let dir = work_dir("scaling")?;
    controller_scaling()
        .into_iter()
        .map(|variant| {
            let rtl = dir
                .path()
                .join(format!("motion_controller_k{}.v", variant.axes));
            write_verilog(&rtl, "motion_controller", &mut *(variant.build)())?;
            Ok(ScalingRow {
                axes: variant.axes,
                figures: synthesize_if_it_fits(&rtl, "motion_controller", seeds, target_mhz)?,
            })
        })
        .collect()
}

fn write_verilog(
    path: &Path,
    name: &str,
    block: &mut dyn rust_hdl::core::prelude::Block,
) -> Result<(), ToolError> {
    let verilog = module_verilog(name, block).map_err(|e| ToolError::Parse {
        tool: "rust-hdl".into(),
        detail: e.to_string(),
    })?;
    write_text(path, &verilog)
}

fn write_text(path: &Path, text: &str) -> Result<(), ToolError> {
    std::fs::write(path, text).map_err(|source| ToolError::Io {
        context: format!("writing {}", path.display()),
        source,
    })
}

/// The report as Markdown.
pub fn render(rows: &[ScalingRow], card: &[SeedCardRow], seeds: &[u64], target_mhz: f64) -> String {
    let mut md = format!(
        "# motion_controller against its axis count: {DEVICE}\n\n\
         Generated by {} with `motion-hdl report --scaling`: the controller with 16-entry FIFOs \
         at K = 1, 3 (the exported configuration) and 6 axes, synthesized like \
         `synthesis-report.md` (yosys `synth_ice40 -dffe_min_ce_use 4`, nextpnr-ice40 at \
         {target_mhz:.0} MHz, seeds {seeds:?}, Fmax median). A configuration with more logic cells \
         than the device's {DEVICE_LOGIC_CELLS} is only packed (`nextpnr-ice40 --pack-only`): \
         its logic cells are what it would need, and it has no Fmax.\n\n\
         | K | LUT4 | DFF | carry | RAM | logic cells | of the HX8K | Fmax median (MHz) | Fmax per seed |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
        crate::export::generator(),
    );
    for row in rows {
        let f = &row.figures;
        let (median, per_seed) = if f.fmax_mhz.is_empty() {
            ("does not fit".to_string(), "-".to_string())
        } else {
            let per_seed: Vec<String> = f.fmax_mhz.iter().map(|x| format!("{x:.1}")).collect();
            (format!("{:.1}", f.median_fmax()), per_seed.join(", "))
        };
        md.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {:.0} % | {} | {} |\n",
            row.axes,
            f.lut4,
            f.dff,
            f.carry,
            f.ram,
            f.logic_cells,
            percent(f.logic_cells),
            median,
            per_seed
        ));
    }
    md.push_str(&render_seed_card(card));
    md
}

/// `report` (the text of `scaling-report.md`) with its seed card section
/// measured again as `card`; `None` if it has no such section.
pub fn replace_seed_card(report: &str, card: &[SeedCardRow]) -> Option<String> {
    let start = report.find(SEED_CARD_HEADING)?;
    Some(format!("{}{}", &report[..start], render_seed_card(card)))
}

#[doc(hidden)]
pub const SEED_CARD_HEADING: &str = "\n## The seed card";

/// The seed card's figures as `scaling-report.md` records them for one
/// controller build.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecordedSeedCard {
    /// The whole card's logic cells.
    pub logic_cells: u32,
    /// The digest of the sources it was placed from.
    pub digest: String,
}

/// `build`'s row of the seed card table in `report` (the text of
/// `scaling-report.md`), if it has one.
pub fn recorded_seed_card(report: &str, build: &str) -> Option<RecordedSeedCard> {
    let line = module_row(report.split(SEED_CARD_HEADING).nth(1)?, build)?;
    let cells: Vec<&str> = line.split('|').map(str::trim).collect();
    Some(RecordedSeedCard {
        logic_cells: cells.get(10)?.parse().ok()?,
        digest: cells.get(14)?.trim_matches('`').to_string(),
    })
}

fn percent(logic_cells: u32) -> f64 {
    100.0 * logic_cells as f64 / DEVICE_LOGIC_CELLS as f64
}

fn render_seed_card(card: &[SeedCardRow]) -> String {
    let yes_no = |b: bool| if b { "yes" } else { "no" };
    let mut md = format!(
        "{SEED_CARD_HEADING}\n\n\
         `boards/ice40-hx8k-breakout/seed_board.v` with its pin file, `host_links` (the 16-bit \
         DSP bus, the 8-bit PC bus and the mailbox) and each controller build in place of its \
         own (`{SEED_CARD_CONTROLLER}`), synthesized the same way and placed at the board's \
         {SEED_CARD_MHZ:.0} MHz, seed {SEED_CARD_SEED}. The card must stay within \
         {SEED_CARD_BUDGET_PERCENT} % of the HX8K's logic cells. `motion_controller_uniform_servo` (uniform \
         generators and analog outputs), `motion_controller_no_probe` (`motion_controller` \
         without the probe latch) and `motion_controller_no_soft_limits` (`motion_controller` \
         without the soft limits) are not exported: they are generated for this table. A card over the \
         {SEED_CARD_BUDGET_PERCENT} % budget is only packed (no Fmax: placing a nearly full HX8K can \
         outlast the tools' time limit). The last column is the digest of the sources placed (board top, pin file, \
         `host_links`, controller: `scaling::seed_card_digest`); the suite checks the card's own \
         row against today's files instead of placing it again.\n\n\
         | controller build | uniform generators | analog outputs | probe | soft limits | LUT4 | DFF | carry | RAM | \
         logic cells | of the HX8K | within {SEED_CARD_BUDGET_PERCENT} % | Fmax seed {SEED_CARD_SEED} (MHz) | sources |\n\
         |---|---|---|---|---|---:|---:|---:|---:|---:|---:|---|---:|---|\n"
    );
    for row in card {
        let f = &row.figures;
        let unplaced = if f.logic_cells > DEVICE_LOGIC_CELLS {
            "does not fit"
        } else {
            "over budget: packed only"
        };
        let fmax = f
            .fmax_mhz
            .first()
            .map_or(unplaced.to_string(), |x| format!("{x:.1}"));
        md.push_str(&format!(
            "| `{}`{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.0} % | {} | {} | `{}` |\n",
            row.build,
            if row.exported { "" } else { " (not exported)" },
            yes_no(row.options.uniform),
            yes_no(row.options.analog),
            yes_no(row.options.probe),
            yes_no(row.options.soft_limits),
            f.lut4,
            f.dff,
            f.carry,
            f.ram,
            f.logic_cells,
            percent(f.logic_cells),
            yes_no(f.logic_cells * 100 <= DEVICE_LOGIC_CELLS * SEED_CARD_BUDGET_PERCENT),
            fmax,
            row.digest
        ));
    }
    md
}
