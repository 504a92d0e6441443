//! The register bus the driver talks to, and its implementations: the RTL
//! simulation of `motion_controller` on either simulation backend (with each
//! axis's steps looped back into its encoder), the reference model, and a
//! recorder of register writes. The two simulated controllers also drive
//! the machine-I/O pins (limits, home, drive alarms, E-stop, general
//! inputs), now or from a given clock on, so that a test or `simulate` can
//! trip a switch in the middle of a move.

use std::fmt::Write as _;

use std::path::Path;

use crate::blocks::motion_controller::io_model::MachinePins;
use crate::blocks::motion_controller::model::{
    ControllerInputs, ControllerOutputs, MotionControllerModel,
};
use crate::blocks::motion_controller::{
    MotionController3, MotionController3DdaLaser, MotionController3DdaSpindle,
    MotionController3Servo,
};
use crate::host::laser_log::LaserLog;
use crate::host::servo::DriveScale;
use crate::host::spi::{SpiError, SpiLink, SpiStats, SpiTiming};
use crate::host::thread_log::GearLog;
use crate::regmap::RegisterMap;
use crate::sim::plant::{quadrature_state, Ad669Bank, ServoMotor, SpindleMotor};
use crate::sim::{stepper, Backend, SimError, SimulatedEncoder, Stepper, VectorPorts};

/// A `motion_controller` register bus as firmware sees it. An
/// implementation provides one bus clock; writes, reads (strobe, then the
/// registered data a clock later) and waits are built on it.
pub trait ControllerBus {
    /// One clock with these bus inputs; returns `bus_read_data` after it.
    fn clock(&mut self, address: u32, write_data: u32, write: bool, read: bool) -> u32;
    /// The interrupt line after the last clock.
    fn irq(&self) -> bool;
    /// Clocks run so far.
    fn cycles(&self) -> u64;

    /// Writes a register (word address).
    fn write(&mut self, address: u32, value: u32) {
        self.clock(address, value, true, false);
    }
    /// Reads a register (word address).
    fn read(&mut self, address: u32) -> u32 {
        self.clock(address, 0, false, true);
        self.clock(0, 0, false, false)
    }
    /// Lets `clocks` clocks pass; returns the interrupt line after them.
    fn wait(&mut self, clocks: u64) -> bool {
        for _ in 0..clocks {
            self.clock(0, 0, false, false);
        }
        self.irq()
    }
}

/// Machine-I/O pin levels scheduled by clock: the pins take each entry's
/// levels from the clock that entry names on.
#[derive(Clone, Debug, Default)]
struct PinSchedule {
    /// (clock, pins), in clock order.
    pending: Vec<(u64, MachinePins)>,
}

impl PinSchedule {
    fn add(&mut self, clock: u64, pins: MachinePins) {
        let at = self.pending.partition_point(|(c, _)| *c <= clock);
        self.pending.insert(at, (clock, pins));
    }

    /// Applies to `pins` every entry due at clock `now`.
    fn apply(&mut self, now: u64, pins: &mut MachinePins) {
        let due = self.pending.partition_point(|(c, _)| *c <= now);
        if due > 0 {
            *pins = self.pending[due - 1].1;
            self.pending.drain(..due);
        }
    }
}

/// The 3-axis exported controller (16-entry FIFOs) in RTL simulation, on
/// either backend, each axis's step/dir pins driving a [`SimulatedEncoder`]
/// on its encoder inputs.
pub struct RtlBus {
    rtl: Box<dyn Stepper>,
    inputs: ControllerInputs,
    vector: Vec<u64>,
    outputs: Vec<u64>,
    encoders: [SimulatedEncoder; 3],
    irq: bool,
    /// Largest pin step rate seen per axis: steps in the busiest window of
    /// `rate_window` clocks.
    window_steps: [u64; 3],
    window_start: u64,
    peak_window_steps: [u64; 3],
    rate_window: u64,
    /// Motor positions (net pin steps) sampled every `sample_every` clocks.
    samples: Vec<[i64; 3]>,
    sample_every: u64,
    schedule: PinSchedule,
    /// Per axis: an analog servo on the DAC pins instead of the step
    /// loopback.
    servos: [Option<ServoPlant>; 3],
    /// The servos' DACs, one per axis on the controller's DAC pins.
    dacs: Ad669Bank,
    /// Seconds per clock (for the servo motors).
    clock_s: f64,
    /// A simulated probe that drives the `probe` pin from the position.
    probe_surface: Option<ProbeSurface>,
    /// The spindle on the `spindle_*` pins (the spindle build only).
    spindle: Option<SpindleMotor>,
    /// While a geared move runs: its record.
    gear_log: Option<GearLog>,
    /// While a laser run is recorded: its record.
    laser_log: Option<LaserLog>,
    /// With an SPI link, register writes and reads go through
    /// `spi_bus_adapter` in frames ([`RtlBus::use_spi`]).
    spi: Option<SpiLink>,
}

