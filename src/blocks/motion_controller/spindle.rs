//! The spindle unit: the spindle encoder's decoder, its position, index
//! and speed registers, and the electronic gearbox that steps one axis in
//! ratio to it (build option `SPINDLE`).
//!
//! Internal to [`super::MotionController`]; the behavior is specified in
//! [`super`] ("Spindle encoder and electronic gearbox") and modelled by
//! [`super::spindle_model::SpindleModel`].
//!
//! The encoder is a [`QuadratureDecoder`] that is never cleared, so its
//! count moves by at most one a clock and its two low bits tell a count and
//! its direction: that is the gearbox's `count_up`/`count_down`, one clock
//! after the count changes. The decoder's index is acted on at every event
//! and re-armed in the next clock, so `index_seen` is a one-clock strobe
//! per event: the gearbox's `index`. The gearbox is
//! [`ElectronicGearbox`]; its steps leave as a one-clock strobe to the
//! selected axis, which merges them with its interpolator's (see
//! [`super::axis`]).

use rust_hdl::prelude::*;

use super::registers::{fields, spindle, GEAR_BITS};
use super::POSITION_BITS;
use crate::blocks::electronic_gearbox::ElectronicGearbox;
use crate::blocks::quadrature_decoder::QuadratureDecoder;

/// The gearbox's lag width E (the exported gearbox's).
const GEAR_LAG_BITS: usize = 40;
/// Width of the ratio, ramp and length registers.
const GEAR_WIDTH: usize = GEAR_BITS as usize;
/// Width of the speed window's clock counter: windows of up to 2^31 clocks.
const WINDOW_COUNTER_BITS: usize = 32;

field_slices! {
    /// The multi-bit fields the unit takes from the bus's write data.
    trait SpindleFields {
        get_value_filter / get_my_offset_filter / get_my_width_filter =
            (fields::SPINDLE_FILTER, fields::SPINDLE_FILTER_WIDTH);
        get_value_window / get_my_offset_window / get_my_width_window =
            (fields::SPINDLE_SPEED_WINDOW, fields::SPINDLE_SPEED_WINDOW_WIDTH);
        get_value_axis / get_my_offset_axis / get_my_width_axis =
            (fields::GEAR_AXIS, fields::GEAR_AXIS_WIDTH);
        get_value_gear / get_my_offset_gear / get_my_width_gear =
            (fields::VALUE, GEAR_BITS);
    }
}

// Single bits are taken at literal indices (rust-hdl prints a named
// constant by name); each is tied to the map here.
const _: () = {
    assert!(fields::SPINDLE_COUNTER_MODE == 4 && fields::SPINDLE_INDEX_INVERT == 5);
    assert!(fields::GEAR_ARM == 0 && fields::GEAR_STOP == 1 && fields::GEAR_HALT == 2);
    assert!(fields::GEAR_CLEAR_ENCODER_ERROR == 3);
    assert!(fields::GEAR_SPINDLE_REVERSE == 4 && fields::GEAR_AXIS_REVERSE == 5);
    assert!(fields::GEAR_PHASE == 0 && fields::GEAR_PHASE_WIDTH == 3);
    assert!(fields::GEAR_LOCKED == 3 && fields::GEAR_DONE == 4 && fields::GEAR_INVALID == 5);
    assert!(fields::GEAR_OVERRUN == 6 && fields::GEAR_ENCODER_ERROR == 7);
    assert!(GEAR_BITS as usize == POSITION_BITS);
    assert!(fields::GEAR_AXIS_WIDTH == 3);
};

