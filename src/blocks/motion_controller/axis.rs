//! One axis of the motion controller: its command FIFO, both fine
//! interpolators, the step output stage, the commanded-position counter,
//! the quadrature decoder and the axis's register window.
//!
//! Internal to [`super::MotionController`]; its behavior is specified there
//! and modelled by [`super::model::AxisModel`].
//!
//! Formal proof: `formal/motion_controller_axis.sv` (the requests let into
//! the output stage, its flush on an abort or a limit cut, and no pin step
//! after an abort; see the controller's datasheet, "Formal proof").

use rust_hdl::prelude::*;

use super::axis_io::AxisIo;
use super::gear_merge::GearMerge;
use super::registers::{fields, AXIS_BASE, AXIS_STRIDE, AXIS_STRIDE_LOG2, DAC_BITS};
use super::{ERROR_BITS, PERIOD_BITS, POSITION_BITS, STAGE_PENDING_BITS};
use crate::blocks::command_fifo::CommandFifo;
use crate::blocks::pulse_counter::PulseCounter;
use crate::blocks::quadrature_decoder::QuadratureDecoder;
use crate::blocks::step_output::StepOutput;
use crate::blocks::uniform_pulse_gen::UniformPulseCore;

use super::axis_registers::{AxisRegisters, WRITE_BITS};
use super::entry::{ENTRY_BITS, ENTRY_CODE_WIDE, ENTRY_NONZERO, ENTRY_SIGN, ENTRY_TOO_LARGE};

// `update()` reads the entry's flags at literal bits, and its bits 15..0
// as both the count and the DAC magnitude.
const _: () = {
    assert!(ENTRY_TOO_LARGE == 16 && ENTRY_SIGN == 17);
    assert!(ENTRY_CODE_WIDE == 18 && ENTRY_NONZERO == 19);
    assert!(PERIOD_BITS == 16 && DAC_BITS == 16);
};

