//! The host's side of `spi_bus_adapter`: an SPI master at the pins, clock
//! by clock, and the register accesses the driver makes as frames.
//!
//! On a Raspberry Pi the same frames go out through Linux's `spidev`
//! (`/dev/spidev0.0`, mode 0, `SPI_IOC_MESSAGE` with one transfer per
//! frame and CS held for the transfer): the bytes of
//! [`frame::write_frame`] and [`frame::read_frame`] are the transfer's
//! TX buffer, its RX buffer is what [`frame::read_answer`] splits. Here the
//! master is simulated: [`SpiLink`] drives the adapter's pins one FPGA
//! clock at a time and clocks the controller's register bus with the
//! adapter's strobes, so the controller behind the SPI link is the same RTL
//! as behind the parallel bus, and the frames' time is counted.

use crate::blocks::spi_bus_adapter::frame::{self, FrameError, ReadAnswer};
use crate::blocks::spi_bus_adapter::model::{SpiInputs, SpiOutputs};
use crate::blocks::spi_bus_adapter::SpiBusAdapter;
use crate::host::bus::ControllerBus;
use crate::sim::{stepper, Backend, SimError, Stepper, VectorPorts};

/// The master's pin timing, in FPGA clocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpiTiming {
    /// Clocks SCLK is high in each bit (at least 2).
    pub high: u32,
    /// Clocks SCLK is low in each bit (at least 2).
    pub low: u32,
    /// Clocks from CS falling to the first SCLK rise (at least 3).
    pub lead: u32,
    /// Clocks from the last SCLK fall to CS rising.
    pub lag: u32,
    /// Clocks CS stays high after a frame (at least 2).
    pub gap: u32,
}

/// Why an SCLK cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpiTimingError {
    /// SCLK above a quarter of the FPGA clock, or not a positive rate.
    #[error(
        "SCLK of {sclk_hz} Hz: the SPI adapter takes at most a quarter of the {clock_hz} Hz FPGA clock, {max} Hz"
    , max = clock_hz / 4.0)]
    TooFast {
        /// The SCLK asked for.
        sclk_hz: f64,
        /// The FPGA clock.
        clock_hz: f64,
    },
}

impl SpiTiming {
    /// The fastest timing the adapter takes: SCLK at a quarter of the clock.
    pub const FASTEST: SpiTiming = SpiTiming {
        high: 2,
        low: 2,
        lead: 3,
        lag: 2,
        gap: 2,
    };

    /// The timing of an SCLK of at most `sclk_hz` with an FPGA clock of
    /// `clock_hz`: each phase the whole clocks of half an SCLK period,
    /// rounded up (so SCLK comes out at or below the rate asked).
    pub fn at(clock_hz: f64, sclk_hz: f64) -> Result<SpiTiming, SpiTimingError> {
        let too_fast = SpiTimingError::TooFast { sclk_hz, clock_hz };
        if !(sclk_hz > 0.0 && sclk_hz.is_finite() && clock_hz > 0.0) {
            return Err(too_fast);
        }
        let clocks = clock_hz / sclk_hz;
        if clocks < 4.0 - 1e-9 {
            return Err(too_fast);
        }
        let half = ((clocks / 2.0) - 1e-9).ceil().max(2.0) as u32;
        Ok(SpiTiming {
            high: half,
            low: half,
            lead: half.max(3),
            lag: half,
            gap: half,
        })
    }

    /// The SCLK rate this timing gives at `clock_hz`.
    pub fn sclk_hz(&self, clock_hz: f64) -> f64 {
        clock_hz / (self.high + self.low) as f64
    }

    /// FPGA clocks one frame of `bytes` bytes takes, CS high after it
    /// included.
    pub fn frame_clocks(&self, bytes: usize) -> u64 {
        let bits = 8 * bytes as u64;
        self.lead as u64
            + bits * self.high as u64
            + (bits - 1) * self.low as u64
            + self.lag as u64
            + self.gap as u64
    }
}

/// The pins of one clock, as the master drives them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpiPins {
    /// SPI clock.
    pub sclk: bool,
    /// Chip select, active low.
    pub cs_n: bool,
    /// Master out.
    pub mosi: bool,
}

