//! Builds a Verilog module with Verilator into a shared library that
//! [`super::CompiledModel`] loads, and caches it by a hash of everything
//! that goes into it.
//!
//! The design is wrapped in a generated top, `mh_sim`, whose ports are
//! `clock`, `i0..` and `o0..`: the C++ member names are then ours, whatever
//! Verilator would have made of the design's own names (`enc_a__0` is
//! `enc_a___05F0` in C++). Verilator flattens the wrapper away.

use std::fmt::Write as _;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::Command;

use super::{CompiledError, Slot};

/// What Debian needs for this backend.
pub const INSTALL_LINE: &str = "apt-get install -y verilator g++";

/// Bumped whenever the generated wrapper, shim or build flags change, so
/// that no stale library is ever loaded from the cache.
pub(super) const SHIM_VERSION: u32 = 2;

/// Verilator's options. `--x-initial unique` with the context's
/// `randReset(0)` powers every register without an `initial` up at 0, as
/// rust-hdl does.
const VERILATOR_FLAGS: &[&str] = &[
    "--cc",
    "-O3",
    "--x-assign",
    "0",
    "--x-initial",
    "unique",
    "--no-timing",
    // The VCD counts picoseconds, as the harness's does.
    "--timescale",
    "1ps/1ps",
    "-Wno-fatal",
    "-Wno-lint",
    "-Wno-style",
];

/// g++ options for the model and the Verilator runtime. `-O1`: the
/// controller's model compiles in 10.2 s instead of 18.7 s at `-O3` and
/// runs about 13 % slower (a laser test's run: 26.0 s of CPU against
/// 23.0 s); most runs are shorter than the compile, and a fresh clone's
/// suite builds about 50 models. (`-Os`, make's default, runs the
/// controller about 3 times slower than `-O3`, and `-O3` is about 5 %
/// faster than `-O2`.)
const CXX_FLAGS: &[&str] = &["-std=c++17", "-O1", "-fPIC", "-pthread", "-faligned-new"];

/// The design's ports as the wrapper and the shim see them.
pub(super) struct Layout<'a> {
    pub module: &'a str,
    pub clock: &'a str,
    pub inputs: &'a [Slot],
    pub outputs: &'a [Slot],
}

/// Returns the path of the shared library for `verilog` (with top module
/// `layout.module`), building it unless the cache has it.
pub(super) fn library(
    verilog: &str,
    layout: &Layout,
    trace: bool,
) -> Result<PathBuf, CompiledError> {
    // The exported file and the Verilog generated now differ only in the
    // export's header comment: one library serves both.
    let design = Design::prepare(verilog, trace);
    let verilog = design.verilog.as_str();
    let verilator = tool_version("verilator", &["--version"])?;
    let compiler = tool_version("g++", &["--version"])?;
    let wrapper = wrapper_verilog(layout);
    let shim = shim_cpp(layout, trace, design.both_edges);
    let mut hasher = DefaultHasher::new();
    (
        SHIM_VERSION,
        verilog,
        &wrapper,
        &shim,
        &verilator,
        &compiler,
        trace,
    )
        .hash(&mut hasher);
    VERILATOR_FLAGS.hash(&mut hasher);
    CXX_FLAGS.hash(&mut hasher);
    let key = format!("{}-{:016x}", layout.module, hasher.finish());
    let root = cache_root();
    let done = root.join(&key);
    let lib = done.join("libmodel.so");
    if lib.exists() {
        return Ok(lib);
    }
    create_root(&root)?;
    // One build per library: a test that needs it while another builds it
    // waits, then loads it (two at once cost both cores the same g++ run).
    let _building = lock(&root.join(format!("{key}.lock")))?;
    if lib.exists() {
        return Ok(lib);
    }
    let runtime = runtime_objects(&root, &verilator, &compiler, trace)?;
    // Built in a private folder, then renamed into place: a test running
    // beside this one sees either no library or a whole one.
    let work = tempfile::Builder::new()
        .prefix(&format!(".{key}-"))
        .tempdir_in(&root)
        .map_err(|e| io(&root, e))?;
    let dir = work.path();
    let built = dir.join("libmodel.so");
    compile(
        dir,
        verilog,
        layout,
        trace,
        &shim,
        &runtime,
        &["-shared"],
        &built,
    )?;
    let staged = work.keep();
    if std::fs::rename(&staged, &done).is_err() && !lib.exists() {
        // A folder left without its library (a cleaner emptied it): replace it.
        let _ = std::fs::remove_dir_all(&done);
        std::fs::rename(&staged, &done).map_err(|e| {
            CompiledError::Build(format!(
                "cannot move {} to {}: {e}",
                staged.display(),
                done.display()
            ))
        })?;
    }
    let _ = std::fs::remove_dir_all(&staged);
    Ok(lib)
}

