//! Reference model of [`super::MotionController`], cycle-exact.
//!
//! Composed of the block models (each proven against its own RTL) and a
//! plain-Rust model of the controller's glue: register file, period
//! counter, run control, interrupt events and read multiplexer. Each clock
//! is computed in two phases, like the hardware: first the combinational
//! values from the registered state of every part, then the edge.

use super::analog_model::{AnalogWalkModel, WalkInputs};
use super::gear_merge::GearMergeModel;
use super::io_model::{
    AxisIoComb, AxisIoModel, AxisSwitches, FeedHoldModel, MachineIoModel, MachinePins, ProbeComb,
    ProbeModel, StepPath,
};
use super::laser_model::{LaserUnitInputs, LaserUnitModel};
use super::registers::{
    self, axis, fields, global, irq, StopCause, AXIS_BASE, AXIS_STRIDE, AXIS_STRIDE_LOG2, ID_VALUE,
    VERSION_VALUE,
};
use super::soft_limits::{SoftLimitsInputs, SoftLimitsModel};
use super::spindle_model::{SpindleInputs, SpindleModel};
use crate::blocks::command_fifo::model::{CommandFifoModel, CommandFifoOutputs};
use crate::blocks::dac_interface::model::{DacInputs, DacModel, DacOutputs};
use crate::blocks::dda_integrator::model::{
    DdaIntegratorInputs, DdaIntegratorModel, DdaIntegratorOutputs,
};
use crate::blocks::freq_divider::model::{FreqDividerInputs, FreqDividerModel};
use crate::blocks::interrupt_controller::model::InterruptControllerModel;
use crate::blocks::pulse_counter::model::{
    PulseCounterInputs, PulseCounterModel, PulseCounterOutputs,
};
use crate::blocks::quadrature_decoder::model::{
    QuadratureDecoderInputs, QuadratureDecoderModel, QuadratureDecoderOutputs,
};
use crate::blocks::sequential_divider::model::{SequentialDividerInputs, SequentialDividerModel};
use crate::blocks::step_output::model::{StepOutputInputs, StepOutputModel, StepOutputOutputs};
use crate::blocks::uniform_pulse_gen::model::{
    UniformPulseGenInputs, UniformPulseGenModel, UniformPulseGenOutputs,
};
use crate::blocks::watchdog::model::WatchdogModel;

/// A POSITION_BITS-wide position count as its register word: the count's
/// sign carried up to bit 31, as the axis's read path does.
pub fn position_word(count: u64) -> u32 {
    crate::blocks::signed_value(count, super::POSITION_BITS as u32) as u32
}

/// The largest count the interpolators take.
const COUNT_MAX: u64 = (1 << super::PERIOD_BITS) - 1;

/// The controller's inputs in one clock.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ControllerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Bus word address.
    pub address: u32,
    /// Bus write data.
    pub write_data: u32,
    /// Bus write strobe.
    pub write: bool,
    /// Bus read strobe.
    pub read: bool,
    /// Per axis: encoder (a, b, index).
    pub encoders: Vec<(bool, bool, bool)>,
    /// Limit, home, alarm, E-stop and general-input pins.
    pub pins: MachinePins,
    /// The spindle encoder: (a, b, index).
    pub spindle: (bool, bool, bool),
}

/// The controller's outputs after one edge.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ControllerOutputs {
    /// Bus read data.
    pub read_data: u32,
    /// Level interrupt.
    pub irq: bool,
    /// Periods are running.
    pub running: bool,
    /// Running, or an axis still busy.
    pub active: bool,
    /// Per axis: (step_a, step_b).
    pub steps: Vec<(bool, bool)>,
    /// drive_enable, bit k for axis k.
    pub drive_enable: u32,
    /// gpio_out.
    pub gpio_out: u8,
    /// The DAC pins: data, chip selects (active low, bit k for axis k),
    /// L1 (active low) and LDAC.
    pub dac: DacPins,
    /// `laser_pwm`.
    pub laser: bool,
}

/// The controller's DAC pins after one edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DacPins {
    /// `dac_data`.
    pub data: u64,
    /// `dac_cs_n`, bit k for axis k.
    pub cs_n: u64,
    /// `dac_l1_n`.
    pub l1_n: bool,
    /// `dac_ldac`.
    pub ldac: bool,
}

impl ControllerInputs {
    /// The RTL's input vector, in its port order (`VectorPorts`).
    pub fn to_vector(&self) -> Vec<u64> {
        let mut vector = Vec::with_capacity(19);
        self.write_vector(&mut vector);
        vector
    }

    /// [`ControllerInputs::to_vector`] into `vector` (cleared first), so a
    /// per-clock caller reuses one buffer.
    pub fn write_vector(&self, vector: &mut Vec<u64>) {
        vector.clear();
        vector.extend([
            self.reset as u64,
            self.address as u64,
            self.write_data as u64,
            self.write as u64,
            self.read as u64,
        ]);
        let word = |f: fn(&(bool, bool, bool)) -> bool| {
            self.encoders
                .iter()
                .enumerate()
                .fold(0u64, |w, (k, e)| w | (f(e) as u64) << k)
        };
        vector.extend([word(|e| e.0), word(|e| e.1), word(|e| e.2)]);
        vector.extend([
            self.pins.limit_pos as u64,
            self.pins.limit_neg as u64,
            self.pins.home as u64,
            self.pins.drive_alarm as u64,
            self.pins.estop as u64,
            self.pins.gpio_in as u64,
            self.pins.probe as u64,
            self.pins.feed_hold as u64,
            self.spindle.0 as u64,
            self.spindle.1 as u64,
            self.spindle.2 as u64,
        ]);
    }
}

impl ControllerOutputs {
    /// Reads the RTL's output vector of a `axes`-axis controller, in its port
    /// order.
    pub fn from_vector(v: &[u64], axes: usize) -> Self {
        Self {
            read_data: v[0] as u32,
            irq: v[1] != 0,
            running: v[2] != 0,
            active: v[3] != 0,
            steps: (0..axes)
                .map(|k| (v[4] >> k & 1 != 0, v[5] >> k & 1 != 0))
                .collect(),
            drive_enable: v[6] as u32,
            gpio_out: v[7] as u8,
            dac: DacPins {
                data: v[8],
                cs_n: v[9],
                l1_n: v[10] != 0,
                ldac: v[11] != 0,
            },
            laser: v[12] != 0,
        }
    }
}

