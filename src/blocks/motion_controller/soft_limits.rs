//! Soft limits: a position window per axis, checked against the feed
//! hold's stopping distance, that requests the controlled stop early
//! enough for the axis to stop inside it.
//!
//! Internal to [`super::MotionController`] (build option `SOFT_LIMITS`);
//! the behavior is specified in [`super`] ("Soft limits") and modelled by
//! [`SoftLimitsModel`].
//!
//! ## Ports
//!
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous: windows 0, nothing enabled, no verdict, the gauge restarted (also the power-up state) |
//! | `address`, `write`, `write_data` | in | 8, 1, 24 | the register bus: `SOFT_LIMIT` and every axis's `SOFT_MIN` and `SOFT_MAX` |
//! | `running` | in | 1 | `STATE.RUNNING`: only a running controller is checked |
//! | `rate` | in | 16 | `HOLD_CONTROL.RATE` as the hold ramp uses it |
//! | `period` | in | 16 | `PERIOD_TICKS` (0 acts as 1) |
//! | `position` | in | 24 | `CMD_POSITION` of the axis `select` names, in this clock |
//! | `magnitude` | in | 16 | \|entry\| of that axis's running period (its steps per period) |
//! | `negative` | in | 1 | that entry is negative |
//! | `step_axis` | in | 1 | that axis makes steps (not an analog axis) |
//! | `select` | out | 3 | the axis being loaded, registered |
//! | `stop` | out | 1 | some axis's verdict is "beyond" (`SOFT_LIMIT.BEYOND` != 0): the hold's request, a level |
//! | `tripped` | out | 1 | a verdict turned "beyond" at the last edge (`STATUS.SOFT_LIMIT`) |
//! | `read_data` | out | 32 | `SOFT_LIMIT` when addressed, else 0 (combinational, for the controller's read register) |
//! | `read` | in | 1 | bus read strobe |
//! | `window_data` | out | 32 | the `SOFT_MIN` / `SOFT_MAX` the last `read` addressed, sign-extended, registered at that read and held; 0 for any other register, a window not written since reset, or a read in the clock of a write (see below) |
//!
//! The windows live in block RAM, addressed by their bus address: one copy
//! the check reads at each load, one the bus reads (a block RAM has one
//! read port). A block RAM cannot be reset, so a valid bit per window
//! (cleared by reset, set by a write) makes an unwritten window 0.
//!
//! A block RAM's read of the word it writes in the same clock is
//! undefined (the iCE40's is), and neither RAM carries yosys's read-first
//! bypass (a delayed write and a compare, in flip-flops and LUTs). The
//! block defines both collisions itself instead:
//! * the check's read at an axis's load takes the word being written in
//!   that clock from the bus, so a window written in the load's clock is
//!   checked as written;
//! * a bus read in the clock of a bus write (one address, so the same
//!   window) reads 0. Every adapter of this crate reads and writes in
//!   separate clocks; a bus master that does both reads the window again.
//!
//! ## The check
//! The axes are checked in turn, one every [`CHECK_CLOCKS`] clocks, so
//! each one every `K` x [`CHECK_CLOCKS`] clocks. In the first clock of its
//! turn (the *load*, `select` = k) axis k's position p, |J| (steps per
//! period) and direction are taken, with the bound b the direction heads
//! for (`SOFT_MAX` moving up, `SOFT_MIN` moving down). The distance left is
//! Δ = b − p moving up, p − b moving down. The verdict, *beyond*, is
//!
//! ```text
//! (Δ − MARGIN) × P  <=  |J| × G'        (P = PERIOD_TICKS, 0 as 1)
//! ```
//!
//! that is, Δ − [`MARGIN`] is at most the steps the axis makes at its
//! rate |J|/P per tick over G' ticks, the stop's reach:
//! * G' = floor(N / 2) + 1 + [`check_latency`]`(K)` ([`reach_ticks`]),
//!   where N = ceil(65536 / RATE) ([`stop_length`]; 1 at RATE 0) is the
//!   length in ticks of a stop from full speed at the present `RATE`.
//! * floor(N / 2) + 1 bounds the ticks such a stop lets through the gate,
//!   whatever the phase the ramp carries: the gate passes a tick whenever
//!   the phase accumulator of the factor carries, so a stop whose factors
//!   in its N ticks are f_k = 1 − k·RATE/65536 passes
//!   floor(phase + Σ f_k) ticks, and as N·RATE lies in
//!   [65536, 65536 + RATE), Σ f_k = N − RATE·N(N − 1)/131072 lies in
//!   (N/2, (N + 1)/2]; with the phase below 1 at most floor(N / 2) + 1
//!   pass. (The tests check it at every rate from the phase that passes
//!   the most.)
//! * N is measured, not computed (no divider): a second [`HoldRamp`], the
//!   *gauge*, ramps down from 1 at `RATE` with a tick every clock, and
//!   its ticks until it stands are counted, from 2·(1 + latency), so
//!   half the count is G'. The gauge restarts as soon as it stops, so N
//!   is re-measured every N + 2 clocks. A `RATE` that differs from the
//!   one measured restarts the gauge, and until the next measurement
//!   ends G' is the maximum, [`REACH_MAX`] = 2^17 − 1: a new rate is
//!   never judged with the old one's reach. After reset (and at power-up)
//!   G' is the maximum too.
//! * [`check_latency`] bounds, in base ticks (one per clock at most), the
//!   time from a position to the ramp's response: up to a turn until the
//!   axis's next load, its own turn, the verdict and hold request
//!   registers, and the steps decided but not yet counted in `CMD_POSITION`.
//! * [`MARGIN`] (2 steps) covers a DDA's rounding: in g ticks it makes at
//!   most g·|J|/P + 1 steps.
//!
//! The verdict is computed exactly in integers (a 17-step serial
//! multiply of both products at once that keeps the sign of their
//! difference, see "Timing") and is taken only
//! while `running`, with the axis enabled (`SOFT_LIMIT.ENABLE`), making
//! steps, and |J| != 0: an axis that stands, or an analog axis, is never
//! beyond. Any other verdict is "not beyond". While not `running` every
//! verdict is cleared at the next edge, and disabling an axis clears its
//! verdict at the edge of the write.
//!
//! A window with `SOFT_MIN` > `SOFT_MAX`, or a position outside it, is
//! judged by the same rule: an axis outside its window moving further out
//! is beyond at once; one moving back in is not.
//!
//! ## Timing
//! A turn lasts [`CHECK_CLOCKS`] = 23 clocks (s = 0 to 22): s = 0 loads
//! the axis (`select` = k in that clock) and reads its bound from block
//! RAM; s = 1 registers the bound; s = 2 forms −Δ (moving down the
//! position and the bound are taken complemented, so one subtractor
//! serves both directions: ~p − ~b = b − p); s = 3 adds the
//! margin and saturates −Δ to 20 bits signed (a distance of more than
//! 2^19 steps either way is judged as 2^19: still beyond any stop's
//! reach in, since |J| <= P and G' < 2^17, and beyond at once out), and
//! takes P and G'; s = 4 forms |J| − Δ;
//! s = 5 to 21 accumulate |J|·G' − Δ·P one bit of P and G' a clock, least
//! significant first, halving as they go (so the adder is 23 bits, not
//! the product's 38: only the sign is kept); at the edge that ends s = 22 the verdict is
//! registered: `stop` and `BEYOND` show it after that edge, and
//! `tripped` is high for the one clock after it if it turned beyond.
//!
//! The verdict of an axis thus reflects its position and |J| at its last
//! load, `RATE` (through G') and `PERIOD_TICKS` as they were at s = 3.

