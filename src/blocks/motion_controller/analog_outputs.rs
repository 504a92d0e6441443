//! The controller's analog outputs: the DAC (one [`DacInterface`] channel
//! per axis), the walk that loads the analog axes' codes into it after
//! each pop, the 0 V update when RUN falls, and the DAC's registers
//! forwarded from the controller's bus.
//!
//! Internal to [`super::MotionController`]; the behavior is the
//! controller's ("Analog axes" in its datasheet), modelled by
//! [`super::model`].
//!
//! ## Contract (as the controller uses it)
//! * The clock after a pop the walk starts at axis 0 and moves one axis a
//!   clock (`walk`, one-hot; the controller answers with that axis's
//!   entry as `code_magnitude`, `code_negative` and `code_wide` in the
//!   same clock). An analog axis's code is loaded into its channel; after
//!   the last axis one update writes every channel and pulses LDAC once.
//! * The code is the magnitude with its sign put back; an entry that does
//!   not fit 16 bits signed saturates to the code's end of its sign.
//! * **Scaled walks.** A walk takes `factor` at its start. Below 1.0
//!   (`slowed_in`) each axis takes [`SCALE_STEPS`] + 2 clocks: the first
//!   registers the saturated |code| and its sign, 16 shift-add steps on
//!   registers, from the factor's LSB, form floor(|code| x factor / 2^16)
//!   exactly, and the 18th loads it with the sign; `walk` stays on the
//!   axis meanwhile. Its update request waits until the DAC is idle (never
//!   deferred). While the factor is below 1, or the last walk was scaled
//!   (`owed`), a re-walk is decided in any clock with RUN, no abort, no
//!   walk or request under way, the DAC idle and an analog axis, and
//!   starts in the next: the outputs follow the factor, and return to the
//!   full codes after the release. A pop restarts the walk at axis 0 with the
//!   factor of that clock.
//! * An abort ends any walk (the DAC refuses loads while it forces the
//!   safe code).
//! * RUN falling by an underrun or a stop (`stop_zero`) loads code 0 into
//!   every analog channel and updates them, one clock later, and ends any
//!   walk. An abort forces the DAC's safe code itself (`abort`).
//! * A read or write of DAC_CONTROL, DAC_STATUS, DAC_TIMING or an axis's
//!   DAC_APPLIED reaches the DAC's own register. Its read data is valid the
//!   clock after `bus_read`, with `read_selected` high, as the
//!   controller's own read register is.
//! * Without the analog outputs (`new(false)`) the registers are absent
//!   (read 0), nothing is loaded or updated, and the pins idle: every
//!   `dac_cs_n` and `dac_l1_n` high, `dac_ldac` and `dac_data` low.
//!   Synthesis removes the DAC.

use rust_hdl::prelude::*;

use super::registers::{self, AXIS_BASE, AXIS_STRIDE, DAC_BITS};
use crate::blocks::dac_interface::DacInterface;

/// The shift-add steps of a scaled walk's multiply: the factor's 16
/// fraction bits. An axis of a scaled walk takes `SCALE_STEPS + 2` clocks
/// (one registers its code, one loads it).
pub const SCALE_STEPS: u32 = 16;

