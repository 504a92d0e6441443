//! The controller's global registers on the bus: its register layer apart
//! from the core (as LiteX's `add_csr` keeps a core's CSRs apart from its
//! logic). It decodes the global writes into their flip-flops and strobes,
//! and multiplexes every global register onto one read word.
//!
//! Internal to [`super::MotionController`]; the registers' behavior is the
//! controller's, modelled by [`super::model`], and their fields are the
//! register map's ([`super::registers`]).
//!
//! ## Contract (as the controller uses it)
//! * A write to IRQ_ENABLE, TICK_DIVISOR, PERIOD_TICKS, FIFO_LOW_WATER or
//!   WATCHDOG_TIMEOUT is in its output from the clock after the write edge,
//!   with its writable bits only (write-any, read-legal). Reset clears
//!   them.
//! * The strobes `control_write`, `status_write`, `kick` and `snapshot` are
//!   combinational: high in the clock of a write to CONTROL, STATUS,
//!   WATCHDOG_KICK and SNAPSHOT.
//! * `read_data` is combinational: the global register at `address` (the
//!   live values as they are in this clock), 0 at any other address. The
//!   controller registers it on `bus_read`.

use rust_hdl::prelude::*;

use super::registers::{fields, global, irq, ID_VALUE, VERSION_VALUE};
use super::PERIOD_BITS;

/// Number of interrupt sources (`STATUS` bits).
pub const IRQ_COUNT: usize = irq::COUNT;

field_slices! {
    /// The multi-bit fields the register layer and the controller take
    /// from the bus's write data, placed by the map.
    pub trait ControllerFields {
        /// `PERIOD_TICKS.VALUE`.
        get_value_period_ticks / get_my_offset_period_ticks / get_my_width_period_ticks =
            (fields::VALUE, PERIOD_BITS);
        /// `STATUS` and `IRQ_ENABLE`: every interrupt bit, in event order.
        get_value_irq_bits / get_my_offset_irq_bits / get_my_width_irq_bits =
            (irq::PERIOD_DONE, IRQ_COUNT);
    }
}

// `update()` reads these fields at literal bits (rust-hdl prints a named
// constant by name; `field_slices!` has no one-bit form and no generic
// width): each literal is tied to the map's constant here.
const _: () = {
    assert!(fields::CONTROL_RUN == 0);
    assert!(fields::FIFO_LEVEL == 0);
    // The interrupt bits are 0..IRQ_COUNT, in event order.
    assert!(irq::PERIOD_DONE == 0 && irq::SPINDLE as usize == IRQ_COUNT - 1);
};