use rust_hdl::prelude::*;

use super::hold_ramp::{HoldRamp, HoldRampInputs, HoldRampModel, UNITY};
use super::registers::{axis, fields, global, AXIS_BASE, AXIS_STRIDE};
use super::POSITION_BITS;
use crate::blocks::holding_ram::HoldingRam;
use crate::blocks::konst;

/// Clocks of one axis's turn.
pub const CHECK_CLOCKS: u32 = 23;

/// Steps subtracted from the distance left: a DDA's rounding.
pub const MARGIN: u32 = 2;

/// Base ticks, at most, from a position to the ramp's response, at `K`
/// axes: until the axis's next load ((K − 1) turns and the rest of its
/// own), its turn ([`CHECK_CLOCKS`]), the verdict, the hold's request and
/// the first ramp tick (3), and the steps not yet counted in
/// `CMD_POSITION` ([`super::TICK_TRAIL`] + 1). A tick is at most one a
/// clock, so clocks bound ticks.
pub const fn check_latency(axes: u32) -> u32 {
    (axes + 1) * CHECK_CLOCKS + 3 + super::TICK_TRAIL as u32 + 1
}

/// Base ticks of a stop from full speed at `rate` (`HOLD_CONTROL.RATE`, 0
/// as [`UNITY`]), until the factor is 0: N = ceil(65536 / RATE).
pub const fn stop_length(rate: u16) -> u32 {
    match rate {
        0 => 1,
        r => UNITY.div_ceil(r as u32),
    }
}

/// The stop's reach G' in base ticks at `rate`, with `axes` axes, once
/// measured: floor(N / 2) + 1 + [`check_latency`], N = [`stop_length`].
/// floor(N / 2) + 1 is the most ticks a stop of N ticks lets through the
/// gate, from any phase (see the module documentation).
pub const fn reach_ticks(rate: u16, axes: u32) -> u32 {
    stop_length(rate) / 2 + 1 + check_latency(axes)
}

/// Width of the stop's reach G' in ticks.
pub const REACH_BITS: usize = 17;

/// G' before the gauge has measured the present `RATE`.
pub const REACH_MAX: u32 = (1 << REACH_BITS) - 1;

/// Width of the saturated distance.
const DELTA_BITS: usize = 20;
/// Width of the accumulator, signed: it holds floor(partial sum / 2^i)
/// after i of the 17 steps, always within ±2^21 (each step adds a term
/// within ±2^20 and halves), so its sum fits 23 bits.
const ACC_BITS: usize = 23;

// The register fields as the RTL takes them: ENABLE by a slice at bit 0,
// the others ORed in at their places.
const _: () = assert!(
    fields::SOFT_ENABLE == 0
        && fields::SOFT_ENABLE_WIDTH == 8
        && fields::SOFT_BEYOND == 8
        && fields::SOFT_AXIS == 16
        && fields::SOFT_AXIS_WIDTH == 3
);
const _: () = assert!(POSITION_BITS == 24 && REACH_BITS == 17 && CHECK_CLOCKS == 23);