/// Glue inputs an axis receives from the controller in one clock.
#[derive(Clone, Copy, Debug, Default)]
struct AxisControl {
    reset: bool,
    tick: bool,
    start: bool,
    halt: bool,
    flush: bool,
    pop: bool,
    underrun: bool,
    period_active: u64,
    modulus: u64,
    snapshot: bool,
    low_water: u64,
    address: u32,
    write: bool,
    write_data: u32,
    abort: bool,
    drive_allowed: bool,
    probe_latch: bool,
}

/// Model of one axis ([`super::axis::MotionAxis`]).
#[derive(Clone, Debug)]
pub struct AxisModel {
    window: u32,
    /// AXIS_CONFIG's writable bits, from the register map: in a build
    /// without uniform generators UNIFORM and INTERLEAVED are not among
    /// them, so the uniform generator is never loaded and stays idle (the
    /// RTL's gating of its outputs changes nothing else).
    config_mask: u32,
    fifo: CommandFifoModel,
    fifo_out: CommandFifoOutputs,
    dda: DdaIntegratorModel,
    dda_out: DdaIntegratorOutputs,
    uniform: UniformPulseGenModel,
    uniform_out: UniformPulseGenOutputs,
    stage: StepOutputModel,
    stage_out: StepOutputOutputs,
    position: PulseCounterModel,
    position_out: PulseCounterOutputs,
    encoder: QuadratureDecoderModel,
    encoder_out: QuadratureDecoderOutputs,
    /// The axis's own registers (everything but the sub-blocks).
    glue: AxisGlue,
    /// Limits, alarm, home and drive enable.
    io: AxisIoModel,
    /// The gearbox's steps merged with the interpolator's.
    merge: GearMergeModel,
}

/// The registers of an axis outside its sub-blocks: all 0 at power-up and
/// after reset (the sub-blocks take the reset themselves).
#[derive(Clone, Debug, Default)]
struct AxisGlue {
    config: u32,
    step_len: u32,
    step_space: u32,
    dir_setup: u32,
    dir_hold: u32,
    sample_rate: u32,
    popped: u32,
    popped_valid: bool,
    underrun_d: bool,
    tick_d: bool,
    integrand: u64,
    overrange_flag: bool,
    overflow_flag: bool,
    overrun_prev: bool,
    dda_overrange_prev: bool,
    uniform_overrange_prev: bool,
    uniform_overflow_prev: bool,
    saturated: bool,
    clear_position_pending: bool,
    forward: bool,
    forward_1: bool,
    forward_2: bool,
    uniform_active: bool,
    analog_active: bool,
    code_wide: bool,
    code_forward: bool,
    code_backward: bool,
    uniform_loaded_forward: bool,
    uniform_running_forward: bool,
    uniform_ready_prev: bool,
    uniform_pulse_prev: bool,
    request: bool,
    request_forward: bool,
    cmd_snapshot: u32,
    act_snapshot: u32,
    encoder_error_prev: bool,
    gear_lost_prev: bool,
}

/// The combinational values of an axis in one clock.
#[derive(Clone, Copy, Debug, Default)]
struct AxisComb {
    io: AxisIoComb,
    /// The gearbox's step for this axis in this clock: `Some(forward)`.
    gear: Option<bool>,
    low: bool,
    overflow_event: bool,
    fault_event: bool,
    encoder_error_event: bool,
    read_data: u32,
}

/// Whether bit `n` of `word` is set.
pub(super) fn bit_set(word: u32, n: u32) -> bool {
    word >> n & 1 != 0
}

/// `on` placed at bit `n` of a register word.
pub(super) fn flag(on: bool, n: u32) -> u32 {
    (on as u32) << n
}

/// The `width`-bit field at `lsb` of `word`.
pub(super) fn field_value(word: u32, lsb: u32, width: u32) -> u32 {
    (word >> lsb) & crate::blocks::width_mask(width) as u32
}

impl AxisModel {
    fn new(index: usize, fifo_log2: u32, config_mask: u32) -> Self {
        let mut fifo = CommandFifoModel::new(1 << fifo_log2);
        let fifo_out = fifo.step(true, false, 0, false, 0, false);
        let mut uniform = UniformPulseGenModel::with_width(super::PERIOD_BITS as u32);
        let uniform_out = uniform.step(UniformPulseGenInputs {
            reset: true,
            ..Default::default()
        });
        // Its power-up state, not its reset state: the stage takes its mode
        // in its first clock after power-up.
        let stage = StepOutputModel::new(super::TIMER_BITS, super::STAGE_PENDING_BITS as u32);
        let stage_out = stage.outputs(0);
        let mut position = PulseCounterModel::new(super::POSITION_BITS as u32);
        let position_out = position.step(PulseCounterInputs {
            reset: true,
            ..Default::default()
        });
        let dda = DdaIntegratorModel::new(super::PERIOD_BITS as u32);
        let encoder = QuadratureDecoderModel::new(super::POSITION_BITS as u32, 8, 16);
        Self {
            window: (AXIS_BASE + index as u32 * AXIS_STRIDE) >> AXIS_STRIDE_LOG2,
            config_mask,
            fifo,
            fifo_out,
            dda_out: dda.outputs(),
            dda,
            uniform,
            uniform_out,
            stage,
            stage_out,
            position,
            position_out,
            encoder_out: encoder.outputs(),
            encoder,
            glue: AxisGlue::default(),
            io: AxisIoModel::default(),
            merge: GearMergeModel::default(),
        }
    }

    /// The machine-I/O state of the axis.
    pub fn io(&self) -> &AxisIoModel {
        &self.io
    }

    /// Steps emitted by the output stage, net (the commanded position).
    pub fn commanded_position(&self) -> i32 {
        position_word(self.position_out.count) as i32
    }

    /// The encoder count (the actual position).
    pub fn actual_position(&self) -> i32 {
        position_word(self.encoder_out.count) as i32
    }

    /// Entries queued in the FIFO.
    pub fn fifo_level(&self) -> u64 {
        self.fifo_out.level
    }

    /// `AXIS_CONFIG` bit `n`.
    fn config_bit(&self, n: u32) -> bool {
        bit_set(self.glue.config, n)
    }

    /// `AXIS_CONFIG.STEP_MODE`.
    fn step_mode(&self) -> u32 {
        field_value(
            self.glue.config,
            fields::AXIS_STEP_MODE,
            fields::AXIS_STEP_MODE_WIDTH,
        )
    }

    /// The bus addresses this axis's motion-core half.
    fn selected(&self, address: u32) -> bool {
        address >> AXIS_STRIDE_LOG2 == self.window && address & 0x10 == 0
    }

