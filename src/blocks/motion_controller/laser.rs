//! The laser unit: the laser FIFO, its registers, and the [`LaserPwm`]
//! whose duty follows the path speed of two axes (build option `LASER`).
//!
//! Internal to [`super::MotionController`]; the behavior is specified in
//! [`super`] ("Laser PWM") and modelled by
//! [`super::laser_model::LaserUnitModel`].
//!
//! * **Per period.** With `LASER_CONTROL.ENABLE` and not `SOURCE` at a
//!   start the laser FIFO takes part in the run: at every boundary its
//!   head pops with the axes' entries and becomes the period's (POWER,
//!   FEED); an empty laser FIFO at a boundary is an underrun like an empty
//!   axis FIFO. When RUN falls the period's entry becomes 0.
//! * **By register.** With `SOURCE` the engine takes (POWER, FEED) from
//!   `LASER_POWER` instead of the period's entry, in every clock.
//! * **The duty engine runs free**: it takes a `load` in every clock it is
//!   idle, with the running period's step counts of the plane's two axes
//!   (their |entry|, saturated to 2^15 - 1), its POWER and FEED and the
//!   feed hold's factor, and commits its result in the clock it finishes.
//!   So a change of the counts, the entry or the factor reaches the duty
//!   within two engine runs: [`LASER_LAG`] clocks at most.
//! * **Off**: `laser_pwm` fires only while RUN and `ENABLE` (low from the
//!   first clock after RUN falls); an abort or
//!   the feed hold's stop (`kill`) turns it off in the next clock and
//!   zeroes the duty in force.

use rust_hdl::prelude::*;

use super::registers::{fields, laser};
use crate::blocks::command_fifo::CommandFifo;
use crate::blocks::konst;
use crate::blocks::laser_pwm::{model::ENGINE_CLOCKS, LaserPwm};

/// The most clocks from a change of the running period (its counts, its
/// entry) or of the hold's factor to the duty in force that reflects it:
/// an engine run that has just taken the old values, then one that takes
/// the new, each [`ENGINE_CLOCKS`] long plus the clock of its load, then
/// the clock of the commit.
pub const LASER_LAG: u32 = 2 * (ENGINE_CLOCKS + 1) + 1;

field_slices! {
    /// The multi-bit fields the unit takes from the bus's write data.
    trait LaserFields {
        get_value_axis_a / get_my_offset_axis_a / get_my_width_axis_a =
            (fields::LASER_AXIS_A, fields::LASER_AXIS_WIDTH);
        get_value_axis_b / get_my_offset_axis_b / get_my_width_axis_b =
            (fields::LASER_AXIS_B, fields::LASER_AXIS_WIDTH);
        get_value_word / get_my_offset_word / get_my_width_word =
            (fields::LASER_POWER, fields::LASER_WORD_WIDTH);
        get_value_feed / get_my_offset_feed / get_my_width_feed =
            (fields::LASER_FEED, fields::LASER_WORD_WIDTH);
    }
}

// Single bits are taken at literal indices (rust-hdl prints a named
// constant by name); each is tied to the map here.
const _: () = {
    assert!(fields::LASER_ENABLE == 0 && fields::LASER_DYNAMIC == 1);
    assert!(fields::LASER_CLEAR_OVERFLOW == 2 && fields::LASER_SOURCE == 3);
    assert!(fields::LASER_OVERFLOW == 8 && fields::LASER_ACTIVE == 9);
    assert!(fields::LASER_BUSY == 10 && fields::LASER_SPEED == 16);
    assert!(fields::LASER_WORD_WIDTH == 16);
};