/// One controller axis with a FIFO of 2^N entries (`NP1` = N + 1).
#[derive(LogicBlock)]
pub struct MotionAxis<const N: usize, const NP1: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Base tick.
    pub tick: Signal<In, Bit>,
    /// RUN was accepted: reset the DDA, latch the interpolator choice,
    /// clear the uniform generator's flags.
    pub start: Signal<In, Bit>,
    /// Stop at once (RUN written 0, or the watchdog).
    pub halt: Signal<In, Bit>,
    /// Period boundary with every FIFO non-empty: pop and load.
    pub pop: Signal<In, Bit>,
    /// Period boundary with some FIFO empty: stop loading.
    pub underrun: Signal<In, Bit>,
    /// The running period's length (the uniform generator's T; updated at
    /// each boundary).
    pub period_active: Signal<In, Bits<PERIOD_BITS>>,
    /// -`period_active` one clock late: the DDA's -M, in step with its
    /// delayed tick and its J.
    pub modulus_negated: Signal<In, Bits<ERROR_BITS>>,
    /// Latch both positions into the snapshot registers.
    pub snapshot: Signal<In, Bit>,
    /// FIFO low-water threshold.
    pub low_water: Signal<In, Bits<NP1>>,
    /// Register bus: word address, write strobe and data.
    pub address: Signal<In, Bits<8>>,
    /// Register bus write strobe.
    pub write: Signal<In, Bit>,
    /// Register bus write data.
    pub write_data: Signal<In, Bits<32>>,
    /// `write_data` as a FIFO entry (see [`ENTRY_BITS`]).
    pub fifo_entry: Signal<In, Bits<ENTRY_BITS>>,
    /// The addressed register of this axis's window, 0 outside it.
    pub read_data: Signal<Out, Bits<32>>,
    /// Encoder channel A (asynchronous).
    pub enc_a: Signal<In, Bit>,
    /// Encoder channel B (asynchronous).
    pub enc_b: Signal<In, Bit>,
    /// Encoder index (asynchronous).
    pub enc_index: Signal<In, Bit>,
    /// Step output A.
    pub out_a: Signal<Out, Bit>,
    /// Step output B.
    pub out_b: Signal<Out, Bit>,
    /// The FIFO is empty.
    pub empty: Signal<Out, Bit>,
    /// The FIFO is at or below the low-water level.
    pub low: Signal<Out, Bit>,
    /// A FIFO write was refused at this edge.
    pub overflow_event: Signal<Out, Bit>,
    /// An axis fault flag rose.
    pub fault_event: Signal<Out, Bit>,
    /// The encoder error flag rose.
    pub encoder_error_event: Signal<Out, Bit>,
    /// Steps are still leaving: the output stage is busy or a uniform
    /// period is running.
    pub busy: Signal<Out, Bit>,
    /// Empty the FIFO.
    pub flush: Signal<In, Bit>,
    /// Abort: no new step request, the output stage flushed (a pulse
    /// already high completes).
    pub abort: Signal<In, Bit>,
    /// limit_pos of this axis, filtered, 1 = active.
    pub limit_forward: Signal<In, Bit>,
    /// limit_neg of this axis, filtered, 1 = active.
    pub limit_backward: Signal<In, Bit>,
    /// home of this axis, filtered, 1 = active.
    pub home: Signal<In, Bit>,
    /// home became active at the last edge.
    pub home_rise: Signal<In, Bit>,
    /// The probe trips in this clock: latch both positions.
    pub probe_latch: Signal<In, Bit>,
    /// drive_alarm of this axis, filtered, 1 = active.
    pub alarm: Signal<In, Bit>,
    /// No E-stop latched from the next edge on, no watchdog expiry.
    pub drive_allowed: Signal<In, Bit>,
    /// drive_enable pin of this axis.
    pub drive_enable: Signal<Out, Bit>,
    /// A limit trip is held.
    pub limit_held: Signal<Out, Bit>,
    /// A drive alarm trip is held.
    pub alarm_held: Signal<Out, Bit>,
    /// A stop on home is held.
    pub home_held: Signal<Out, Bit>,
    /// A limit trip flag rose.
    pub limit_event: Signal<Out, Bit>,
    /// The alarm trip flag rose.
    pub alarm_event: Signal<Out, Bit>,
    /// HOME_SEEN rose.
    pub home_event: Signal<Out, Bit>,
    /// The uniform generator's planning port, answered by the controller's
    /// shared planner: see [`UniformPulseCore`].
    pub div_request: Signal<Out, Bit>,
    /// T/2 to divide.
    pub div_dividend: Signal<Out, Bits<PERIOD_BITS>>,
    /// N to divide by.
    pub div_divisor: Signal<Out, Bits<PERIOD_BITS>>,
    /// This axis's division is done.
    pub div_done: Signal<In, Bit>,
    /// The shared plan's Tp1 / 2.
    pub div_half: Signal<In, Bits<PERIOD_BITS>>,
    /// The shared plan's N2.
    pub div_long_pulses: Signal<In, Bits<PERIOD_BITS>>,
    /// The shared plan's -N1.
    pub div_short_negated: Signal<In, Bits<PERIOD_BITS>>,
    /// The shared plan's half is one tick.
    pub div_half_is_one: Signal<In, Bit>,
    /// The shared plan has pulses.
    pub div_has_pulses: Signal<In, Bit>,
    /// The shared plan clamped N.
    pub div_clamped: Signal<In, Bit>,
    /// The axis is an analog axis in this run (`AXIS_CONFIG.ANALOG`,
    /// latched at the start; always 0 in a build without the DAC).
    pub analog: Signal<Out, Bit>,
    /// The magnitude of the running period's entry (valid from the clock
    /// after the pop): the controller turns it into the analog code with
    /// `code_negative` and saturates it with `code_out_of_range`, once for
    /// all axes.
    pub dac_code: Signal<Out, Bits<DAC_BITS>>,
    /// The popped entry does not fit 16 bits signed.
    pub code_out_of_range: Signal<Out, Bit>,
    /// The popped entry is negative.
    pub code_negative: Signal<Out, Bit>,
    /// `CMD_POSITION`, the count (for the soft limits).
    pub cmd_position: Signal<Out, Bits<POSITION_BITS>>,
    /// A gearbox step for this axis in this clock (build option `SPINDLE`).
    pub gear_step: Signal<In, Bit>,
    /// Its direction: 1 = forward.
    pub gear_forward: Signal<In, Bit>,

    fifo: CommandFifo<N, NP1, ENTRY_BITS>,
    /// The uniform generator, whose engine also runs the DDA (its DDA
    /// mode, while J != 0).
    uniform: UniformPulseCore<PERIOD_BITS, ERROR_BITS>,
    stage: StepOutput<16, STAGE_PENDING_BITS>,
    position: PulseCounter<POSITION_BITS>,
    encoder: QuadratureDecoder<POSITION_BITS, 8, 16>,
    io: AxisIo,
    /// The gearbox's steps merged with the interpolator's.
    merge: GearMerge,
    gear_lost_prev: DFF<Bit>,

    /// The register window (configuration, strobes, snapshots, reads).
    registers: AxisRegisters<NP1>,
    /// The entry popped at the last edge (0 after reset: every flag
    /// clear), and that a pop (an underrun) happened then: the
    /// interpolators take it one clock after the boundary, so the block
    /// RAM's read path ends in a flip-flop.
    popped: DFF<Bits<ENTRY_BITS>>,
    popped_valid: DFF<Bit>,
    underrun_d: DFF<Bit>,
    /// The base tick one clock late: the interpolators see each tick after
    /// the period counter, so the boundary tick still uses the old entry.
    tick_d: DFF<Bit>,
    /// The DDA's J for the running period (0 when stopped or uniform).
    integrand: DFF<Bits<PERIOD_BITS>>,
    /// J != 0, registered with J (the entry's nonzero flag): the DDA's
    /// decisions come from a flip-flop, not a 16-input OR.
    integrand_nonzero: DFF<Bit>,
    /// J (and M) changed at the last edge: the DDA reloads its error.
    dda_reload: DFF<Bit>,
    /// AXIS_STATUS.INTERP_OVERRANGE: an entry did not fit the
    /// interpolators (saturated to 2^PERIOD_BITS - 1) or an interpolator
    /// clamped one. Kept here, cleared only by CLEAR_FAULTS: the
    /// interpolators' own flags are also cleared by a start or a stop.
    overrange_flag: DFF<Bit>,
    /// AXIS_STATUS.INTERP_OVERFLOW: the uniform generator refused a period.
    overflow_flag: DFF<Bit>,
    /// The sub-blocks' sticky flags one clock ago: each rise is a fault
    /// event (a flag re-arms when cleared, by CLEAR_FAULTS or a start).
    overrun_prev: DFF<Bit>,
    dda_overrange_prev: DFF<Bit>,
    uniform_overrange_prev: DFF<Bit>,
    uniform_overflow_prev: DFF<Bit>,
    /// The entry taken at the last edge was saturated. Registered so that
    /// the magnitude test does not sit in front of the flag and interrupt
    /// logic: the fault is flagged one clock after the entry is taken.
    saturated: DFF<Bit>,
    /// A CLEAR_POSITION waiting for a clock on which no step is counted.
    clear_position_pending: DFF<Bit>,
    /// CLEAR_POSITION written now or still waiting.
    clear_position: Signal<Local, Bit>,
    /// The running period's direction (DDA).
    forward: DFF<Bit>,
    /// The direction travels with the DDA's two clocks of latency.
    forward_1: DFF<Bit>,
    forward_2: DFF<Bit>,
    /// The uniform generator, not the DDA, drives this axis (latched at start).
    uniform_active: DFF<Bit>,
    /// The axis is analog: its entries are DAC codes (latched at start).
    analog_active: DFF<Bit>,
    /// The analog code of the running period is positive / negative: the
    /// axis moves toward its forward / backward limit (for the limit cut).
    code_forward: DFF<Bit>,
    code_backward: DFF<Bit>,
    /// The popped entry as a code is not 0 (saturated or not).
    code_nonzero: Signal<Local, Bit>,
    /// Direction of the period loaded into the uniform generator, and of
    /// the one it is running.
    uniform_loaded_forward: DFF<Bit>,
    uniform_running_forward: DFF<Bit>,
    uniform_ready_prev: DFF<Bit>,
    uniform_pulse_prev: DFF<Bit>,
    /// The step request to the output stage, registered.
    request: DFF<Bit>,
    request_forward: DFF<Bit>,
    encoder_error_prev: DFF<Bit>,

    /// The interpolator's step, and its direction.
    interp: Signal<Local, Bit>,
    interp_forward: Signal<Local, Bit>,
    /// The step offered to the request register (the interpolator's or
    /// the gearbox's), and its direction.
    candidate: Signal<Local, Bit>,
    candidate_forward: Signal<Local, Bit>,
    candidate_blocked: Signal<Local, Bit>,
    clear_faults: Signal<Local, Bit>,
    /// |popped| does not fit the interpolators.
    too_large: Signal<Local, Bit>,
    /// |popped| saturated to the interpolators' width.
    count: Signal<Local, Bits<PERIOD_BITS>>,
    uniform_started: Signal<Local, Bit>,
    uniform_forward: Signal<Local, Bit>,
    /// The uniform generator's outputs as the axis uses them: every use
    /// goes through these, which are 0 in a build without the generator
    /// (`has_uniform` = 0). The generator then drives nothing, and
    /// synthesis removes it.
    uniform_pulse: Signal<Local, Bit>,
    uniform_ready: Signal<Local, Bit>,
    uniform_running: Signal<Local, Bit>,
    uniform_overrange: Signal<Local, Bit>,
    uniform_overflow: Signal<Local, Bit>,

    window: Constant<Bits<3>>,
    /// The build has the uniform generator (the controller's `UNIFORM`).
    has_uniform: Constant<Bit>,
    /// The build has the analog outputs (the controller's `ANALOG`).
    has_analog: Constant<Bit>,
    /// The build has the spindle unit (the controller's `SPINDLE`).
    has_spindle: Constant<Bit>,
    zero_position: Constant<Bits<POSITION_BITS>>,
    /// Bits 31..POSITION_BITS set: ORed into a negative position's word.
    position_extension: Constant<Bits<32>>,
    /// A position's sign bit, as a mask (rust-hdl prints a constant's name
    /// in a bit index).
    position_sign: Constant<Bits<POSITION_BITS>>,
    /// The positions as 32-bit register words, sign-extended.
    cmd_word: Signal<Local, Bits<32>>,
    act_word: Signal<Local, Bits<32>>,
    index_word: Signal<Local, Bits<32>>,
    zero_count: Constant<Bits<PERIOD_BITS>>,
    zero_entry: Constant<Bits<ENTRY_BITS>>,
}