/// The soft limits of `K` axes. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct SoftLimits<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data, bits 23..0 (no field of these registers is above).
    pub write_data: Signal<In, Bits<POSITION_BITS>>,
    /// `STATE.RUNNING`.
    pub running: Signal<In, Bit>,
    /// `HOLD_CONTROL.RATE`.
    pub rate: Signal<In, Bits<16>>,
    /// `PERIOD_TICKS`.
    pub period: Signal<In, Bits<16>>,
    /// The selected axis's `CMD_POSITION`.
    pub position: Signal<In, Bits<POSITION_BITS>>,
    /// The selected axis's |entry|.
    pub magnitude: Signal<In, Bits<16>>,
    /// The selected axis's entry is negative.
    pub negative: Signal<In, Bit>,
    /// The selected axis makes steps.
    pub step_axis: Signal<In, Bit>,
    /// The axis being loaded.
    pub select: Signal<Out, Bits<3>>,
    /// Some verdict is "beyond".
    pub stop: Signal<Out, Bit>,
    /// A verdict turned "beyond" at the last edge.
    pub tripped: Signal<Out, Bit>,
    /// The addressed register, else 0 (`SOFT_LIMIT`; combinational).
    pub read_data: Signal<Out, Bits<32>>,
    /// Bus read strobe.
    pub read: Signal<In, Bit>,
    /// The window register of the last `read`, sign-extended, registered
    /// at that read and held (0 for any other register).
    pub window_data: Signal<Out, Bits<32>>,

    /// The windows, addressed by their bus address: one copy the check
    /// reads, one the bus reads (each has a single read port).
    check_ram: HoldingRam<Bits<POSITION_BITS>, 8>,
    bus_ram: HoldingRam<Bits<POSITION_BITS>, 8>,
    /// Per axis: SOFT_MIN / SOFT_MAX written since reset (a block RAM
    /// cannot be reset: an unwritten window reads 0).
    min_valid: DFF<Bits<8>>,
    max_valid: DFF<Bits<8>>,
    /// The checked bound's word is valid (taken with the RAM's read).
    bound_valid: DFF<Bit>,
    /// The bound, registered from the check RAM's word (or from the bus
    /// write that collided with its read), complemented moving down.
    bound_q: DFF<Bits<POSITION_BITS>>,
    /// The bound was taken from a bus write at the load.
    bound_taken: DFF<Bit>,
    /// The last bus read addressed a valid window.
    window_selected: DFF<Bit>,
    enable: DFF<Bits<8>>,
    beyond: DFF<Bits<8>>,
    event_q: DFF<Bit>,
    last_axis: DFF<Bits<3>>,
    last_negative: DFF<Bit>,
    turn_axis: DFF<Bits<3>>,
    turn_step: DFF<Bits<5>>,
    /// The position, complemented moving down.
    position_q: DFF<Bits<POSITION_BITS>>,
    magnitude_q: DFF<Bits<16>>,
    negative_q: DFF<Bit>,
    live_q: DFF<Bit>,
    /// −Δ, then −(Δ − MARGIN) saturated.
    distance: DFF<Bits<26>>,
    neg_delta: DFF<Bits<DELTA_BITS>>,
    /// |J| − (Δ − MARGIN).
    both: DFF<Bits<21>>,
    period_bits: DFF<Bits<REACH_BITS>>,
    reach_bits: DFF<Bits<REACH_BITS>>,
    acc: DFF<Bits<ACC_BITS>>,

    gauge: HoldRamp,
    gauge_rate: DFF<Bits<16>>,
    gauge_count: DFF<Bits<REACH_BITS>>,
    /// Low for the clock that restarts the gauge (so at power-up too).
    gauge_measuring: DFF<Bit>,
    /// G', complemented: power-up's 0 is [`REACH_MAX`].
    reach_n: DFF<Bits<REACH_BITS>>,
    reach_valid: DFF<Bit>,

    upper: Signal<Local, Bits<26>>,
    lower: Signal<Local, Bits<26>>,
    with_margin: Signal<Local, Bits<26>>,
    term: Signal<Local, Bits<ACC_BITS>>,
    sum: Signal<Local, Bits<ACC_BITS>>,
    verdict: Signal<Local, Bit>,
    enable_now: Signal<Local, Bits<8>>,
    word24: Signal<Local, Bits<32>>,
    delta21: Signal<Local, Bits<21>>,
    bound: Signal<Local, Bits<POSITION_BITS>>,
    load_mask: Signal<Local, Bits<POSITION_BITS>>,
    loaded_mask: Signal<Local, Bits<POSITION_BITS>>,
    check_address: Signal<Local, Bits<8>>,
    window_write: Signal<Local, Bit>,
    window_hit: Signal<Local, Bit>,
    window_valid: Signal<Local, Bit>,

    a_control: Constant<Bits<8>>,
    a_min: [Constant<Bits<8>>; K],
    a_max: [Constant<Bits<8>>; K],
    axis_id: [Constant<Bits<3>>; K],
    axis_bit: [Constant<Bits<8>>; K],
    last_turn: Constant<Bits<3>>,
    enable_mask: Constant<Bits<8>>,
    count_start: Constant<Bits<REACH_BITS>>,
    margin: Constant<Bits<26>>,
    sat_high: Constant<Bits<DELTA_BITS>>,
    sat_low: Constant<Bits<DELTA_BITS>>,
    ext21: Constant<Bits<21>>,
    ext26: Constant<Bits<26>>,
    ext32: Constant<Bits<32>>,
    ext_both: Constant<Bits<ACC_BITS>>,
    ext_delta: Constant<Bits<ACC_BITS>>,
    acc_sign: Constant<Bits<ACC_BITS>>,
    m_negative: Constant<Bits<32>>,
    m_measured: Constant<Bits<32>>,
    s_load: Constant<Bits<5>>,
    s_bound: Constant<Bits<5>>,
    s_distance: Constant<Bits<5>>,
    s_margin: Constant<Bits<5>>,
    s_both: Constant<Bits<5>>,
    s_first: Constant<Bits<5>>,
    s_last: Constant<Bits<5>>,
    s_verdict: Constant<Bits<5>>,
    one3: Constant<Bits<3>>,
    one5: Constant<Bits<5>>,
    zero3: Constant<Bits<3>>,
    zero17: Constant<Bits<REACH_BITS>>,
    zero24: Constant<Bits<POSITION_BITS>>,
    ones24: Constant<Bits<POSITION_BITS>>,
    zero7: Constant<Bits<7>>,
    ones7: Constant<Bits<7>>,
    zero8: Constant<Bits<8>>,
    zero16: Constant<Bits<16>>,
    one17: Constant<Bits<REACH_BITS>>,
    zero_acc: Constant<Bits<ACC_BITS>>,
    zero32: Constant<Bits<32>>,
}