    /// The bus addresses this axis's machine-I/O half.
    fn io_selected(&self, address: u32) -> bool {
        address >> AXIS_STRIDE_LOG2 == self.window && address & 0x10 != 0
    }

    /// The step the interpolator offers in this clock, and its direction
    /// (held with or without a step).
    fn interp(&self) -> (bool, bool) {
        if self.glue.uniform_active {
            (
                self.uniform_out.pulse && !self.glue.uniform_pulse_prev,
                self.uniform_forward(),
            )
        } else {
            (self.dda_out.pulse, self.glue.forward_2)
        }
    }

    /// The step offered to the request register in this clock (the
    /// interpolator's or the gearbox's `gear`), and its direction.
    fn candidate(&self, gear: Option<bool>) -> (bool, bool) {
        self.merge
            .candidate(self.interp(), gear, self.glue.analog_active)
    }

    /// The direction of the uniform generator's pulses in this clock: the
    /// loaded period's from the clock its first pulse comes (`ready` rises).
    fn uniform_forward(&self) -> bool {
        if self.uniform_out.ready && !self.glue.uniform_ready_prev {
            self.glue.uniform_loaded_forward
        } else {
            self.glue.uniform_running_forward
        }
    }

    /// The axis is analog in this run (`AXIS_CONFIG.ANALOG` at the start).
    pub fn analog(&self) -> bool {
        self.glue.analog_active
    }

    /// The analog code of the running period: the popped entry saturated
    /// to 16 bits signed, as 16 bits.
    pub fn dac_code(&self) -> u64 {
        let popped = self.glue.popped as i32;
        let code = if self.glue.code_wide {
            if popped < 0 {
                i16::MIN
            } else {
                i16::MAX
            }
        } else {
            popped as i16
        };
        code as u16 as u64
    }

    /// The running period's |entry|, saturated to 16 bits, and its sign,
    /// as the axis offers them to the soft limits.
    pub fn entry_steps(&self) -> (u16, bool) {
        (
            self.popped_magnitude().min(COUNT_MAX) as u16,
            self.glue.popped & (1 << 31) != 0,
        )
    }

    fn popped_magnitude(&self) -> u64 {
        (self.glue.popped as i32).unsigned_abs() as u64
    }

    fn too_large(&self) -> bool {
        self.popped_magnitude() > COUNT_MAX
    }

    /// Rises of the sub-blocks' sticky flags in this clock.
    fn rises(&self) -> (bool, bool, bool, bool) {
        (
            self.stage_out.overrun && !self.glue.overrun_prev,
            self.dda_out.overrange && !self.glue.dda_overrange_prev,
            self.uniform_out.overrange && !self.glue.uniform_overrange_prev,
            self.uniform_out.overflow && !self.glue.uniform_overflow_prev,
        )
    }

    fn busy(&self) -> bool {
        self.stage_out.busy || self.uniform_out.running
    }

    #[allow(clippy::too_many_arguments)]
    fn comb(
        &self,
        reset: bool,
        address: u32,
        write: bool,
        write_data: u32,
        pop: bool,
        low_water: u64,
        switches: AxisSwitches,
        gear: Option<bool>,
    ) -> AxisComb {
        let selected = self.selected(address);
        let offset = address & 0xf;
        let (pulse, pulse_forward) = self.candidate(gear);
        // An analog axis moves the way its code points.
        let pulse = pulse || self.glue.code_forward || self.glue.code_backward;
        let pulse_forward = if self.glue.analog_active {
            self.glue.code_forward
        } else {
            pulse_forward
        };
        let path = StepPath {
            pending_forward: self.stage_out.pending_forward,
            pending_backward: self.stage_out.pending_backward,
            request: self.glue.request,
            request_forward: self.glue.request_forward,
            pulse,
            pulse_forward,
        };
        let io_offset = address & (AXIS_STRIDE - 1);
        let io_command = (write && self.io_selected(address) && io_offset == axis::IO_COMMAND)
            .then_some(write_data);
        let io = self.io.comb(reset, &switches, &path, io_command);
        let fifo_write = write && selected && offset == axis::FIFO_WRITE;
        let low = self.fifo_out.level <= low_water;
        let io_read = if self.io_selected(address) {
            self.io.read(io_offset, &switches)
        } else {
            0
        };
        let read_data = io_read
            | if !selected {
                0
            } else {
                match offset {
                    axis::FIFO_STATUS => {
                        (self.fifo_out.level as u32) << fields::FIFO_LEVEL
                            | flag(self.fifo_out.empty, fields::FIFO_EMPTY)
                            | flag(self.fifo_out.full, fields::FIFO_FULL)
                            | flag(low, fields::FIFO_LOW)
                    }
                    axis::AXIS_CONFIG => self.glue.config,
                    axis::STEP_LEN => self.glue.step_len,
                    axis::STEP_SPACE => self.glue.step_space,
                    axis::DIR_SETUP => self.glue.dir_setup,
                    axis::DIR_HOLD => self.glue.dir_hold,
                    axis::ENC_SAMPLE_RATE => self.glue.sample_rate,
                    axis::CMD_POSITION => position_word(self.position_out.count),
                    axis::ACT_POSITION => position_word(self.encoder_out.count),
                    axis::CMD_SNAPSHOT => self.glue.cmd_snapshot,
                    axis::ACT_SNAPSHOT => self.glue.act_snapshot,
                    axis::AXIS_STATUS => {
                        flag(
                            self.stage_out.overrun || self.merge.lost(),
                            fields::STATUS_STEP_OVERRUN,
                        ) | flag(self.glue.overrange_flag, fields::STATUS_INTERP_OVERRANGE)
                            | flag(self.glue.overflow_flag, fields::STATUS_INTERP_OVERFLOW)
                            | flag(self.encoder_out.error, fields::STATUS_ENCODER_ERROR)
                            | flag(self.encoder_out.index_seen, fields::STATUS_INDEX_SEEN)
                            | flag(self.stage_out.busy, fields::STATUS_STEP_BUSY)
                            | flag(self.uniform_out.running, fields::STATUS_UNIFORM_RUNNING)
                            | flag(self.step_mode() == 3, fields::STATUS_STEP_MODE_INVALID)
                    }
                    axis::INDEX_POSITION => position_word(self.encoder_out.index_count),
                    _ => 0,
                }
            };
        AxisComb {
            io,
            low,
            overflow_event: fifo_write && self.fifo_out.full && !pop,
            fault_event: {
                let (a, b, c, d) = self.rises();
                a || b
                    || c
                    || d
                    || self.glue.saturated
                    || self.merge.lost() && !self.glue.gear_lost_prev
            },
            gear,
            encoder_error_event: self.encoder_out.error && !self.glue.encoder_error_prev,
            read_data,
        }
    }