/// Clocks one frame: `clock` runs one FPGA clock with the pins given and
/// returns MISO as it is during that clock (before its edge). Returns the
/// MISO bytes, sampled at each SCLK rise.
pub fn transfer(timing: SpiTiming, mosi: &[u8], mut clock: impl FnMut(SpiPins) -> bool) -> Vec<u8> {
    let bit = |k: usize| mosi[k / 8] >> (7 - k % 8) & 1 != 0;
    let bits = 8 * mosi.len();
    let mut miso = vec![0u8; mosi.len()];
    for k in 0..bits {
        let low = if k == 0 { timing.lead } else { timing.low };
        for _ in 0..low {
            clock(SpiPins {
                sclk: false,
                cs_n: false,
                mosi: bit(k),
            });
        }
        for h in 0..timing.high {
            let sampled = clock(SpiPins {
                sclk: true,
                cs_n: false,
                mosi: bit(k),
            });
            if h == 0 && sampled {
                miso[k / 8] |= 1 << (7 - k % 8);
            }
        }
    }
    let last = bits.checked_sub(1).map(bit).unwrap_or(false);
    for _ in 0..timing.lag {
        clock(SpiPins {
            sclk: false,
            cs_n: false,
            mosi: last,
        });
    }
    for _ in 0..timing.gap {
        clock(SpiPins {
            sclk: false,
            cs_n: true,
            mosi: false,
        });
    }
    miso
}

/// What the link has carried.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SpiStats {
    /// Frames sent.
    pub frames: u64,
    /// Bytes clocked, both directions counted once.
    pub bytes: u64,
    /// FPGA clocks the frames took (CS low, and CS high after each).
    pub clocks: u64,
}

/// Why an access over SPI failed.
#[derive(Debug, thiserror::Error)]
pub enum SpiError {
    /// The frame could not be built.
    #[error(transparent)]
    Frame(#[from] FrameError),
    /// The adapter's status reported a fault.
    #[error("the SPI adapter's status is {status:#04x} (CRC_ERROR 0x01, OVERSPEED 0x02)")]
    Status {
        /// The status byte.
        status: u8,
    },
    /// The read data's CRC did not match.
    #[error("the CRC of the words read over SPI does not match")]
    ReadCrc,
}

/// `spi_bus_adapter`'s RTL, its pins driven by a simulated master at a
/// fixed timing, in front of a register bus clocked by the caller.
pub struct SpiLink {
    adapter: Box<dyn Stepper>,
    timing: SpiTiming,
    vector: Vec<u64>,
    outputs: Vec<u64>,
    /// The adapter's outputs as the bus sees them this clock.
    shown: SpiOutputs,
    /// The bus's read data as the adapter sees it this clock.
    read_data: u32,
    stats: SpiStats,
}

impl SpiLink {
    /// The exported adapter on `backend`, driven at `timing`.
    pub fn new(backend: Backend, timing: SpiTiming) -> Result<Self, SimError> {
        Ok(Self {
            adapter: stepper(backend, "spi_bus_adapter", SpiBusAdapter::default(), None)?,
            timing,
            vector: Vec::new(),
            outputs: vec![0; SpiBusAdapter::output_names().len()],
            shown: SpiOutputs::default(),
            read_data: 0,
            stats: SpiStats::default(),
        })
    }

    /// The master's timing.
    pub fn timing(&self) -> SpiTiming {
        self.timing
    }

    /// What the link has carried so far.
    pub fn stats(&self) -> SpiStats {
        self.stats
    }

    /// One frame; `bus` clocks the register bus once (address, write
    /// data, write, read) and returns its read data after the clock.
    pub fn frame(
        &mut self,
        mosi: &[u8],
        mut bus: impl FnMut(u32, u32, bool, bool) -> u32,
    ) -> Vec<u8> {
        let mut clocks = 0;
        let miso = transfer(self.timing, mosi, |pins| {
            let before = self.shown;
            self.vector = SpiInputs {
                reset: false,
                sclk: pins.sclk,
                cs_n: pins.cs_n,
                mosi: pins.mosi,
                bus_read_data: self.read_data,
            }
            .to_vector();
            self.adapter
                .step_into(&self.vector, &mut self.outputs)
                .expect("the SPI adapter steps");
            self.shown = SpiOutputs::from_vector(&self.outputs);
            self.read_data = bus(
                before.bus_address as u32,
                before.bus_write_data,
                before.bus_write,
                before.bus_read,
            );
            clocks += 1;
            before.miso
        });
        self.stats.frames += 1;
        self.stats.bytes += mosi.len() as u64;
        self.stats.clocks += clocks;
        miso
    }