impl<const K: usize> Default for SoftLimits<K> {
    fn default() -> Self {
        assert!((1..=8).contains(&K), "SoftLimits: 1 to 8 axes");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            running: Default::default(),
            rate: Default::default(),
            period: Default::default(),
            position: Default::default(),
            magnitude: Default::default(),
            negative: Default::default(),
            step_axis: Default::default(),
            select: Default::default(),
            stop: Default::default(),
            tripped: Default::default(),
            read_data: Default::default(),
            read: Default::default(),
            window_data: Default::default(),
            check_ram: HoldingRam::collisions_unobserved().power_up_unobserved(),
            bus_ram: HoldingRam::collisions_unobserved().power_up_unobserved(),
            min_valid: Default::default(),
            max_valid: Default::default(),
            bound_valid: Default::default(),
            bound_q: Default::default(),
            bound_taken: Default::default(),
            window_selected: Default::default(),
            enable: Default::default(),
            beyond: Default::default(),
            event_q: Default::default(),
            last_axis: Default::default(),
            last_negative: Default::default(),
            turn_axis: Default::default(),
            turn_step: Default::default(),
            position_q: Default::default(),
            magnitude_q: Default::default(),
            negative_q: Default::default(),
            live_q: Default::default(),
            distance: Default::default(),
            neg_delta: Default::default(),
            both: Default::default(),
            period_bits: Default::default(),
            reach_bits: Default::default(),
            acc: Default::default(),
            gauge: Default::default(),
            gauge_rate: Default::default(),
            gauge_count: Default::default(),
            gauge_measuring: Default::default(),
            reach_n: Default::default(),
            reach_valid: Default::default(),
            upper: Default::default(),
            lower: Default::default(),
            with_margin: Default::default(),
            term: Default::default(),
            sum: Default::default(),
            verdict: Default::default(),
            enable_now: Default::default(),
            word24: Default::default(),
            delta21: Default::default(),
            bound: Default::default(),
            load_mask: Default::default(),
            loaded_mask: Default::default(),
            check_address: Default::default(),
            window_write: Default::default(),
            window_hit: Default::default(),
            window_valid: Default::default(),
            a_control: konst(global::SOFT_LIMIT as u64),
            a_min: array_init::array_init(|k| {
                konst((AXIS_BASE + k as u32 * AXIS_STRIDE + axis::SOFT_MIN) as u64)
            }),
            a_max: array_init::array_init(|k| {
                konst((AXIS_BASE + k as u32 * AXIS_STRIDE + axis::SOFT_MAX) as u64)
            }),
            axis_id: array_init::array_init(|k| konst(k as u64)),
            axis_bit: array_init::array_init(|k| konst(1 << k)),
            last_turn: konst(K as u64 - 1),
            enable_mask: konst((1 << K) - 1),
            count_start: konst(2 * (check_latency(K as u32) as u64 + 1)),
            margin: konst(MARGIN as u64),
            sat_high: konst((1 << (DELTA_BITS - 1)) - 1),
            sat_low: konst(1 << (DELTA_BITS - 1)),
            ext21: konst(1 << 20),
            ext26: konst(0x3ff_ffff ^ 0xff_ffff),
            ext32: konst(0xffff_ffff ^ 0xff_ffff),
            ext_both: konst(crate::blocks::width_mask(ACC_BITS as u32) ^ 0x1f_ffff),
            ext_delta: konst(crate::blocks::width_mask(ACC_BITS as u32) ^ 0xf_ffff),
            acc_sign: konst(1 << (ACC_BITS - 1)),
            m_negative: konst(1 << fields::SOFT_NEGATIVE),
            m_measured: konst(1 << fields::SOFT_MEASURED),
            s_load: konst(0),
            s_bound: konst(1),
            s_distance: konst(2),
            s_margin: konst(3),
            s_both: konst(4),
            s_first: konst(5),
            s_last: konst(21),
            s_verdict: konst(CHECK_CLOCKS as u64 - 1),
            one3: konst(1),
            one5: konst(1),
            zero3: konst(0),
            zero17: konst(0),
            zero24: konst(0),
            ones24: konst(0xff_ffff),
            zero7: konst(0),
            ones7: konst(0x7f),
            zero8: konst(0),
            zero16: konst(0),
            one17: konst(1),
            zero_acc: konst(0),
            zero32: konst(0),
        }
    }
}