    fn edge(
        &mut self,
        c: &AxisControl,
        (a, b, index): (bool, bool, bool),
        comb: &AxisComb,
        div_granted: bool,
    ) {
        let selected = self.selected(c.address);
        let offset = c.address & 0xf;
        let command = c.write && selected && offset == axis::AXIS_COMMAND;
        let command_bit = |n: u32| command && bit_set(c.write_data, n);
        let clear_faults = command_bit(fields::CMD_CLEAR_FAULTS);
        let mut next = self.clone();
        let timing = |word: u32| field_value(word, fields::VALUE, fields::STEP_TIMING_WIDTH);
        if c.write && selected {
            match offset {
                axis::AXIS_CONFIG => next.glue.config = c.write_data & self.config_mask,
                axis::STEP_LEN => next.glue.step_len = timing(c.write_data),
                axis::STEP_SPACE => next.glue.step_space = timing(c.write_data),
                axis::DIR_SETUP => next.glue.dir_setup = timing(c.write_data),
                axis::DIR_HOLD => next.glue.dir_hold = timing(c.write_data),
                axis::ENC_SAMPLE_RATE => {
                    next.glue.sample_rate =
                        field_value(c.write_data, fields::VALUE, fields::ENC_SAMPLE_RATE_WIDTH)
                }
                _ => {}
            }
        }
        // The entry popped at the last edge is taken now.
        next.glue.popped_valid = c.pop;
        next.glue.underrun_d = c.underrun;
        next.glue.tick_d = c.tick;
        if c.pop {
            next.glue.popped = self.fifo_out.head as u32;
            next.glue.code_wide = i16::try_from(self.fifo_out.head as u32 as i32).is_err();
        }
        let magnitude = self.popped_magnitude().min(COUNT_MAX);
        let popped_forward = self.glue.popped & (1 << 31) == 0;
        let (_, dda_rise, uniform_overrange_rise, uniform_overflow_rise) = self.rises();
        if clear_faults {
            next.glue.overrange_flag = false;
            next.glue.overflow_flag = false;
        }
        next.glue.saturated = self.glue.popped_valid
            && if self.glue.analog_active {
                self.glue.code_wide
            } else {
                self.too_large()
            };
        if self.glue.saturated || dda_rise || uniform_overrange_rise {
            next.glue.overrange_flag = true;
        }
        if uniform_overflow_rise {
            next.glue.overflow_flag = true;
        }
        next.glue.overrun_prev = self.stage_out.overrun;
        next.glue.gear_lost_prev = self.merge.lost();
        next.glue.dda_overrange_prev = self.dda_out.overrange;
        next.glue.uniform_overrange_prev = self.uniform_out.overrange;
        next.glue.uniform_overflow_prev = self.uniform_out.overflow;
        if c.start && !self.uniform_out.running {
            next.glue.uniform_active = self.config_bit(fields::AXIS_UNIFORM);
        }
        if c.start {
            next.glue.analog_active = self.config_bit(fields::AXIS_ANALOG);
        }
        if self.glue.popped_valid {
            next.glue.forward = popped_forward;
            let stepless = self.glue.uniform_active || self.glue.analog_active;
            next.glue.integrand = if stepless { 0 } else { magnitude };
            if self.glue.analog_active {
                let code = self.dac_code() as u16 as i16;
                next.glue.code_forward = code > 0;
                next.glue.code_backward = code < 0;
            }
        }
        if self.glue.underrun_d || c.halt {
            next.glue.integrand = 0;
            next.glue.code_forward = false;
            next.glue.code_backward = false;
        }
        next.glue.forward_1 = self.glue.forward;
        next.glue.forward_2 = self.glue.forward_1;

        next.fifo_out = next.fifo.step(
            c.reset || c.flush,
            c.write && selected && offset == axis::FIFO_WRITE,
            c.write_data as u64,
            c.pop,
            c.low_water,
            false,
        );
        next.dda_out = next.dda.step(DdaIntegratorInputs {
            reset: c.reset || c.halt,
            tick: self.glue.tick_d,
            integrand: self.glue.integrand,
            modulus: c.modulus,
            clear_overrange: clear_faults,
        });
        next.uniform_out = next.uniform.step_with_divider(
            UniformPulseGenInputs {
                reset: c.reset || c.halt,
                tick: self.glue.tick_d,
                period: c.period_active,
                count: magnitude,
                mode: self.config_bit(fields::AXIS_INTERLEAVED),
                load: self.glue.popped_valid
                    && self.glue.uniform_active
                    && !self.glue.analog_active,
                clear_flags: clear_faults || c.start,
            },
            div_granted,
        );
        if self.glue.popped_valid
            && self.glue.uniform_active
            && !self.glue.analog_active
            && self.uniform_out.ready
        {
            next.glue.uniform_loaded_forward = popped_forward;
        }
        next.glue.uniform_ready_prev = self.uniform_out.ready;
        next.glue.uniform_pulse_prev = self.uniform_out.pulse;
        next.glue.uniform_running_forward = self.uniform_forward();
        // An abort or a blocked direction keeps the offered step out.
        let (candidate, candidate_forward) = self.candidate(comb.gear);
        let (interp, interp_forward) = self.interp();
        next.merge.edge(
            interp.then_some(interp_forward),
            comb.gear,
            self.glue.analog_active,
            c.abort,
            clear_faults,
            c.reset,
        );
        let blocked = if candidate_forward {
            comb.io.block_forward
        } else {
            comb.io.block_backward
        };
        next.glue.request = candidate && !c.abort && !blocked;
        next.glue.request_forward = candidate_forward;
        let (step, dir) = (self.glue.request, self.glue.request_forward);
        next.stage_out = next.stage.step(StepOutputInputs {
            reset: c.reset,
            step,
            dir,
            mode: self.step_mode() as u8,
            step_len: self.glue.step_len as u64,
            step_space: self.glue.step_space as u64,
            dir_setup: self.glue.dir_setup as u64,
            dir_hold: self.glue.dir_hold as u64,
            clear_overrun: clear_faults,
            flush: c.abort || comb.io.cut(),
        });
        // CLEAR_POSITION waits for a clock without a counted step.
        let clear_position =
            command_bit(fields::CMD_CLEAR_POSITION) || self.glue.clear_position_pending;
        next.glue.clear_position_pending = clear_position && self.stage_out.emitted;
        next.position_out = next.position.step(PulseCounterInputs {
            reset: c.reset,
            up: self.stage_out.emitted && self.stage_out.emitted_forward,
            down: self.stage_out.emitted && !self.stage_out.emitted_forward,
            clear: clear_position && !self.stage_out.emitted,
            load: false,
            load_value: 0,
            compare_value: 0,
        });
        next.encoder_out = next.encoder.step(QuadratureDecoderInputs {
            reset: c.reset,
            a,
            b,
            index,
            filter: field_value(
                self.glue.config,
                fields::AXIS_ENC_FILTER,
                fields::AXIS_ENC_FILTER_WIDTH,
            ) as u8,
            clear: command_bit(fields::CMD_CLEAR_ENCODER),
            sample_rate: self.glue.sample_rate as u64,
            counter_mode: self.config_bit(fields::AXIS_ENC_COUNTER_MODE),
            index_invert: self.config_bit(fields::AXIS_INDEX_INVERT),
            index_clear: self.config_bit(fields::AXIS_INDEX_CLEAR),
            index_latch: self.config_bit(fields::AXIS_INDEX_LATCH),
            index_once: self.config_bit(fields::AXIS_INDEX_ONCE),
            index_rearm: command_bit(fields::CMD_REARM_INDEX),
            clear_error: command_bit(fields::CMD_CLEAR_ENCODER_ERROR),
        });
        if c.snapshot {
            next.glue.cmd_snapshot = position_word(self.position_out.count);
            next.glue.act_snapshot = position_word(self.encoder_out.count);
        }
        next.glue.encoder_error_prev = self.encoder_out.error;
        let io_offset = c.address & (AXIS_STRIDE - 1);
        let io_write =
            (c.write && self.io_selected(c.address)).then_some((io_offset, c.write_data));
        next.io.edge(
            c.reset,
            io_write,
            &comb.io,
            (
                position_word(self.position_out.count),
                position_word(self.encoder_out.count),
            ),
            c.drive_allowed,
            c.probe_latch,
        );
        if c.reset {
            next.glue = AxisGlue::default();
        }
        *self = next;
    }
}