/// The laser unit of a controller with FIFOs of 2^`N` entries. See the
/// [module documentation](self).
#[derive(LogicBlock)]
pub struct LaserUnit<const N: usize, const NP1: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data.
    pub write_data: Signal<In, Bits<32>>,
    /// RUN starts in this clock.
    pub start: Signal<In, Bit>,
    /// A boundary pops every FIFO in this clock.
    pub pop: Signal<In, Bit>,
    /// RUN falls in this clock (an underrun or a halt).
    pub stop: Signal<In, Bit>,
    /// A CONTROL.FLUSH write in this clock.
    pub flush: Signal<In, Bit>,
    /// RUN.
    pub running: Signal<In, Bit>,
    /// An abort or the feed hold's stop.
    pub kill: Signal<In, Bit>,
    /// The feed hold's factor, 1/65536.
    pub factor: Signal<In, Bits<17>>,
    /// |entry| of the plane's first axis's running period (saturated to 16 bits).
    pub count_a: Signal<In, Bits<16>>,
    /// |entry| of the plane's second axis's running period.
    pub count_b: Signal<In, Bits<16>>,
    /// The addressed register of the unit, 0 outside it.
    pub read_data: Signal<Out, Bits<32>>,
    /// A boundary may pop: the laser FIFO is not part of the run, or it
    /// has an entry.
    pub ready: Signal<Out, Bit>,
    /// `LASER_CONTROL.AXIS_A`.
    pub axis_a: Signal<Out, Bits<3>>,
    /// `LASER_CONTROL.AXIS_B`.
    pub axis_b: Signal<Out, Bits<3>>,
    /// The laser's PWM, registered.
    pub pwm: Signal<Out, Bit>,

    fifo: CommandFifo<N, NP1, 32>,
    engine: LaserPwm,
    /// `LASER_CONTROL`'s read-write bits, in place (synthesis drops the
    /// constant others).
    control: DFF<Bits<32>>,
    pwm_period: DFF<Bits<16>>,
    /// The running period's entry: POWER, FEED.
    entry: DFF<Bits<32>>,
    /// `LASER_POWER`: POWER, FEED by register.
    power: DFF<Bits<32>>,
    /// The laser FIFO takes part in the run.
    active: DFF<Bit>,
    overflow: DFF<Bit>,
    busy_prev: DFF<Bit>,

    control_write: Signal<Local, Bit>,
    fifo_write: Signal<Local, Bit>,
    saturated_a: Signal<Local, Bits<16>>,
    saturated_b: Signal<Local, Bits<16>>,
    status_word: Signal<Local, Bits<32>>,
    /// The engine's (POWER, FEED): the period's entry or `LASER_POWER`.
    setpoint: Signal<Local, Bits<32>>,
    /// The setpoint's FEED, zero-extended to the engine's 24 bits.
    entry_feed: Signal<Local, Bits<16>>,

    a_control: Constant<Bits<8>>,
    a_period: Constant<Bits<8>>,
    a_fifo: Constant<Bits<8>>,
    a_status: Constant<Bits<8>>,
    a_output: Constant<Bits<8>>,
    a_power: Constant<Bits<8>>,
    control_mask: Constant<Bits<32>>,
    count_max: Constant<Bits<16>>,
    zero16: Constant<Bits<16>>,
    zero32: Constant<Bits<32>>,
    zero_level: Constant<Bits<NP1>>,
    m_overflow: Constant<Bits<32>>,
    m_active: Constant<Bits<32>>,
    m_busy: Constant<Bits<32>>,
}

impl<const N: usize, const NP1: usize> Default for LaserUnit<N, NP1> {
    fn default() -> Self {
        let field_mask = |lsb: u32, width: u32| crate::blocks::width_mask(width) << lsb;
        let control_mask = field_mask(fields::LASER_ENABLE, 1)
            | field_mask(fields::LASER_DYNAMIC, 1)
            | field_mask(fields::LASER_SOURCE, 1)
            | field_mask(fields::LASER_AXIS_A, fields::LASER_AXIS_WIDTH)
            | field_mask(fields::LASER_AXIS_B, fields::LASER_AXIS_WIDTH);
        let a = |address: u32| konst(address as u64);
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            start: Default::default(),
            pop: Default::default(),
            stop: Default::default(),
            flush: Default::default(),
            running: Default::default(),
            kill: Default::default(),
            factor: Default::default(),
            count_a: Default::default(),
            count_b: Default::default(),
            read_data: Default::default(),
            ready: Default::default(),
            axis_a: Default::default(),
            axis_b: Default::default(),
            pwm: Default::default(),
            fifo: Default::default(),
            engine: Default::default(),
            control: Default::default(),
            pwm_period: Default::default(),
            entry: Default::default(),
            power: Default::default(),
            active: Default::default(),
            overflow: Default::default(),
            busy_prev: Default::default(),
            control_write: Default::default(),
            fifo_write: Default::default(),
            saturated_a: Default::default(),
            saturated_b: Default::default(),
            status_word: Default::default(),
            setpoint: Default::default(),
            entry_feed: Default::default(),
            a_control: a(laser::LASER_CONTROL),
            a_period: a(laser::LASER_PWM_PERIOD),
            a_fifo: a(laser::LASER_FIFO),
            a_status: a(laser::LASER_STATUS),
            a_output: a(laser::LASER_OUTPUT),
            a_power: a(laser::LASER_POWER),
            control_mask: konst(control_mask),
            count_max: konst(0x7fff),
            zero16: konst(0),
            zero32: konst(0),
            zero_level: konst(0),
            m_overflow: konst(1 << fields::LASER_OVERFLOW),
            m_active: konst(1 << fields::LASER_ACTIVE),
            m_busy: konst(1 << fields::LASER_BUSY),
        }
    }
}