impl<const K: usize> Logic for SoftLimits<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            enable,
            beyond,
            event_q,
            last_axis,
            last_negative,
            turn_axis,
            turn_step,
            position_q,
            magnitude_q,
            negative_q,
            live_q,
            distance,
            neg_delta,
            both,
            period_bits,
            reach_bits,
            acc,
            gauge_rate,
            gauge_count,
            gauge_measuring,
            reach_n,
            reach_valid,
            min_valid,
            max_valid,
            bound_valid,
            bound_q,
            bound_taken,
            window_selected
        );
        clock!(self, clock, gauge, check_ram, bus_ram);
        // The windows: both RAMs take every write of one; a read of a word
        // not written since reset gives 0. Neither RAM's word is used when
        // it was read in the clock of a write to it (a block RAM's is
        // undefined then): the bus read gives 0, and the check takes the
        // written word from the bus.
        self.window_hit.next = false;
        self.window_valid.next = false;
        for k in 0..K {
            if self.address.val() == self.a_min[k].val() {
                self.window_hit.next = true;
                self.window_valid.next =
                    (self.min_valid.q.val() & self.axis_bit[k].val()) != self.zero8.val();
                if self.write.val() {
                    self.min_valid.d.next = self.min_valid.q.val() | self.axis_bit[k].val();
                }
            }
            if self.address.val() == self.a_max[k].val() {
                self.window_hit.next = true;
                self.window_valid.next =
                    (self.max_valid.q.val() & self.axis_bit[k].val()) != self.zero8.val();
                if self.write.val() {
                    self.max_valid.d.next = self.max_valid.q.val() | self.axis_bit[k].val();
                }
            }
        }
        self.window_write.next = self.write.val() & self.window_hit.val();
        self.check_ram.write_enable.next = self.window_write.val();
        self.check_ram.write_address.next = self.address.val();
        self.check_ram.write_data.next = self.write_data.val();
        self.bus_ram.write_enable.next = self.window_write.val();
        self.bus_ram.write_address.next = self.address.val();
        self.bus_ram.write_data.next = self.write_data.val();
        self.bus_ram.read_enable.next = self.read.val();
        self.bus_ram.read_address.next = self.address.val();
        if self.read.val() {
            self.window_selected.d.next =
                self.window_hit.val() & self.window_valid.val() & !self.write.val();
        }
        self.enable_now.next = self.enable.q.val();
        if self.write.val() & (self.address.val() == self.a_control.val()) {
            self.enable_now.next = self.write_data.val().get_bits::<8>(0) & self.enable_mask.val();
        }
        self.enable.d.next = self.enable_now.val();

        // The gauge: a stop from full speed at the present RATE, a tick a
        // clock. Its length N in ticks is counted from 2·(1 + latency), so
        // half the count is G' = floor(N / 2) + 1 + latency.
        self.gauge.reset.next = self.reset.val() | !self.gauge_measuring.q.val();
        self.gauge.tick.next = true;
        self.gauge.hold.next = true;
        self.gauge.rate.next = self.gauge_rate.q.val();
        self.gauge_measuring.d.next = true;
        if !self.gauge_measuring.q.val() {
            self.gauge_count.d.next = self.count_start.val();
            self.gauge_rate.d.next = self.rate.val();
            // The reach is that of the rate just measured.
            if self.rate.val() != self.gauge_rate.q.val() {
                self.reach_valid.d.next = false;
                self.reach_n.d.next = self.zero17.val();
            }
        } else if self.rate.val() != self.gauge_rate.q.val() {
            self.reach_valid.d.next = false;
            self.reach_n.d.next = self.zero17.val();
            self.gauge_measuring.d.next = false;
        } else if self.gauge.stopped.val() {
            self.reach_n.d.next = !(self.gauge_count.q.val() >> 1);
            self.reach_valid.d.next = true;
            self.gauge_measuring.d.next = false;
        } else {
            self.gauge_count.d.next = self.gauge_count.q.val() + self.one17.val();
        }

        // The turns: s = 0 loads the selected axis (its bound is the check
        // RAM's read register from s = 1 on).
        self.turn_step.d.next = self.turn_step.q.val() + self.one5.val();
        self.check_ram.read_enable.next = self.turn_step.q.val() == self.s_load.val();
        // Moving down, the position and the bound are complemented: then
        // one subtractor gives -delta both ways (~p - ~b = b - p).
        self.load_mask.next = self.zero24.val();
        if self.negative.val() {
            self.load_mask.next = self.ones24.val();
        }
        self.check_address.next = self.a_max[0].val();
        if self.turn_step.q.val() == self.s_load.val() {
            self.position_q.d.next = self.position.val() ^ self.load_mask.val();
            self.magnitude_q.d.next = self.magnitude.val();
            self.negative_q.d.next = self.negative.val();
            self.live_q.d.next = false;
            for k in 0..K {
                if self.turn_axis.q.val() == self.axis_id[k].val() {
                    self.check_address.next = self.a_max[k].val();
                    self.bound_valid.d.next =
                        (self.max_valid.q.val() & self.axis_bit[k].val()) != self.zero8.val();
                    if self.negative.val() {
                        self.check_address.next = self.a_min[k].val();
                        self.bound_valid.d.next =
                            (self.min_valid.q.val() & self.axis_bit[k].val()) != self.zero8.val();
                    }
                    self.live_q.d.next = self.running.val()
                        & ((self.enable.q.val() & self.axis_bit[k].val()) != self.zero8.val())
                        & self.step_axis.val()
                        & (self.magnitude.val() != self.zero16.val());
                }
            }
            self.bound_taken.d.next = false;
            if self.window_write.val() & (self.address.val() == self.check_address.val()) {
                self.bound_q.d.next = self.write_data.val() ^ self.load_mask.val();
                self.bound_taken.d.next = true;
            }
        }
        self.check_ram.read_address.next = self.check_address.val();
        // s = 2: -delta = p - b moving up, b - p moving down (26 bits, signed).
        self.upper.next = bit_cast::<26, 24>(self.position_q.q.val());
        if self.position_q.q.val().get_bit(23) {
            self.upper.next = self.upper.val() | self.ext26.val();
        }
        // s = 1: the bound registered (a block RAM's clock-to-out is slow:
        // straight into the subtractor it set ECP5's Fmax).
        self.loaded_mask.next = self.zero24.val();
        if self.negative_q.q.val() {
            self.loaded_mask.next = self.ones24.val();
        }
        self.bound.next = self.zero24.val();
        if self.bound_valid.q.val() {
            self.bound.next = self.check_ram.read_data.val();
        }
        if (self.turn_step.q.val() == self.s_bound.val()) & !self.bound_taken.q.val() {
            self.bound_q.d.next = self.bound.val() ^ self.loaded_mask.val();
        }
        self.lower.next = bit_cast::<26, 24>(self.bound_q.q.val());
        if self.bound_q.q.val().get_bit(23) {
            self.lower.next = self.lower.val() | self.ext26.val();
        }
        if self.turn_step.q.val() == self.s_distance.val() {
            self.distance.d.next = self.upper.val() - self.lower.val();
        }
        // s = 3: the margin, saturation to 20 bits; P (0 as 1) and G'.
        self.with_margin.next = self.distance.q.val() + self.margin.val();
        if self.turn_step.q.val() == self.s_margin.val() {
            self.neg_delta.d.next = self.with_margin.val().get_bits::<20>(0);
            if (self.with_margin.val().get_bits::<7>(19) != self.zero7.val())
                & (self.with_margin.val().get_bits::<7>(19) != self.ones7.val())
            {
                self.neg_delta.d.next = self.sat_high.val();
                if self.with_margin.val().get_bit(25) {
                    self.neg_delta.d.next = self.sat_low.val();
                }
            }
            self.period_bits.d.next = bit_cast::<17, 16>(self.period.val());
            if self.period.val() == self.zero16.val() {
                self.period_bits.d.next = self.one17.val();
            }
            self.reach_bits.d.next = !self.reach_n.q.val();
        }
        // s = 4: |J| - delta, and the accumulator cleared.
        self.delta21.next = bit_cast::<21, 20>(self.neg_delta.q.val());
        if self.neg_delta.q.val().get_bit(19) {
            self.delta21.next = self.delta21.val() | self.ext21.val();
        }
        if self.turn_step.q.val() == self.s_both.val() {
            self.both.d.next = bit_cast::<21, 16>(self.magnitude_q.q.val()) + self.delta21.val();
            self.acc.d.next = self.zero_acc.val();
        }
        // s = 5..21: acc = floor((acc + |J| g - delta p) / 2), bits of P and
        // G' from the bottom: after the 17th, acc = floor(T / 2^17) for
        // T = |J| G' - delta P, whose sign it keeps. (Most significant bit
        // first would need T's full 38 bits in the adder.)
        self.term.next = self.zero_acc.val();
        if self.reach_bits.q.val().get_bit(0) {
            if self.period_bits.q.val().get_bit(0) {
                self.term.next = bit_cast::<ACC_BITS, 21>(self.both.q.val());
                if self.both.q.val().get_bit(20) {
                    self.term.next = self.term.val() | self.ext_both.val();
                }
            } else {
                self.term.next = bit_cast::<ACC_BITS, 16>(self.magnitude_q.q.val());
            }
        } else if self.period_bits.q.val().get_bit(0) {
            self.term.next = bit_cast::<ACC_BITS, 20>(self.neg_delta.q.val());
            if self.neg_delta.q.val().get_bit(19) {
                self.term.next = self.term.val() | self.ext_delta.val();
            }
        }
        self.sum.next = self.acc.q.val() + self.term.val();
        if (self.turn_step.q.val() >= self.s_first.val())
            & (self.turn_step.q.val() <= self.s_last.val())
        {
            self.acc.d.next = self.sum.val() >> 1;
            if self.sum.val().get_bit(22) {
                self.acc.d.next = (self.sum.val() >> 1) | self.acc_sign.val();
            }
            self.period_bits.d.next = self.period_bits.q.val() >> 1;
            self.reach_bits.d.next = self.reach_bits.q.val() >> 1;
        }
        // s = 22: the verdict; the next axis.
        self.verdict.next = self.live_q.q.val() & !self.acc.q.val().get_bit(22);
        self.beyond.d.next = self.beyond.q.val() & self.enable_now.val();
        self.event_q.d.next = false;
        if self.turn_step.q.val() == self.s_verdict.val() {
            self.turn_step.d.next = self.s_load.val();
            self.turn_axis.d.next = self.turn_axis.q.val() + self.one3.val();
            if self.turn_axis.q.val() == self.last_turn.val() {
                self.turn_axis.d.next = self.zero3.val();
            }
            for k in 0..K {
                if self.turn_axis.q.val() == self.axis_id[k].val() {
                    self.beyond.d.next =
                        self.beyond.q.val() & !self.axis_bit[k].val() & self.enable_now.val();
                    if self.verdict.val()
                        & self.running.val()
                        & ((self.enable_now.val() & self.axis_bit[k].val()) != self.zero8.val())
                    {
                        self.beyond.d.next =
                            (self.beyond.q.val() | self.axis_bit[k].val()) & self.enable_now.val();
                        if (self.beyond.q.val() & self.axis_bit[k].val()) == self.zero8.val() {
                            self.event_q.d.next = true;
                            self.last_axis.d.next = self.turn_axis.q.val();
                            self.last_negative.d.next = self.negative_q.q.val();
                        }
                    }
                }
            }
        }
        if !self.running.val() {
            self.beyond.d.next = self.zero8.val();
        }
        if self.reset.val() {
            self.min_valid.d.next = self.zero8.val();
            self.max_valid.d.next = self.zero8.val();
            self.window_selected.d.next = false;
            self.enable.d.next = self.zero8.val();
            self.beyond.d.next = self.zero8.val();
            self.event_q.d.next = false;
            self.last_axis.d.next = self.zero3.val();
            self.last_negative.d.next = false;
            self.turn_axis.d.next = self.zero3.val();
            self.turn_step.d.next = self.s_load.val();
            self.live_q.d.next = false;
            self.gauge_rate.d.next = self.zero16.val();
            self.gauge_count.d.next = self.zero17.val();
            self.gauge_measuring.d.next = false;
            self.reach_valid.d.next = false;
            self.reach_n.d.next = self.zero17.val();
        }

        self.select.next = self.turn_axis.q.val();
        self.stop.next = self.beyond.q.val() != self.zero8.val();
        self.tripped.next = self.event_q.q.val();

        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_control.val() {
            self.read_data.next = bit_cast::<32, 8>(self.enable.q.val())
                | (bit_cast::<32, 8>(self.beyond.q.val()) << 8)
                | (bit_cast::<32, 3>(self.last_axis.q.val()) << 16);
            if self.last_negative.q.val() {
                self.read_data.next = self.read_data.val() | self.m_negative.val();
            }
            if self.reach_valid.q.val() {
                self.read_data.next = self.read_data.val() | self.m_measured.val();
            }
        }
        self.word24.next = bit_cast::<32, 24>(self.bus_ram.read_data.val());
        if self.bus_ram.read_data.val().get_bit(23) {
            self.word24.next = self.word24.val() | self.ext32.val();
        }
        self.window_data.next = self.zero32.val();
        if self.window_selected.q.val() {
            self.window_data.next = self.word24.val();
        }
    }
}