/// The analog outputs of `K` axes. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct AnalogOutputs<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// The register bus's word address.
    pub bus_address: Signal<In, Bits<8>>,
    /// Write data.
    pub bus_write_data: Signal<In, Bits<32>>,
    /// Write strobe.
    pub bus_write: Signal<In, Bit>,
    /// Read strobe.
    pub bus_read: Signal<In, Bit>,
    /// Every FIFO pops in this clock.
    pub pop: Signal<In, Bit>,
    /// RUN falls in this clock, not by an abort: every analog channel to 0.
    pub stop_zero: Signal<In, Bit>,
    /// Force the DAC's safe code; ends any walk.
    pub abort: Signal<In, Bit>,
    /// Periods are running: re-walks while slowed only then.
    pub running: Signal<In, Bit>,
    /// The feed hold's factor is below 1.0 (`STATE.HOLDING`): a shallow
    /// test of the ramp's register, kept off the factor's subtractor.
    pub slowed_in: Signal<In, Bit>,
    /// The feed hold's velocity factor's fraction bits (the factor below
    /// 1.0; taken only while `slowed_in`).
    pub factor: Signal<In, Bits<16>>,
    /// Per axis: the axis is in analog mode.
    pub analog_axes: Signal<In, Bits<K>>,
    /// |entry| of the walked axis, saturated to 16 bits.
    pub code_magnitude: Signal<In, Bits<DAC_BITS>>,
    /// The walked axis's entry is negative.
    pub code_negative: Signal<In, Bit>,
    /// The walked axis's entry does not fit 16 bits signed.
    pub code_wide: Signal<In, Bit>,
    /// One-hot: the axis whose code is loaded in this clock (0: none).
    pub walk: Signal<Out, Bits<K>>,
    /// The DAC's read data, with `read_selected`.
    pub read_data: Signal<Out, Bits<32>>,
    /// The last read addressed a DAC register.
    pub read_selected: Signal<Out, Bit>,
    /// DAC data bus.
    pub dac_data: Signal<Out, Bits<DAC_BITS>>,
    /// Per axis: DAC chip select, active low.
    pub dac_cs_n: Signal<Out, Bits<K>>,
    /// DAC first-rank load, active low.
    pub dac_l1_n: Signal<Out, Bit>,
    /// DAC second-rank load, active high.
    pub dac_ldac: Signal<Out, Bit>,

    dac: DacInterface<K, DAC_BITS>,
    /// The analog outputs are built (else the DAC drives nothing and
    /// synthesis removes it).
    has_analog: Constant<Bit>,
    /// The walk's axis in the next clock (one-hot; 0: none). A pop sets
    /// axis 0: the axes' codes are valid from the clock after it.
    walk_next: DFF<Bits<K>>,
    /// The DAC's update request, the clock after the walk's last load.
    update_request: DFF<Bit>,
    /// The last read addressed a DAC register (its read data is the DAC's).
    read_sel: DFF<Bit>,
    /// `stop_zero` one clock late (registered: the underrun decode is long).
    stop_zero_d: DFF<Bit>,
    /// The running walk scales its codes (the factor was below 1 when it
    /// was decided): `SCALE_STEPS` + 2 clocks an axis.
    scaled: DFF<Bit>,
    /// The walk's factor (below 1: 16 bits), rotated one bit a clock so
    /// that bit 0 is the multiplier's bit; 16 rotations bring it back.
    factor_bits: DFF<Bits<16>>,
    /// The scaled walk's clock within its axis: 0 registers the axis's
    /// magnitude and sign, 1 to 16 multiply, 17 loads.
    step_count: DFF<Bits<5>>,
    /// The walked axis's saturated |entry|, and its sign.
    magnitude_q: DFF<Bits<DAC_BITS>>,
    negative_q: DFF<Bit>,
    /// The shift-add product: after 16 steps, floor(magnitude x factor / 2^16).
    product: DFF<Bits<16>>,
    /// The outputs carry scaled codes: walk again (at 1.0, a last plain walk).
    owed: DFF<Bit>,
    /// A scaled walk has loaded its last axis and waits for the DAC to be idle.
    update_wait: DFF<Bit>,
    slowed: Signal<Local, Bit>,
    walking: Signal<Local, Bit>,
    rewalk: Signal<Local, Bit>,
    start: Signal<Local, Bit>,
    scaled_now: Signal<Local, Bit>,
    count_now: Signal<Local, Bits<5>>,
    last_load: Signal<Local, Bit>,
    saturated: Signal<Local, Bits<DAC_BITS>>,
    addend: Signal<Local, Bits<17>>,
    sum: Signal<Local, Bits<17>>,
    load_clock: Constant<Bits<5>>,
    zero5b: Constant<Bits<5>>,
    one5: Constant<Bits<5>>,
    zero16: Constant<Bits<16>>,
    zero17: Constant<Bits<17>>,
    walk_now: Signal<Local, Bits<K>>,
    load: Signal<Local, Bits<K>>,
    code: Signal<Local, Bits<DAC_BITS>>,
    code_max: Constant<Bits<DAC_BITS>>,
    code_min: Constant<Bits<DAC_BITS>>,
    /// The forwarded register's DAC address: its low 3 bits, and bits 4 and
    /// 3 both from `applied_hit` (the DAC's globals are below 8, its
    /// APPLIED at 0x18 + k): its CODE addresses (0x10 + k, bit 4 without
    /// bit 3) cannot occur, and synthesis removes their logic.
    dac_low: Signal<Local, Bits<5>>,
    applied_hit: Signal<Local, Bit>,
    applied_bits: Constant<Bits<5>>,
    hit: Signal<Local, Bit>,
    dac_address: Signal<Local, Bits<5>>,
    /// The controller's and the DAC's addresses of the forwarded registers.
    a_dac_global: [Constant<Bits<8>>; 3],
    d_dac_global: [Constant<Bits<5>>; 3],
    a_dac_applied: [Constant<Bits<8>>; K],
    d_dac_applied: [Constant<Bits<5>>; K],
    zero5: Constant<Bits<5>>,
    /// Bit 0: the walk's first axis; bit K - 1: its last.
    first_axis: Constant<Bits<K>>,
    last_axis: Constant<Bits<K>>,
    zero_k: Constant<Bits<K>>,
    zero_code: Constant<Bits<DAC_BITS>>,
    /// All ones with the analog outputs, else 0 (pins held idle).
    data_mask: Constant<Bits<DAC_BITS>>,
    /// 0 with the analog outputs, else all ones (chip selects held high).
    cs_idle: Constant<Bits<K>>,
}

