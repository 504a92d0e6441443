//! The controller-wide machine I/O: the input conditioners of every
//! switch, alarm, E-stop and general input, the filter's sample clock, the
//! E-stop latch, the general outputs and their registers (`INPUT_FILTER`,
//! `INPUT_POLARITY`, `GPIO_IN` to `GPIO_EDGES`).
//!
//! Internal to [`super::MotionController`]; the behavior is specified in
//! [`super`] ("Machine I/O and safety") and modelled by
//! [`super::io_model::MachineIoModel`].
//!
//! Formal proof: `formal/motion_controller_machine_io.sv` (the E-stop's
//! conditioning at the reset `INPUT_FILTER`, and its latch; see the
//! controller's datasheet, "Formal proof").

use rust_hdl::prelude::*;

use super::registers::{fields, global};
use crate::blocks::input_conditioner::InputConditioner;

field_slices! {
    /// The register fields `update()` takes from a register or a written
    /// word, placed by the map.
    trait MachineIoFields {
        get_value_filter_length / get_my_offset_filter_length / get_my_width_filter_length =
            (fields::FILTER_LENGTH, fields::FILTER_LENGTH_WIDTH);
        get_value_filter_sample_rate / get_my_offset_filter_sample_rate / get_my_width_filter_sample_rate =
            (fields::FILTER_SAMPLE_RATE, fields::FILTER_SAMPLE_RATE_WIDTH);
        get_value_polarity_gpio / get_my_offset_polarity_gpio / get_my_width_polarity_gpio =
            (fields::POLARITY_GPIO, fields::GPIO_WIDTH);
        /// `GPIO_OUT.LEVEL`, `GPIO_SAFE.MASK`.
        get_value_gpio_level / get_my_offset_gpio_level / get_my_width_gpio_level =
            (fields::GPIO_LEVEL, fields::GPIO_WIDTH);
        /// `GPIO_IRQ_ENABLE` and `GPIO_EDGES`: `RISE` and `FALL` together.
        get_value_gpio_edges / get_my_offset_gpio_edges / get_my_width_gpio_edges =
            (fields::GPIO_RISE, 2 * fields::GPIO_WIDTH);
    }
}

// The edge registers are held as one word of RISE then FALL, and the
// general I/O ports and the per-bit loops of `update()` are 8 wide.
const _: () =
    assert!(fields::GPIO_FALL == fields::GPIO_RISE + fields::GPIO_WIDTH && fields::GPIO_WIDTH == 8);