/// Verilates `verilog` with its wrapper in `dir` and compiles it with
/// `glue` (the shim, or a main) and the runtime into `output`.
#[allow(clippy::too_many_arguments)]
fn compile(
    dir: &Path,
    verilog: &str,
    layout: &Layout,
    trace: bool,
    glue: &str,
    runtime: &[PathBuf],
    link: &[&str],
    output: &Path,
) -> Result<(), CompiledError> {
    write(&dir.join("design.v"), verilog)?;
    write(&dir.join("wrapper.v"), &wrapper_verilog(layout))?;
    write(&dir.join("glue.cpp"), glue)?;
    let obj = dir.join("obj");
    let mut verilate = Command::new("verilator");
    verilate
        .args(VERILATOR_FLAGS)
        .args(if trace { &["--trace"][..] } else { &[] })
        .arg("--top-module")
        .arg("mh_sim")
        .arg("--Mdir")
        .arg(&obj)
        .arg(dir.join("design.v"))
        .arg(dir.join("wrapper.v"));
    run(&mut verilate)?;
    // One translation unit for the model and the glue: several times faster
    // to compile than Verilator's split files.
    let mut unity = String::new();
    let mut sources: Vec<_> = std::fs::read_dir(&obj)
        .map_err(|e| io(&obj, e))?
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
        .filter(|n| n.starts_with("Vmh_sim") && n.ends_with(".cpp"))
        .collect();
    sources.sort();
    for source in &sources {
        let _ = writeln!(unity, "#include \"{source}\"");
    }
    unity.push_str("#include \"../glue.cpp\"\n");
    write(&obj.join("unity.cpp"), &unity)?;
    let include = verilator_include()?;
    let mut compile = Command::new("g++");
    compile
        .args(CXX_FLAGS)
        .args(link)
        .args(["-fvisibility=hidden", "-Wl,--no-undefined"])
        .arg(format!("-I{}", include.display()))
        .arg(format!("-I{}", include.join("vltstd").display()))
        .arg(format!("-I{}", obj.display()))
        .arg(obj.join("unity.cpp"))
        .args(runtime)
        .arg("-o")
        .arg(output);
    run(&mut compile)?;
    Ok(())
}

/// Builds, in `dir`, the reference for the backend's speed: a plain C++
/// program that runs the same model over a file of input words (one cycle
/// after another, the shim's cycle), from power-up, a given number of
/// times, and prints `cycles seconds checksum` for each run.
pub(super) fn plain_loop(
    verilog: &str,
    layout: &Layout,
    dir: &Path,
) -> Result<PathBuf, CompiledError> {
    let design = Design::prepare(verilog, false);
    let verilator = tool_version("verilator", &["--version"])?;
    let compiler = tool_version("g++", &["--version"])?;
    let runtime = runtime_objects(&cache_root(), &verilator, &compiler, false)?;
    let in_words: usize = layout.inputs.iter().map(Slot::words).sum();
    let out_words: usize = layout.outputs.iter().map(Slot::words).sum::<usize>().max(1);
    let main = format!(
        r#"{shim}
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
int main(int argc, char** argv) {{
    if (argc != 3) return 2;
    FILE* f = std::fopen(argv[1], "rb");
    if (!f) return 2;
    std::vector<uint64_t> words;
    uint64_t w;
    while (std::fread(&w, 8, 1, f) == 1) words.push_back(w);
    std::fclose(f);
    size_t cycles = words.size() / {in_words};
    int repeats = std::atoi(argv[2]);
    for (int r = 0; r < repeats; r++) {{
        void* h = mh_new();
        uint64_t out[{out_words}] = {{0}};
        uint64_t checksum = 0;
        auto start = std::chrono::steady_clock::now();
        for (size_t c = 0; c < cycles; c++) {{
            mh_cycle(h, &words[c * {in_words}], out);
            for (int k = 0; k < {out_words}; k++) checksum = checksum * 31 + out[k];
        }}
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%zu %.6f %llu\n", cycles, seconds, (unsigned long long)checksum);
        mh_free(h);
    }}
    return 0;
}}
"#,
        shim = shim_cpp(layout, false, design.both_edges)
    );
    let program = dir.join("plain_loop");
    compile(
        dir,
        &design.verilog,
        layout,
        false,
        &main,
        &runtime,
        &[],
        &program,
    )?;
    Ok(program)
}