impl<const N: usize, const NP1: usize> MotionAxis<N, NP1> {
    /// Axis number `index` (its register window is at
    /// `AXIS_BASE + index * AXIS_STRIDE`), with its uniform generator if
    /// `uniform`, its analog mode if `analog` and the gearbox's steps if
    /// `spindle`; `config_mask` is AXIS_CONFIG's read-write bits in the
    /// controller's register map.
    pub fn new(index: usize, uniform: bool, analog: bool, spindle: bool, config_mask: u32) -> Self {
        let window = (AXIS_BASE + index as u32 * AXIS_STRIDE) >> AXIS_STRIDE_LOG2;
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            start: Default::default(),
            halt: Default::default(),
            pop: Default::default(),
            underrun: Default::default(),
            period_active: Default::default(),
            modulus_negated: Default::default(),
            snapshot: Default::default(),
            low_water: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            fifo_entry: Default::default(),
            read_data: Default::default(),
            enc_a: Default::default(),
            enc_b: Default::default(),
            enc_index: Default::default(),
            out_a: Default::default(),
            out_b: Default::default(),
            empty: Default::default(),
            low: Default::default(),
            overflow_event: Default::default(),
            fault_event: Default::default(),
            encoder_error_event: Default::default(),
            busy: Default::default(),
            flush: Default::default(),
            abort: Default::default(),
            limit_forward: Default::default(),
            limit_backward: Default::default(),
            home: Default::default(),
            home_rise: Default::default(),
            probe_latch: Default::default(),
            alarm: Default::default(),
            drive_allowed: Default::default(),
            drive_enable: Default::default(),
            limit_held: Default::default(),
            alarm_held: Default::default(),
            home_held: Default::default(),
            limit_event: Default::default(),
            alarm_event: Default::default(),
            home_event: Default::default(),
            div_request: Default::default(),
            div_dividend: Default::default(),
            div_divisor: Default::default(),
            div_done: Default::default(),
            div_half: Default::default(),
            div_long_pulses: Default::default(),
            div_short_negated: Default::default(),
            div_half_is_one: Default::default(),
            div_has_pulses: Default::default(),
            div_clamped: Default::default(),
            analog: Default::default(),
            dac_code: Default::default(),
            code_out_of_range: Default::default(),
            code_negative: Default::default(),
            cmd_position: Default::default(),
            gear_step: Default::default(),
            gear_forward: Default::default(),
            fifo: Default::default(),
            uniform: if uniform {
                UniformPulseCore::default()
            } else {
                UniformPulseCore::without_generator()
            },
            stage: Default::default(),
            position: Default::default(),
            encoder: Default::default(),
            io: Default::default(),
            merge: Default::default(),
            gear_lost_prev: Default::default(),
            registers: AxisRegisters::new(index, config_mask),
            popped: Default::default(),
            popped_valid: Default::default(),
            underrun_d: Default::default(),
            tick_d: Default::default(),
            integrand: Default::default(),
            integrand_nonzero: Default::default(),
            dda_reload: Default::default(),
            overrange_flag: Default::default(),
            overflow_flag: Default::default(),
            overrun_prev: Default::default(),
            dda_overrange_prev: Default::default(),
            uniform_overrange_prev: Default::default(),
            uniform_overflow_prev: Default::default(),
            saturated: Default::default(),
            clear_position_pending: Default::default(),
            clear_position: Default::default(),
            forward: Default::default(),
            forward_1: Default::default(),
            forward_2: Default::default(),
            uniform_active: Default::default(),
            analog_active: Default::default(),
            code_forward: Default::default(),
            code_backward: Default::default(),
            code_nonzero: Default::default(),
            uniform_loaded_forward: Default::default(),
            uniform_running_forward: Default::default(),
            uniform_ready_prev: Default::default(),
            uniform_pulse_prev: Default::default(),
            request: Default::default(),
            request_forward: Default::default(),
            encoder_error_prev: Default::default(),
            interp: Default::default(),
            interp_forward: Default::default(),
            candidate: Default::default(),
            candidate_forward: Default::default(),
            candidate_blocked: Default::default(),
            clear_faults: Default::default(),
            too_large: Default::default(),
            count: Default::default(),
            uniform_started: Default::default(),
            uniform_forward: Default::default(),
            uniform_pulse: Default::default(),
            uniform_ready: Default::default(),
            uniform_running: Default::default(),
            uniform_overrange: Default::default(),
            uniform_overflow: Default::default(),
            window: Constant::new((window as u64).into()),
            has_uniform: Constant::new(uniform),
            has_spindle: Constant::new(spindle),
            has_analog: Constant::new(analog),
            zero_position: Constant::new(0u64.into()),
            position_extension: Constant::new(
                (0xffff_ffffu64 & !crate::blocks::width_mask(POSITION_BITS as u32)).into(),
            ),
            position_sign: Constant::new((1u64 << (POSITION_BITS - 1)).into()),
            cmd_word: Default::default(),
            act_word: Default::default(),
            index_word: Default::default(),
            zero_count: Constant::new(0u64.into()),
            zero_entry: Constant::new(0u64.into()),
        }
    }
}

