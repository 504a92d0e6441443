//! The cross-simulation itself must be able to fail: a corrupted expectation
//! is reported by every simulator at the right cycle and signal.

use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::export::top_ports;
use motion_hdl::tools::cosim::{
    compare_compiled, compare_in, rust_outputs, CosimDesign, CosimError, Simulator,
};
use rust_hdl::prelude::*;

#[test]
fn a_wrong_output_is_reported_with_its_cycle_and_signal() {
    let stimulus: Vec<Vec<u64>> = std::iter::once(vec![1, 0, 5])
        .chain((0..3000).map(|_| vec![0, 1, 5]))
        .collect();
    let mut expected =
        rust_outputs("freq_divider", FreqDivider::<32>::default(), &stimulus).unwrap();
    expected[1234][0] ^= 1;
    let design = CosimDesign::exported("freq_divider");
    let ports = top_ports(&FreqDivider::<32>::default());
    for simulator in Simulator::ALL {
        let verdict = match simulator {
            Simulator::Compiled => {
                compare_compiled::<FreqDivider<32>>(&design, &ports, &stimulus, &expected)
            }
            _ => compare_in(simulator, &design, &stimulus, &expected),
        };
        match verdict {
            Err(CosimError::Mismatch(m)) => {
                assert_eq!(
                    (m.simulator, m.cycle, m.signal.as_str()),
                    (simulator, 1234, "strobe")
                );
            }
            other => panic!("{simulator:?}: corrupted vectors were not caught: {other:?}"),
        }
    }
}

/// A block whose `vector_ports!` list has its inputs in the wrong order.
#[derive(LogicBlock, Default)]
struct MisListed {
    clock: Signal<In, Clock>,
    a: Signal<In, Bit>,
    b: Signal<In, Bit>,
    y: Signal<Out, Bit>,
}

impl Logic for MisListed {
    #[hdl_gen]
    fn update(&mut self) {
        self.y.next = self.a.val() & !self.b.val();
    }
}

motion_hdl::vector_ports!(impl[] MisListed { inputs: [b, a], outputs: [y] });

#[test]
fn vector_ports_that_disagree_with_the_verilog_ports_are_rejected() {
    match rust_outputs("mis_listed", MisListed::default(), &[vec![1, 0]]) {
        Err(CosimError::Setup(message)) => assert!(message.contains("[\"b\", \"a\"]"), "{message}"),
        other => panic!("a mis-ordered vector_ports! list was accepted: {other:?}"),
    }
}