/// The spindle unit of a `K`-axis controller. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct SpindleUnit<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Pin: spindle encoder A, asynchronous.
    pub spindle_a: Signal<In, Bit>,
    /// Pin: spindle encoder B, asynchronous.
    pub spindle_b: Signal<In, Bit>,
    /// Pin: spindle encoder index, asynchronous.
    pub spindle_index: Signal<In, Bit>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data, its low 24 bits (every field and number of the
    /// window).
    pub write_data: Signal<In, Bits<GEAR_WIDTH>>,
    /// The controller aborts: halt the gearbox.
    pub abort: Signal<In, Bit>,
    /// The addressed register of the window, 0 outside it.
    pub read_data: Signal<Out, Bits<32>>,
    /// Bit k: a gearbox step for axis k in this clock.
    pub step: Signal<Out, Bits<K>>,
    /// That step's direction: 1 = forward.
    pub step_forward: Signal<Out, Bit>,
    /// A `STATUS.SPINDLE` cause rose in this clock.
    pub cause: Signal<Out, Bit>,

    decoder: QuadratureDecoder<POSITION_BITS, 1, 1>,
    gearbox: ElectronicGearbox<GEAR_WIDTH, GEAR_LAG_BITS, GEAR_WIDTH>,
    /// SPINDLE_CONFIG and GEAR_CONTROL's read-write bits, in place.
    settings: DFF<Bits<GEAR_WIDTH>>,
    control: DFF<Bits<GEAR_WIDTH>>,
    numerator: DFF<Bits<GEAR_WIDTH>>,
    denominator: DFF<Bits<GEAR_WIDTH>>,
    ramp: DFF<Bits<GEAR_WIDTH>>,
    length: DFF<Bits<GEAR_WIDTH>>,
    /// The decoder's two low count bits in the last clock.
    count_low: DFF<Bits<2>>,
    clocks: DFF<Bits<WINDOW_COUNTER_BITS>>,
    window_bit: DFF<Bit>,
    window_start: DFF<Bits<POSITION_BITS>>,
    speed: DFF<Bits<POSITION_BITS>>,
    axis_invalid: DFF<Bit>,
    /// DONE, INVALID, OVERRUN and ENCODER_ERROR in the last clock.
    flags_prev: DFF<Bits<4>>,

    control_write: Signal<Local, Bit>,
    idle: Signal<Local, Bit>,
    control_now: Signal<Local, Bits<GEAR_WIDTH>>,
    arm_request: Signal<Local, Bit>,
    axis_ok: Signal<Local, Bit>,
    counted: Signal<Local, Bit>,
    count_forward: Signal<Local, Bit>,
    window_shifted: Signal<Local, Bits<WINDOW_COUNTER_BITS>>,
    window_bit_now: Signal<Local, Bit>,
    flags: Signal<Local, Bits<4>>,
    invalid: Signal<Local, Bit>,
    /// The addressed register's low 24 bits (every register of the
    /// window fits them), and whether it is a signed one.
    read_wide: Signal<Local, Bits<GEAR_WIDTH>>,
    read_signed: Signal<Local, Bit>,
    status_word: Signal<Local, Bits<GEAR_WIDTH>>,

    a_position: Constant<Bits<8>>,
    a_index: Constant<Bits<8>>,
    a_speed: Constant<Bits<8>>,
    a_config: Constant<Bits<8>>,
    a_control: Constant<Bits<8>>,
    a_status: Constant<Bits<8>>,
    a_numerator: Constant<Bits<8>>,
    a_denominator: Constant<Bits<8>>,
    a_ramp: Constant<Bits<8>>,
    a_length: Constant<Bits<8>>,
    a_gear_position: Constant<Bits<8>>,
    axes: Constant<Bits<3>>,
    axis_bit: [Constant<Bits<3>>; K],
    config_reset: Constant<Bits<GEAR_WIDTH>>,
    config_mask: Constant<Bits<GEAR_WIDTH>>,
    control_mask: Constant<Bits<GEAR_WIDTH>>,
    one_clock: Constant<Bits<WINDOW_COUNTER_BITS>>,
    sign: Constant<Bits<POSITION_BITS>>,
    extension: Constant<Bits<32>>,
    zero_position: Constant<Bits<POSITION_BITS>>,
    zero_gear: Constant<Bits<GEAR_WIDTH>>,
    zero_phase: Constant<Bits<3>>,
    zero1: Constant<Bits<1>>,
    zero2: Constant<Bits<2>>,
    zero4: Constant<Bits<4>>,
    flag_done: Constant<Bits<4>>,
    flag_invalid: Constant<Bits<4>>,
    flag_overrun: Constant<Bits<4>>,
    flag_encoder: Constant<Bits<4>>,
    zero_clocks: Constant<Bits<WINDOW_COUNTER_BITS>>,
    zero_k: Constant<Bits<K>>,
    k_bit: [Constant<Bits<K>>; K],
    m_phase: [Constant<Bits<GEAR_WIDTH>>; 3],
    m_locked: Constant<Bits<GEAR_WIDTH>>,
    m_done: Constant<Bits<GEAR_WIDTH>>,
    m_invalid: Constant<Bits<GEAR_WIDTH>>,
    m_overrun: Constant<Bits<GEAR_WIDTH>>,
    m_encoder_error: Constant<Bits<GEAR_WIDTH>>,
}