/// Machine I/O shared by `K` axes. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct MachineIo<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Pins: positive limit per axis.
    pub limit_pos: Signal<In, Bits<K>>,
    /// Pins: negative limit per axis.
    pub limit_neg: Signal<In, Bits<K>>,
    /// Pins: home per axis.
    pub home: Signal<In, Bits<K>>,
    /// Pins: drive alarm per axis.
    pub drive_alarm: Signal<In, Bits<K>>,
    /// Pin: E-stop chain.
    pub estop: Signal<In, Bit>,
    /// Pins: general inputs.
    pub gpio_in: Signal<In, Bits<8>>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data.
    pub write_data: Signal<In, Bits<32>>,
    /// STATUS.ESTOP written 1: release the latch if the input is inactive.
    pub estop_clear: Signal<In, Bit>,
    /// The watchdog has expired.
    pub watchdog_expired: Signal<In, Bit>,
    /// Active levels, polarity applied.
    pub limit_pos_active: Signal<Out, Bits<K>>,
    /// Active levels.
    pub limit_neg_active: Signal<Out, Bits<K>>,
    /// Active levels.
    pub home_active: Signal<Out, Bits<K>>,
    /// Home became active at the last edge.
    pub home_rise: Signal<Out, Bits<K>>,
    /// Active levels.
    pub alarm_active: Signal<Out, Bits<K>>,
    /// The E-stop input is active.
    pub estop_active: Signal<Out, Bit>,
    /// The E-stop latch.
    pub estop_latched: Signal<Out, Bit>,
    /// The E-stop latch after the next edge.
    pub estop_latched_next: Signal<Out, Bit>,
    /// The E-stop latch rises at this edge.
    pub estop_event: Signal<Out, Bit>,
    /// An enabled general-input edge at the last edge.
    pub gpio_event: Signal<Out, Bit>,
    /// General output pins, registered.
    pub gpio_out: Signal<Out, Bits<8>>,
    /// The conditioners are primed.
    pub ready: Signal<Out, Bit>,
    /// This edge is a filter sample (for the probe's conditioner).
    pub filter_sample: Signal<Out, Bit>,
    /// `INPUT_FILTER.LENGTH` (for the probe's conditioner).
    pub filter_length: Signal<Out, Bits<4>>,
    /// The addressed register of this block, 0 otherwise.
    pub read_data: Signal<Out, Bits<32>>,

    limit_pos_in: InputConditioner<K>,
    limit_neg_in: InputConditioner<K>,
    home_in: InputConditioner<K>,
    alarm_in: InputConditioner<K>,
    estop_in: InputConditioner<1>,
    gpio: InputConditioner<8>,

    /// INPUT_FILTER XOR its reset value (so power-up reads the reset
    /// value); LENGTH and SAMPLE_RATE, other bits always 0.
    filter_x: DFF<Bits<32>>,
    filter: Signal<Local, Bits<32>>,
    /// INPUT_POLARITY.
    polarity: DFF<Bits<32>>,
    /// Clocks to the next filter sample.
    sample_count: DFF<Bits<8>>,
    estop_latch: DFF<Bit>,
    gpio_out_reg: DFF<Bits<8>>,
    gpio_safe: DFF<Bits<8>>,
    /// GPIO_IRQ_ENABLE: RISE in bits 7..0, FALL in 15..8.
    gpio_irq_enable: DFF<Bits<16>>,
    /// GPIO_EDGES: RISE in bits 7..0, FALL in 15..8.
    gpio_edges: DFF<Bits<16>>,

    sample: Signal<Local, Bit>,
    estop_vec: Signal<Local, Bits<1>>,
    gpio_out_next: Signal<Local, Bits<8>>,
    estop_next: Signal<Local, Bit>,
    invert_limit_pos: Signal<Local, Bits<K>>,
    invert_limit_neg: Signal<Local, Bits<K>>,
    invert_home: Signal<Local, Bits<K>>,
    invert_alarm: Signal<Local, Bits<K>>,
    edges_now: Signal<Local, Bits<16>>,
    gpio_edges_next: Signal<Local, Bits<16>>,
    gpio_word: Signal<Local, Bits<32>>,
    safe_word: Signal<Local, Bits<32>>,
    out_word: Signal<Local, Bits<32>>,
    irq_word: Signal<Local, Bits<32>>,
    edges_word: Signal<Local, Bits<32>>,

    a_filter: Constant<Bits<8>>,
    a_polarity: Constant<Bits<8>>,
    a_gpio_in: Constant<Bits<8>>,
    a_gpio_out: Constant<Bits<8>>,
    a_gpio_safe: Constant<Bits<8>>,
    a_gpio_irq_enable: Constant<Bits<8>>,
    a_gpio_edges: Constant<Bits<8>>,
    filter_mask: Constant<Bits<32>>,
    filter_reset: Constant<Bits<32>>,
    polarity_mask: Constant<Bits<32>>,
    p_limit_pos: Constant<Bits<32>>,
    p_limit_neg: Constant<Bits<32>>,
    p_home: Constant<Bits<32>>,
    p_alarm: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    zero16: Constant<Bits<16>>,
    zero8: Constant<Bits<8>>,
    one8: Constant<Bits<8>>,
    zero_k: Constant<Bits<K>>,
    ones_k: Constant<Bits<K>>,
    zero1: Constant<Bits<1>>,
    one1: Constant<Bits<1>>,
    /// GPIO_EDGES.RISE / FALL bit of general input i.
    rise_mask: [Constant<Bits<16>>; 8],
    fall_mask: [Constant<Bits<16>>; 8],
    /// 1 << i in 32 bits, to zero-extend the narrow registers.
    bit_mask: [Constant<Bits<32>>; 16],
}