impl<const K: usize> AnalogOutputs<K> {
    /// The analog outputs, built if `analog`.
    pub fn new(analog: bool) -> Self {
        let a8 = |v: u32| Constant::new((v as u64).into());
        let dac_map = crate::blocks::dac_interface::registers::register_map(K, DAC_BITS)
            .expect("a dac_interface of K channels");
        let dac_applied = dac_map
            .register("APPLIED")
            .expect("the DAC's APPLIED")
            .address as u64;
        // The forwarded addresses are built so that CODE's cannot occur
        // (see `dac_low`): the DAC's map must keep this layout.
        assert_eq!(
            dac_applied, 0b11000,
            "the DAC's APPLIED moved: dac_address builds 0x18 + k"
        );
        assert_eq!(
            crate::blocks::dac_interface::registers::CODE_BASE,
            0b10000,
            "the DAC's CODE moved"
        );
        for (_, _, name) in registers::DAC_GLOBAL {
            assert!(
                dac_map.register(name).expect("a DAC register").address < 8,
                "DAC {name} moved above 7"
            );
        }
        Self {
            clock: Default::default(),
            reset: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            pop: Default::default(),
            stop_zero: Default::default(),
            abort: Default::default(),
            running: Default::default(),
            slowed_in: Default::default(),
            factor: Default::default(),
            analog_axes: Default::default(),
            code_magnitude: Default::default(),
            code_negative: Default::default(),
            code_wide: Default::default(),
            walk: Default::default(),
            read_data: Default::default(),
            read_selected: Default::default(),
            dac_data: Default::default(),
            dac_cs_n: Default::default(),
            dac_l1_n: Default::default(),
            dac_ldac: Default::default(),
            dac: Default::default(),
            has_analog: Constant::new(analog),
            walk_next: Default::default(),
            update_request: Default::default(),
            read_sel: Default::default(),
            stop_zero_d: Default::default(),
            scaled: Default::default(),
            factor_bits: Default::default(),
            step_count: Default::default(),
            magnitude_q: Default::default(),
            negative_q: Default::default(),
            product: Default::default(),
            owed: Default::default(),
            update_wait: Default::default(),
            slowed: Default::default(),
            walking: Default::default(),
            rewalk: Default::default(),
            start: Default::default(),
            scaled_now: Default::default(),
            count_now: Default::default(),
            last_load: Default::default(),
            saturated: Default::default(),
            addend: Default::default(),
            sum: Default::default(),
            load_clock: Constant::new((SCALE_STEPS as u64 + 1).into()),
            zero5b: Constant::new(0u64.into()),
            one5: Constant::new(1u64.into()),
            zero16: Constant::new(0u64.into()),
            zero17: Constant::new(0u64.into()),
            walk_now: Default::default(),
            load: Default::default(),
            code: Default::default(),
            code_max: Constant::new(crate::blocks::width_mask(DAC_BITS as u32 - 1).into()),
            code_min: Constant::new((1u64 << (DAC_BITS - 1)).into()),
            dac_low: Default::default(),
            applied_hit: Default::default(),
            applied_bits: Constant::new(0b11000u64.into()),
            hit: Default::default(),
            dac_address: Default::default(),
            a_dac_global: array_init::array_init(|i| a8(registers::DAC_GLOBAL[i].1)),
            d_dac_global: array_init::array_init(|i| {
                Constant::new(
                    (dac_map
                        .register(registers::DAC_GLOBAL[i].2)
                        .expect("a dac_interface register")
                        .address as u64)
                        .into(),
                )
            }),
            a_dac_applied: array_init::array_init(|k| {
                a8(AXIS_BASE + k as u32 * AXIS_STRIDE + registers::axis::DAC_APPLIED)
            }),
            d_dac_applied: array_init::array_init(|k| Constant::new((k as u64).into())),
            zero5: Constant::new(0u64.into()),
            first_axis: Constant::new(1u64.into()),
            last_axis: Constant::new((1u64 << (K - 1)).into()),
            zero_k: Constant::new(0u64.into()),
            zero_code: Constant::new(0u64.into()),
            data_mask: Constant::new(
                (if analog {
                    crate::blocks::width_mask(DAC_BITS as u32)
                } else {
                    0
                })
                .into(),
            ),
            cs_idle: Constant::new(
                (if analog {
                    0
                } else {
                    crate::blocks::width_mask(K as u32)
                })
                .into(),
            ),
        }
    }
}