/// Where built libraries are kept: `$MOTION_HDL_SIM_CACHE`, else
/// `motion-hdl/verilated` in the user's cache folder (`$XDG_CACHE_HOME`, or
/// `~/.cache`). Never a shared temporary folder: a library found there is
/// loaded and run, so nobody else may be able to put one there.
pub fn cache_root() -> PathBuf {
    if let Some(root) = std::env::var_os("MOTION_HDL_SIM_CACHE") {
        return PathBuf::from(root);
    }
    let user_cache = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache")));
    match user_cache {
        Some(cache) => cache.join("motion-hdl").join("verilated"),
        None => std::env::temp_dir().join(format!(
            "motion-hdl-verilated-{}",
            std::env::var("USER").unwrap_or_else(|_| "user".into())
        )),
    }
}

/// Creates the cache root readable and writable by its owner only.
fn create_root(root: &Path) -> Result<(), CompiledError> {
    use std::os::unix::fs::DirBuilderExt;
    std::fs::DirBuilder::new()
        .recursive(true)
        .mode(0o700)
        .create(root)
        .map_err(|e| io(root, e))
}

/// The design text Verilator builds, and how the shim clocks it.
#[doc(hidden)]
pub struct Design {
    pub verilog: String,
    /// Every clocked block runs on both edges of its clock, so that one
    /// toggle of `clock` is one clock cycle of the design.
    pub both_edges: bool,
}

impl Design {
    /// `verilog` without the export's header ([`without_header`]); unless
    /// the model is to `trace`, with every `@(posedge c)` made
    /// `@(posedge c or negedge c)`.
    ///
    /// Why: each `eval` of a Verilator 5 model first evaluates all the
    /// logic that reads a top-level input (its `ico` region), whether or
    /// not an input changed. A cycle as a falling and a rising edge is two
    /// `eval`s, and so twice that logic, half of the controller's run time;
    /// a cycle as one toggle of a clock that both edges trigger is one
    /// `eval` and the same cycle: the inputs settle through the logic, then
    /// the registers take what it computed, then the logic settles again.
    /// A trace keeps the two `eval`s (a waveform viewer expects a clock
    /// with one rising edge a period), and so does a design with a
    /// falling-edge block of its own or any rising edge not written
    /// `@(posedge name)` (an asynchronous reset, say): rewritten, such a
    /// block would run every other cycle.
    pub fn prepare(verilog: &str, trace: bool) -> Design {
        let verilog = without_header(verilog);
        let posedge =
            regex::Regex::new(r"@\(posedge ([A-Za-z_][A-Za-z0-9_$]*)\)").expect("a valid pattern");
        let all_plain = posedge.find_iter(verilog).count() == verilog.matches("posedge").count();
        if trace || verilog.contains("negedge") || !all_plain {
            return Design {
                verilog: verilog.to_string(),
                both_edges: false,
            };
        }
        Design {
            verilog: posedge
                .replace_all(verilog, "@(posedge $1 or negedge $1)")
                .into_owned(),
            both_edges: true,
        }
    }
}

/// `verilog` without the export's wrapping: its leading comment and blank
/// lines, and the `` `default_nettype none `` ... `` `default_nettype wire ``
/// pair around the modules (a design that elaborates with it elaborates
/// the same without it).
fn without_header(verilog: &str) -> &str {
    let mut rest = verilog;
    while let Some(line) = rest.lines().next() {
        let trimmed = line.trim();
        if !(trimmed.is_empty() || trimmed.starts_with("//") || trimmed == "`default_nettype none")
        {
            break;
        }
        rest = rest[line.len()..].trim_start_matches(['\r', '\n']);
    }
    let rest = rest.trim_end();
    rest.strip_suffix("`default_nettype wire")
        .map_or(rest, str::trim_end)
}

/// An exclusive lock on `path` (created if missing), held until the file
/// is dropped; the operating system releases it if the process dies.
fn lock(path: &Path) -> Result<std::fs::File, CompiledError> {
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .map_err(|e| io(path, e))?;
    file.lock().map_err(|e| io(path, e))?;
    Ok(file)
}