impl<const K: usize> Default for MachineIo<K> {
    fn default() -> Self {
        let a8 = |v: u32| Constant::new((v as u64).into());
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            limit_pos: Default::default(),
            limit_neg: Default::default(),
            home: Default::default(),
            drive_alarm: Default::default(),
            estop: Default::default(),
            gpio_in: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            estop_clear: Default::default(),
            watchdog_expired: Default::default(),
            limit_pos_active: Default::default(),
            limit_neg_active: Default::default(),
            home_active: Default::default(),
            home_rise: Default::default(),
            alarm_active: Default::default(),
            estop_active: Default::default(),
            estop_latched: Default::default(),
            estop_latched_next: Default::default(),
            estop_event: Default::default(),
            gpio_event: Default::default(),
            gpio_out: Default::default(),
            ready: Default::default(),
            filter_sample: Default::default(),
            filter_length: Default::default(),
            read_data: Default::default(),
            limit_pos_in: Default::default(),
            limit_neg_in: Default::default(),
            home_in: Default::default(),
            alarm_in: Default::default(),
            estop_in: Default::default(),
            gpio: Default::default(),
            filter_x: Default::default(),
            filter: Default::default(),
            polarity: Default::default(),
            sample_count: Default::default(),
            estop_latch: Default::default(),
            gpio_out_reg: Default::default(),
            gpio_safe: Default::default(),
            gpio_irq_enable: Default::default(),
            gpio_edges: Default::default(),
            sample: Default::default(),
            estop_vec: Default::default(),
            gpio_out_next: Default::default(),
            estop_next: Default::default(),
            invert_limit_pos: Default::default(),
            invert_limit_neg: Default::default(),
            invert_home: Default::default(),
            invert_alarm: Default::default(),
            edges_now: Default::default(),
            gpio_edges_next: Default::default(),
            gpio_word: Default::default(),
            safe_word: Default::default(),
            out_word: Default::default(),
            irq_word: Default::default(),
            edges_word: Default::default(),
            a_filter: a8(global::INPUT_FILTER),
            a_polarity: a8(global::INPUT_POLARITY),
            a_gpio_in: a8(global::GPIO_IN),
            a_gpio_out: a8(global::GPIO_OUT),
            a_gpio_safe: a8(global::GPIO_SAFE),
            a_gpio_irq_enable: a8(global::GPIO_IRQ_ENABLE),
            a_gpio_edges: a8(global::GPIO_EDGES),
            filter_mask: Constant::new(
                ((0xfu64 << fields::FILTER_LENGTH) | (0xffu64 << fields::FILTER_SAMPLE_RATE))
                    .into(),
            ),
            filter_reset: Constant::new(
                (fields::FILTER_LENGTH_RESET << fields::FILTER_LENGTH).into(),
            ),
            polarity_mask: Constant::new(
                ((1u64 << fields::POLARITY_LIMIT_POS)
                    | (1u64 << fields::POLARITY_LIMIT_NEG)
                    | (1u64 << fields::POLARITY_HOME)
                    | (1u64 << fields::POLARITY_DRIVE_ALARM)
                    | (0xffu64 << fields::POLARITY_GPIO))
                    .into(),
            ),
            p_limit_pos: m32(fields::POLARITY_LIMIT_POS),
            p_limit_neg: m32(fields::POLARITY_LIMIT_NEG),
            p_home: m32(fields::POLARITY_HOME),
            p_alarm: m32(fields::POLARITY_DRIVE_ALARM),
            zero32: Constant::new(0u64.into()),
            zero16: Constant::new(0u64.into()),
            zero8: Constant::new(0u64.into()),
            one8: Constant::new(1u64.into()),
            zero_k: Constant::new(0u64.into()),
            ones_k: Constant::new(crate::blocks::width_mask(K as u32).into()),
            zero1: Constant::new(0u64.into()),
            one1: Constant::new(1u64.into()),
            rise_mask: array_init::array_init(|i| {
                Constant::new((1u64 << (fields::GPIO_RISE as usize + i)).into())
            }),
            fall_mask: array_init::array_init(|i| {
                Constant::new((1u64 << (fields::GPIO_FALL as usize + i)).into())
            }),
            bit_mask: array_init::array_init(|i| Constant::new((1u64 << i).into())),
        }
    }
}