/// Plain-Rust, cycle-exact model of a `motion_controller` with `axes` axes,
/// FIFOs of 2^`fifo_log2` entries, and uniform pulse generators or not
/// (the RTL's `UNIFORM`).
#[derive(Clone, Debug)]
pub struct MotionControllerModel {
    fifo_log2: u32,
    config_value: u32,
    axes: Vec<AxisModel>,
    tick_divider: FreqDividerModel,
    tick: bool,
    watchdog: WatchdogModel,
    watchdog_out: (bool, bool),
    interrupts: InterruptControllerModel,
    status: u64,
    irq: bool,
    run: bool,
    irq_enable: u32,
    tick_divisor: u32,
    period_ticks: u32,
    low_water: u32,
    watchdog_timeout: u32,
    ticks_left: u32,
    boundary_next: bool,
    in_period: bool,
    period_active: u32,
    modulus: u32,
    period_count: u32,
    read_data: u32,
    /// Inverted like the RTL's: reset counts as "already low".
    any_low_prev_n: bool,
    expired_prev: bool,
    io: MachineIoModel,
    probe: ProbeModel,
    feed_hold: FeedHoldModel,
    /// The soft limits (`SOFT_LIMITS`; without them never stepped).
    soft: SoftLimitsModel,
    has_soft: bool,
    /// The soft limits' `event` output (registered in the block).
    soft_event: bool,
    held_prev: bool,
    /// The gated tick, registered: the periods and the axes see it.
    motion_tick: bool,
    /// Bit j: a motion tick while running j + 1 clocks ago (`TICK_TRAIL` bits).
    tick_trail: u32,
    /// The build has the probe latch (`PROBE`): without it the trigger's
    /// latch, event and read data are unused.
    has_probe: bool,
    abort_hold: bool,
    stop_cause: u32,
    /// The uniform generators' shared period planner: only its timing matters
    /// here (each axis's plan computes its own quotient).
    divider: SequentialDividerModel,
    /// The build has the analog outputs (`ANALOG`).
    analog: bool,
    dac: DacModel,
    dac_out: DacOutputs,
    /// The walk loading the axes' codes into the DAC.
    walk: AnalogWalkModel,
    /// The last read addressed a DAC register.
    dac_read_sel: bool,
    /// The controller's and the DAC's address of each forwarded register.
    dac_addresses: Vec<(u32, u64)>,
    /// The spindle encoder and the gearbox (`SPINDLE`; without it never
    /// written, its steps and event unused).
    spindle: SpindleModel,
    has_spindle: bool,
    /// The laser FIFO and PWM (`LASER`; without it never written, its pin
    /// and readiness unused).
    laser: LaserUnitModel,
    has_laser: bool,
}

impl MotionControllerModel {
    /// A controller in its power-up state, with the options `build` (see
    /// the controller's "Build options"). Fails like
    /// [`registers::register_map`] for an unsupported axis count.
    pub fn new(
        axes: usize,
        fifo_log2: u32,
        build: registers::BuildOptions,
    ) -> Result<Self, crate::regmap::RegMapError> {
        let map = registers::register_map(axes, fifo_log2, build)?;
        let registers::BuildOptions {
            analog,
            probe,
            soft_limits,
            spindle,
            laser,
            ..
        } = build;
        let dac_map =
            crate::blocks::dac_interface::registers::register_map(axes, registers::DAC_BITS)?;
        let mut dac_addresses = Vec::new();
        for (_, address, name) in registers::DAC_GLOBAL {
            dac_addresses.push((address, dac_map.register(name)?.address as u64));
        }
        for k in 0..axes as u32 {
            dac_addresses.push((
                AXIS_BASE + k * AXIS_STRIDE + axis::DAC_APPLIED,
                dac_map.address_of("APPLIED", k)? as u64,
            ));
        }
        let dac = DacModel::power_up(axes, registers::DAC_BITS);
        let dac_out = dac.outputs();
        let config_value = map.register("CONFIG")?.reset_value();
        let config_mask = map.register("AXIS_CONFIG")?.rw_mask();
        Ok(Self {
            fifo_log2,
            config_value,
            axes: (0..axes)
                .map(|i| AxisModel::new(i, fifo_log2, config_mask))
                .collect(),
            tick_divider: FreqDividerModel::new(32),
            tick: false,
            watchdog: WatchdogModel::new(),
            watchdog_out: (false, false),
            interrupts: InterruptControllerModel::new(),
            status: 0,
            irq: false,
            run: false,
            irq_enable: 0,
            tick_divisor: 0,
            period_ticks: 0,
            low_water: 0,
            watchdog_timeout: 0,
            ticks_left: 0,
            boundary_next: false,
            in_period: false,
            period_active: 0,
            modulus: 0,
            period_count: 0,
            read_data: 0,
            any_low_prev_n: false,
            expired_prev: false,
            io: MachineIoModel::new(axes),
            probe: ProbeModel::default(),
            feed_hold: FeedHoldModel::default(),
            soft: SoftLimitsModel::new(axes),
            has_soft: soft_limits,
            soft_event: false,
            held_prev: false,
            motion_tick: false,
            tick_trail: 0,
            has_probe: probe,
            abort_hold: false,
            stop_cause: 0,
            divider: SequentialDividerModel::new(
                super::PERIOD_BITS as u32,
                super::PERIOD_BITS as u32,
            ),
            analog,
            dac,
            dac_out,
            walk: AnalogWalkModel::default(),
            dac_read_sel: false,
            dac_addresses,
            spindle: SpindleModel::new(axes),
            has_spindle: spindle,
            laser: LaserUnitModel::new(
                fifo_log2,
                map.register("LASER_CONTROL").map_or(0, |r| r.rw_mask()),
            ),
            has_laser: laser,
        })
    }