field_slices! {
    /// The multi-bit fields `update()` takes from the axis registers.
    trait AxisFields {
        get_value_step_mode / get_my_offset_step_mode / get_my_width_step_mode =
            (fields::AXIS_STEP_MODE, fields::AXIS_STEP_MODE_WIDTH);
        get_value_enc_filter / get_my_offset_enc_filter / get_my_width_enc_filter =
            (fields::AXIS_ENC_FILTER, fields::AXIS_ENC_FILTER_WIDTH);
        get_value_step_timing / get_my_offset_step_timing / get_my_width_step_timing =
            (fields::VALUE, fields::STEP_TIMING_WIDTH);
        get_value_enc_sample_rate / get_my_offset_enc_sample_rate / get_my_width_enc_sample_rate =
            (fields::VALUE, fields::ENC_SAMPLE_RATE_WIDTH);
    }
}

// `update()` reads these single-bit fields at literal bits (rust-hdl prints
// a named constant by name, and has no one-bit form of `field_slices!`):
// each literal is tied to the map's constant here, so a field moved in the
// map fails the build.
const _: () = {
    // AXIS_COMMAND, written with `command`.
    assert!(fields::CMD_CLEAR_FAULTS == 0);
    assert!(fields::CMD_CLEAR_ENCODER == 1);
    assert!(fields::CMD_REARM_INDEX == 2);
    assert!(fields::CMD_CLEAR_POSITION == 3);
    assert!(fields::CMD_CLEAR_ENCODER_ERROR == 4);
    // AXIS_CONFIG, held in `settings`.
    assert!(fields::AXIS_UNIFORM == 0);
    assert!(fields::AXIS_INTERLEAVED == 1);
    assert!(fields::AXIS_ENC_COUNTER_MODE == 8);
    assert!(fields::AXIS_INDEX_INVERT == 9);
    assert!(fields::AXIS_INDEX_CLEAR == 10);
    assert!(fields::AXIS_INDEX_LATCH == 11);
    assert!(fields::AXIS_INDEX_ONCE == 12);
    assert!(fields::AXIS_ANALOG == 13);
    // Not fields: the address decode (window in bits 7..5, the machine I/O
    // half in bit 4, the word offset in 3..0).
    assert!(AXIS_STRIDE_LOG2 == 5 && AXIS_STRIDE == 1 << 5);
};