/// The global registers of a controller with FIFO levels of `NP1` bits.
/// See the [module documentation](self).
#[derive(LogicBlock)]
pub struct GlobalRegisters<const NP1: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: every register 0.
    pub reset: Signal<In, Bit>,
    /// The register bus's word address.
    pub address: Signal<In, Bits<8>>,
    /// Write data.
    pub write_data: Signal<In, Bits<32>>,
    /// Write strobe.
    pub write: Signal<In, Bit>,
    /// CONTROL.RUN and STATE.RUNNING.
    pub running: Signal<In, Bit>,
    /// STATUS: the interrupt controller's pending bits.
    pub status: Signal<In, Bits<IRQ_COUNT>>,
    /// STATE.WATCHDOG_ARMED.
    pub watchdog_armed: Signal<In, Bit>,
    /// STATE.WATCHDOG_EXPIRED.
    pub watchdog_expired: Signal<In, Bit>,
    /// STATE.ESTOP_INPUT.
    pub estop_input: Signal<In, Bit>,
    /// STATE.ESTOP_LATCHED.
    pub estop_latched: Signal<In, Bit>,
    /// STATE.ABORTED.
    pub aborted: Signal<In, Bit>,
    /// STATE.INPUTS_READY.
    pub inputs_ready: Signal<In, Bit>,
    /// STATE.HOLDING.
    pub holding: Signal<In, Bit>,
    /// STATE.HELD.
    pub held: Signal<In, Bit>,
    /// PERIOD_COUNT.
    pub period_count: Signal<In, Bits<32>>,
    /// STOP_CAUSE.
    pub stop_cause: Signal<In, Bits<32>>,
    /// IRQ_ENABLE.
    pub irq_enable: Signal<Out, Bits<IRQ_COUNT>>,
    /// TICK_DIVISOR.
    pub tick_divisor: Signal<Out, Bits<32>>,
    /// PERIOD_TICKS.VALUE.
    pub period_ticks: Signal<Out, Bits<PERIOD_BITS>>,
    /// FIFO_LOW_WATER.LEVEL.
    pub low_water: Signal<Out, Bits<NP1>>,
    /// WATCHDOG_TIMEOUT.
    pub watchdog_timeout: Signal<Out, Bits<32>>,
    /// A write to CONTROL in this clock.
    pub control_write: Signal<Out, Bit>,
    /// A write to STATUS in this clock (write 1 to clear).
    pub status_write: Signal<Out, Bit>,
    /// A write to WATCHDOG_KICK in this clock.
    pub kick: Signal<Out, Bit>,
    /// A write to SNAPSHOT in this clock.
    pub snapshot: Signal<Out, Bit>,
    /// The global register at `address`, or 0.
    pub read_data: Signal<Out, Bits<32>>,

    irq_enable_reg: DFF<Bits<IRQ_COUNT>>,
    tick_divisor_reg: DFF<Bits<32>>,
    period_ticks_reg: DFF<Bits<PERIOD_BITS>>,
    low_water_reg: DFF<Bits<NP1>>,
    watchdog_timeout_reg: DFF<Bits<32>>,
    state_word: Signal<Local, Bits<32>>,

    a_id: Constant<Bits<8>>,
    a_version: Constant<Bits<8>>,
    a_config: Constant<Bits<8>>,
    a_control: Constant<Bits<8>>,
    a_status: Constant<Bits<8>>,
    a_irq_enable: Constant<Bits<8>>,
    a_tick_divisor: Constant<Bits<8>>,
    a_period_ticks: Constant<Bits<8>>,
    a_low_water: Constant<Bits<8>>,
    a_watchdog_timeout: Constant<Bits<8>>,
    a_watchdog_kick: Constant<Bits<8>>,
    a_snapshot: Constant<Bits<8>>,
    a_state: Constant<Bits<8>>,
    a_period_count: Constant<Bits<8>>,
    a_stop_cause: Constant<Bits<8>>,
    id_value: Constant<Bits<32>>,
    version_value: Constant<Bits<32>>,
    config_value: Constant<Bits<32>>,
    /// STATE fields, in place.
    m_state_running: Constant<Bits<32>>,
    m_state_watchdog_armed: Constant<Bits<32>>,
    m_state_watchdog_expired: Constant<Bits<32>>,
    m_state_estop_input: Constant<Bits<32>>,
    m_state_estop_latched: Constant<Bits<32>>,
    m_state_aborted: Constant<Bits<32>>,
    m_state_inputs_ready: Constant<Bits<32>>,
    m_state_holding: Constant<Bits<32>>,
    m_state_held: Constant<Bits<32>>,
    /// CONTROL.RUN, in place.
    m_control_run: Constant<Bits<32>>,
    /// `bit_mask[i]` = 1 << i, to zero-extend the narrow registers.
    bit_mask: [Constant<Bits<32>>; PERIOD_BITS],
    zero32: Constant<Bits<32>>,
    zero_irq: Constant<Bits<IRQ_COUNT>>,
    zero_p: Constant<Bits<PERIOD_BITS>>,
    zero_level: Constant<Bits<NP1>>,
}

