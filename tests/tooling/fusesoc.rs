//! The FuseSoC cores: `fusesoc --cores-root . core list` finds one for
//! every exported module and its testbench; a `lint` and a `sim` target run
//! through FuseSoC (Verilator and Icarus), and the sim target fails on a
//! wrong expected output.

use motion_hdl::blocks::freq_divider::model::FreqDividerInputs;
use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::export::catalog::catalog;
use motion_hdl::export::fusesoc::module_core_name;
use motion_hdl::tools::cosim::rust_outputs;
use motion_hdl::tools::repo_root;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::process::Command;

/// The FuseSoC the cores are written for (tests/run.sh installs it).
const INSTALL: &str = "pip install fusesoc==2.4.3";

fn fusesoc(args: &[&str], build_root: &std::path::Path) -> (bool, String) {
    let out = Command::new("fusesoc")
        .arg("--cores-root")
        .arg(repo_root())
        .args(args)
        .current_dir(build_root)
        .output()
        .unwrap_or_else(|e| panic!("fusesoc cannot run ({e}): install it with `{INSTALL}`"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

#[test]
fn fusesoc_finds_a_core_for_every_exported_module_testbench_and_board() {
    let dir = tempfile::tempdir().unwrap();
    let (ok, list) = fusesoc(&["core", "list"], dir.path());
    assert!(ok, "{list}");
    for spec in catalog() {
        assert!(
            list.contains(&module_core_name(spec.name)),
            "{}: {list}",
            spec.name
        );
        assert!(
            list.contains(&format!("motion-hdl:tb:{}_tb:", spec.name)),
            "{}: {list}",
            spec.name
        );
    }
    assert!(list.contains("motion-hdl:tb:lint_waivers:"), "{list}");
    for board in motion_hdl::export::boards::boards() {
        let core = format!("motion-hdl:board:{}:", board.dir);
        assert!(list.contains(&core), "{core}: {list}");
    }
    assert!(!list.contains("WARNING"), "{list}");
}

#[test]
fn a_lint_and_a_sim_target_run_through_fusesoc() {
    let dir = tempfile::tempdir().unwrap();
    let core = module_core_name("freq_divider");
    let build = dir.path().join("build");
    let build = build.to_str().unwrap();
    let (ok, lint) = fusesoc(
        &["run", "--build-root", build, "--target", "lint", &core],
        dir.path(),
    );
    assert!(ok, "{lint}");
    // The cross-simulation's vectors: random inputs, the Rust RTL's outputs.
    let mut rng = StdRng::seed_from_u64(0xf5);
    let stimulus: Vec<Vec<u64>> = (0..2_000)
        .map(|k| {
            FreqDividerInputs {
                reset: k == 0 || rng.gen_bool(0.01),
                enable: rng.gen_bool(0.9),
                divisor: rng.gen_range(0..8),
            }
            .to_vector()
        })
        .collect();
    let expected = rust_outputs("freq_divider", FreqDivider::<32>::default(), &stimulus).unwrap();
    let sim = |expected: &[Vec<u64>]| {
        let vectors = dir.path().join("vectors.hex");
        let lines: Vec<String> = stimulus
            .iter()
            .zip(expected)
            .map(|(i, o)| {
                i.iter()
                    .chain(o)
                    .map(|v| format!("{v:x}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect();
        std::fs::write(&vectors, lines.join("\n") + "\n").unwrap();
        let vectors = format!("--vectors={}", vectors.display());
        fusesoc(
            &[
                "run",
                "--build-root",
                build,
                "--target",
                "sim",
                &core,
                &vectors,
            ],
            dir.path(),
        )
    };
    let (ok, out) = sim(&expected);
    assert!(ok && out.contains("PASS cycles=2000"), "{out}");
    // One wrong expected strobe: the testbench names it.
    let mut wrong = expected.clone();
    let k = wrong.iter().position(|o| o[0] == 1).unwrap();
    wrong[k][0] = 0;
    let (_, out) = sim(&wrong);
    assert!(out.contains(&format!("MISMATCH cycle={k}")), "{out}");
}