/// A simulated probe against a flat surface across one axis: the `probe`
/// pin is high (contact) in every clock whose position at the pins, before
/// the clock's steps, is at or beyond `contact_at` on that axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeSurface {
    /// The axis, 0 to 2.
    pub axis: usize,
    /// The first position in contact, steps (the controller's count).
    pub contact_at: i64,
    /// Contact at and below `contact_at` (else at and above).
    pub contact_below: bool,
}

impl ProbeSurface {
    /// Whether the probe touches at `position` (the axis's steps).
    pub fn touches(&self, position: i64) -> bool {
        match self.contact_below {
            true => position <= self.contact_at,
            false => position >= self.contact_at,
        }
    }
}

/// An analog axis's plant: the drive and motor its DAC commands, and the
/// motor's encoder.
#[derive(Clone, Debug)]
struct ServoPlant {
    motor: ServoMotor,
    scale: DriveScale,
}

impl RtlBus {
    /// A controller in its power-up state on `backend`; with `vcd`, every
    /// signal goes to that file (on Verilator, a build with its tracer).
    pub fn new(backend: Backend, vcd: Option<&Path>) -> Result<Self, SimError> {
        Ok(Self {
            rtl: stepper(
                backend,
                "motion_controller",
                MotionController3::default(),
                vcd,
            )?,
            inputs: ControllerInputs {
                encoders: vec![(false, false, false); 3],
                ..Default::default()
            },
            vector: Vec::new(),
            outputs: vec![0; MotionController3::output_names().len()],
            encoders: [SimulatedEncoder::default(); 3],
            irq: false,
            window_steps: [0; 3],
            window_start: 0,
            peak_window_steps: [0; 3],
            rate_window: 10_000,
            samples: Vec::new(),
            sample_every: 0,
            schedule: PinSchedule::default(),
            servos: [None, None, None],
            dacs: Ad669Bank::new(3),
            clock_s: 0.0,
            probe_surface: None,
            spindle: None,
            gear_log: None,
            laser_log: None,
            spi: None,
        })
    }

    /// The laser build (`motion_controller_dda_laser`: DDA only, the
    /// probe and the laser unit); each axis's steps are looped back into
    /// its encoder, and `laser_pwm` may be recorded
    /// ([`RtlBus::start_laser_log`]).
    pub fn with_laser(backend: Backend, vcd: Option<&Path>) -> Result<Self, SimError> {
        let mut bus = Self::new(backend, vcd)?;
        bus.rtl = stepper(
            backend,
            "motion_controller_dda_laser",
            MotionController3DdaLaser::default(),
            vcd,
        )?;
        bus.outputs = vec![0; MotionController3DdaLaser::output_names().len()];
        Ok(bus)
    }

    /// Starts recording `laser_pwm` and the steps (see [`LaserLog`]).
    pub fn start_laser_log(&mut self) {
        self.laser_log = Some(LaserLog::new());
    }

    /// The laser record so far, if one is kept.
    pub fn laser_log(&self) -> Option<&LaserLog> {
        self.laser_log.as_ref()
    }

    /// The spindle build (`motion_controller_dda_spindle`: DDA only, the
    /// probe, the spindle encoder and the gearbox) at `clock_hz`, with
    /// `spindle` on its `spindle_*` pins; each axis's steps are looped
    /// back into its encoder.
    pub fn with_spindle(
        backend: Backend,
        vcd: Option<&Path>,
        spindle: SpindleMotor,
        clock_hz: f64,
    ) -> Result<Self, SimError> {
        let mut bus = Self::new(backend, vcd)?;
        bus.rtl = stepper(
            backend,
            "motion_controller_dda_spindle",
            MotionController3DdaSpindle::default(),
            vcd,
        )?;
        bus.outputs = vec![0; MotionController3DdaSpindle::output_names().len()];
        bus.spindle = Some(spindle);
        bus.clock_s = 1.0 / clock_hz;
        Ok(bus)
    }