impl<const K: usize> Default for SpindleUnit<K> {
    fn default() -> Self {
        // AXIS is 3 bits; a controller with the unit has at most
        // MAX_AXES_SPINDLE axes (its register map refuses more).
        assert!((1..=8).contains(&K), "SpindleUnit: 1 to 8 axes");
        let a = |address: u32| Constant::new((address as u64).into());
        let m = |bit: u32| Constant::new((1u64 << bit).into());
        let field_mask = |lsb: u32, width: u32| crate::blocks::width_mask(width) << lsb;
        let config_mask = field_mask(fields::SPINDLE_FILTER, fields::SPINDLE_FILTER_WIDTH)
            | field_mask(fields::SPINDLE_COUNTER_MODE, 1)
            | field_mask(fields::SPINDLE_INDEX_INVERT, 1)
            | field_mask(
                fields::SPINDLE_SPEED_WINDOW,
                fields::SPINDLE_SPEED_WINDOW_WIDTH,
            );
        let control_mask = field_mask(fields::GEAR_SPINDLE_REVERSE, 1)
            | field_mask(fields::GEAR_AXIS_REVERSE, 1)
            | field_mask(fields::GEAR_AXIS, fields::GEAR_AXIS_WIDTH);
        Self {
            clock: Default::default(),
            reset: Default::default(),
            spindle_a: Default::default(),
            spindle_b: Default::default(),
            spindle_index: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            abort: Default::default(),
            read_data: Default::default(),
            step: Default::default(),
            step_forward: Default::default(),
            cause: Default::default(),
            decoder: Default::default(),
            gearbox: Default::default(),
            settings: Default::default(),
            control: Default::default(),
            numerator: Default::default(),
            denominator: Default::default(),
            ramp: Default::default(),
            length: Default::default(),
            count_low: Default::default(),
            clocks: Default::default(),
            window_bit: Default::default(),
            window_start: Default::default(),
            speed: Default::default(),
            axis_invalid: Default::default(),
            flags_prev: Default::default(),
            control_write: Default::default(),
            idle: Default::default(),
            control_now: Default::default(),
            arm_request: Default::default(),
            axis_ok: Default::default(),
            counted: Default::default(),
            count_forward: Default::default(),
            window_shifted: Default::default(),
            window_bit_now: Default::default(),
            flags: Default::default(),
            invalid: Default::default(),
            read_wide: Default::default(),
            read_signed: Default::default(),
            status_word: Default::default(),
            a_position: a(spindle::SPINDLE_POSITION),
            a_index: a(spindle::SPINDLE_INDEX_POSITION),
            a_speed: a(spindle::SPINDLE_SPEED),
            a_config: a(spindle::SPINDLE_CONFIG),
            a_control: a(spindle::GEAR_CONTROL),
            a_status: a(spindle::GEAR_STATUS),
            a_numerator: a(spindle::GEAR_NUMERATOR),
            a_denominator: a(spindle::GEAR_DENOMINATOR),
            a_ramp: a(spindle::GEAR_RAMP),
            a_length: a(spindle::GEAR_LENGTH),
            a_gear_position: a(spindle::GEAR_POSITION),
            axes: Constant::new((K as u64).into()),
            axis_bit: array_init::array_init(|k| Constant::new((k as u64).into())),
            config_reset: Constant::new(
                (fields::SPINDLE_SPEED_WINDOW_RESET << fields::SPINDLE_SPEED_WINDOW).into(),
            ),
            config_mask: Constant::new(config_mask.into()),
            control_mask: Constant::new(control_mask.into()),
            one_clock: Constant::new(1u64.into()),
            sign: Constant::new((1u64 << (POSITION_BITS - 1)).into()),
            extension: Constant::new(
                ((u32::MAX as u64) & !crate::blocks::width_mask(POSITION_BITS as u32)).into(),
            ),
            zero_position: Constant::new(0u64.into()),
            zero_gear: Constant::new(0u64.into()),
            zero_phase: Constant::new(0u64.into()),
            zero1: Constant::new(0u64.into()),
            zero2: Constant::new(0u64.into()),
            zero4: Constant::new(0u64.into()),
            flag_done: Constant::new(1u64.into()),
            flag_invalid: Constant::new(2u64.into()),
            flag_overrun: Constant::new(4u64.into()),
            flag_encoder: Constant::new(8u64.into()),
            zero_clocks: Constant::new(0u64.into()),
            zero_k: Constant::new(0u64.into()),
            k_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
            m_phase: array_init::array_init(|b| m(fields::GEAR_PHASE + b as u32)),
            m_locked: m(fields::GEAR_LOCKED),
            m_done: m(fields::GEAR_DONE),
            m_invalid: m(fields::GEAR_INVALID),
            m_overrun: m(fields::GEAR_OVERRUN),
            m_encoder_error: m(fields::GEAR_ENCODER_ERROR),
        }
    }
}