    /// Writes `words` from `address` on in one frame; returns the status.
    pub fn write(
        &mut self,
        address: u8,
        words: &[u32],
        bus: impl FnMut(u32, u32, bool, bool) -> u32,
    ) -> Result<(), SpiError> {
        let mosi = frame::write_frame(address, words)?;
        let miso = self.frame(&mosi, bus);
        let status = miso[frame::write_status_position(words.len())];
        match frame::status_ok(status) {
            true => Ok(()),
            false => Err(SpiError::Status { status }),
        }
    }

    /// Reads `count` words from `address` on in one frame (after a
    /// `SNAPSHOT` write with `snapshot`).
    pub fn read(
        &mut self,
        address: u8,
        count: usize,
        snapshot: bool,
        bus: impl FnMut(u32, u32, bool, bool) -> u32,
    ) -> Result<Vec<u32>, SpiError> {
        let mosi = frame::read_frame(address, count, snapshot)?;
        let miso = self.frame(&mosi, bus);
        let ReadAnswer {
            status,
            words,
            crc_ok,
            ..
        } = frame::read_answer(&miso, count);
        if !frame::status_ok(status) {
            return Err(SpiError::Status { status });
        }
        match crc_ok {
            true => Ok(words),
            false => Err(SpiError::ReadCrc),
        }
    }
}

/// Any register bus behind `spi_bus_adapter`: the driver's bus over SPI.
/// Every [`ControllerBus::write`] and [`ControllerBus::read`] is one frame
/// through the adapter's RTL, clocked with `inner`; [`SpiBus::write_burst`]
/// and [`SpiBus::read_burst`] carry up to 16 registers in one frame. (The
/// simulated controller of `simulate` has the same link built in:
/// [`crate::host::bus::RtlBus::use_spi`].)
pub struct SpiBus<B: ControllerBus> {
    inner: B,
    link: SpiLink,
}

impl<B: ControllerBus> SpiBus<B> {
    /// `inner` behind the exported adapter on `backend`, at `timing`.
    pub fn new(inner: B, backend: Backend, timing: SpiTiming) -> Result<Self, SimError> {
        Ok(Self {
            inner,
            link: SpiLink::new(backend, timing)?,
        })
    }

    /// The bus behind the adapter.
    pub fn inner(&self) -> &B {
        &self.inner
    }

    /// The bus behind the adapter, mutable.
    pub fn inner_mut(&mut self) -> &mut B {
        &mut self.inner
    }

    /// What the link has carried so far.
    pub fn stats(&self) -> SpiStats {
        self.link.stats()
    }

    /// Writes `words` from `address` on in one frame.
    pub fn write_burst(&mut self, address: u8, words: &[u32]) -> Result<(), SpiError> {
        let inner = &mut self.inner;
        self.link
            .write(address, words, |a, d, w, r| inner.clock(a, d, w, r))
    }

    /// Reads `count` registers from `address` on in one frame (after the
    /// controller's `SNAPSHOT` write with `snapshot`).
    pub fn read_burst(
        &mut self,
        address: u8,
        count: usize,
        snapshot: bool,
    ) -> Result<Vec<u32>, SpiError> {
        let inner = &mut self.inner;
        self.link.read(address, count, snapshot, |a, d, w, r| {
            inner.clock(a, d, w, r)
        })
    }
}

impl<B: ControllerBus> ControllerBus for SpiBus<B> {
    fn clock(&mut self, address: u32, write_data: u32, write: bool, read: bool) -> u32 {
        self.inner.clock(address, write_data, write, read)
    }
    fn irq(&self) -> bool {
        self.inner.irq()
    }
    fn cycles(&self) -> u64 {
        self.inner.cycles()
    }
    fn write(&mut self, address: u32, value: u32) {
        // The simulated pins are clean: a fault is the adapter's bug.
        self.write_burst(address as u8, &[value])
            .expect("a write frame on a clean simulated SPI link");
    }
    fn read(&mut self, address: u32) -> u32 {
        self.read_burst(address as u8, 1, false)
            .expect("a read frame on a clean simulated SPI link")[0]
    }
}
