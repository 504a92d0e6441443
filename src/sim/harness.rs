use rust_hdl::core::check_error::check_all;
use rust_hdl::core::prelude::*;
use rust_hdl::core::vcd_probe::{write_vcd_change, write_vcd_dump, write_vcd_header, VCDProbe};
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use super::ports::VectorPorts;

/// Update passes allowed per clock phase before the logic counts as not
/// settling. rust-hdl's own simulator allows 100; a correct design needs a few.
const SETTLE_LIMIT: usize = 100;

/// Simulated time of one clock period in the VCD, in picoseconds (a 100 MHz clock).
pub const CLOCK_PERIOD_PS: u64 = 10_000;

/// Why a harness could not be built or stepped.
#[derive(Debug, thiserror::Error)]
pub enum HarnessError {
    /// `check_all` rejected the block: undriven inputs, a written input, or a
    /// local read before it is written.
    #[error("block `{block}` fails rust-hdl's structural checks: {detail}")]
    Check { block: String, detail: String },
    /// The logic did not settle: a combinational loop.
    #[error("block `{block}` did not settle after {SETTLE_LIMIT} update passes in cycle {cycle}: a combinational loop")]
    CombinationalLoop { block: String, cycle: u64 },
    /// Writing the waveform failed.
    #[error("waveform file `{path}`: {source}")]
    Waveform {
        path: String,
        source: std::io::Error,
    },
}

/// Steps one rust-hdl block clock by clock, without threads.
///
/// A cycle is: the caller sets inputs through [`Harness::block`], then
/// [`Harness::cycle`] lowers the clock and settles the logic, raises the
/// clock (registers capture) and settles again. Outputs read after `cycle`
/// show the state after that rising edge, with the inputs still applied;
/// that is exactly what the Verilog testbenches in `testbench/` sample.
pub struct Harness<B: VectorPorts> {
    block: B,
    name: String,
    cycle: u64,
    vcd: Option<VCDProbe<BufWriter<File>>>,
}

impl<B: VectorPorts> Harness<B> {
    /// Wraps `block`, runs `connect_all` and `check_all` once, and settles
    /// the power-up state. `name` identifies the block in errors.
    pub fn new(name: &str, mut block: B) -> Result<Self, HarnessError> {
        block.connect_all();
        check_all(&block).map_err(|e| HarnessError::Check {
            block: name.to_string(),
            detail: format!("{e:?}"),
        })?;
        let mut harness = Self {
            block,
            name: name.to_string(),
            cycle: 0,
            vcd: None,
        };
        harness.settle()?;
        Ok(harness)
    }

    /// The block, to set inputs (`.next`) and read outputs (`.val()`).
    pub fn block(&mut self) -> &mut B {
        &mut self.block
    }

    /// Clock cycles run so far.
    pub fn cycles(&self) -> u64 {
        self.cycle
    }

    /// Records every signal of the block to a VCD file from now on.
    pub fn record_vcd(&mut self, path: &Path) -> Result<(), HarnessError> {
        // The last cycle left the clock high (its fall settles with the next
        // inputs); the waveform starts from a settled fall instead.
        self.block.clock_mut().next = Clock { clk: false };
        self.settle()?;
        let file = File::create(path).map_err(|source| HarnessError::Waveform {
            path: path.display().to_string(),
            source,
        })?;
        let mut vcd = write_vcd_header(BufWriter::new(file), &self.block);
        vcd = write_vcd_dump(vcd, &self.block);
        self.vcd = Some(vcd);
        Ok(())
    }

    /// Propagates the inputs just set through the combinational logic.
    pub fn settle(&mut self) -> Result<(), HarnessError> {
        for _ in 0..SETTLE_LIMIT {
            self.block.update_all();
            if !self.block.has_changed() {
                return Ok(());
            }
        }
        Err(HarnessError::CombinationalLoop {
            block: self.name.clone(),
            cycle: self.cycle,
        })
    }

    /// Runs one full clock cycle with the inputs currently set.
    ///
    /// Every flip-flop in rust-hdl (and in this crate) is rising-edge, so
    /// the clock's fall changes nothing but the clock: it is settled
    /// together with the next cycle's inputs, which saves one settle of the
    /// whole design per cycle. Only a VCD, which shows the fall at its own
    /// time, settles it on its own.
    pub fn cycle(&mut self) -> Result<(), HarnessError> {
        self.block.clock_mut().next = Clock { clk: false };
        self.settle()?;
        self.block.clock_mut().next = Clock { clk: true };
        self.settle()?;
        if self.vcd.is_some() {
            self.trace(self.cycle * CLOCK_PERIOD_PS + CLOCK_PERIOD_PS / 2);
            self.block.clock_mut().next = Clock { clk: false };
            self.settle()?;
        }
        self.cycle += 1;
        self.trace(self.cycle * CLOCK_PERIOD_PS);
        Ok(())
    }

    /// Applies one vector of input values (in [`VectorPorts::input_names`]
    /// order), runs a cycle and returns the outputs (in
    /// [`VectorPorts::output_names`] order).
    pub fn step_vector(&mut self, inputs: &[u64]) -> Result<Vec<u64>, HarnessError> {
        self.block.set_inputs(inputs);
        self.cycle()?;
        Ok(self.block.outputs())
    }

    /// Applies one vector of input values and returns the outputs before
    /// the next clock edge (the combinational outputs of this clock's
    /// inputs and the present state); [`Harness::cycle`] then clocks it.
    /// For blocks whose outputs depend combinationally on their inputs,
    /// where [`Harness::step_vector`] shows them only after the edge.
    pub fn peek_vector(&mut self, inputs: &[u64]) -> Result<Vec<u64>, HarnessError> {
        self.block.set_inputs(inputs);
        self.block.clock_mut().next = Clock { clk: false };
        self.settle()?;
        Ok(self.block.outputs())
    }

    /// Flushes and closes the VCD file, if one is open, and returns the block.
    pub fn finish(mut self) -> B {
        if let Some(mut vcd) = self.vcd.take() {
            let _ = vcd.timestamp(self.cycle * CLOCK_PERIOD_PS + 1);
        }
        self.block
    }

    fn trace(&mut self, time_ps: u64) {
        if let Some(mut vcd) = self.vcd.take() {
            // A failed write only loses the waveform, never the simulation.
            if vcd.timestamp(time_ps).is_ok() {
                vcd = write_vcd_change(vcd, &self.block);
            }
            self.vcd = Some(vcd);
        }
    }
}