impl<const K: usize> Logic for MachineIo<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            filter_x,
            polarity,
            sample_count,
            estop_latch,
            gpio_out_reg,
            gpio_safe,
            gpio_irq_enable,
            gpio_edges
        );
        clock!(
            self,
            clock,
            limit_pos_in,
            limit_neg_in,
            home_in,
            alarm_in,
            estop_in,
            gpio
        );

        // INPUT_FILTER and INPUT_POLARITY.
        self.filter.next = self.filter_x.q.val() ^ self.filter_reset.val();
        if self.write.val() & (self.address.val() == self.a_filter.val()) {
            self.filter_x.d.next =
                (self.write_data.val() & self.filter_mask.val()) ^ self.filter_reset.val();
        }
        if self.write.val() & (self.address.val() == self.a_polarity.val()) {
            self.polarity.d.next = self.write_data.val() & self.polarity_mask.val();
        }
        if self.reset.val() {
            self.filter_x.d.next = self.zero32.val();
            self.polarity.d.next = self.zero32.val();
        }

        // One filter sample every SAMPLE_RATE + 1 clocks, for every input.
        self.sample.next = self.sample_count.q.val() == self.zero8.val();
        self.sample_count.d.next = self.sample_count.q.val() - self.one8.val();
        if self.sample.val() {
            self.sample_count.d.next = self.filter.val().get_value_filter_sample_rate();
        }
        if self.reset.val() {
            self.sample_count.d.next = self.zero8.val();
        }
        self.filter_sample.next = self.sample.val();
        self.filter_length.next = self.filter.val().get_value_filter_length();

        // Conditioners: one polarity bit per class.
        self.invert_limit_pos.next = self.zero_k.val();
        if (self.polarity.q.val() & self.p_limit_pos.val()) != self.zero32.val() {
            self.invert_limit_pos.next = self.ones_k.val();
        }
        self.invert_limit_neg.next = self.zero_k.val();
        if (self.polarity.q.val() & self.p_limit_neg.val()) != self.zero32.val() {
            self.invert_limit_neg.next = self.ones_k.val();
        }
        self.invert_home.next = self.zero_k.val();
        if (self.polarity.q.val() & self.p_home.val()) != self.zero32.val() {
            self.invert_home.next = self.ones_k.val();
        }
        self.invert_alarm.next = self.zero_k.val();
        if (self.polarity.q.val() & self.p_alarm.val()) != self.zero32.val() {
            self.invert_alarm.next = self.ones_k.val();
        }
        self.limit_pos_in.reset.next = self.reset.val();
        self.limit_pos_in.raw.next = self.limit_pos.val();
        self.limit_pos_in.invert.next = self.invert_limit_pos.val();
        self.limit_pos_in.sample.next = self.sample.val();
        self.limit_pos_in.length.next = self.filter.val().get_value_filter_length();
        self.limit_neg_in.reset.next = self.reset.val();
        self.limit_neg_in.raw.next = self.limit_neg.val();
        self.limit_neg_in.invert.next = self.invert_limit_neg.val();
        self.limit_neg_in.sample.next = self.sample.val();
        self.limit_neg_in.length.next = self.filter.val().get_value_filter_length();
        self.home_in.reset.next = self.reset.val();
        self.home_in.raw.next = self.home.val();
        self.home_in.invert.next = self.invert_home.val();
        self.home_in.sample.next = self.sample.val();
        self.home_in.length.next = self.filter.val().get_value_filter_length();
        self.alarm_in.reset.next = self.reset.val();
        self.alarm_in.raw.next = self.drive_alarm.val();
        self.alarm_in.invert.next = self.invert_alarm.val();
        self.alarm_in.sample.next = self.sample.val();
        self.alarm_in.length.next = self.filter.val().get_value_filter_length();
        // E-stop has no polarity: always active high (a broken wire stops).
        self.estop_in.reset.next = self.reset.val();
        self.estop_vec.next = self.zero1.val();
        if self.estop.val() {
            self.estop_vec.next = self.one1.val();
        }
        self.estop_in.raw.next = self.estop_vec.val();
        self.estop_in.invert.next = self.zero1.val();
        self.estop_in.sample.next = self.sample.val();
        self.estop_in.length.next = self.filter.val().get_value_filter_length();
        self.gpio.reset.next = self.reset.val();
        self.gpio.raw.next = self.gpio_in.val();
        self.gpio.invert.next = self.polarity.q.val().get_value_polarity_gpio();
        self.gpio.sample.next = self.sample.val();
        self.gpio.length.next = self.filter.val().get_value_filter_length();

        self.limit_pos_active.next = self.limit_pos_in.active.val();
        self.limit_neg_active.next = self.limit_neg_in.active.val();
        self.home_active.next = self.home_in.active.val();
        self.home_rise.next = self.home_in.rise.val();
        self.alarm_active.next = self.alarm_in.active.val();
        self.estop_active.next = self.estop_in.active.val() != self.zero1.val();
        self.ready.next = self.estop_in.ready.val();

        // E-stop latch: set while the input is active, released by
        // STATUS.ESTOP only once the input is inactive.
        self.estop_next.next = self.estop_latch.q.val();
        if self.estop_clear.val() {
            self.estop_next.next = false;
        }
        if self.estop_in.active.val() != self.zero1.val() {
            self.estop_next.next = true;
        }
        if self.reset.val() {
            self.estop_next.next = false;
        }
        self.estop_latch.d.next = self.estop_next.val();
        self.estop_latched.next = self.estop_latch.q.val();
        self.estop_latched_next.next = self.estop_next.val();
        self.estop_event.next =
            (self.estop_in.active.val() != self.zero1.val()) & !self.estop_latch.q.val();

        // General outputs: the safe ones are cleared, and held 0, from the
        // edge that latches the E-stop and while the watchdog is expired.
        self.gpio_out_next.next = self.gpio_out_reg.q.val();
        if self.write.val() & (self.address.val() == self.a_gpio_out.val()) {
            self.gpio_out_next.next = self.write_data.val().get_value_gpio_level();
        }
        if self.write.val() & (self.address.val() == self.a_gpio_safe.val()) {
            self.gpio_safe.d.next = self.write_data.val().get_value_gpio_level();
        }
        if self.estop_next.val() | self.watchdog_expired.val() {
            self.gpio_out_next.next = self.gpio_out_next.val() & !self.gpio_safe.q.val();
        }
        self.gpio_out_reg.d.next = self.gpio_out_next.val();
        if self.reset.val() {
            self.gpio_out_reg.d.next = self.zero8.val();
            self.gpio_safe.d.next = self.zero8.val();
        }
        self.gpio_out.next = self.gpio_out_reg.q.val();

        // General-input edges: all recorded, the enabled ones interrupt.
        self.edges_now.next = self.zero16.val();
        for i in 0..8 {
            if self.gpio.rise.val().get_bit(i) {
                self.edges_now.next = self.edges_now.val() | self.rise_mask[i].val();
            }
            if self.gpio.fall.val().get_bit(i) {
                self.edges_now.next = self.edges_now.val() | self.fall_mask[i].val();
            }
        }
        if self.write.val() & (self.address.val() == self.a_gpio_irq_enable.val()) {
            self.gpio_irq_enable.d.next = self.write_data.val().get_value_gpio_edges();
        }
        self.gpio_edges_next.next = self.gpio_edges.q.val();
        if self.write.val() & (self.address.val() == self.a_gpio_edges.val()) {
            self.gpio_edges_next.next =
                self.gpio_edges.q.val() & !self.write_data.val().get_value_gpio_edges();
        }
        self.gpio_edges.d.next = self.gpio_edges_next.val() | self.edges_now.val();
        self.gpio_event.next =
            (self.edges_now.val() & self.gpio_irq_enable.q.val()) != self.zero16.val();
        if self.reset.val() {
            self.gpio_irq_enable.d.next = self.zero16.val();
            self.gpio_edges.d.next = self.zero16.val();
        }

        // Reads, zero-extended bit by bit.
        self.gpio_word.next = self.zero32.val();
        self.out_word.next = self.zero32.val();
        self.safe_word.next = self.zero32.val();
        for i in 0..8 {
            if self.gpio.active.val().get_bit(i) {
                self.gpio_word.next = self.gpio_word.val() | self.bit_mask[i].val();
            }
            if self.gpio_out_reg.q.val().get_bit(i) {
                self.out_word.next = self.out_word.val() | self.bit_mask[i].val();
            }
            if self.gpio_safe.q.val().get_bit(i) {
                self.safe_word.next = self.safe_word.val() | self.bit_mask[i].val();
            }
        }
        self.irq_word.next = self.zero32.val();
        self.edges_word.next = self.zero32.val();
        for i in 0..16 {
            if self.gpio_irq_enable.q.val().get_bit(i) {
                self.irq_word.next = self.irq_word.val() | self.bit_mask[i].val();
            }
            if self.gpio_edges.q.val().get_bit(i) {
                self.edges_word.next = self.edges_word.val() | self.bit_mask[i].val();
            }
        }
        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_filter.val() {
            self.read_data.next = self.read_data.val() | self.filter.val();
        }
        if self.address.val() == self.a_polarity.val() {
            self.read_data.next = self.read_data.val() | self.polarity.q.val();
        }
        if self.address.val() == self.a_gpio_in.val() {
            self.read_data.next = self.read_data.val() | self.gpio_word.val();
        }
        if self.address.val() == self.a_gpio_out.val() {
            self.read_data.next = self.read_data.val() | self.out_word.val();
        }
        if self.address.val() == self.a_gpio_safe.val() {
            self.read_data.next = self.read_data.val() | self.safe_word.val();
        }
        if self.address.val() == self.a_gpio_irq_enable.val() {
            self.read_data.next = self.read_data.val() | self.irq_word.val();
        }
        if self.address.val() == self.a_gpio_edges.val() {
            self.read_data.next = self.read_data.val() | self.edges_word.val();
        }
    }
}