impl<const K: usize> Logic for AnalogOutputs<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            walk_next,
            update_request,
            read_sel,
            stop_zero_d,
            scaled,
            factor_bits,
            step_count,
            magnitude_q,
            negative_q,
            product,
            owed,
            update_wait
        );
        clock!(self, clock, dac);

        // The walk. A pop starts one; while the feed hold's factor is below
        // 1 (or the outputs still carry scaled codes) a re-walk starts
        // whenever none runs and the DAC is idle. Both are decided a clock
        // ahead (`start`), so that the walk, its mode and its factor come
        // from registers: at 1.0 it loads one axis a clock (the plain walk);
        // below, each axis takes SCALE_STEPS + 2 clocks: the walked axis's
        // magnitude and sign are registered, a shift-add multiply runs on
        // registers only, and the last clock loads. After the last axis,
        // one update.
        self.slowed.next = self.slowed_in.val();
        self.walking.next = self.walk_next.q.val() != self.zero_k.val();
        self.rewalk.next = (self.slowed.val() | self.owed.q.val())
            & self.running.val()
            & !self.abort.val()
            & !self.walking.val()
            & !self.update_wait.q.val()
            & !self.update_request.q.val()
            & !self.dac.busy.val()
            & (self.analog_axes.val() != self.zero_k.val())
            & self.has_analog.val();
        self.start.next = self.pop.val() | self.rewalk.val();
        self.walk_now.next = self.walk_next.q.val();
        self.scaled_now.next = self.scaled.q.val();
        self.count_now.next = self.step_count.q.val();
        self.walk.next = self.walk_now.val();

        // The walked axis's |entry| saturated (32767 or 32768 with the sign).
        self.saturated.next = self.code_magnitude.val();
        if self.code_wide.val() {
            if self.code_negative.val() {
                self.saturated.next = self.code_min.val();
            } else {
                self.saturated.next = self.code_max.val();
            }
        }
        // The multiply: the factor bit by bit from its LSB, halving each
        // step: after 16 steps floor(magnitude x factor / 2^16), exactly
        // (each halving drops only bits below the result's LSB).
        self.addend.next = self.zero17.val();
        if self.factor_bits.q.val().get_bit(0) {
            self.addend.next = bit_cast::<17, DAC_BITS>(self.magnitude_q.q.val());
        }
        self.sum.next = bit_cast::<17, 16>(self.product.q.val()) + self.addend.val();
        self.last_load.next = false;
        self.load.next = self.walk_now.val() & self.analog_axes.val();
        self.walk_next.d.next = self.walk_now.val() << 1;
        self.step_count.d.next = self.zero5b.val();
        if self.scaled_now.val() & (self.walk_now.val() != self.zero_k.val()) {
            if self.count_now.val() == self.load_clock.val() {
                self.last_load.next =
                    (self.walk_now.val() & self.last_axis.val()) != self.zero_k.val();
            } else {
                self.load.next = self.zero_k.val();
                self.walk_next.d.next = self.walk_now.val();
                self.step_count.d.next = self.count_now.val() + self.one5.val();
                if self.count_now.val() == self.zero5b.val() {
                    self.magnitude_q.d.next = self.saturated.val();
                    self.negative_q.d.next = self.code_negative.val();
                    self.product.d.next = self.zero16.val();
                } else {
                    self.product.d.next = self.sum.val().get_bits::<16>(1);
                    self.factor_bits.d.next =
                        (self.factor_bits.q.val() >> 1) | (self.factor_bits.q.val() << 15);
                }
            }
        }
        // A decided walk starts at axis 0 in the next clock, replacing any
        // walk under way.
        if self.start.val() {
            self.walk_next.d.next = self.first_axis.val();
            self.scaled.d.next = self.slowed.val();
            self.step_count.d.next = self.zero5b.val();
            self.factor_bits.d.next = self.factor.val();
            self.owed.d.next = self.slowed.val();
        }
        // The code: the magnitude with its sign put back (exact for every
        // entry that fits 16 bits signed, -2^15 included); an entry beyond
        // 16 bits signed saturates (a scaled code was saturated before its
        // multiply).
        self.code.next = self.code_magnitude.val();
        if self.code_negative.val() {
            self.code.next = self.zero_code.val() - self.code_magnitude.val();
        }
        if self.code_wide.val() {
            if self.code_negative.val() {
                self.code.next = self.code_min.val();
            } else {
                self.code.next = self.code_max.val();
            }
        }
        if self.scaled_now.val() {
            self.code.next = self.product.q.val();
            if self.negative_q.q.val() {
                self.code.next = self.zero_code.val() - self.product.q.val();
            }
        }
        // A plain walk requests its update at once (a busy DAC defers it
        // and flags DEFERRED: the period is too short); a scaled walk's
        // request waits for the DAC to be idle, so re-walks never defer.
        self.update_request.d.next = ((self.walk_now.val() & self.last_axis.val())
            != self.zero_k.val())
            & (self.analog_axes.val() != self.zero_k.val())
            & !self.scaled_now.val();
        if self.update_wait.q.val() & !self.start.val() {
            if !self.dac.busy.val() {
                self.update_request.d.next = true;
                self.update_wait.d.next = false;
            } else {
                self.update_wait.d.next = true;
            }
        } else {
            self.update_wait.d.next = false;
        }
        if self.last_load.val() & (self.analog_axes.val() != self.zero_k.val()) {
            self.update_wait.d.next = true;
        }
        self.stop_zero_d.d.next = self.stop_zero.val() & self.has_analog.val();
        if self.stop_zero_d.q.val() {
            self.load.next = self.analog_axes.val();
            self.code.next = self.zero_code.val();
            self.walk_next.d.next = self.zero_k.val();
            self.update_request.d.next = self.analog_axes.val() != self.zero_k.val();
            self.update_wait.d.next = false;
            self.owed.d.next = false;
        }
        // An abort ends any walk: the DAC refuses loads and updates while
        // it forces the safe code.
        if self.abort.val() {
            self.walk_next.d.next = self.zero_k.val();
            self.update_wait.d.next = false;
            self.owed.d.next = false;
        }

        // The DAC's registers on our bus.
        self.hit.next = false;
        self.applied_hit.next = false;
        self.dac_low.next = self.zero5.val();
        for i in 0..3 {
            if self.bus_address.val() == self.a_dac_global[i].val() {
                self.hit.next = self.has_analog.val();
                self.dac_low.next = self.d_dac_global[i].val();
            }
        }
        for i in 0..K {
            if self.bus_address.val() == self.a_dac_applied[i].val() {
                self.hit.next = self.has_analog.val();
                self.applied_hit.next = true;
                self.dac_low.next = self.d_dac_applied[i].val();
            }
        }
        self.dac_address.next = self.dac_low.val();
        if self.applied_hit.val() {
            self.dac_address.next = self.dac_low.val() | self.applied_bits.val();
        }
        if self.bus_read.val() {
            self.read_sel.d.next = self.hit.val();
        }
        self.read_selected.next = self.read_sel.q.val();
        self.read_data.next = self.dac.bus_read_data.val();

        self.dac.reset.next = self.reset.val();
        self.dac.bus_address.next = self.dac_address.val();
        self.dac.bus_write_data.next = self.bus_write_data.val();
        self.dac.bus_write.next = self.bus_write.val() & self.hit.val();
        self.dac.bus_read.next = self.bus_read.val() & self.hit.val();
        self.dac.update.next = self.update_request.q.val();
        self.dac.force_safe.next = self.abort.val();
        self.dac.load.next = self.load.val();
        self.dac.load_code.next = self.code.val();
        self.dac_data.next = self.dac.dac_data.val() & self.data_mask.val();
        self.dac_cs_n.next = self.dac.dac_cs_n.val() | self.cs_idle.val();
        self.dac_l1_n.next = self.dac.dac_l1_n.val() | !self.has_analog.val();
        self.dac_ldac.next = self.dac.dac_ldac.val() & self.has_analog.val();

        if self.reset.val() {
            self.walk_next.d.next = self.zero_k.val();
            self.update_request.d.next = false;
            self.read_sel.d.next = false;
            self.stop_zero_d.d.next = false;
            self.owed.d.next = false;
            self.update_wait.d.next = false;
        }
    }
}