    /// The spindle, if the bus has one.
    pub fn spindle(&self) -> Option<&SpindleMotor> {
        self.spindle.as_ref()
    }

    /// The spindle, to command it.
    pub fn spindle_mut(&mut self) -> Option<&mut SpindleMotor> {
        self.spindle.as_mut()
    }

    /// Starts recording a geared move of `axis` (see [`GearLog`]).
    pub fn start_gear_log(&mut self, axis: usize) {
        self.gear_log = Some(GearLog::new(axis));
    }

    /// Stops recording; the record.
    pub fn take_gear_log(&mut self) -> Option<GearLog> {
        self.gear_log.take()
    }

    /// The analog build (`motion_controller_servo`) at `clock_hz`, with an
    /// analog servo on each axis that has a motor in `servos`: its AD669 on
    /// the DAC pins (channel k, two's complement) drives `scale`'s volts
    /// into the motor, whose encoder feeds the axis's encoder pins. The
    /// other axes' steps are looped back into their encoders.
    pub fn with_servos(
        backend: Backend,
        vcd: Option<&Path>,
        servos: [Option<ServoMotor>; 3],
        scale: DriveScale,
        clock_hz: f64,
    ) -> Result<Self, SimError> {
        let mut bus = Self::new(backend, vcd)?;
        bus.rtl = stepper(
            backend,
            "motion_controller_servo",
            MotionController3Servo::default(),
            vcd,
        )?;
        bus.outputs = vec![0; MotionController3Servo::output_names().len()];
        bus.servos = servos.map(|m| m.map(|motor| ServoPlant { motor, scale }));
        bus.clock_s = 1.0 / clock_hz;
        Ok(bus)
    }

    /// Per axis: its position, counts: the servo motor's encoder count, or
    /// the net steps looped back.
    pub fn positions(&self) -> [i64; 3] {
        std::array::from_fn(|k| match &self.servos[k] {
            Some(plant) => plant.motor.counts(),
            None => self.encoders[k].net,
        })
    }

    /// Drives the machine-I/O pins with `pins` from the next clock on. At
    /// power-up every pin is low: no switch tripped, no alarm, no E-stop.
    pub fn set_pins(&mut self, pins: MachinePins) {
        self.inputs.pins = pins;
    }

    /// Drives the machine-I/O pins with `pins` from clock `clock` on
    /// ([`ControllerBus::cycles`] counts the clocks run): a switch tripped
    /// in the middle of a move.
    pub fn set_pins_at(&mut self, clock: u64, pins: MachinePins) {
        self.schedule.add(clock, pins);
    }

    /// Drives the `probe` pin from the position at the pins from the next
    /// clock on (`None`: the pin as [`RtlBus::set_pins`] leaves it).
    pub fn set_probe_surface(&mut self, surface: Option<ProbeSurface>) {
        self.probe_surface = surface;
    }

    /// The machine-I/O pins driven now.
    pub fn pins(&self) -> MachinePins {
        self.inputs.pins
    }

    /// Samples the motor positions (net steps at the pins) every `clocks`
    /// clocks from now on (0: never).
    pub fn sample_positions(&mut self, clocks: u64) {
        self.sample_every = clocks;
    }

    /// The sampled motor positions.
    pub fn samples(&self) -> &[[i64; 3]] {
        &self.samples
    }

    /// The simulated encoders (their `net` and `total` count the pins).
    pub fn encoders(&self) -> &[SimulatedEncoder; 3] {
        &self.encoders
    }

    /// Measures the peak step rates over windows of `clocks` clocks from
    /// now on (default 10,000).
    pub fn set_rate_window(&mut self, clocks: u64) {
        self.rate_window = clocks.max(1);
    }

    /// From now on, every register write and read goes through
    /// `spi_bus_adapter` (its RTL, on the controller's backend) as one SPI
    /// frame at `timing`, the controller clocked with the adapter.
    pub fn use_spi(&mut self, backend: Backend, timing: SpiTiming) -> Result<(), SimError> {
        self.spi = Some(SpiLink::new(backend, timing)?);
        Ok(())
    }