impl<const NP1: usize> GlobalRegisters<NP1> {
    /// The layer of a controller whose CONFIG reads `config`.
    pub fn new(config: u32) -> Self {
        assert!(
            NP1 <= PERIOD_BITS && IRQ_COUNT <= PERIOD_BITS,
            "GlobalRegisters: a register wider than its read-back"
        );
        let a8 = |v: u32| Constant::new((v as u64).into());
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write_data: Default::default(),
            write: Default::default(),
            running: Default::default(),
            status: Default::default(),
            watchdog_armed: Default::default(),
            watchdog_expired: Default::default(),
            estop_input: Default::default(),
            estop_latched: Default::default(),
            aborted: Default::default(),
            inputs_ready: Default::default(),
            holding: Default::default(),
            held: Default::default(),
            period_count: Default::default(),
            stop_cause: Default::default(),
            irq_enable: Default::default(),
            tick_divisor: Default::default(),
            period_ticks: Default::default(),
            low_water: Default::default(),
            watchdog_timeout: Default::default(),
            control_write: Default::default(),
            status_write: Default::default(),
            kick: Default::default(),
            snapshot: Default::default(),
            read_data: Default::default(),
            irq_enable_reg: Default::default(),
            tick_divisor_reg: Default::default(),
            period_ticks_reg: Default::default(),
            low_water_reg: Default::default(),
            watchdog_timeout_reg: Default::default(),
            state_word: Default::default(),
            a_id: a8(global::ID),
            a_version: a8(global::VERSION),
            a_config: a8(global::CONFIG),
            a_control: a8(global::CONTROL),
            a_status: a8(global::STATUS),
            a_irq_enable: a8(global::IRQ_ENABLE),
            a_tick_divisor: a8(global::TICK_DIVISOR),
            a_period_ticks: a8(global::PERIOD_TICKS),
            a_low_water: a8(global::FIFO_LOW_WATER),
            a_watchdog_timeout: a8(global::WATCHDOG_TIMEOUT),
            a_watchdog_kick: a8(global::WATCHDOG_KICK),
            a_snapshot: a8(global::SNAPSHOT),
            a_state: a8(global::STATE),
            a_period_count: a8(global::PERIOD_COUNT),
            a_stop_cause: a8(global::STOP_CAUSE),
            id_value: Constant::new((ID_VALUE as u64).into()),
            version_value: Constant::new((VERSION_VALUE as u64).into()),
            config_value: Constant::new((config as u64).into()),
            m_state_running: m32(fields::STATE_RUNNING),
            m_state_watchdog_armed: m32(fields::STATE_WATCHDOG_ARMED),
            m_state_watchdog_expired: m32(fields::STATE_WATCHDOG_EXPIRED),
            m_state_estop_input: m32(fields::STATE_ESTOP_INPUT),
            m_state_estop_latched: m32(fields::STATE_ESTOP_LATCHED),
            m_state_aborted: m32(fields::STATE_ABORTED),
            m_state_inputs_ready: m32(fields::STATE_INPUTS_READY),
            m_state_holding: m32(fields::STATE_HOLDING),
            m_state_held: m32(fields::STATE_HELD),
            m_control_run: m32(fields::CONTROL_RUN),
            bit_mask: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            zero32: Constant::new(0u64.into()),
            zero_irq: Constant::new(0u64.into()),
            zero_p: Constant::new(0u64.into()),
            zero_level: Constant::new(0u64.into()),
        }
    }
}

