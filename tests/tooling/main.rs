//! The export and its tools: `rtl-out/` freshness and lint, the datasheets'
//! port tables, register maps, the board examples' pin files and builds,
//! cross-simulation, the harness, plots, and synthesis of every exported
//! module and the board example, and the crate package.

mod boards;
mod cross_simulation;
mod datasheets;
mod export;
mod fusesoc;
mod harness;
mod package;
mod plots;
mod regmap;
mod rtl_out;
mod synthesis;
mod tools;

/// Every `.rs` file below `dir`.
fn rust_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files = vec![];
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files
}