impl<const N: usize, const NP1: usize> Logic for MotionAxis<N, NP1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            popped,
            popped_valid,
            underrun_d,
            tick_d,
            integrand,
            integrand_nonzero,
            dda_reload,
            overrange_flag,
            overflow_flag,
            overrun_prev,
            dda_overrange_prev,
            uniform_overrange_prev,
            uniform_overflow_prev,
            saturated,
            clear_position_pending,
            forward,
            forward_1,
            forward_2,
            uniform_active,
            analog_active,
            code_forward,
            code_backward,
            uniform_loaded_forward,
            uniform_running_forward,
            uniform_ready_prev,
            uniform_pulse_prev,
            request,
            request_forward,
            encoder_error_prev,
            gear_lost_prev
        );
        self.fifo.clock.next = self.clock.val();
        self.uniform.clock.next = self.clock.val();
        self.stage.clock.next = self.clock.val();
        self.position.clock.next = self.clock.val();
        self.encoder.clock.next = self.clock.val();
        self.io.clock.next = self.clock.val();
        self.merge.clock.next = self.clock.val();

        // The register window: configuration, strobes, snapshots, reads.
        self.registers.clock.next = self.clock.val();
        self.registers.reset.next = self.reset.val();
        self.registers.address.next = self.address.val();
        self.registers.write.next = self.write.val();
        self.registers.write_data.next = self.write_data.val().get_bits::<WRITE_BITS>(0);
        self.registers.snapshot.next = self.snapshot.val();
        // AXIS_COMMAND.CLEAR_FAULTS
        self.clear_faults.next = self.registers.command.val() & self.write_data.val().get_bit(0);

        // Command FIFO.
        self.fifo.reset.next = self.reset.val() | self.flush.val();
        self.fifo.write.next = self.registers.fifo_write.val();
        self.fifo.write_data.next = self.fifo_entry.val();
        self.fifo.pop.next = self.pop.val();
        self.fifo.low_water.next = self.low_water.val();
        self.fifo.clear_flags.next = false;
        self.empty.next = self.fifo.empty.val();
        self.low.next = self.fifo.low.val();
        // CommandFifo refuses a write when full unless a pop frees a slot.
        self.overflow_event.next = self.fifo.write.val() & self.fifo.full.val() & !self.pop.val();
        self.popped_valid.d.next = self.pop.val();
        self.underrun_d.d.next = self.underrun.val();
        self.tick_d.d.next = self.tick.val();
        // The entry arrives converted (see ENTRY_BITS): bit 16 too large,
        // 17 sign, 18 code wide, 19 nonzero.
        if self.pop.val() {
            self.popped.d.next = self.fifo.head.val();
        }
        self.dac_code.next = self.popped.q.val().get_bits::<DAC_BITS>(0);
        self.code_out_of_range.next = self.popped.q.val().get_bit(18);
        self.code_negative.next = self.popped.q.val().get_bit(17);
        self.cmd_position.next = self.position.count.val();
        self.code_nonzero.next = self.popped.q.val().get_bit(19);
        self.analog.next = self.analog_active.q.val();
        self.too_large.next = self.popped.q.val().get_bit(16);
        self.count.next = self.popped.q.val().get_bits::<PERIOD_BITS>(0);
        // The uniform generator's outputs, and its division request, are
        // taken only in a build with the generator: without it they are
        // constant 0, its core is built `without_generator`, and only the
        // engine of its DDA mode is left (the controller's planner has no
        // fanout): synthesis removes the rest.
        // (One assignment each, no default-then-override: see the
        // controller's divider grant.) The dividend and divisor matter only
        // with a request.
        self.uniform_pulse.next = self.has_uniform.val() & self.uniform.pulse.val();
        self.uniform_ready.next = self.has_uniform.val() & self.uniform.ready.val();
        self.uniform_running.next = self.has_uniform.val() & self.uniform.running.val();
        self.uniform_overrange.next = self.has_uniform.val() & self.uniform.overrange.val();
        self.uniform_overflow.next = self.has_uniform.val() & self.uniform.overflow.val();
        self.div_request.next = self.has_uniform.val() & self.uniform.div_request.val();
        self.div_dividend.next = self.uniform.div_dividend.val();
        self.div_divisor.next = self.uniform.div_divisor.val();
        if self.clear_faults.val() {
            self.overrange_flag.d.next = false;
            self.overflow_flag.d.next = false;
        }
        // Set by the rises of the sub-blocks' flags (their levels would
        // defeat a CLEAR_FAULTS that clears them on the same clock).
        self.saturated.d.next = self.popped_valid.q.val()
            & ((self.analog_active.q.val() & self.popped.q.val().get_bit(18))
                | (!self.analog_active.q.val() & self.too_large.val()));
        if self.saturated.q.val()
            | (self.uniform.dda_overrange.val() & !self.dda_overrange_prev.q.val())
            | (self.uniform_overrange.val() & !self.uniform_overrange_prev.q.val())
        {
            self.overrange_flag.d.next = true;
        }
        if self.uniform_overflow.val() & !self.uniform_overflow_prev.q.val() {
            self.overflow_flag.d.next = true;
        }

        // Per-period state. The DDA takes J and its direction at the
        // boundary edge; the boundary tick itself still uses the old ones.
        // A uniform period still finishing keeps its generator in charge:
        // the switch waits for the next start, and no pulse is cut off.
        if self.start.val() & !self.uniform_running.val() {
            // AXIS_CONFIG.UNIFORM
            self.uniform_active.d.next = self.registers.axis_config.val().get_bit(0);
        }
        // An analog axis takes no steps: its entries are DAC codes
        // (AXIS_CONFIG.ANALOG).
        if self.start.val() {
            self.analog_active.d.next =
                self.has_analog.val() & self.registers.axis_config.val().get_bit(13);
        }
        if self.popped_valid.q.val() {
            self.forward.d.next = !self.popped.q.val().get_bit(17);
            if self.uniform_active.q.val() | self.analog_active.q.val() {
                self.integrand.d.next = self.zero_count.val();
                self.integrand_nonzero.d.next = false;
            } else {
                self.integrand.d.next = self.count.val();
                self.integrand_nonzero.d.next = self.code_nonzero.val();
            }
            if self.analog_active.q.val() {
                self.code_forward.d.next =
                    !self.popped.q.val().get_bit(17) & self.code_nonzero.val();
                self.code_backward.d.next = self.popped.q.val().get_bit(17);
            }
        }
        // The controller sets the analog channels to 0 when RUN falls.
        if self.underrun_d.q.val() | self.halt.val() {
            self.integrand.d.next = self.zero_count.val();
            self.integrand_nonzero.d.next = false;
            self.code_forward.d.next = false;
            self.code_backward.d.next = false;
        }
        self.forward_1.d.next = self.forward.q.val();
        self.forward_2.d.next = self.forward_1.q.val();

        // Not reset at a start: the boundary tick's pulse may still be in
        // its pipeline. J and M change together, at the edge after a pop or
        // an underrun (M with `period_active`, one clock late), or J alone
        // to 0 on a halt; every period before had all its M ticks, so the
        // DDA's phase is 0 and the error is reloaded in the next clock.
        self.dda_reload.d.next =
            self.popped_valid.q.val() | self.underrun_d.q.val() | self.halt.val();
        self.uniform.dda_tick.next = self.tick_d.q.val();
        self.uniform.dda_reload.next = self.dda_reload.q.val();
        self.uniform.dda_integrand.next = self.integrand.q.val();
        self.uniform.dda_active.next = self.integrand_nonzero.q.val();
        self.uniform.dda_modulus_negated.next = self.modulus_negated.val();
        self.uniform.dda_clear_overrange.next = self.clear_faults.val();

        // The uniform generator runs each loaded period after its set-up
        // time; the direction moves with the period it belongs to: `ready`
        // rises in the clock after the edge that starts a loaded period,
        // together with that period's first pulse.
        self.uniform.reset.next = self.reset.val() | self.halt.val();
        // Without the generator (`has_uniform` = 0) no tick reaches it, so
        // no period starts and only the DDA mode of its engine is left.
        self.uniform.tick.next = self.has_uniform.val() & self.tick_d.q.val();
        self.uniform.period.next = self.period_active.val();
        self.uniform.count.next = self.count.val();
        // AXIS_CONFIG.INTERLEAVED
        self.uniform.mode.next = self.registers.axis_config.val().get_bit(1);
        self.uniform.load.next =
            self.popped_valid.q.val() & self.uniform_active.q.val() & !self.analog_active.q.val();
        self.uniform.clear_flags.next = self.clear_faults.val() | self.start.val();
        self.uniform.div_done.next = self.div_done.val();
        self.uniform.div_half.next = self.div_half.val();
        self.uniform.div_long_pulses.next = self.div_long_pulses.val();
        self.uniform.div_short_negated.next = self.div_short_negated.val();
        self.uniform.div_half_is_one.next = self.div_half_is_one.val();
        self.uniform.div_has_pulses.next = self.div_has_pulses.val();
        self.uniform.div_clamped.next = self.div_clamped.val();
        if self.popped_valid.q.val()
            & self.uniform_active.q.val()
            & !self.analog_active.q.val()
            & self.uniform_ready.val()
        {
            self.uniform_loaded_forward.d.next = !self.popped.q.val().get_bit(17);
        }
        self.uniform_ready_prev.d.next = self.uniform_ready.val();
        self.uniform_pulse_prev.d.next = self.uniform_pulse.val();
        self.uniform_started.next = self.uniform_ready.val() & !self.uniform_ready_prev.q.val();
        self.uniform_forward.next = self.uniform_running_forward.q.val();
        if self.uniform_started.val() {
            self.uniform_forward.next = self.uniform_loaded_forward.q.val();
        }
        self.uniform_running_forward.d.next = self.uniform_forward.val();

        // Output stage.
        self.stage.reset.next = self.reset.val();
        // The request is registered: the interpolators' decode and the
        // stage's pending-count logic are each a clock deep. An abort or a
        // blocked direction keeps a step out of it; a step already in it or
        // pending in the stage is dropped by the stage's flush.
        if self.uniform_active.q.val() {
            self.interp.next = self.uniform_pulse.val() & !self.uniform_pulse_prev.q.val();
            self.interp_forward.next = self.uniform_forward.val();
        } else {
            self.interp.next = self.uniform.dda_pulse.val();
            self.interp_forward.next = self.forward_2.q.val();
        }
        // The gearbox's steps join the interpolator's (gated off without
        // SPINDLE, so synthesis removes the merge).
        self.merge.reset.next = self.reset.val();
        self.merge.interp.next = self.interp.val();
        self.merge.interp_forward.next = self.interp_forward.val();
        self.merge.gear.next = self.gear_step.val() & self.has_spindle.val();
        self.merge.gear_forward.next = self.gear_forward.val();
        self.merge.analog.next = self.analog_active.q.val();
        self.merge.abort.next = self.abort.val();
        self.merge.clear_lost.next = self.clear_faults.val();
        self.candidate.next = self.interp.val();
        self.candidate_forward.next = self.interp_forward.val();
        if self.has_spindle.val() {
            self.candidate.next = self.merge.candidate.val();
            self.candidate_forward.next = self.merge.candidate_forward.val();
        }
        self.candidate_blocked.next = self.io.block_backward.val();
        if self.candidate_forward.val() {
            self.candidate_blocked.next = self.io.block_forward.val();
        }
        self.request.d.next =
            self.candidate.val() & !self.abort.val() & !self.candidate_blocked.val();
        self.request_forward.d.next = self.candidate_forward.val();
        self.stage.step.next = self.request.q.val();
        self.stage.dir.next = self.request_forward.q.val();
        self.stage.flush.next = self.abort.val() | self.io.cut.val();
        self.stage.mode.next = self.registers.axis_config.val().get_value_step_mode();
        self.stage.step_len.next = self.registers.step_len.val().get_value_step_timing();
        self.stage.step_space.next = self.registers.step_space.val().get_value_step_timing();
        self.stage.dir_setup.next = self.registers.dir_setup.val().get_value_step_timing();
        self.stage.dir_hold.next = self.registers.dir_hold.val().get_value_step_timing();
        self.stage.clear_overrun.next = self.clear_faults.val();
        self.out_a.next = self.stage.out_a.val();
        self.out_b.next = self.stage.out_b.val();

        // Commanded position: the steps that left the output stage.
        self.position.reset.next = self.reset.val();
        self.position.up.next = self.stage.emitted.val() & self.stage.emitted_forward.val();
        self.position.down.next = self.stage.emitted.val() & !self.stage.emitted_forward.val();
        // CLEAR_POSITION waits for a clock on which no step is counted,
        // since the counter's clear would win over that step: every step
        // then lands in the old count or the new one. (Loading +-1 instead
        // gives every bit's adder LUT a fourth input, which splits the
        // 32-bit carry chain in placement: nextpnr allows 32 LUT inputs per
        // tile. It was the slowest path of the top.)
        // AXIS_COMMAND.CLEAR_POSITION
        self.clear_position.next = (self.registers.command.val()
            & self.write_data.val().get_bit(3))
            | self.clear_position_pending.q.val();
        self.position.clear.next = self.clear_position.val() & !self.stage.emitted.val();
        self.clear_position_pending.d.next = self.clear_position.val() & self.stage.emitted.val();
        self.position.load.next = false;
        self.position.load_value.next = self.zero_position.val();
        self.position.compare_value.next = self.zero_position.val();

        // Encoder.
        self.encoder.reset.next = self.reset.val();
        self.encoder.a.next = self.enc_a.val();
        self.encoder.b.next = self.enc_b.val();
        self.encoder.index.next = self.enc_index.val();
        self.encoder.filter.next = self.registers.axis_config.val().get_value_enc_filter();
        self.encoder.sample_rate.next =
            self.registers.sample_rate.val().get_value_enc_sample_rate();
        // AXIS_CONFIG.ENC_COUNTER_MODE, INDEX_INVERT, INDEX_CLEAR,
        // INDEX_LATCH, INDEX_ONCE; AXIS_COMMAND.CLEAR_ENCODER, REARM_INDEX,
        // CLEAR_ENCODER_ERROR.
        self.encoder.counter_mode.next = self.registers.axis_config.val().get_bit(8);
        self.encoder.index_invert.next = self.registers.axis_config.val().get_bit(9);
        self.encoder.index_clear.next = self.registers.axis_config.val().get_bit(10);
        self.encoder.index_latch.next = self.registers.axis_config.val().get_bit(11);
        self.encoder.index_once.next = self.registers.axis_config.val().get_bit(12);
        self.encoder.clear.next = self.registers.command.val() & self.write_data.val().get_bit(1);
        self.encoder.index_rearm.next =
            self.registers.command.val() & self.write_data.val().get_bit(2);
        self.encoder.clear_error.next =
            self.registers.command.val() & self.write_data.val().get_bit(4);

        // Machine I/O: limits, alarm, home and drive enable.
        self.io.reset.next = self.reset.val();
        self.io.selected.next = (self.address.val().get_bits::<3>(5) == self.window.val())
            & self.address.val().get_bit(4);
        self.io.offset.next = self.address.val().get_bits::<4>(0);
        self.io.write.next = self.write.val();
        self.io.write_data.next = self.write_data.val();
        self.io.limit_forward.next = self.limit_forward.val();
        self.io.limit_backward.next = self.limit_backward.val();
        self.io.home.next = self.home.val();
        self.io.home_rise.next = self.home_rise.val();
        self.io.probe_latch.next = self.probe_latch.val();
        self.io.alarm.next = self.alarm.val();
        self.io.drive_allowed.next = self.drive_allowed.val();
        self.io.pending_forward.next = self.stage.pending_forward.val();
        self.io.pending_backward.next = self.stage.pending_backward.val();
        self.io.request.next = self.request.q.val();
        self.io.request_forward.next = self.request_forward.q.val();
        // An analog axis's motion is its code's sign: a code toward an
        // enabled, active limit is cut like a step (and aborts).
        self.io.pulse.next =
            self.candidate.val() | self.code_forward.q.val() | self.code_backward.q.val();
        self.io.pulse_forward.next = (self.analog_active.q.val() & self.code_forward.q.val())
            | (!self.analog_active.q.val() & self.candidate_forward.val());
        // The positions wrap at POSITION_BITS; the register words carry
        // their sign up to bit 31 (the host extends them further).
        self.cmd_word.next = bit_cast::<32, POSITION_BITS>(self.position.count.val());
        if (self.position.count.val() & self.position_sign.val()) != self.zero_position.val() {
            self.cmd_word.next = self.cmd_word.val() | self.position_extension.val();
        }
        self.act_word.next = bit_cast::<32, POSITION_BITS>(self.encoder.count.val());
        if (self.encoder.count.val() & self.position_sign.val()) != self.zero_position.val() {
            self.act_word.next = self.act_word.val() | self.position_extension.val();
        }
        self.index_word.next = bit_cast::<32, POSITION_BITS>(self.encoder.index_count.val());
        if (self.encoder.index_count.val() & self.position_sign.val()) != self.zero_position.val() {
            self.index_word.next = self.index_word.val() | self.position_extension.val();
        }
        self.io.cmd_position.next = self.cmd_word.val();
        self.io.act_position.next = self.act_word.val();
        self.drive_enable.next = self.io.drive_enable.val();
        self.limit_held.next = self.io.limit_held.val();
        self.alarm_held.next = self.io.alarm_held.val();
        self.home_held.next = self.io.home_held.val();
        self.limit_event.next = self.io.limit_event.val();
        self.alarm_event.next = self.io.alarm_event.val();
        self.home_event.next = self.io.home_event.val();

        // Events: each rise of a sub-block's sticky flag, and each
        // saturated entry.
        self.overrun_prev.d.next = self.stage.overrun.val();
        self.gear_lost_prev.d.next = self.merge.lost.val();
        self.dda_overrange_prev.d.next = self.uniform.dda_overrange.val();
        self.uniform_overrange_prev.d.next = self.uniform_overrange.val();
        self.uniform_overflow_prev.d.next = self.uniform_overflow.val();
        self.fault_event.next = (self.stage.overrun.val() & !self.overrun_prev.q.val())
            | (self.uniform.dda_overrange.val() & !self.dda_overrange_prev.q.val())
            | (self.uniform_overrange.val() & !self.uniform_overrange_prev.q.val())
            | (self.uniform_overflow.val() & !self.uniform_overflow_prev.q.val())
            | (self.merge.lost.val() & !self.gear_lost_prev.q.val() & self.has_spindle.val())
            | self.saturated.q.val();
        self.busy.next = self.stage.busy.val() | self.uniform_running.val();
        self.encoder_error_prev.d.next = self.encoder.error.val();
        self.encoder_error_event.next = self.encoder.error.val() & !self.encoder_error_prev.q.val();

        // Read data: the window's registers and the axis I/O's.
        self.registers.fifo_level.next = self.fifo.level.val();
        self.registers.fifo_empty.next = self.fifo.empty.val();
        self.registers.fifo_full.next = self.fifo.full.val();
        self.registers.fifo_low.next = self.fifo.low.val();
        self.registers.step_overrun.next =
            self.stage.overrun.val() | (self.merge.lost.val() & self.has_spindle.val());
        self.registers.interp_overrange.next = self.overrange_flag.q.val();
        self.registers.interp_overflow.next = self.overflow_flag.q.val();
        self.registers.encoder_error.next = self.encoder.error.val();
        self.registers.index_seen.next = self.encoder.index_seen.val();
        self.registers.step_busy.next = self.stage.busy.val();
        self.registers.uniform_running.next = self.uniform_running.val();
        self.registers.step_mode_invalid.next = self.stage.mode_invalid.val();
        self.registers.cmd_position.next = self.cmd_word.val();
        self.registers.act_position.next = self.act_word.val();
        self.registers.index_position.next = self.index_word.val();
        self.registers.io_read_data.next = self.io.read_data.val();
        self.read_data.next = self.registers.read_data.val();

        if self.reset.val() {
            self.popped.d.next = self.zero_entry.val();
            self.popped_valid.d.next = false;
            self.underrun_d.d.next = false;
            self.tick_d.d.next = false;
            self.integrand.d.next = self.zero_count.val();
            self.integrand_nonzero.d.next = false;
            self.dda_reload.d.next = false;
            self.overrange_flag.d.next = false;
            self.overflow_flag.d.next = false;
            self.overrun_prev.d.next = false;
            self.gear_lost_prev.d.next = false;
            self.dda_overrange_prev.d.next = false;
            self.uniform_overrange_prev.d.next = false;
            self.uniform_overflow_prev.d.next = false;
            self.saturated.d.next = false;
            self.clear_position_pending.d.next = false;
            self.forward.d.next = false;
            self.forward_1.d.next = false;
            self.forward_2.d.next = false;
            self.uniform_active.d.next = false;
            self.analog_active.d.next = false;
            self.code_forward.d.next = false;
            self.code_backward.d.next = false;
            self.uniform_loaded_forward.d.next = false;
            self.uniform_running_forward.d.next = false;
            self.uniform_ready_prev.d.next = false;
            self.uniform_pulse_prev.d.next = false;
            self.request.d.next = false;
            self.request_forward.d.next = false;
            self.encoder_error_prev.d.next = false;
        }
    }
}