    /// Reads `count` consecutive registers from `address` in one SPI read
    /// frame (after the controller's `SNAPSHOT` write with `snapshot`): a
    /// burst the adapter reads on consecutive clocks. `None` without an SPI
    /// link.
    pub fn spi_read_burst(
        &mut self,
        address: u8,
        count: usize,
        snapshot: bool,
    ) -> Option<Result<Vec<u32>, SpiError>> {
        self.with_spi(|link, bus| {
            link.read(address, count, snapshot, |a, d, w, r| bus.clock(a, d, w, r))
        })
    }

    /// Runs `frame` with the SPI link and this bus to clock the controller
    /// with (the link is lent out for the frame); `None` without a link.
    fn with_spi<T>(&mut self, frame: impl FnOnce(&mut SpiLink, &mut Self) -> T) -> Option<T> {
        let mut link = self.spi.take()?;
        let result = frame(&mut link, self);
        self.spi = Some(link);
        Some(result)
    }

    /// The SPI link's timing, if the bus has one.
    pub fn spi_timing(&self) -> Option<SpiTiming> {
        self.spi.as_ref().map(SpiLink::timing)
    }

    /// What the SPI link has carried, if the bus has one.
    pub fn spi_stats(&self) -> Option<SpiStats> {
        self.spi.as_ref().map(SpiLink::stats)
    }

    /// Peak step rate per axis at the pins, in steps per clock, measured
    /// over windows of [`RtlBus::set_rate_window`] clocks.
    pub fn peak_steps_per_clock(&self) -> [f64; 3] {
        self.peak_window_steps
            .map(|n| n as f64 / self.rate_window as f64)
    }
}

impl ControllerBus for RtlBus {
    fn clock(&mut self, address: u32, data: u32, write: bool, read: bool) -> u32 {
        self.inputs.address = address;
        self.inputs.write_data = data;
        self.inputs.write = write;
        self.inputs.read = read;
        for (k, (pins, e)) in self
            .inputs
            .encoders
            .iter_mut()
            .zip(&self.encoders)
            .enumerate()
        {
            *pins = match &self.servos[k] {
                Some(plant) => {
                    let (a, b) = quadrature_state(plant.motor.counts());
                    (a, b, false)
                }
                None => e.outputs(),
            };
        }
        self.schedule
            .apply(self.rtl.cycles(), &mut self.inputs.pins);
        if let Some(surface) = self.probe_surface {
            self.inputs.pins.probe = surface.touches(self.positions()[surface.axis]);
        }
        if let Some(spindle) = &self.spindle {
            self.inputs.spindle = spindle.pins();
        }
        self.inputs.write_vector(&mut self.vector);
        self.rtl
            .step_into(&self.vector, &mut self.outputs)
            .expect("the controller steps");
        let out = ControllerOutputs::from_vector(&self.outputs, 3);
        self.irq = out.irq;
        let mut new_steps = 0;
        for (i, e) in self.encoders.iter_mut().enumerate() {
            let before = e.total;
            e.follow(out.steps[i]);
            self.window_steps[i] += e.total - before;
            new_steps += e.total - before;
        }
        if let Some(log) = &mut self.laser_log {
            log.clock(out.laser, new_steps);
        }
        let cycles = self.rtl.cycles();
        self.dacs
            .clock(out.dac.data, out.dac.cs_n, out.dac.l1_n, out.dac.ldac);
        for (k, servo) in self.servos.iter_mut().enumerate() {
            if let Some(plant) = servo {
                plant
                    .motor
                    .advance(plant.scale.volts(self.dacs.code(k)), self.clock_s);
            }
        }
        if let Some(spindle) = &mut self.spindle {
            spindle.advance(self.clock_s);
            if let Some(log) = &mut self.gear_log {
                let position = self.encoders[log.axis].net;
                log.clock(cycles, spindle.count(), spindle.pins().2, position);
            }
        }
        if self.sample_every > 0 && cycles.is_multiple_of(self.sample_every) {
            let positions = self.positions();
            self.samples.push(positions);
        }
        if cycles - self.window_start >= self.rate_window {
            for i in 0..3 {
                self.peak_window_steps[i] = self.peak_window_steps[i].max(self.window_steps[i]);
            }
            self.window_steps = [0; 3];
            self.window_start = cycles;
        }
        out.read_data
    }
    // The simulated SPI pins are clean: a faulted frame is the adapter's bug.
    fn write(&mut self, address: u32, value: u32) {
        let frame = self.with_spi(|link, bus| {
            link.write(address as u8, &[value], |a, d, w, r| bus.clock(a, d, w, r))
        });
        match frame {
            None => {
                self.clock(address, value, true, false);
            }
            Some(written) => written.expect("a write frame on a clean simulated SPI link"),
        }
    }
    fn read(&mut self, address: u32) -> u32 {
        let frame = self.with_spi(|link, bus| {
            link.read(address as u8, 1, false, |a, d, w, r| bus.clock(a, d, w, r))
        });
        match frame {
            None => {
                self.clock(address, 0, false, true);
                self.clock(0, 0, false, false)
            }
            Some(words) => words.expect("a read frame on a clean simulated SPI link")[0],
        }
    }
    fn irq(&self) -> bool {
        self.irq
    }
    fn cycles(&self) -> u64 {
        self.rtl.cycles()
    }
}