/// One clock's inputs of [`SoftLimitsModel`] (the block's input ports).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SoftLimitsInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Bus word address.
    pub address: u32,
    /// Bus write strobe.
    pub write: bool,
    /// Bus write data.
    pub write_data: u32,
    /// `STATE.RUNNING`.
    pub running: bool,
    /// `HOLD_CONTROL.RATE`.
    pub rate: u16,
    /// `PERIOD_TICKS`.
    pub period: u16,
    /// The selected axis's `CMD_POSITION` (24 bits).
    pub position: u32,
    /// The selected axis's |entry|.
    pub magnitude: u16,
    /// The selected axis's entry is negative.
    pub negative: bool,
    /// The selected axis makes steps.
    pub step_axis: bool,
    /// Bus read strobe.
    pub read: bool,
}

/// One clock's outputs of [`SoftLimitsModel`], after the edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SoftLimitsOutputs {
    /// The axis being loaded.
    pub select: u32,
    /// Some verdict is "beyond".
    pub stop: bool,
    /// A verdict turned "beyond" at the last edge.
    pub tripped: bool,
    /// `SOFT_LIMIT` when addressed, else 0.
    pub read_data: u32,
    /// The window register of the last read, held.
    pub window_data: u32,
}

/// What the verdict of a turn compares, as taken at its load and at s = 3:
/// the contract's rule in plain integers, for the model and the tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Check {
    /// The axis's position (signed).
    pub position: i64,
    /// The bound it heads for (signed).
    pub bound: i64,
    /// |J|.
    pub magnitude: u64,
    /// Moving down.
    pub negative: bool,
    /// `PERIOD_TICKS` (0 acts as 1).
    pub period: u64,
    /// The stop's reach G' in ticks.
    pub reach: u64,
}