impl<const N: usize, const NP1: usize> Logic for LaserUnit<N, NP1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, control, pwm_period, entry, power, active, overflow, busy_prev);
        clock!(self, clock, fifo, engine);

        // Registers.
        self.control_write.next = self.write.val() & (self.address.val() == self.a_control.val());
        if self.control_write.val() {
            self.control.d.next = self.write_data.val() & self.control_mask.val();
        }
        if self.write.val() & (self.address.val() == self.a_period.val()) {
            self.pwm_period.d.next = self.write_data.val().get_value_word();
        }
        if self.write.val() & (self.address.val() == self.a_power.val()) {
            self.power.d.next = self.write_data.val();
        }
        self.axis_a.next = self.control.q.val().get_value_axis_a();
        self.axis_b.next = self.control.q.val().get_value_axis_b();

        // The FIFO: a write to a full one (no pop freeing a slot) is
        // refused and flagged.
        self.fifo_write.next = self.write.val() & (self.address.val() == self.a_fifo.val());
        self.fifo.reset.next = self.reset.val() | self.flush.val();
        self.fifo.write.next = self.fifo_write.val();
        self.fifo.write_data.next = self.write_data.val();
        self.fifo.pop.next = self.pop.val() & self.active.q.val();
        self.fifo.low_water.next = self.zero_level.val();
        self.fifo.clear_flags.next = false;
        if self.control_write.val() & self.write_data.val().get_bit(2) {
            self.overflow.d.next = false;
        }
        if self.fifo_write.val() & self.fifo.full.val() & !(self.pop.val() & self.active.q.val()) {
            self.overflow.d.next = true;
        }
        self.ready.next = !self.active.q.val() | !self.fifo.empty.val();

        // The run: ENABLE without SOURCE at the start decides whether the
        // FIFO takes part; the period's entry is the popped head, 0 once
        // RUN falls.
        if self.start.val() {
            self.active.d.next = self.control.q.val().get_bit(0) & !self.control.q.val().get_bit(3);
        }
        if self.pop.val() & self.active.q.val() {
            self.entry.d.next = self.fifo.head.val();
        }
        if self.stop.val() {
            self.entry.d.next = self.zero32.val();
            self.active.d.next = false;
        }

        // The engine runs free: a load whenever idle, committed when done.
        self.saturated_a.next = self.count_a.val();
        if self.count_a.val() > self.count_max.val() {
            self.saturated_a.next = self.count_max.val();
        }
        self.saturated_b.next = self.count_b.val();
        if self.count_b.val() > self.count_max.val() {
            self.saturated_b.next = self.count_max.val();
        }
        self.busy_prev.d.next = self.engine.busy.val();
        self.engine.reset.next = self.reset.val();
        self.engine.pwm_period.next = self.pwm_period.q.val();
        self.setpoint.next = self.entry.q.val();
        if self.control.q.val().get_bit(3) {
            self.setpoint.next = self.power.q.val();
        }
        self.engine.power.next = self.setpoint.val().get_value_word();
        self.engine.dynamic.next = self.control.q.val().get_bit(1);
        self.engine.load.next = !self.engine.busy.val();
        self.engine.commit.next = self.busy_prev.q.val() & !self.engine.busy.val();
        self.engine.count_a.next = self.saturated_a.val();
        self.engine.count_b.next = self.saturated_b.val();
        self.entry_feed.next = self.setpoint.val().get_value_feed();
        self.engine.feed.next = bit_cast::<24, 16>(self.entry_feed.val());
        self.engine.factor.next = self.factor.val();
        // Off in the clock RUN falls, so that the registered pin is low
        // from the first clock without RUN.
        self.engine.enable.next =
            self.control.q.val().get_bit(0) & self.running.val() & !self.stop.val();
        self.engine.kill.next = self.kill.val();
        self.pwm.next = self.engine.pwm.val();

        // Reads.
        self.status_word.next = bit_cast::<32, NP1>(self.fifo.level.val());
        if self.overflow.q.val() {
            self.status_word.next = self.status_word.val() | self.m_overflow.val();
        }
        if self.active.q.val() {
            self.status_word.next = self.status_word.val() | self.m_active.val();
        }
        if self.engine.busy.val() {
            self.status_word.next = self.status_word.val() | self.m_busy.val();
        }
        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_control.val() {
            self.read_data.next = self.control.q.val();
        }
        if self.address.val() == self.a_period.val() {
            self.read_data.next = bit_cast::<32, 16>(self.pwm_period.q.val());
        }
        if self.address.val() == self.a_status.val() {
            self.read_data.next = self.status_word.val();
        }
        if self.address.val() == self.a_output.val() {
            self.read_data.next = bit_cast::<32, 16>(self.engine.duty.val())
                | (bit_cast::<32, 16>(self.engine.speed.val()) << 16);
        }
        if self.address.val() == self.a_power.val() {
            self.read_data.next = self.power.q.val();
        }

        if self.reset.val() {
            self.control.d.next = self.zero32.val();
            self.pwm_period.d.next = self.zero16.val();
            self.entry.d.next = self.zero32.val();
            self.power.d.next = self.zero32.val();
            self.active.d.next = false;
            self.overflow.d.next = false;
            self.busy_prev.d.next = false;
        }
    }
}
