//! `motion-hdl`: export the Verilog, and measure it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use motion_hdl::export::{catalog, write_export};
use motion_hdl::plots::{plot_pulse_trains, plot_unevenness};
use motion_hdl::tools::report;

/// motion-hdl: FPGA motion-control blocks, exported to Verilog.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write every exported module as <module>.v, with its index, and its
    /// vector testbench.
    Export {
        /// Folder for the Verilog and its README index.
        #[arg(long, default_value = "rtl-out")]
        out: PathBuf,
        /// Folder for the generated vector testbenches.
        #[arg(long, default_value = "testbench")]
        testbench_out: PathBuf,
    },
    /// Synthesize every exported module for iCE40 HX8K and write the
    /// LUT4/DFF/carry/RAM/Fmax report (needs yosys and nextpnr-ice40).
    Report {
        /// Folder holding the exported <module>.v files.
        #[arg(long, default_value = "rtl-out")]
        rtl: PathBuf,
        /// The report file.
        #[arg(long, default_value = "rtl-out/synthesis-report.md")]
        out: PathBuf,
        /// Placement seeds; Fmax is the median over them.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
        seeds: u64,
        /// Only these modules (default: all).
        #[arg(long = "module")]
        modules: Vec<String>,
    },
    /// Draw the uniform pulse generator's figures as SVG: one period of
    /// (T, N) in single-period, paper-order and interleaved form, and the
    /// single-period unevenness mu against N for this T.
    PlotPulses {
        /// T: the interpolation period in ticks (even, at least 2).
        #[arg(long)]
        period: u64,
        /// N: pulses in the period (at most T/2).
        #[arg(long)]
        count: u64,
        /// Folder for pulse-trains-T<T>-N<N>.svg and unevenness-T<T>.svg.
        #[arg(long, default_value = "plots")]
        out_dir: PathBuf,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("motion-hdl: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::PlotPulses {
            period,
            count,
            out_dir,
        } => {
            std::fs::create_dir_all(&out_dir)
                .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
            let trains = out_dir.join(format!("pulse-trains-T{period}-N{count}.svg"));
            let mu = plot_pulse_trains(period, count, &trains).map_err(|e| e.to_string())?;
            println!("wrote {} (single-period mu = {mu:.4})", trains.display());
            let curve = out_dir.join(format!("unevenness-T{period}.svg"));
            let (worst, at) = plot_unevenness(period, &curve).map_err(|e| e.to_string())?;
            println!(
                "wrote {} (worst single-period mu = {worst:.4} at N = {at})",
                curve.display()
            );
            Ok(())
        }
        Command::Export { out, testbench_out } => {
            let written = write_export(&out, &testbench_out).map_err(|e| e.to_string())?;
            for path in written {
                println!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Report {
            rtl,
            out,
            seeds,
            modules,
        } => {
            let known: Vec<&str> = catalog().iter().map(|s| s.name).collect();
            if let Some(unknown) = modules.iter().find(|m| !known.contains(&m.as_str())) {
                return Err(format!(
                    "unknown module `{unknown}`; exported modules: {}",
                    known.join(", ")
                ));
            }
            let specs: Vec<_> = catalog()
                .into_iter()
                .filter(|s| modules.is_empty() || modules.iter().any(|m| m == s.name))
                .collect();
            let seeds: Vec<u64> = (1..=seeds).collect();
            let rows = report::measure(&specs, &rtl, &seeds).map_err(|e| e.to_string())?;
            let text = report::render(&rows, &seeds).map_err(|e| e.to_string())?;
            std::fs::write(&out, text)
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!("wrote {}", out.display());
            Ok(())
        }
    }
}