impl Check {
    /// The distance left minus the margin, as the block saturates it.
    pub fn distance(&self) -> i64 {
        let delta = if self.negative {
            self.position - self.bound
        } else {
            self.bound - self.position
        };
        let limit = 1i64 << (DELTA_BITS - 1);
        (delta - MARGIN as i64).clamp(-limit + 1, limit)
    }

    /// The verdict: (Δ − MARGIN) × P <= |J| × G'.
    pub fn beyond(&self) -> bool {
        (self.distance() as i128) * (self.period.max(1) as i128)
            <= self.magnitude as i128 * self.reach as i128
    }
}

/// Reference model of [`SoftLimits`].
#[derive(Clone, Debug)]
pub struct SoftLimitsModel {
    axes: usize,
    minimum: Vec<u32>,
    maximum: Vec<u32>,
    enable: u32,
    beyond: u32,
    event: bool,
    last_axis: u32,
    last_negative: bool,
    turn_axis: u32,
    turn_step: u32,
    loaded: Check,
    live: bool,
    gauge: HoldRampModel,
    gauge_rate: u16,
    gauge_count: u32,
    gauge_measuring: bool,
    reach: u32,
    reach_valid: bool,
    window_data: u32,
}

/// A 24-bit position as a signed number.
fn signed24(v: u32) -> i64 {
    ((v << 8) as i32 >> 8) as i64
}

impl SoftLimitsModel {
    /// `axes` axes in the power-up state.
    pub fn new(axes: usize) -> Self {
        Self {
            axes,
            minimum: vec![0; axes],
            maximum: vec![0; axes],
            enable: 0,
            beyond: 0,
            event: false,
            last_axis: 0,
            last_negative: false,
            turn_axis: 0,
            turn_step: 0,
            loaded: Check {
                position: 0,
                bound: 0,
                magnitude: 0,
                negative: false,
                period: 1,
                reach: 0,
            },
            live: false,
            gauge: HoldRampModel::default(),
            gauge_rate: 0,
            gauge_count: 0,
            gauge_measuring: false,
            reach: REACH_MAX,
            reach_valid: false,
            window_data: 0,
        }
    }

    /// The axis whose position, entry and kind the block takes in this
    /// clock (`select`).
    pub fn select(&self) -> usize {
        self.turn_axis as usize
    }

    /// Some verdict is "beyond": the hold's request.
    pub fn stop(&self) -> bool {
        self.beyond != 0
    }

    /// The stop's reach G' the next s = 3 takes.
    pub fn reach(&self) -> u32 {
        self.reach
    }

    /// The register at `address` as a bus read at this clock's edge
    /// returns it (`SOFT_LIMIT` or a window), or 0.
    /// A read in the clock of a `write` (to the same address: the bus has
    /// one) reads a window as 0.
    pub fn read(&self, address: u32, write: bool) -> u32 {
        self.control_read(address) | self.window_read(address, write)
    }

    /// `SOFT_LIMIT` at `address`, or 0.
    fn control_read(&self, address: u32) -> u32 {
        if address == global::SOFT_LIMIT {
            return self.enable
                | self.beyond << fields::SOFT_BEYOND
                | self.last_axis << fields::SOFT_AXIS
                | (self.last_negative as u32) << fields::SOFT_NEGATIVE
                | (self.reach_valid as u32) << fields::SOFT_MEASURED;
        }
        0
    }

    /// A window at `address`, sign-extended, or 0 (also in the clock of
    /// a `write`).
    fn window_read(&self, address: u32, write: bool) -> u32 {
        if write {
            return 0;
        }
        for k in 0..self.axes {
            let base = AXIS_BASE + k as u32 * AXIS_STRIDE;
            if address == base + axis::SOFT_MIN {
                return signed24(self.minimum[k]) as u32;
            }
            if address == base + axis::SOFT_MAX {
                return signed24(self.maximum[k]) as u32;
            }
        }
        0
    }