impl<const K: usize> Logic for SpindleUnit<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            settings,
            control,
            numerator,
            denominator,
            ramp,
            length,
            count_low,
            clocks,
            window_bit,
            window_start,
            speed,
            axis_invalid,
            flags_prev
        );
        clock!(self, clock, decoder, gearbox);

        // Configuration and ratio registers.
        self.control_write.next = self.write.val() & (self.address.val() == self.a_control.val());
        if self.write.val() & (self.address.val() == self.a_config.val()) {
            self.settings.d.next = self.write_data.val() & self.config_mask.val();
        }
        if self.write.val() & (self.address.val() == self.a_numerator.val()) {
            self.numerator.d.next = self.write_data.val().get_value_gear();
        }
        if self.write.val() & (self.address.val() == self.a_denominator.val()) {
            self.denominator.d.next = self.write_data.val().get_value_gear();
        }
        if self.write.val() & (self.address.val() == self.a_ramp.val()) {
            self.ramp.d.next = self.write_data.val().get_value_gear();
        }
        if self.write.val() & (self.address.val() == self.a_length.val()) {
            self.length.d.next = self.write_data.val().get_value_gear();
        }

        // The encoder: never cleared, the index acted on at every event
        // and re-armed in the next clock.
        self.decoder.reset.next = self.reset.val();
        self.decoder.a.next = self.spindle_a.val();
        self.decoder.b.next = self.spindle_b.val();
        self.decoder.index.next = self.spindle_index.val();
        self.decoder.filter.next = self.settings.q.val().get_value_filter();
        self.decoder.clear.next = false;
        self.decoder.sample_rate.next = self.zero1.val();
        self.decoder.counter_mode.next = self.settings.q.val().get_bit(4);
        self.decoder.index_invert.next = self.settings.q.val().get_bit(5);
        self.decoder.index_clear.next = false;
        self.decoder.index_latch.next = true;
        self.decoder.index_once.next = false;
        self.decoder.index_rearm.next = self.decoder.index_seen.val();
        self.decoder.clear_error.next = self.control_write.val() & self.write_data.val().get_bit(3);

        // A count changes the low bit; +1 makes bit 1 the XOR of the old
        // two, -1 its complement.
        self.count_low.d.next = self.decoder.count.val().get_bits::<2>(0);
        self.counted.next =
            self.decoder.count.val().get_bit(0) != self.count_low.q.val().get_bit(0);
        self.count_forward.next = self.decoder.count.val().get_bit(1)
            == (self.count_low.q.val().get_bit(1) ^ self.count_low.q.val().get_bit(0));

        // GEAR_CONTROL: the directions and the axis are written while idle
        // (an arm's own write included), the strobes at any time.
        self.idle.next = self.gearbox.phase.val() == self.zero_phase.val();
        self.control_now.next = self.control.q.val();
        if self.control_write.val() & self.idle.val() {
            self.control_now.next = self.write_data.val() & self.control_mask.val();
        }
        self.control.d.next = self.control_now.val();
        self.arm_request.next = self.control_write.val() & self.write_data.val().get_bit(0);
        self.axis_ok.next = self.control_now.val().get_value_axis() < self.axes.val();
        if self.arm_request.val() & self.idle.val() {
            self.axis_invalid.d.next = !self.axis_ok.val();
        }

        self.gearbox.reset.next = self.reset.val();
        self.gearbox.count_up.next = self.counted.val() & self.count_forward.val();
        self.gearbox.count_down.next = self.counted.val() & !self.count_forward.val();
        self.gearbox.index.next = self.decoder.index_seen.val();
        self.gearbox.arm.next = self.arm_request.val() & self.axis_ok.val();
        self.gearbox.stop.next = self.control_write.val() & self.write_data.val().get_bit(1);
        self.gearbox.halt.next =
            (self.control_write.val() & self.write_data.val().get_bit(2)) | self.abort.val();
        self.gearbox.spindle_reverse.next = self.control_now.val().get_bit(4);
        self.gearbox.axis_reverse.next = self.control_now.val().get_bit(5);
        self.gearbox.numerator.next = self.numerator.q.val();
        self.gearbox.denominator.next = self.denominator.q.val();
        self.gearbox.ramp.next = self.ramp.q.val();
        self.gearbox.length.next = self.length.q.val();

        // The gearbox's registered step, to the axis taken at the arm.
        self.step.next = self.zero_k.val();
        for k in 0..K {
            if (self.gearbox.step_up.val() | self.gearbox.step_down.val())
                & (self.control.q.val().get_value_axis() == self.axis_bit[k].val())
            {
                self.step.next = self.step.val() | self.k_bit[k].val();
            }
        }
        self.step_forward.next = self.gearbox.step_up.val();

        // Speed: the count's change over each window, whose end is a
        // change of the clock counter's bit n.
        self.clocks.d.next = self.clocks.q.val() + self.one_clock.val();
        // (rust-hdl prints a bit select of an expression as illegal
        // Verilog: the shift goes through a signal.)
        self.window_shifted.next = self.clocks.q.val() >> self.settings.q.val().get_value_window();
        self.window_bit_now.next = self.window_shifted.val().get_bit(0);
        self.window_bit.d.next = self.window_bit_now.val();
        if self.window_bit_now.val() != self.window_bit.q.val() {
            self.speed.d.next = self.decoder.count.val() - self.window_start.q.val();
            self.window_start.d.next = self.decoder.count.val();
        }

        // STATUS.SPINDLE: a rise of DONE, INVALID, OVERRUN or ENCODER_ERROR.
        self.invalid.next = self.gearbox.invalid.val() | self.axis_invalid.q.val();
        self.flags.next = self.zero4.val();
        if self.gearbox.done.val() {
            self.flags.next = self.flags.val() | self.flag_done.val();
        }
        if self.invalid.val() {
            self.flags.next = self.flags.val() | self.flag_invalid.val();
        }
        if self.gearbox.overrun.val() {
            self.flags.next = self.flags.val() | self.flag_overrun.val();
        }
        if self.decoder.error.val() {
            self.flags.next = self.flags.val() | self.flag_encoder.val();
        }
        self.flags_prev.d.next = self.flags.val();
        self.cause.next = (self.flags.val() & !self.flags_prev.q.val()) != self.zero4.val();

        // Reads: every register of the window fits 24 bits; the signed
        // ones carry their sign up to bit 31.
        self.status_word.next = self.zero_gear.val();
        for b in 0..3 {
            if self.gearbox.phase.val().get_bit(b) {
                self.status_word.next = self.status_word.val() | self.m_phase[b].val();
            }
        }
        if self.gearbox.locked.val() {
            self.status_word.next = self.status_word.val() | self.m_locked.val();
        }
        if self.gearbox.done.val() {
            self.status_word.next = self.status_word.val() | self.m_done.val();
        }
        if self.invalid.val() {
            self.status_word.next = self.status_word.val() | self.m_invalid.val();
        }
        if self.gearbox.overrun.val() {
            self.status_word.next = self.status_word.val() | self.m_overrun.val();
        }
        if self.decoder.error.val() {
            self.status_word.next = self.status_word.val() | self.m_encoder_error.val();
        }
        self.read_wide.next = self.zero_gear.val();
        self.read_signed.next = false;
        if self.address.val() == self.a_position.val() {
            self.read_wide.next = self.decoder.count.val();
            self.read_signed.next = true;
        }
        if self.address.val() == self.a_index.val() {
            self.read_wide.next = self.read_wide.val() | self.decoder.index_count.val();
            self.read_signed.next = true;
        }
        if self.address.val() == self.a_speed.val() {
            self.read_wide.next = self.read_wide.val() | self.speed.q.val();
            self.read_signed.next = true;
        }
        if self.address.val() == self.a_gear_position.val() {
            self.read_wide.next = self.read_wide.val() | self.gearbox.position.val();
            self.read_signed.next = true;
        }
        if self.address.val() == self.a_config.val() {
            self.read_wide.next = self.read_wide.val() | self.settings.q.val();
        }
        if self.address.val() == self.a_control.val() {
            self.read_wide.next = self.read_wide.val() | self.control.q.val();
        }
        if self.address.val() == self.a_status.val() {
            self.read_wide.next = self.read_wide.val() | self.status_word.val();
        }
        if self.address.val() == self.a_numerator.val() {
            self.read_wide.next = self.read_wide.val() | self.numerator.q.val();
        }
        if self.address.val() == self.a_denominator.val() {
            self.read_wide.next = self.read_wide.val() | self.denominator.q.val();
        }
        if self.address.val() == self.a_ramp.val() {
            self.read_wide.next = self.read_wide.val() | self.ramp.q.val();
        }
        if self.address.val() == self.a_length.val() {
            self.read_wide.next = self.read_wide.val() | self.length.q.val();
        }
        self.read_data.next = bit_cast::<32, GEAR_WIDTH>(self.read_wide.val());
        if self.read_signed.val()
            & ((self.read_wide.val() & self.sign.val()) != self.zero_gear.val())
        {
            self.read_data.next = self.read_data.val() | self.extension.val();
        }

        if self.reset.val() {
            self.settings.d.next = self.config_reset.val();
            self.control.d.next = self.zero_gear.val();
            self.numerator.d.next = self.zero_gear.val();
            self.denominator.d.next = self.zero_gear.val();
            self.ramp.d.next = self.zero_gear.val();
            self.length.d.next = self.zero_gear.val();
            self.count_low.d.next = self.zero2.val();
            self.clocks.d.next = self.zero_clocks.val();
            self.window_bit.d.next = false;
            self.window_start.d.next = self.zero_position.val();
            self.speed.d.next = self.zero_position.val();
            self.axis_invalid.d.next = false;
            self.flags_prev.d.next = self.zero4.val();
        }
    }
}