/// Verilator's runtime (`verilated.cpp` and friends), compiled once per
/// Verilator and compiler version.
fn runtime_objects(
    root: &Path,
    verilator: &str,
    compiler: &str,
    trace: bool,
) -> Result<Vec<PathBuf>, CompiledError> {
    let mut names = vec!["verilated", "verilated_threads"];
    if trace {
        names.push("verilated_vcd_c");
    }
    let mut hasher = DefaultHasher::new();
    (SHIM_VERSION, verilator, compiler).hash(&mut hasher);
    CXX_FLAGS.hash(&mut hasher);
    let dir = root.join(format!("runtime-{:016x}", hasher.finish()));
    std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
    let _building = lock(&dir.join("build.lock"))?;
    let include = verilator_include()?;
    let mut objects = Vec::new();
    for name in names {
        let object = dir.join(format!("{name}.o"));
        if !object.exists() {
            let staged = tempfile::Builder::new()
                .prefix(&format!(".{name}-"))
                .suffix(".o")
                .tempfile_in(&dir)
                .map_err(|e| io(&dir, e))?
                .into_temp_path();
            let mut compile = Command::new("g++");
            compile
                .args(CXX_FLAGS)
                .arg(format!("-I{}", include.display()))
                .arg(format!("-I{}", include.join("vltstd").display()))
                .arg("-c")
                .arg(include.join(format!("{name}.cpp")))
                .arg("-o")
                .arg(&staged);
            run(&mut compile)?;
            staged.persist(&object).map_err(|e| io(&object, e.error))?;
        }
        objects.push(object);
    }
    Ok(objects)
}

/// `$VERILATOR_ROOT/include`, as Verilator itself reports it (its first
/// line: a Perl warning on stderr comes after it).
fn verilator_include() -> Result<PathBuf, CompiledError> {
    let root = run(Command::new("verilator")
        .arg("--getenv")
        .arg("VERILATOR_ROOT"))?;
    Ok(PathBuf::from(root.lines().next().unwrap_or_default().trim()).join("include"))
}

/// The top Verilator builds: the design with its ports renamed `i0..`, `o0..`.
fn wrapper_verilog(layout: &Layout) -> String {
    let range = |w: usize| {
        if w > 1 {
            format!("[{}:0] ", w - 1)
        } else {
            String::new()
        }
    };
    let mut ports = vec!["clock".to_string()];
    let mut declarations = vec!["    input wire clock;".to_string()];
    let mut connections = vec![format!("        .{}(clock)", layout.clock)];
    for (k, slot) in layout.inputs.iter().enumerate() {
        ports.push(format!("i{k}"));
        declarations.push(format!("    input wire {}i{k};", range(slot.width)));
        connections.push(format!("        .{}(i{k})", slot.name));
    }
    for (k, slot) in layout.outputs.iter().enumerate() {
        ports.push(format!("o{k}"));
        declarations.push(format!("    output wire {}o{k};", range(slot.width)));
        connections.push(format!("        .{}(o{k})", slot.name));
    }
    format!(
        "// Generated by motion-hdl's compiled simulation backend.\nmodule mh_sim({});\n{}\n    {} dut (\n{}\n    );\nendmodule\n",
        ports.join(", "),
        declarations.join("\n"),
        layout.module,
        connections.join(",\n")
    )
}

