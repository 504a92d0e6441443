//! Tests of `motion_hdl::sim::lockstep` (`src/sim/lockstep.rs`).

use motion_hdl::blocks::freq_divider::model::{FreqDividerInputs, FreqDividerModel};
use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::sim::*;

/// A divider model that is wrong from the fourth clock on.
struct Wrong(FreqDividerModel);

impl LockstepModel for Wrong {
    type Inputs = FreqDividerInputs;
    type Outputs = bool;
    fn input_vector(inputs: &FreqDividerInputs, vector: &mut Vec<u64>) {
        FreqDividerModel::input_vector(inputs, vector);
    }
    fn read_outputs(&self, vector: &[u64]) -> bool {
        self.0.read_outputs(vector)
    }
    fn expected(&mut self, inputs: &FreqDividerInputs) -> bool {
        let strobe = self.0.expected(inputs);
        strobe ^ (inputs.divisor == 4)
    }
}

#[test]
fn a_mismatch_names_the_cycle_the_inputs_and_both_outputs() {
    let mut pair = Lockstep::harness(
        "freq_divider",
        FreqDivider::<8>::default(),
        Wrong(FreqDividerModel::new(8)),
    );
    let mut seen = vec![];
    let error = pair
        .run(
            |cycle, _| {
                Some(FreqDividerInputs {
                    reset: false,
                    enable: true,
                    divisor: 1 + cycle,
                })
            },
            |cycle, _, &strobe| seen.push((cycle, strobe)),
        )
        .unwrap_err();
    assert_eq!(seen.len(), 3, "three clocks agreed: {seen:?}");
    let text = error.to_string();
    assert!(
        matches!(error, LockstepError::Mismatch { cycle: 3, .. }),
        "{text}"
    );
    assert!(
        text.contains("cycle 3") && text.contains("divisor: 4"),
        "{text}"
    );
    assert!(text.contains("RTL ") && text.contains("model "), "{text}");
}
