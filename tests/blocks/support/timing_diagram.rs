//! A datasheet's timing diagram (`src/blocks/<block>/timing.txt`, included
//! in its rustdoc) is a simulation, not a drawing: the test compares the
//! file with the simulation, and `UPDATE_TIMING_DIAGRAM=1` rewrites it.

/// Fails unless `src/blocks/<block>/timing.txt` is `simulated`.
pub fn assert_timing_diagram_is(block: &str, simulated: &str) {
    let path = motion_hdl::tools::repo_root()
        .join("src/blocks")
        .join(block)
        .join("timing.txt");
    let drawn = std::fs::read_to_string(&path).unwrap_or_default();
    if std::env::var_os("UPDATE_TIMING_DIAGRAM").is_some() {
        std::fs::write(&path, simulated).unwrap();
    }
    assert_eq!(
        drawn, simulated,
        "{block}/timing.txt differs from the simulation (rerun with UPDATE_TIMING_DIAGRAM=1)"
    );
}