    /// One clock; the outputs after its edge.
    pub fn step(&mut self, i: &SoftLimitsInputs) -> SoftLimitsOutputs {
        let s = self.clone();
        let n = self;
        let axis_bit = |k: u32| 1u32 << k;
        for k in 0..s.axes {
            let base = AXIS_BASE + k as u32 * AXIS_STRIDE;
            if i.write && i.address == base + axis::SOFT_MIN {
                n.minimum[k] = i.write_data & 0xff_ffff;
            }
            if i.write && i.address == base + axis::SOFT_MAX {
                n.maximum[k] = i.write_data & 0xff_ffff;
            }
        }
        let enable_now = match i.write && i.address == global::SOFT_LIMIT {
            true => i.write_data & ((1 << s.axes) - 1),
            false => s.enable,
        };
        n.enable = enable_now;

        // The gauge: its length counted from 2·(1 + latency); G' is half.
        let stopped = s.gauge.factor() == 0;
        n.gauge_measuring = true;
        if !s.gauge_measuring {
            n.gauge_count = 2 * (check_latency(s.axes as u32) + 1);
            n.gauge_rate = i.rate;
            if i.rate != s.gauge_rate {
                n.reach_valid = false;
                n.reach = REACH_MAX;
            }
        } else if i.rate != s.gauge_rate {
            n.reach_valid = false;
            n.reach = REACH_MAX;
            n.gauge_measuring = false;
        } else if stopped {
            n.reach = s.gauge_count / 2;
            n.reach_valid = true;
            n.gauge_measuring = false;
        } else {
            n.gauge_count = s.gauge_count + 1;
        }
        n.gauge.step(HoldRampInputs {
            reset: i.reset || !s.gauge_measuring,
            tick: true,
            hold: true,
            rate: s.gauge_rate,
        });

        // The turn.
        let a = s.turn_axis;
        n.turn_step = s.turn_step + 1;
        match s.turn_step {
            0 => {
                let k = a as usize;
                n.loaded.position = signed24(i.position & 0xff_ffff);
                n.loaded.magnitude = i.magnitude as u64;
                n.loaded.negative = i.negative;
                // A window written in this clock is checked as written.
                n.loaded.bound = signed24(match i.negative {
                    true => n.minimum[k],
                    false => n.maximum[k],
                });
                n.live =
                    i.running && s.enable & axis_bit(a) != 0 && i.step_axis && i.magnitude != 0;
            }
            3 => {
                n.loaded.period = (i.period as u64).max(1);
                n.loaded.reach = s.reach() as u64;
            }
            _ => {}
        }
        if i.read {
            n.window_data = s.window_read(i.address, i.write);
        }
        n.beyond = s.beyond & enable_now;
        n.event = false;
        if s.turn_step == CHECK_CLOCKS - 1 {
            n.turn_step = 0;
            n.turn_axis = if a as usize == s.axes - 1 { 0 } else { a + 1 };
            n.beyond = s.beyond & !axis_bit(a) & enable_now;
            let verdict = s.live && s.loaded.beyond();
            if verdict && i.running && enable_now & axis_bit(a) != 0 {
                n.beyond = (s.beyond | axis_bit(a)) & enable_now;
                if s.beyond & axis_bit(a) == 0 {
                    n.event = true;
                    n.last_axis = a;
                    n.last_negative = s.loaded.negative;
                }
            }
        }
        if !i.running {
            n.beyond = 0;
        }
        if i.reset {
            n.minimum.iter_mut().for_each(|v| *v = 0);
            n.maximum.iter_mut().for_each(|v| *v = 0);
            n.enable = 0;
            n.beyond = 0;
            n.event = false;
            n.last_axis = 0;
            n.last_negative = false;
            n.turn_axis = 0;
            n.turn_step = 0;
            n.live = false;
            n.gauge_rate = 0;
            n.gauge_count = 0;
            n.gauge_measuring = false;
            n.reach_valid = false;
            n.reach = REACH_MAX;
            n.window_data = 0;
        }
        SoftLimitsOutputs {
            select: n.turn_axis,
            stop: n.beyond != 0,
            tripped: n.event,
            read_data: n.control_read(i.address),
            window_data: n.window_data,
        }
    }
}

crate::vector_ports!(impl[const K: usize] SoftLimits<K> {
    inputs: [reset, address, write, write_data, running, rate, period, position, magnitude, negative, step_axis, read],
    outputs: [select, stop, tripped, read_data, window_data],
});

impl SoftLimitsInputs {
    /// The input vector, in `SoftLimits`'s input order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.address as u64 & 0xff,
            self.write as u64,
            self.write_data as u64 & 0xff_ffff,
            self.running as u64,
            self.rate as u64,
            self.period as u64,
            self.position as u64 & 0xff_ffff,
            self.magnitude as u64,
            self.negative as u64,
            self.step_axis as u64,
            self.read as u64,
        ]
    }
}

impl SoftLimitsOutputs {
    /// The outputs from `SoftLimits`'s output vector.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            select: v[0] as u32,
            stop: v[1] != 0,
            tripped: v[2] != 0,
            read_data: v[3] as u32,
            window_data: v[4] as u32,
        }
    }
}

impl crate::sim::LockstepModel for SoftLimitsModel {
    type Inputs = SoftLimitsInputs;
    type Outputs = SoftLimitsOutputs;
    fn input_vector(inputs: &SoftLimitsInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> SoftLimitsOutputs {
        SoftLimitsOutputs::from_vector(vector)
    }
    fn expected(&mut self, inputs: &SoftLimitsInputs) -> SoftLimitsOutputs {
        self.step(inputs)
    }
}
