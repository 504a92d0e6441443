//! The README's "What is proved" table is the catalog's, row for row:
//! each proof with its instance, properties and depths. The wall times
//! are measured, so `motion-hdl prove` prints them and the README has
//! none.

use motion_hdl::tools::formal::{formal_catalog, table_row_prefix};
use motion_hdl::tools::repo_root;

#[test]
fn the_readme_lists_every_proof_with_its_depths() {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let section = readme
        .split_once("## What is proved")
        .map(|(_, rest)| rest.split("\n## ").next().unwrap_or(rest))
        .expect("README.md has a `## What is proved` section");
    let rows: Vec<&str> = section.lines().filter(|l| l.starts_with("| `")).collect();
    let catalog = formal_catalog();
    for spec in &catalog {
        let prefix = table_row_prefix(spec);
        assert!(
            rows.contains(&prefix.as_str()),
            "README.md's \"What is proved\" lacks, or has stale, the row of {}: expected\n{prefix}\n(`cargo run --release -- prove --proof {}` prints it)",
            spec.name,
            spec.name
        );
    }
    assert_eq!(
        rows.len(),
        catalog.len(),
        "README.md's \"What is proved\" has rows for proofs the catalog does not have"
    );
}
