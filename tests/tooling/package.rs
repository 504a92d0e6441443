//! The crate can be published: `cargo package` lists every file the
//! library reads at compile time (each datasheet's `ports.md` and
//! `timing.txt`), and the package stays small. The full `cargo package`
//! (which builds the packaged crate) is run by hand; its result is on the
//! issue that set it up (#34).

use std::process::Command;

use motion_hdl::tools::repo_root;
use regex::Regex;

#[test]
fn the_package_holds_every_file_the_library_includes() {
    let out = Command::new(env!("CARGO"))
        .args(["package", "--list", "--allow-dirty", "-p", "motion-hdl"])
        .current_dir(repo_root())
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo package --list failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let listed: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(str::to_string)
        .collect();
    let include = Regex::new(r#"include_(?:str|bytes)!\("([^"]+)"\)"#).unwrap();
    let mut needed = vec![];
    for dir in crate::rust_files(&repo_root().join("src")) {
        let text = std::fs::read_to_string(&dir).unwrap();
        for c in include.captures_iter(&text) {
            let file = dir.parent().unwrap().join(&c[1]);
            let relative = file
                .strip_prefix(repo_root())
                .unwrap()
                .display()
                .to_string();
            needed.push(relative);
        }
    }
    assert!(needed.len() > 20, "{needed:?}");
    let missing: Vec<&String> = needed.iter().filter(|f| !listed.contains(f)).collect();
    assert!(missing.is_empty(), "not in the package: {missing:?}");
    let bytes: u64 = listed
        .iter()
        .filter_map(|f| std::fs::metadata(repo_root().join(f)).ok())
        .map(|m| m.len())
        .sum();
    assert!(
        bytes < 3_000_000,
        "the package's files are {bytes} bytes: keep the export and tests out"
    );
}