impl<const NP1: usize> Logic for GlobalRegisters<NP1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            irq_enable_reg,
            tick_divisor_reg,
            period_ticks_reg,
            low_water_reg,
            watchdog_timeout_reg
        );
        self.irq_enable.next = self.irq_enable_reg.q.val();
        self.tick_divisor.next = self.tick_divisor_reg.q.val();
        self.period_ticks.next = self.period_ticks_reg.q.val();
        self.low_water.next = self.low_water_reg.q.val();
        self.watchdog_timeout.next = self.watchdog_timeout_reg.q.val();

        // Writes. FIFO_LOW_WATER.LEVEL: its width is NP1, a generic, so not
        // a field_slices! field; the literal is asserted above.
        if self.write.val() {
            if self.address.val() == self.a_irq_enable.val() {
                self.irq_enable_reg.d.next = self.write_data.val().get_value_irq_bits();
            }
            if self.address.val() == self.a_tick_divisor.val() {
                self.tick_divisor_reg.d.next = self.write_data.val();
            }
            if self.address.val() == self.a_period_ticks.val() {
                self.period_ticks_reg.d.next = self.write_data.val().get_value_period_ticks();
            }
            if self.address.val() == self.a_low_water.val() {
                self.low_water_reg.d.next = self.write_data.val().get_bits::<NP1>(0);
            }
            if self.address.val() == self.a_watchdog_timeout.val() {
                self.watchdog_timeout_reg.d.next = self.write_data.val();
            }
        }
        self.control_write.next = self.write.val() & (self.address.val() == self.a_control.val());
        self.status_write.next = self.write.val() & (self.address.val() == self.a_status.val());
        self.kick.next = self.write.val() & (self.address.val() == self.a_watchdog_kick.val());
        self.snapshot.next = self.write.val() & (self.address.val() == self.a_snapshot.val());

        // STATE.
        self.state_word.next = self.zero32.val();
        if self.running.val() {
            self.state_word.next = self.state_word.val() | self.m_state_running.val();
        }
        if self.watchdog_armed.val() {
            self.state_word.next = self.state_word.val() | self.m_state_watchdog_armed.val();
        }
        if self.watchdog_expired.val() {
            self.state_word.next = self.state_word.val() | self.m_state_watchdog_expired.val();
        }
        if self.estop_input.val() {
            self.state_word.next = self.state_word.val() | self.m_state_estop_input.val();
        }
        if self.estop_latched.val() {
            self.state_word.next = self.state_word.val() | self.m_state_estop_latched.val();
        }
        if self.aborted.val() {
            self.state_word.next = self.state_word.val() | self.m_state_aborted.val();
        }
        if self.inputs_ready.val() {
            self.state_word.next = self.state_word.val() | self.m_state_inputs_ready.val();
        }
        if self.holding.val() {
            self.state_word.next = self.state_word.val() | self.m_state_holding.val();
        }
        if self.held.val() {
            self.state_word.next = self.state_word.val() | self.m_state_held.val();
        }

        // Reads: one-hot AND-OR over exclusive addresses (see the axis read
        // mux); the narrow registers zero-extended bit by bit.
        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_id.val() {
            self.read_data.next = self.read_data.val() | self.id_value.val();
        }
        if self.address.val() == self.a_version.val() {
            self.read_data.next = self.read_data.val() | self.version_value.val();
        }
        if self.address.val() == self.a_config.val() {
            self.read_data.next = self.read_data.val() | self.config_value.val();
        }
        if (self.address.val() == self.a_control.val()) & self.running.val() {
            self.read_data.next = self.read_data.val() | self.m_control_run.val();
        }
        for i in 0..IRQ_COUNT {
            if (self.address.val() == self.a_status.val()) & self.status.val().get_bit(i) {
                self.read_data.next = self.read_data.val() | self.bit_mask[i].val();
            }
            if (self.address.val() == self.a_irq_enable.val())
                & self.irq_enable_reg.q.val().get_bit(i)
            {
                self.read_data.next = self.read_data.val() | self.bit_mask[i].val();
            }
        }
        if self.address.val() == self.a_tick_divisor.val() {
            self.read_data.next = self.read_data.val() | self.tick_divisor_reg.q.val();
        }
        for i in 0..PERIOD_BITS {
            if (self.address.val() == self.a_period_ticks.val())
                & self.period_ticks_reg.q.val().get_bit(i)
            {
                self.read_data.next = self.read_data.val() | self.bit_mask[i].val();
            }
        }
        for i in 0..NP1 {
            if (self.address.val() == self.a_low_water.val())
                & self.low_water_reg.q.val().get_bit(i)
            {
                self.read_data.next = self.read_data.val() | self.bit_mask[i].val();
            }
        }
        if self.address.val() == self.a_watchdog_timeout.val() {
            self.read_data.next = self.read_data.val() | self.watchdog_timeout_reg.q.val();
        }
        if self.address.val() == self.a_state.val() {
            self.read_data.next = self.read_data.val() | self.state_word.val();
        }
        if self.address.val() == self.a_period_count.val() {
            self.read_data.next = self.read_data.val() | self.period_count.val();
        }
        if self.address.val() == self.a_stop_cause.val() {
            self.read_data.next = self.read_data.val() | self.stop_cause.val();
        }

        if self.reset.val() {
            self.irq_enable_reg.d.next = self.zero_irq.val();
            self.tick_divisor_reg.d.next = self.zero32.val();
            self.period_ticks_reg.d.next = self.zero_p.val();
            self.low_water_reg.d.next = self.zero_level.val();
            self.watchdog_timeout_reg.d.next = self.zero32.val();
        }
    }
}
