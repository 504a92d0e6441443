//! The two checks every property file gets: its proofs pass, and a
//! deliberate bug in the block fails them with a counterexample.

use motion_hdl::tools::formal::{
    find, instance_verilog, prove, prove_verilog, Checks, FailedCheck, FormalSpec, Outcome,
};

fn spec(name: &str) -> FormalSpec {
    find(name).unwrap_or_else(|| panic!("no proof named {name} in formal_catalog()"))
}

/// Proves the catalog's proof `name` (bounded check and k-induction).
pub fn assert_proved(name: &str) {
    let spec = spec(name);
    let report = prove(&spec).unwrap_or_else(|e| panic!("{name}: {e}"));
    println!(
        "{name}: {:?}; yosys {:.2} s, bounded ({} clocks) {:.2} s, induction (k = {}) {:.2} s",
        report.outcome,
        report.build_time.as_secs_f64(),
        spec.bmc_depth,
        report.bmc_time.as_secs_f64(),
        spec.induction_depth,
        report.induction_time.as_secs_f64()
    );
    assert!(
        matches!(report.outcome, Outcome::Proved),
        "{name}: {:?}",
        report.outcome
    );
}

/// Proof `name`'s spec, and its generated Verilog with the one occurrence
/// of `find` replaced by `replace` (the bug).
fn mutant(name: &str, find: &str, replace: &str) -> (FormalSpec, String) {
    let spec = spec(name);
    let verilog = instance_verilog(&spec).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        verilog.matches(find).count(),
        1,
        "{name}: the mutation's text `{find}` must occur exactly once in the generated Verilog"
    );
    let mutant = verilog.replacen(find, replace, 1);
    (spec, mutant)
}

/// Replaces the one occurrence of `find` in the generated Verilog of proof
/// `name` with `replace` (the bug), and checks that the bounded check of
/// the contract alone (no induction invariants) finds a counterexample
/// from power-up.
pub fn assert_mutation_caught(name: &str, find: &str, replace: &str) {
    let (spec, mutant) = mutant(name, find, replace);
    let report = prove_verilog(&spec, &mutant, Checks::ContractBounded)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    match report.outcome {
        Outcome::Counterexample { check, steps, assertion, vcd } => {
            println!("{name} with `{find}` -> `{replace}`: {assertion} fails after {steps} clocks ({})", vcd.display());
            assert_eq!(check, FailedCheck::Bounded, "{name}: the mutant must fail from power-up, not only in induction");
            assert!(steps > 0, "{name}: a counterexample has at least one clock");
            assert!(vcd.exists(), "{name}: the counterexample's VCD {} was not written", vcd.display());
            assert!(assertion.contains(spec.property_file), "{name}: the failed assertion {assertion} is not in {}", spec.property_file);
        }
        Outcome::Proved => panic!("{name}: the proof passes with `{find}` replaced by `{replace}`: the properties cannot see this bug"),
    }
}

/// Replaces the one occurrence of `find` in the generated Verilog of proof
/// `name` with `replace`, and checks that the proof (bounded check and
/// induction, with the invariants) fails on it, with a failed assertion of
/// the property file. For a bug deeper than any bounded check reaches from
/// power-up (a frame of the SPI adapter is a hundred clocks and more): the
/// induction's counterexample may start in an unreachable state, so this
/// shows only that the proof cannot pass on the bug, not a trace of it;
/// the block's tests show the bug itself in simulation.
pub fn assert_proof_fails(name: &str, find: &str, replace: &str) {
    let (spec, mutant) = mutant(name, find, replace);
    let report =
        prove_verilog(&spec, &mutant, Checks::Proof).unwrap_or_else(|e| panic!("{name}: {e}"));
    match report.outcome {
        Outcome::Counterexample {
            check,
            steps,
            assertion,
            ..
        } => {
            println!("{name} with `{find}` -> `{replace}`: {check:?} check, {assertion} fails after {steps} clocks");
            assert!(
                assertion.contains(spec.property_file),
                "{name}: the failed assertion {assertion} is not in {}",
                spec.property_file
            );
        }
        Outcome::Proved => panic!("{name}: the proof passes with `{find}` replaced by `{replace}`"),
    }
}