    /// The shared planner at one edge: the lowest-numbered axis whose
    /// uniform generator waits for its division gets it, if it is idle.
    /// `axes` is the state before the edge; a reset (or halt) idles it.
    fn divider_edge(&mut self, reset: bool, axes: &[AxisModel]) -> Option<usize> {
        let divider = self.divider.outputs();
        let grant = if divider.busy || divider.done {
            None
        } else {
            axes.iter().position(|axis| axis.uniform.wants_division())
        };
        self.divider.step(SequentialDividerInputs {
            reset,
            start: grant.is_some(),
            ..Default::default()
        });
        grant
    }

    /// `STOP_CAUSE.CAUSE`: why RUN last fell.
    pub fn stop_cause(&self) -> StopCause {
        StopCause::from_code(field_value(
            self.stop_cause,
            fields::STOP_CAUSE_CAUSE,
            fields::STOP_CAUSE_WIDTH,
        ))
    }

    /// The axes, for positions and FIFO levels.
    pub fn axes(&self) -> &[AxisModel] {
        &self.axes
    }

    /// Periods are running.
    pub fn running(&self) -> bool {
        self.run
    }

    /// The feed hold: its request and ramp.
    pub fn feed_hold(&self) -> &FeedHoldModel {
        &self.feed_hold
    }

    /// The laser unit (its state is meaningful in a `LASER` build).
    pub fn laser(&self) -> &LaserUnitModel {
        &self.laser
    }

    /// The spindle unit (its state is meaningful in a `SPINDLE` build).
    pub fn spindle(&self) -> &SpindleModel {
        &self.spindle
    }

    fn outputs(&self) -> ControllerOutputs {
        let k = self.axes.len() as u32;
        let dac = if self.analog {
            DacPins {
                data: self.dac_out.dac_data,
                cs_n: self.dac_out.dac_cs_n,
                l1_n: self.dac_out.dac_l1_n,
                ldac: self.dac_out.dac_ldac,
            }
        } else {
            DacPins {
                data: 0,
                cs_n: crate::blocks::width_mask(k),
                l1_n: true,
                ldac: false,
            }
        };
        ControllerOutputs {
            dac,
            read_data: if self.dac_read_sel {
                self.dac_out.bus_read_data as u32
            } else {
                self.read_data
            },
            irq: self.irq,
            running: self.run,
            active: self.run || self.axes.iter().any(AxisModel::busy) || self.tick_trail != 0,
            steps: self
                .axes
                .iter()
                .map(|a| (a.stage_out.out_a, a.stage_out.out_b))
                .collect(),
            drive_enable: self
                .axes
                .iter()
                .enumerate()
                .fold(0, |w, (k, a)| w | (a.io.drive_enable() as u32) << k),
            gpio_out: self.io.gpio_out(),
            laser: self.has_laser && self.laser.pwm(),
        }
    }

