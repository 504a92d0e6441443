//! Issue #40's corpus: real G-code programs that we did not write
//! (LinuxCNC's examples, CAM posts), listed with their sources in
//! `tests/corpus/manifest.tsv` and copied by `tests/corpus/fetch.sh` into
//! `target/corpus/` (or `$MOTION_HDL_CORPUS`). The files are not in the
//! repository, so these tests are ignored; run them with
//! `cargo nextest run --run-ignored only -E 'test(/gcode_corpus/)'` and
//! record the table they print on the issue.
//!
//! Each program must end as its manifest row says: `runs` (to its end
//! with commanded = actual = target and no underrun) or `refused line N:
//! <message start>`.

use std::path::PathBuf;

use motion_hdl::host::planner::to_steps;
use motion_hdl::host::simulation::{simulate, Job};
use motion_hdl::host::tool_table::ToolTable;
use motion_hdl::host::{interpolate, plan_toolpath};

use super::gcode::options;

/// One manifest row: the file, its tool table and the outcome it should
/// have.
struct Entry {
    file: String,
    tools: Option<ToolTable>,
    outcome: String,
}

fn manifest() -> Vec<Entry> {
    let path = motion_hdl::tools::repo_root().join("tests/corpus/manifest.tsv");
    let text = std::fs::read_to_string(&path).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|line| {
            let columns: Vec<&str> = line.split('\t').collect();
            assert_eq!(columns.len(), 8, "manifest row of 8 columns: {line}");
            let tools = (columns[6] != "-").then(|| {
                let path = motion_hdl::tools::repo_root()
                    .join("tests/corpus/tools")
                    .join(columns[6]);
                ToolTable::parse(&std::fs::read_to_string(&path).unwrap())
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            });
            Entry {
                file: columns[0].to_string(),
                tools,
                outcome: columns[7].to_string(),
            }
        })
        .collect()
}

fn corpus_dir() -> PathBuf {
    std::env::var_os("MOTION_HDL_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| motion_hdl::tools::repo_root().join("target/corpus"))
}

/// The file of `entry`, or a panic that says how to fetch the corpus.
fn corpus_file(entry: &Entry) -> PathBuf {
    let path = corpus_dir().join(&entry.file);
    assert!(
        path.is_file(),
        "{} is missing: run `bash tests/corpus/fetch.sh` first",
        path.display()
    );
    path
}

/// Whether `outcome` (Ok: the program runs; Err: its message) is what the
/// manifest row expects; prints the row's result either way.
fn check(entry: &Entry, outcome: Result<String, String>) -> bool {
    let (seen, good) = match &outcome {
        Ok(figures) => (format!("runs ({figures})"), entry.outcome == "runs"),
        Err(message) => {
            let expected = entry.outcome.strip_prefix("refused ");
            let good = expected.is_some_and(|e| message.contains(e));
            (format!("refused {message}"), good)
        }
    };
    let mark = if good { "ok  " } else { "DIFF" };
    println!("{mark} {:<62} {seen}", entry.file);
    if !good {
        println!("     the manifest says: {}", entry.outcome);
    }
    good
}

/// The host half: read, plan and interpolate each program; a program that
/// runs ends, in steps, exactly at its target.
#[test]
#[ignore = "needs the corpus: bash tests/corpus/fetch.sh"]
fn corpus_programs_plan_as_the_manifest_says() {
    let mut differ = 0;
    for entry in manifest() {
        let path = corpus_file(&entry);
        let outcome = Job::read(&path, None, None, entry.tools.clone()).and_then(|job| {
            let machine = job.machine;
            let segments = plan_toolpath(&job.toolpath, &machine).map_err(|e| e.to_string())?;
            let start = to_steps(job.toolpath.start, machine.steps_per_mm);
            let target = to_steps(job.toolpath.end(), machine.steps_per_mm);
            let interpolation = interpolate(start, &segments, machine.period);
            let last = interpolation.positions.last().copied().unwrap_or(start);
            if last != target {
                return Err(format!("the path ends at {last:?} steps, not {target:?}"));
            }
            Ok(format!(
                "{} moves, {} periods",
                job.toolpath.items.len(),
                interpolation.counts.len()
            ))
        });
        differ += usize::from(!check(&entry, outcome));
    }
    assert_eq!(differ, 0, "programs that do not end as the manifest says");
}

/// The whole of `simulate`, through the RTL controller on the compiled
/// backend at 50 clocks a period: every program that runs ends with
/// commanded = actual = target and no underrun.
#[test]
#[ignore = "needs the corpus: bash tests/corpus/fetch.sh; minutes of RTL simulation"]
fn corpus_programs_simulate_as_the_manifest_says() {
    let dir = tempfile::tempdir().unwrap();
    let mut options = options(dir.path());
    options.out_dir = None;
    let mut differ = 0;
    for entry in manifest() {
        let path = corpus_file(&entry);
        options.tools = entry.tools.clone();
        let outcome = simulate(&path, &options).and_then(|r| {
            let commanded = r.commanded.map(i64::from);
            let actual = r.actual.map(i64::from);
            if commanded != r.target || actual != r.target || r.underruns != 0 {
                return Err(format!(
                    "target {:?}, commanded {commanded:?}, actual {actual:?}, {} underruns",
                    r.target, r.underruns
                ));
            }
            Ok(format!(
                "{} periods, {} clocks in {:.1} s",
                r.periods, r.cycles, r.seconds
            ))
        });
        differ += usize::from(!check(&entry, outcome));
    }
    assert_eq!(differ, 0, "programs that do not end as the manifest says");
}
