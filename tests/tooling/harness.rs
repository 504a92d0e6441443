//! The stepping harness: structural checks, loop detection, waveforms.

use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::plots::render_svg;
use motion_hdl::sim::{Harness, HarnessError};
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
struct Inverter {
    i: Signal<In, Bit>,
    o: Signal<Out, Bit>,
}

impl Logic for Inverter {
    #[hdl_gen]
    fn update(&mut self) {
        self.o.next = !self.i.val();
    }
}

/// An inverter whose output feeds its own input through the parent: a loop
/// across modules, which rust-hdl's `check_all` does not see.
#[derive(LogicBlock, Default)]
struct RingOscillator {
    clock: Signal<In, Clock>,
    out: Signal<Out, Bit>,
    inverter: Inverter,
}

impl Logic for RingOscillator {
    #[hdl_gen]
    fn update(&mut self) {
        self.inverter.i.next = self.inverter.o.val();
        self.out.next = self.inverter.o.val();
    }
}

motion_hdl::vector_ports!(impl[] RingOscillator { inputs: [], outputs: [out] });

#[test]
fn a_combinational_loop_is_an_error_naming_the_block() {
    let error = Harness::new("ring_oscillator", RingOscillator::default())
        .and_then(|mut h| h.cycle())
        .expect_err("a ring oscillator must not settle");
    assert!(
        matches!(error, HarnessError::CombinationalLoop { .. }),
        "{error:?}"
    );
    assert!(error.to_string().contains("ring_oscillator"), "{error}");
}

#[derive(LogicBlock, Default)]
struct Undriven {
    clock: Signal<In, Clock>,
    out: Signal<Out, Bit>,
    inverter: Inverter,
}

impl Logic for Undriven {
    #[hdl_gen]
    fn update(&mut self) {
        self.out.next = self.inverter.o.val();
    }
}

motion_hdl::vector_ports!(impl[] Undriven { inputs: [], outputs: [out] });

#[test]
fn an_undriven_child_input_fails_the_structural_check() {
    let error = Harness::new("undriven", Undriven::default())
        .err()
        .expect("check_all must fail");
    assert!(matches!(error, HarnessError::Check { .. }), "{error:?}");
    assert!(error.to_string().contains("undriven"), "{error}");
}

#[test]
fn records_a_vcd_and_renders_chosen_signals_to_svg() {
    let dir = tempfile::tempdir().unwrap();
    let (vcd, svg) = (
        dir.path().join("divider.vcd"),
        dir.path().join("divider.svg"),
    );
    let mut harness = Harness::new("freq_divider", FreqDivider::<8>::default()).unwrap();
    harness.record_vcd(&vcd).unwrap();
    harness.step_vector(&[1, 0, 3]).unwrap();
    for _ in 0..20 {
        harness.step_vector(&[0, 1, 3]).unwrap();
    }
    drop(harness.finish());
    let text = std::fs::read_to_string(&vcd).unwrap();
    assert!(
        text.contains("strobe") && text.contains("latched_divisor"),
        "VCD lacks the block's signals"
    );
    render_svg(
        &vcd,
        &svg,
        &["uut.clock", "uut.enable", "uut.strobe"],
        0,
        20,
    )
    .unwrap();
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(
        picture.starts_with("<svg") && picture.contains("strobe"),
        "not an SVG waveform"
    );
    assert!(render_svg(&vcd, &svg, &["uut.no_such_signal"], 0, 20).is_err());
}
