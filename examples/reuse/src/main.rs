//! Writes the jog generator's Verilog: `motion-hdl-reuse-example [FILE]`
//! (default `jog_generator.v`).

use std::process::ExitCode;

fn main() -> ExitCode {
    let path = std::env::args().nth(1).unwrap_or("jog_generator.v".into());
    match motion_hdl_reuse_example::verilog() {
        Ok(verilog) => match std::fs::write(&path, verilog) {
            Ok(()) => {
                println!("wrote {path}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("cannot write {path}: {e}");
                ExitCode::FAILURE
            }
        },
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