/// The controller's reference model as a bus (no RTL: fast), with no
/// encoder motion. For recording a driver's register traffic.
pub struct ModelBus {
    model: MotionControllerModel,
    irq: bool,
    cycles: u64,
    pins: MachinePins,
    schedule: PinSchedule,
}

impl ModelBus {
    /// A 3-axis, 16-entry model in its power-up state.
    pub fn new() -> Self {
        Self {
            model: MotionControllerModel::new(
                3,
                4,
                crate::blocks::motion_controller::registers::BuildOptions::MOTION_CONTROLLER,
            )
            .expect("3 axes fit"),
            irq: false,
            cycles: 0,
            pins: MachinePins::default(),
            schedule: PinSchedule::default(),
        }
    }

    /// Drives the machine-I/O pins with `pins` from the next clock on (at
    /// power-up every pin is low).
    pub fn set_pins(&mut self, pins: MachinePins) {
        self.pins = pins;
    }

    /// Drives the machine-I/O pins with `pins` from clock `clock` on.
    pub fn set_pins_at(&mut self, clock: u64, pins: MachinePins) {
        self.schedule.add(clock, pins);
    }

    /// The machine-I/O pins driven now.
    pub fn pins(&self) -> MachinePins {
        self.pins
    }
}

impl ControllerBus for ModelBus {
    fn clock(&mut self, address: u32, write_data: u32, write: bool, read: bool) -> u32 {
        self.schedule.apply(self.cycles, &mut self.pins);
        let out = self.model.step(&ControllerInputs {
            reset: false,
            address,
            write_data,
            write,
            read,
            encoders: vec![(false, false, false); 3],
            pins: self.pins,
            spindle: Default::default(),
        });
        self.cycles += 1;
        self.irq = out.irq;
        out.read_data
    }
    fn irq(&self) -> bool {
        self.irq
    }
    fn cycles(&self) -> u64 {
        self.cycles
    }
}

impl Default for ModelBus {
    fn default() -> Self {
        Self::new()
    }
}

/// Records every register write of a driver as a line of text, named with
/// the register map (`@clock  FIFO_WRITE[1] <- 0x00000005`), and passes
/// the traffic on to `inner` (which answers the reads).
pub struct RecordingBus<B: ControllerBus> {
    inner: B,
    names: Vec<(u32, String)>,
    /// One line per write.
    pub log: String,
}

impl<B: ControllerBus> RecordingBus<B> {
    /// Records the writes going to `inner`, named after `map`.
    pub fn new(inner: B, map: &RegisterMap) -> Self {
        let mut names = Vec::new();
        for r in &map.registers {
            for (i, address) in r.addresses().enumerate() {
                let name = if r.count > 1 {
                    format!("{}[{i}]", r.name)
                } else {
                    r.name.to_string()
                };
                names.push((address, name));
            }
        }
        Self {
            inner,
            names,
            log: String::new(),
        }
    }

    /// The bus behind the recorder.
    pub fn inner(&self) -> &B {
        &self.inner
    }
}

impl<B: ControllerBus> ControllerBus for RecordingBus<B> {
    fn clock(&mut self, address: u32, write_data: u32, write: bool, read: bool) -> u32 {
        if write {
            let name = self
                .names
                .iter()
                .find(|(a, _)| *a == address)
                .map_or_else(|| format!("{address:#04x}"), |(_, n)| n.clone());
            let _ = writeln!(
                self.log,
                "@{:<10} {name} <- {write_data:#010x}",
                self.inner.cycles()
            );
        }
        self.inner.clock(address, write_data, write, read)
    }
    fn irq(&self) -> bool {
        self.inner.irq()
    }
    fn cycles(&self) -> u64 {
        self.inner.cycles()
    }
}