    fn global_read(&self, address: u32, io: &super::io_model::MachineIoComb) -> u32 {
        let (expired, armed) = self.watchdog_out;
        match address {
            global::ID => ID_VALUE,
            global::VERSION => VERSION_VALUE,
            global::CONFIG => self.config_value,
            global::CONTROL => flag(self.run, fields::CONTROL_RUN),
            global::STATUS => self.status as u32,
            global::IRQ_ENABLE => self.irq_enable,
            global::TICK_DIVISOR => self.tick_divisor,
            global::PERIOD_TICKS => self.period_ticks,
            global::FIFO_LOW_WATER => self.low_water,
            global::WATCHDOG_TIMEOUT => self.watchdog_timeout,
            global::STATE => {
                flag(self.run, fields::STATE_RUNNING)
                    | flag(armed, fields::STATE_WATCHDOG_ARMED)
                    | flag(expired, fields::STATE_WATCHDOG_EXPIRED)
                    | flag(io.estop_active, fields::STATE_ESTOP_INPUT)
                    | flag(io.estop_latched, fields::STATE_ESTOP_LATCHED)
                    | flag(self.abort_hold || expired, fields::STATE_ABORTED)
                    | flag(io.ready, fields::STATE_INPUTS_READY)
                    | flag(self.feed_hold.holding(), fields::STATE_HOLDING)
                    | flag(self.feed_hold.held(), fields::STATE_HELD)
            }
            global::PERIOD_COUNT => self.period_count,
            global::STOP_CAUSE => self.stop_cause,
            _ => io.read_data,
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: &ControllerInputs) -> ControllerOutputs {
        assert_eq!(
            i.encoders.len(),
            self.axes.len(),
            "one encoder input per axis"
        );
        let level_mask = (1u32 << (self.fifo_log2 + 1)) - 1;
        let address = i.address & 0xff;
        let write = |a: u32| i.write && address == a;
        let (expired, _) = self.watchdog_out;

        // Combinational phase.
        let status_write = write(global::STATUS).then_some(i.write_data);
        let status_bit = |n: u32| status_write.is_some_and(|d| d >> n & 1 != 0);
        let io = self.io.comb(i.reset, address, status_bit(irq::ESTOP));
        let bus_write = i.write.then_some((address, i.write_data));
        let probe = match self.has_probe {
            true => self.probe.comb(address, bus_write),
            false => ProbeComb::default(),
        };
        let soft_stop = self.has_soft && self.soft.stop();
        let hold = self
            .feed_hold
            .comb(address, bus_write, probe.stop || soft_stop, self.tick);
        // The periods and the axes run on the gated tick, registered.
        let tick = self.motion_tick;
        let drive_allowed = !io.estop_latched_next && !expired;
        let any_limit_held = self.axes.iter().any(|a| a.io.limit_held());
        let any_alarm_held = self.axes.iter().any(|a| a.io.alarm_held());
        let any_home_held = self.axes.iter().any(|a| a.io.home_held());
        let abort = self.abort_hold || expired;
        let refuse_run = self.run
            || expired
            || io.estop_active
            || io.estop_latched
            || any_limit_held
            || any_alarm_held
            || any_home_held
            || !io.ready;
        let write_control = write(global::CONTROL);
        let run_written = bit_set(i.write_data, fields::CONTROL_RUN);
        let start = write_control && run_written && !refuse_run;
        let halt = (write_control && !run_written) || abort;
        let boundary = self.run && tick && self.boundary_next;
        let all_ready =
            self.axes.iter().all(|a| !a.fifo_out.empty) && (!self.has_laser || self.laser.ready());
        let pop = boundary && all_ready && !halt;
        let underrun = boundary && !all_ready && !halt;
        let period_next = self.period_ticks.max(1);
        let gear_step = self.spindle.step_out().filter(|_| self.has_spindle);
        let combs: Vec<AxisComb> = self
            .axes
            .iter()
            .zip(&io.switches)
            .enumerate()
            .map(|(k, (a, s))| {
                a.comb(
                    i.reset,
                    address,
                    i.write,
                    i.write_data,
                    pop,
                    self.low_water as u64,
                    *s,
                    gear_step.filter(|(axis, _)| *axis == k).map(|(_, f)| f),
                )
            })
            .collect();
        let any_low = combs.iter().any(|c| c.low);
        let mut events = 0u64;
        let mut set = |bit: u32, on: bool| events |= (on as u64) << bit;
        set(irq::PERIOD_DONE, pop && self.in_period);
        set(irq::FIFO_LOW, any_low && self.any_low_prev_n);
        set(irq::UNDERRUN, underrun);
        set(irq::OVERFLOW, combs.iter().any(|c| c.overflow_event));
        set(
            irq::ENCODER_ERROR,
            combs.iter().any(|c| c.encoder_error_event),
        );
        set(irq::WATCHDOG, expired && !self.expired_prev);
        set(irq::AXIS_FAULT, combs.iter().any(|c| c.fault_event));
        set(irq::LIMIT, combs.iter().any(|c| c.io.limit_event));
        set(irq::ALARM, combs.iter().any(|c| c.io.alarm_event));
        set(irq::ESTOP, io.estop_event);
        set(irq::HOME, combs.iter().any(|c| c.io.home_event));
        set(irq::GPIO, io.gpio_event);
        set(irq::PROBE, probe.latch);
        set(irq::HELD, self.feed_hold.held() && !self.held_prev);
        set(irq::SOFT_LIMIT, self.has_soft && self.soft_event);
        set(irq::SPINDLE, self.has_spindle && self.spindle.event());
        let spindle_read = match self.has_spindle {
            true => self.spindle.read(address),
            false => 0,
        };
        let laser_read = match self.has_laser {
            true => self.laser.read(address),
            false => 0,
        };
        let soft_read = match self.has_soft {
            true => self.soft.read(address, i.write),
            false => 0,
        };
        let read_word = combs.iter().fold(
            self.global_read(address, &io)
                | probe.read_data
                | hold.read_data
                | soft_read
                | spindle_read
                | laser_read,
            |w, c| w | c.read_data,
        );
        // STOP_CAUSE: the highest of this clock's causes, with the lowest
        // axis that holds it.
        let lowest = |held: fn(&AxisIoModel) -> bool| {
            self.axes.iter().position(|a| held(&a.io)).unwrap_or(0) as u32
        };
        let cause_now = if self.abort_hold && io.estop_latched {
            (StopCause::Estop, 0)
        } else if self.abort_hold && any_alarm_held {
            (StopCause::DriveAlarm, lowest(AxisIoModel::alarm_held))
        } else if self.abort_hold && any_limit_held {
            (StopCause::Limit, lowest(AxisIoModel::limit_held))
        } else if self.abort_hold && any_home_held {
            (StopCause::Home, lowest(AxisIoModel::home_held))
        } else if expired {
            (StopCause::Watchdog, 0)
        } else if underrun {
            (StopCause::Underrun, 0)
        } else {
            (StopCause::Stop, 0)
        };

        // Edge.
        let mut next = self.clone();
        if i.write {
            match address {
                global::IRQ_ENABLE => next.irq_enable = i.write_data & ((1 << irq::COUNT) - 1),
                global::TICK_DIVISOR => next.tick_divisor = i.write_data,
                global::PERIOD_TICKS => next.period_ticks = i.write_data & COUNT_MAX as u32,
                global::FIFO_LOW_WATER => next.low_water = i.write_data & level_mask,
                global::WATCHDOG_TIMEOUT => next.watchdog_timeout = i.write_data,
                _ => {}
            }
        }
        next.tick = next.tick_divider.step(FreqDividerInputs {
            reset: i.reset,
            enable: true,
            divisor: self.tick_divisor as u64,
        });
        next.watchdog_out = next.watchdog.step(
            i.reset,
            self.tick,
            self.watchdog_timeout as u64,
            write(global::WATCHDOG_KICK),
            status_bit(irq::WATCHDOG),
        );
        if start {
            next.run = true;
            next.boundary_next = true;
            next.in_period = false;
        }
        if self.run && tick {
            if self.boundary_next {
                next.ticks_left = period_next;
                next.boundary_next = self.period_ticks <= 1;
                next.period_active = period_next;
            } else {
                next.ticks_left = self.ticks_left.wrapping_sub(1);
                next.boundary_next = self.ticks_left == 2;
            }
        }
        next.modulus = self.period_active;
        if pop {
            next.in_period = true;
            next.period_count = self.period_count.wrapping_add(1);
        }
        if underrun || halt {
            next.run = false;
            next.in_period = false;
        }
        if self.run && (underrun || halt) {
            next.stop_cause = (cause_now.0 as u32) << fields::STOP_CAUSE_CAUSE
                | cause_now.1 << fields::STOP_CAUSE_AXIS;
        }
        next.abort_hold = io.estop_latched || any_limit_held || any_alarm_held || any_home_held;
        next.io.edge(i.reset, &i.pins, bus_write, &io, expired);
        next.probe.edge(
            i.reset,
            i.pins.probe,
            bus_write,
            &probe,
            self.io.filter_inputs(),
        );
        next.feed_hold.edge(
            i.reset,
            i.pins.feed_hold,
            bus_write,
            &hold,
            self.io.filter_inputs(),
            self.tick,
        );
        next.held_prev = self.feed_hold.held();
        next.spindle.edge(SpindleInputs {
            reset: i.reset,
            pins: i.spindle,
            address,
            write: i.write && self.has_spindle,
            write_data: i.write_data,
            abort,
        });
        // The laser: the plane's axes' running |entry| (an analog axis or
        // one beyond K counts as standing).
        let (axis_a, axis_b) = self.laser.axes();
        let count = |k: u32| {
            self.axes
                .get(k as usize)
                .filter(|a| !a.analog())
                .map_or(0, |a| a.entry_steps().0 as u64)
        };
        // AXIS_B equal to AXIS_A: a plane of one axis.
        let count_b = if axis_b == axis_a { 0 } else { count(axis_b) };
        next.laser.edge(&LaserUnitInputs {
            reset: i.reset,
            address,
            write: i.write && self.has_laser,
            write_data: i.write_data,
            start,
            pop,
            stop: underrun || halt,
            flush: write_control && bit_set(i.write_data, fields::CONTROL_FLUSH),
            running: self.run,
            kill: abort || self.feed_hold.held(),
            factor: self.feed_hold.ramp().factor() as u64,
            counts: (count(axis_a), count_b),
        });
        let picked = &self.axes[self.soft.select()];
        let (magnitude, negative) = picked.entry_steps();
        let soft_out = next.soft.step(&SoftLimitsInputs {
            reset: i.reset,
            address,
            write: i.write && self.has_soft,
            write_data: i.write_data,
            running: self.run,
            rate: self.feed_hold.rate(),
            period: self.period_ticks as u16,
            position: picked.position_out.count as u32,
            magnitude,
            negative,
            step_axis: !picked.analog(),
            read: i.read && self.has_soft,
        });
        next.soft_event = soft_out.tripped;
        next.motion_tick = hold.tick && !i.reset;
        next.tick_trail = (self.tick_trail << 1 | (self.motion_tick && self.run) as u32)
            & crate::blocks::width_mask(super::TICK_TRAIL as u32) as u32;
        let control = AxisControl {
            reset: i.reset,
            tick,
            start,
            halt,
            flush: write_control && bit_set(i.write_data, fields::CONTROL_FLUSH),
            pop,
            underrun,
            period_active: self.period_active as u64,
            modulus: self.modulus as u64,
            snapshot: write(global::SNAPSHOT),
            low_water: self.low_water as u64,
            address,
            write: i.write,
            write_data: i.write_data,
            abort,
            drive_allowed,
            probe_latch: probe.latch,
        };
        // Analog outputs: after each pop a walk loads the analog axes' codes
        // one a clock, then one update; when RUN falls (not by an abort)
        // every analog channel gets 0.
        let analog_axes = self
            .axes
            .iter()
            .enumerate()
            .fold(0u64, |w, (k, a)| w | (a.analog() as u64) << k);
        let code = self
            .walk
            .walked_axis()
            .map_or(0, |k| self.axes[k].dac_code() as u16 as i16);
        let walk = next.walk.step(&WalkInputs {
            reset: i.reset,
            pop,
            stop_zero: self.analog && self.run && (underrun || halt) && !abort,
            abort,
            running: self.run,
            factor: self.feed_hold.ramp().factor(),
            analog_axes,
            has_analog: self.analog,
            dac_busy: self.dac_out.busy,
            axes: self.axes.len(),
            code,
        });
        let dac_target = self
            .dac_addresses
            .iter()
            .find(|(a, _)| *a == address)
            .filter(|_| self.analog)
            .map(|(_, d)| *d);
        next.dac_out = next.dac.step(DacInputs {
            reset: i.reset,
            bus_address: dac_target.unwrap_or(0),
            bus_write_data: i.write_data as u64,
            bus_write: i.write && dac_target.is_some(),
            bus_read: i.read && dac_target.is_some(),
            update: walk.update,
            force_safe: abort,
            load: walk.load,
            load_code: walk.load_code,
        });
        if i.read {
            next.dac_read_sel = dac_target.is_some();
        }
        let grant = next.divider_edge(i.reset || halt, &self.axes);
        for (k, ((axis, pins), comb)) in next
            .axes
            .iter_mut()
            .zip(&i.encoders)
            .zip(&combs)
            .enumerate()
        {
            axis.edge(&control, *pins, comb, grant == Some(k));
        }
        next.any_low_prev_n = !any_low;
        next.expired_prev = expired;
        let clear = status_write.map(|d| (d & ((1 << irq::COUNT) - 1)) as u64);
        (next.status, next.irq) =
            next.interrupts
                .step(i.reset, events, clear, self.irq_enable as u64);
        if i.read {
            next.read_data = read_word;
        }
        if i.reset {
            next.tick_trail = 0;
            next.run = false;
            next.irq_enable = 0;
            next.tick_divisor = 0;
            next.period_ticks = 0;
            next.low_water = 0;
            next.watchdog_timeout = 0;
            next.ticks_left = 0;
            next.boundary_next = false;
            next.in_period = false;
            next.period_active = 0;
            next.modulus = 0;
            next.period_count = 0;
            next.read_data = 0;
            next.any_low_prev_n = false;
            next.expired_prev = false;
            next.held_prev = false;
            next.abort_hold = false;
            next.stop_cause = 0;
            next.dac_read_sel = false;
        }
        *self = next;
        self.outputs()
    }
}

impl crate::sim::LockstepModel for MotionControllerModel {
    type Inputs = ControllerInputs;
    type Outputs = ControllerOutputs;
    fn input_vector(inputs: &ControllerInputs, vector: &mut Vec<u64>) {
        inputs.write_vector(vector);
    }
    fn read_outputs(&self, vector: &[u64]) -> ControllerOutputs {
        ControllerOutputs::from_vector(vector, self.axes.len())
    }
    fn expected(&mut self, inputs: &ControllerInputs) -> ControllerOutputs {
        self.step(inputs)
    }
}
