//! Tests of `motion_hdl::tools::scaling` (`src/tools/scaling.rs`).

use motion_hdl::blocks::motion_controller::registers::BuildOptions;
use motion_hdl::tools::scaling::{render, ScalingRow, SeedCardRow};
use motion_hdl::tools::synth::SynthFigures;

#[test]
fn a_configuration_that_does_not_fit_has_no_fmax() {
    let figures = |logic_cells, fmax_mhz: Vec<f64>| SynthFigures {
        lut4: 1,
        dff: 2,
        carry: 3,
        ram: 4,
        logic_cells,
        fmax_mhz,
    };
    let rows = [
        ScalingRow {
            axes: 1,
            figures: figures(3840, vec![101.0, 99.0, 100.0]),
        },
        ScalingRow {
            axes: 6,
            figures: figures(15360, vec![]),
        },
    ];
    let md = render(&rows, &[], &[1, 2, 3], 100.0);
    assert!(
        md.contains("| 1 | 1 | 2 | 3 | 4 | 3840 | 50 % | 100.0 | 101.0, 99.0, 100.0 |"),
        "{md}"
    );
    assert!(
        md.contains("| 6 | 1 | 2 | 3 | 4 | 15360 | 200 % | does not fit | - |"),
        "{md}"
    );
}

#[test]
fn the_seed_card_table_says_which_builds_fit_within_the_budget() {
    let row = |build, logic_cells, fmax_mhz: Vec<f64>| SeedCardRow {
        build,
        options: BuildOptions {
            uniform: true,
            analog: true,
            probe: false,
            soft_limits: false,
            spindle: false,
            laser: false,
        },
        exported: build != "b",
        figures: SynthFigures {
            lut4: 1,
            dff: 2,
            carry: 3,
            ram: 4,
            logic_cells,
            fmax_mhz,
        },
        digest: format!("d{build}"),
    };
    let card = [
        row("a", 6528, vec![64.25]),
        row("b", 6529, vec![61.0]),
        row("c", 8000, vec![]),
    ];
    let md = render(&[], &card, &[1], 100.0);
    assert!(
        md.contains(
            "| `a` | yes | yes | no | no | 1 | 2 | 3 | 4 | 6528 | 85 % | yes | 64.2 | `da` |"
        ),
        "{md}"
    );
    assert!(
        md.contains(
            "| `b` (not exported) | yes | yes | no | no | 1 | 2 | 3 | 4 | 6529 | 85 % | no | 61.0 | `db` |"
        ),
        "{md}"
    );
    assert!(
        md.contains(
            "| `c` | yes | yes | no | no | 1 | 2 | 3 | 4 | 8000 | 104 % | no | does not fit | `dc` |"
        ),
        "{md}"
    );
    assert_eq!(
        motion_hdl::tools::scaling::recorded_seed_card(&md, "a"),
        Some(motion_hdl::tools::scaling::RecordedSeedCard {
            logic_cells: 6528,
            digest: "da".into()
        })
    );
    assert_eq!(
        motion_hdl::tools::scaling::recorded_seed_card(&md, "d"),
        None
    );
    let again = motion_hdl::tools::scaling::replace_seed_card(&md, &card[..1]).unwrap();
    assert!(
        again.contains("| `a` |") && !again.contains("| `c` |"),
        "{again}"
    );
    assert_eq!(
        again
            .matches(motion_hdl::tools::scaling::SEED_CARD_HEADING)
            .count(),
        1
    );
}