/// The C ABI the Rust side loads: new, free, one clock cycle (inputs in,
/// outputs out, as 64-bit words, least significant first), and the VCD.
fn shim_cpp(layout: &Layout, trace: bool, both_edges: bool) -> String {
    let mut set = String::new();
    for (k, slot) in layout.inputs.iter().enumerate() {
        let _ = writeln!(set, "    {}", store(&format!("t->i{k}"), slot));
    }
    let mut get = String::new();
    for (k, slot) in layout.outputs.iter().enumerate() {
        let _ = writeln!(get, "    {}", load(&format!("t->o{k}"), slot));
    }
    let (trace_include, trace_member, trace_dump, trace_close, trace_open) = if trace {
        (
            "#include \"verilated_vcd_c.h\"\n",
            "    VerilatedVcdC* vcd = nullptr;\n",
            "if (h->vcd) h->vcd->dump(h->time); ",
            "    if (h->vcd) { h->vcd->close(); delete h->vcd; }\n",
            "    if (h->vcd) return 3;\n    h->ctx.traceEverOn(true);\n    h->vcd = new VerilatedVcdC;\n    h->top->trace(h->vcd, 99);\n    h->vcd->open(path);\n    return h->vcd->isOpen() ? 0 : 1;\n",
        )
    } else {
        ("", "", "", "", "    (void)h; (void)path;\n    return 2;\n")
    };
    let half = crate::sim::harness::CLOCK_PERIOD_PS / 2;
    // The inputs settle with the clock low, then the rising edge: as two
    // `eval`s, or as one toggle of a clock whose both edges are the
    // design's ([`Design::prepare`]).
    let edge = if both_edges {
        format!(
            "    t->clock = !t->clock;\n    t->eval();\n    h->time += {};\n",
            2 * half
        )
    } else {
        format!(
            "    t->clock = 0;\n    t->eval();\n    {trace_dump}h->time += {half};\n    \
             t->clock = 1;\n    t->eval();\n    {trace_dump}h->time += {half};\n"
        )
    };
    format!(
        r#"// Generated by motion-hdl's compiled simulation backend.
#include <cstdint>
#include "verilated.h"
{trace_include}#include "Vmh_sim.h"

#define MH_EXPORT extern "C" __attribute__((visibility("default")))

namespace {{
struct Handle {{
    VerilatedContext ctx;
    Vmh_sim* top;
{trace_member}    uint64_t time = 0;
    Handle() {{
        ctx.randReset(0);
        top = new Vmh_sim{{&ctx, "TOP"}};
        top->clock = 0;
        top->eval();  // runs the initial blocks: the power-up state
    }}
}};
}}  // namespace

MH_EXPORT uint32_t mh_abi_version() {{ return {SHIM_VERSION}; }}
MH_EXPORT void* mh_new() {{ return new Handle(); }}
MH_EXPORT void mh_free(void* p) {{
    Handle* h = static_cast<Handle*>(p);
{trace_close}    h->top->final();
    delete h->top;
    delete h;
}}
MH_EXPORT int mh_trace(void* p, const char* path) {{
    Handle* h = static_cast<Handle*>(p);
{trace_open}}}
// Inputs settle with the clock low, then the rising edge; outputs are read
// after it with the inputs still applied (the Rust harness's cycle).
MH_EXPORT void mh_cycle(void* p, const uint64_t* in, uint64_t* out) {{
    Handle* h = static_cast<Handle*>(p);
    Vmh_sim* t = h->top;
{set}{edge}{get}}}
"#
    )
}

/// C++ that stores a port's words from `in` (upper bits masked: Verilator
/// assumes them clean).
fn store(member: &str, slot: &Slot) -> String {
    let w = slot.width;
    let o = slot.offset;
    if w <= 64 {
        let mask = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
        format!("{member} = in[{o}] & 0x{mask:x}ULL;")
    } else {
        let words = w.div_ceil(32);
        let top_mask = if w.is_multiple_of(32) {
            u32::MAX
        } else {
            (1u32 << (w % 32)) - 1
        };
        format!(
            "for (int k = 0; k < {words}; k++) {member}[k] = (uint32_t)(in[{o} + k / 2] >> (32 * (k % 2))); {member}[{last}] &= 0x{top_mask:x}u;",
            last = words - 1
        )
    }
}

/// C++ that loads a port's words into `out`.
fn load(member: &str, slot: &Slot) -> String {
    let o = slot.offset;
    if slot.width <= 64 {
        format!("out[{o}] = {member};")
    } else {
        let words = slot.width.div_ceil(32);
        format!(
            "for (int k = 0; k < {n}; k++) out[{o} + k] = 0; for (int k = 0; k < {words}; k++) out[{o} + k / 2] |= (uint64_t){member}[k] << (32 * (k % 2));",
            n = slot.width.div_ceil(64)
        )
    }
}

/// The first line a tool prints for `args`; a missing tool is an error that
/// names the install line.
pub(crate) fn tool_version(tool: &str, args: &[&str]) -> Result<String, CompiledError> {
    let text = run(Command::new(tool).args(args))?;
    Ok(text.lines().next().unwrap_or_default().to_string())
}

fn run(command: &mut Command) -> Result<String, CompiledError> {
    crate::tools::run(command, false).map_err(|e| match e {
        crate::tools::ToolError::Missing { tool } => CompiledError::Missing { tool },
        other => CompiledError::Build(other.to_string()),
    })
}

fn write(path: &Path, text: &str) -> Result<(), CompiledError> {
    std::fs::write(path, text).map_err(|e| io(path, e))
}

fn io(path: &Path, e: std::io::Error) -> CompiledError {
    CompiledError::Build(format!("{}: {e}", path.display()))
}
