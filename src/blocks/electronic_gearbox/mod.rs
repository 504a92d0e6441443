//! # `electronic_gearbox`: an axis geared to the spindle's encoder, exact ratio, ramp-in, catch-up, bounded ramp-out
//!
//! Threading and rigid tapping in gateware: the axis steps n / d steps per
//! spindle count, with the fraction carried, so the axis is within a step
//! of pitch x spindle angle over any number of revolutions. It is armed by
//! the host and engages at the next index, so every pass starts at the same
//! spindle angle. If the spindle is already turning, the axis ramps in at a
//! bounded rate change per count, then catches up the phase the ramp lost,
//! then stays locked. It stops at a stated length or on a command, ramping
//! out at the same bound, and at once on `halt`. The step requests go to
//! the axis's output stage beside its interpolator's (the controller adds
//! them to the period FIFO's motion).
//!
//! Everything is counted in spindle counts, not in time: the ramp, the
//! catch-up and the ramp-out are the same sequence of rates at every
//! spindle speed, so the axis's position is a function of the spindle's
//! angle alone, from the index on, as long as the spindle turns forward
//! until the lock. Every pass of a thread at any speed therefore lands in
//! the same groove.
//!
//! ## Ports (`W` = 24-bit ratio, `E` = 40-bit lag, `L` = 24-bit position in the exported `electronic_gearbox`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## The ratio
//! The rate r is in 1/d step per spindle count, 0 <= r <= d: at most one
//! step per count. A fraction f (0 <= f < d) is carried: on a forward
//! count at rate r, f + r >= d makes a step and f becomes f + r - d,
//! else f becomes f + r. A backward count (the spindle turning back, as in
//! a rigid tap's reversal) runs the same backward at the rate it has:
//! f < r makes a step back and f becomes f + d - r. Forward is
//! `count_up`, or `count_down` with `spindle_reverse`; a forward step is
//! `step_up`, or `step_down` with `axis_reverse`. With r = n the position
//! is therefore floor((n x m + c) / d) after m net counts, for a constant
//! c: nothing drifts, over any number of revolutions. A pitch that needs
//! more than one step per count (n > d) is refused: use an encoder with
//! more counts per revolution.
//!
//! `numerator`, `denominator`, `ramp`, `length`, `spindle_reverse` and
//! `axis_reverse` are taken at the arm; later changes act at the next arm.
//!
//! ## Phases (`phase`)
//! | code | phase | what the axis does |
//! |---|---|---|
//! | 0 | idle | nothing; `arm` arms |
//! | 1 | armed | nothing; the next `index` engages |
//! | 2 | ramp-in | on each forward count the rate rises by `ramp`, to n |
//! | 3 | track | catches up the lag at most `ramp` per count faster than n, then runs at n (`locked`) |
//! | 4 | stopping | on each forward count the rate falls by `ramp` to the crawl rate c, then stops |
//!
//! * **Arm.** In idle, `arm` checks the ratio: d >= 1, n <= d, and ramp
//!   = 0 or ramp x 2^(E - W - 1) >= n (a ramp-in of at most 2^15 counts in
//!   the export, which keeps the lag within E bits). A valid arm clears
//!   the position, `done`, `invalid` and `overrun` and arms; an invalid one sets
//!   `invalid` and stays idle. `arm` in any other phase is ignored.
//! * **Engage.** An `index` while armed engages at the edge: the rate is
//!   0, the fraction 0, the lag 0. A count in the index's own clock is not
//!   geared; counts from the next clock on are.
//! * **Ramp-in.** On each forward count the rate becomes min(r + ramp, n)
//!   (n at once with `ramp` = 0), and that count moves the axis at the new
//!   rate. At r = n the gearbox tracks.
//! * **Lag.** The lag e is n x (net counts) minus the axis's motion, in
//!   1/d step: each forward count adds n - r, each backward count
//!   subtracts it. The ramp-in leaves about n^2 / (2 ramp) in it.
//! * **Catch-up (track).** The rate is n + u, u = k x ramp >= 0. With
//!   S = ramp x k (k + 1) / 2 (the catch-up made by this count and a
//!   braking of u to 0 after it), each forward count takes the largest of
//!   k + 1, k, k - 1 whose S fits in e (k + 1 only if n + u + ramp <= d),
//!   so the axis never passes the ideal; then e shrinks by u. It ends
//!   at u = 0 with 0 <= e < ramp, and from then on e stays constant;
//!   `locked` rises with the first forward count that finds it so. With ramp <= d the axis is then 0 or 1 step behind
//!   floor(n x m / d) at every count. With n + ramp > d there is no room
//!   to catch up: the lag of the ramp-in stays, and `locked` stays 0.
//!   Backward counts before the lock move the axis back at its rate; the
//!   catch-up acts on forward counts only.
//! * **Stop at `length`** (not 0): the gearbox keeps D, an upper bound on
//!   the steps its ramp-out takes from the present rate (each rise of the
//!   rate from r adds r, each fall to r subtracts r, in 1/d step, carried
//!   into whole steps). In ramp-in or track, once t + D + 3 >= length (t
//!   the net steps since the engage, not wrapped at 2^L), it stops: the
//!   rate falls by `ramp` per forward count to the
//!   crawl rate c = min(ramp, n) (n with `ramp` = 0), runs at c, and
//!   the forward step that brings the position to `length` ends the run
//!   (idle, `done`). The margin of 3 steps makes the ramp-out end at c
//!   before the length, so the last rate change is c <= ramp. Reached
//!   position: exactly `length`.
//! * **`stop`** while engaged ramps out the same way to c, and the next
//!   forward count at c ends the run there (no `done`). While armed it
//!   disarms.
//! * **`halt`** goes idle at once from any phase, with no ramp: for an
//!   abort or an E-stop. The count in work is dropped and requests no
//!   step; a step request already on the pins keeps its clock (the output
//!   stage never cuts a pulse).
//!
//! **Acceleration.** Every rate change is at most `ramp` / d step per count
//! per count, so at a spindle count rate f_c the axis accelerates at most
//! ramp / d x f_c^2 steps/s^2: the host sets `ramp` from the axis's
//! acceleration and the fastest spindle it allows. The two exceptions are
//! stated: `ramp` = 0 (engage and stop at full rate, for a spindle that
//! starts from rest after the engage), and `halt`.
//!
//! ## The engine
//! A spindle count needs about fifteen additions and comparisons (the
//! rate, the lag X, the ramp-out bound D, the fraction, the length
//! counters). Spindle counts come far slower than the clock (a 4096-count
//! encoder at 6000 rpm is 410 kHz), so one 40-bit adder does them in turn:
//! fifteen micro-steps of two clocks each, the operands registered in the
//! first and the sum and its writes in the second. The RTL keeps the lag
//! and the catch-up's braking distance as their difference X = e - S (the
//! model keeps both): the catch-up's choice is then X >= u + ramp
//! (accelerate), X >= 0 (hold), else brake, and X moves by -2 u', -u or
//! +ramp. It keeps the length as G = length - t and R = G - D, counted
//! with the steps, so the ramp-out starts at R <= 3 and the run ends at
//! G = 0 without comparing wide sums.
//!
//! * **Taking a count.** A count is taken in a clock where the engine is
//!   idle and the gearbox engaged. The engine then works on it for
//!   [`model::ENGINE_CLOCKS`] = 30 clocks, and the count's step, position,
//!   phase, `locked` and `done` show after the 30th edge after the take;
//!   the outputs hold until then.
//! * **A count while the engine works** waits in a slot of one and is
//!   taken in the first clock the engine is idle (the clock after it
//!   shows the last count's results). A second count while one waits is
//!   an **overrun**: a count would be lost, so the gearbox halts (idle, no
//!   further step, the count in work dropped) and sets `overrun`.
//! * **Count rate.** So the spindle may count at most once per 31 clocks
//!   on average, with one count of jitter: 3.2 M counts/s at 100 MHz, 1.5
//!   M counts/s at 48 MHz (a 4096-count encoder at 22 000 rpm). A faster
//!   spindle overruns; an encoder with fewer counts per revolution keeps
//!   it below.
//! * A `stop` while the engine works is applied in the first clock it is
//!   idle. `halt` acts at once and drops the count in work (its step is
//!   not requested).
//!
//! Area and Fmax are in the synthesis report (`rtl-out/synthesis-report.md`).
//!
//! ## Timing
//! * A count taken at edge c requests its step on `step_up`/`step_down`
//!   after edge c + 30, for one clock: at most one step per count, and
//!   one step per 31 clocks at most.
//! * `phase`, `locked`, `done`, `invalid`, `overrun` and `position` are
//!   registered. `arm`, `index` (while armed), `stop` (while idle or
//!   armed, or engaged with the engine idle) and `halt` show after their
//!   edge; a count's effects after its 30 clocks.
//!
//! ## Bad input
//! * `count_up` and `count_down` together: no count.
//! * Counts faster than the engine: `overrun`, and the gearbox halts (see
//!   "The engine").
//! * An invalid ratio at the arm: refused, `invalid` set, idle.
//! * `stop` and `arm` in one clock while idle: stays idle. `halt` wins over
//!   everything.
//! * A length shorter than its ramp-out (D + 3 >= length at
//!   the engage): the ramp-out starts at the engage, at the crawl rate c.
//! * A length behind the position (the spindle turned back past it during
//!   the ramp-out): the run ends at the crawl rate, with `done`, where it
//!   is.
//! * Position and length are L bits: the position wraps at 2^L.
//! * Backward counts before the lock (the spindle reversing during the
//!   ramp-in or catch-up): defined as above, but the lock's one-step bound
//!   is not claimed for them.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::konst;
use crate::blocks::port_doc::{port, PortDoc};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "electronic gearbox: an axis geared to the spindle encoder, exact rational ratio, engage on index, bounded ramp-in, catch-up and ramp-out";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: idle, every register 0"),
    port("count_up", "1", "one spindle count up (from the spindle's quadrature decoder), synchronous; with `count_down` no count"),
    port("count_down", "1", "one spindle count down, synchronous"),
    port("index", "1", "one-clock strobe: the spindle's index event; engages an armed gearbox"),
    port("arm", "1", "strobe, idle only: take the ratio, ramp, length and directions, clear `position`, `done` and `invalid`, and wait for the next index (refused with `invalid` if the ratio is not valid)"),
    port("stop", "1", "strobe: ramp out to the crawl rate and stop there; disarms while armed"),
    port("halt", "1", "strobe: idle at once, no ramp (abort, E-stop); wins over every other input"),
    port("spindle_reverse", "1", "taken at the arm: 1 = `count_down` is the spindle's forward direction"),
    port("axis_reverse", "1", "taken at the arm: 1 = a forward count steps the axis down"),
    port("numerator", "W", "taken at the arm: n, the ratio's numerator: n / d steps per spindle count, n <= d"),
    port("denominator", "W", "taken at the arm: d >= 1"),
    port("ramp", "W", "taken at the arm: the rate's change per forward count while ramping and catching up, in 1/d step per count; 0 = engage and stop at full rate; ramp x 2^(E - W - 1) >= n"),
    port("length", "L", "taken at the arm: steps from the index at which the run ends (ramped out to reach it exactly); 0 = no end"),
    port("step_up", "1", "one-clock step request, axis up; registered"),
    port("step_down", "1", "one-clock step request, axis down; registered"),
    port("phase", "3", "0 idle, 1 armed, 2 ramp-in, 3 track, 4 stopping; registered"),
    port("locked", "1", "tracking at the ratio with the lag caught up: the axis 0 or 1 step behind floor(n x counts / d) (with ramp <= d)"),
    port("done", "1", "sticky: the last run reached `length`; cleared by an arm"),
    port("invalid", "1", "sticky: an arm was refused (d = 0, n > d, or ramp too small for n); cleared by a valid arm"),
    port("overrun", "1", "sticky: a count came while the engine worked on one and another waited: it was lost, and the gearbox halted; cleared by an arm"),
    port("position", "L", "net steps requested since the arm, forward positive, two's complement, wrapping; registered"),
];

/// Phase codes.
const IDLE: u64 = 0;
const ARMED: u64 = 1;
const RAMP_IN: u64 = 2;
const TRACK: u64 = 3;
const STOPPING: u64 = 4;

/// The exported gearbox: W = 24, E = 40, L = 24.
pub type ElectronicGearbox24 = ElectronicGearbox<24, 40, 24>;

/// The electronic gearbox. `E` >= `W` + 2 and `E` >= `L` + 2. See the
/// [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct ElectronicGearbox<const W: usize, const E: usize, const L: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// A spindle count up.
    pub count_up: Signal<In, Bit>,
    /// A spindle count down.
    pub count_down: Signal<In, Bit>,
    /// The spindle's index event.
    pub index: Signal<In, Bit>,
    /// Arm (idle only).
    pub arm: Signal<In, Bit>,
    /// Ramp out and stop.
    pub stop: Signal<In, Bit>,
    /// Stop at once.
    pub halt: Signal<In, Bit>,
    /// `count_down` is forward.
    pub spindle_reverse: Signal<In, Bit>,
    /// A forward count steps the axis down.
    pub axis_reverse: Signal<In, Bit>,
    /// Ratio numerator.
    pub numerator: Signal<In, Bits<W>>,
    /// Ratio denominator.
    pub denominator: Signal<In, Bits<W>>,
    /// Rate change per count.
    pub ramp: Signal<In, Bits<W>>,
    /// The run's length in steps, 0 = none.
    pub length: Signal<In, Bits<L>>,
    /// Step request up.
    pub step_up: Signal<Out, Bit>,
    /// Step request down.
    pub step_down: Signal<Out, Bit>,
    /// The phase code.
    pub phase: Signal<Out, Bits<3>>,
    /// Locked to the ratio.
    pub locked: Signal<Out, Bit>,
    /// The last run reached its length.
    pub done: Signal<Out, Bit>,
    /// An arm was refused.
    pub invalid: Signal<Out, Bit>,
    /// A count was lost: the gearbox halted.
    pub overrun: Signal<Out, Bit>,
    /// Net steps since the arm.
    pub position: Signal<Out, Bits<L>>,

    /// The phase code.
    state: DFF<Bits<3>>,
    /// A `stop` ramps this run out.
    command_stop: DFF<Bit>,
    /// The rate r, 1/d step per count.
    rate: DFF<Bits<W>>,
    /// The rate before this count's change.
    rate_old: DFF<Bits<W>>,
    /// u = r - n while tracking.
    catch_up: DFF<Bits<W>>,
    /// d - f: the rate still to add before the next step, in (0, d].
    to_step: DFF<Bits<W>>,
    /// X = e - S: the lag less the catch-up's braking distance (signed).
    slack: DFF<Bits<E>>,
    /// The ramp-out bound D's distance to its next whole step, in (0, d].
    to_brake: DFF<Bits<W>>,
    /// The position.
    steps: DFF<Bits<L>>,
    /// G = length - travel (signed).
    to_length: DFF<Bits<E>>,
    /// R = G - D's whole steps: the ramp-out starts at R <= 3 (signed).
    beyond_brake: DFF<Bits<E>>,
    locked_flag: DFF<Bit>,
    done_flag: DFF<Bit>,
    invalid_flag: DFF<Bit>,
    overrun_flag: DFF<Bit>,
    up_request: DFF<Bit>,
    down_request: DFF<Bit>,
    num: DFF<Bits<W>>,
    den: DFF<Bits<W>>,
    ramp_taken: DFF<Bits<W>>,
    /// d - n, taken at the arm.
    headroom: DFF<Bits<W>>,
    /// c = min(ramp, n) (n with ramp 0), taken at the arm.
    crawl: DFF<Bits<W>>,
    has_length: DFF<Bit>,
    spindle_back: DFF<Bit>,
    axis_back: DFF<Bit>,
    /// The engine's micro-step, one-hot; 0 = idle.
    seq: DFF<Bits<15>>,
    /// The engine's scratch value.
    work: DFF<Bits<E>>,
    /// The second clock of a micro-step (its adder and writes).
    second_half: DFF<Bit>,
    operand_a: DFF<Bits<E>>,
    operand_b: DFF<Bits<E>>,
    operand_sub: DFF<Bit>,
    /// The count in work is forward.
    fwd: DFF<Bit>,
    /// The phase the count in work sees.
    eff_ramp_in: DFF<Bit>,
    eff_track: DFF<Bit>,
    eff_stopping: DFF<Bit>,
    /// A count waits.
    pending: DFF<Bit>,
    pending_fwd: DFF<Bit>,
    /// A `stop` came while the engine worked.
    stop_request: DFF<Bit>,
    /// Flags the engine's steps leave for later ones.
    gap_zero: DFF<Bit>,
    full: DFF<Bit>,
    room: DFF<Bit>,
    covers: DFF<Bit>,
    hold_q: DFF<Bit>,
    lock_now: DFF<Bit>,
    ge: DFF<Bit>,
    slows: DFF<Bit>,
    le: DFF<Bit>,
    step_back: DFF<Bit>,
    step_fwd: DFF<Bit>,
    brake_carry: DFF<Bit>,
    brake_borrow: DFF<Bit>,
    reached: DFF<Bit>,
    forward_in: Signal<Local, Bit>,
    counted: Signal<Local, Bit>,
    engaged: Signal<Local, Bit>,
    ratio_valid: Signal<Local, Bit>,
    arm_crawl: Signal<Local, Bits<W>>,
    slack_negative: Signal<Local, Bit>,
    length_near: Signal<Local, Bit>,
    at_length: Signal<Local, Bit>,
    trigger: Signal<Local, Bit>,
    stop_now: Signal<Local, Bit>,
    stopping_now: Signal<Local, Bit>,
    accelerate: Signal<Local, Bit>,
    decelerate: Signal<Local, Bit>,
    brake_up: Signal<Local, Bit>,
    brake_down: Signal<Local, Bit>,
    run_over: Signal<Local, Bit>,
    ramp_zero: Signal<Local, Bit>,
    catch_up_zero: Signal<Local, Bit>,
    a_num: Signal<Local, Bits<W>>,
    a_rate: Signal<Local, Bits<W>>,
    a_catch: Signal<Local, Bits<W>>,
    a_step: Signal<Local, Bits<W>>,
    a_ramp: Signal<Local, Bits<W>>,
    a_head: Signal<Local, Bits<W>>,
    a_den: Signal<Local, Bits<W>>,
    a_crawl: Signal<Local, Bits<W>>,
    a_rold: Signal<Local, Bits<W>>,
    a_brake: Signal<Local, Bits<W>>,
    a_work_e: Signal<Local, Bits<E>>,
    a_slack_e: Signal<Local, Bits<E>>,
    a_len_e: Signal<Local, Bits<E>>,
    a_beyond_e: Signal<Local, Bits<E>>,
    a_narrow: Signal<Local, Bits<W>>,
    b_rate: Signal<Local, Bits<W>>,
    b_ramp: Signal<Local, Bits<W>>,
    b_crawl: Signal<Local, Bits<W>>,
    b_den: Signal<Local, Bits<W>>,
    b_catch: Signal<Local, Bits<W>>,
    b_brake: Signal<Local, Bits<W>>,
    b_rold: Signal<Local, Bits<W>>,
    b_step: Signal<Local, Bits<W>>,
    b_work_e: Signal<Local, Bits<E>>,
    b_one_e: Signal<Local, Bits<E>>,
    b_two_e: Signal<Local, Bits<E>>,
    b_narrow: Signal<Local, Bits<W>>,
    overrunning: Signal<Local, Bit>,
    arm_take: Signal<Local, Bit>,
    arm_load: Signal<Local, Bit>,
    run_end: Signal<Local, Bit>,
    stepped: Signal<Local, Bit>,
    idle_now: Signal<Local, Bit>,
    narrow_out: Signal<Local, Bits<W>>,
    step_delta: Signal<Local, Bits<L>>,
    write_seq: Signal<Local, Bits<15>>,
    alu_a: Signal<Local, Bits<E>>,
    alu_b: Signal<Local, Bits<E>>,
    alu_sub: Signal<Local, Bit>,
    alu_out: Signal<Local, Bits<E>>,
    alu_negative: Signal<Local, Bit>,
    alu_zero: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
    commit: Signal<Local, Bit>,
    abort: Signal<Local, Bit>,
    zero_w: Constant<Bits<W>>,
    zero_e: Constant<Bits<E>>,
    zero_l: Constant<Bits<L>>,
    one_e: Constant<Bits<E>>,
    two_e: Constant<Bits<E>>,
    one_l: Constant<Bits<L>>,
    all_ones_l: Constant<Bits<L>>,
    four_e: Constant<Bits<E>>,
    sign_e: Constant<Bits<E>>,
    ramp_shift: Constant<Bits<8>>,
    zero_seq: Constant<Bits<15>>,
    first_seq: Constant<Bits<15>>,
    idle_code: Constant<Bits<3>>,
    armed_code: Constant<Bits<3>>,
    ramp_in_code: Constant<Bits<3>>,
    track_code: Constant<Bits<3>>,
    stopping_code: Constant<Bits<3>>,
}

impl<const W: usize, const E: usize, const L: usize> Default for ElectronicGearbox<W, E, L> {
    fn default() -> Self {
        assert!(
            E >= W + 2 && E >= L + 2 && E <= 64,
            "electronic_gearbox: E >= W + 2, E >= L + 2, E <= 64"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            count_up: Default::default(),
            count_down: Default::default(),
            index: Default::default(),
            arm: Default::default(),
            stop: Default::default(),
            halt: Default::default(),
            spindle_reverse: Default::default(),
            axis_reverse: Default::default(),
            numerator: Default::default(),
            denominator: Default::default(),
            ramp: Default::default(),
            length: Default::default(),
            step_up: Default::default(),
            step_down: Default::default(),
            phase: Default::default(),
            locked: Default::default(),
            done: Default::default(),
            invalid: Default::default(),
            overrun: Default::default(),
            position: Default::default(),
            state: Default::default(),
            command_stop: Default::default(),
            rate: Default::default(),
            rate_old: Default::default(),
            catch_up: Default::default(),
            to_step: Default::default(),
            slack: Default::default(),
            to_brake: Default::default(),
            steps: Default::default(),
            to_length: Default::default(),
            beyond_brake: Default::default(),
            locked_flag: Default::default(),
            done_flag: Default::default(),
            invalid_flag: Default::default(),
            overrun_flag: Default::default(),
            up_request: Default::default(),
            down_request: Default::default(),
            num: Default::default(),
            den: Default::default(),
            ramp_taken: Default::default(),
            headroom: Default::default(),
            crawl: Default::default(),
            has_length: Default::default(),
            spindle_back: Default::default(),
            axis_back: Default::default(),
            seq: Default::default(),
            work: Default::default(),
            second_half: Default::default(),
            operand_a: Default::default(),
            operand_b: Default::default(),
            operand_sub: Default::default(),
            fwd: Default::default(),
            eff_ramp_in: Default::default(),
            eff_track: Default::default(),
            eff_stopping: Default::default(),
            pending: Default::default(),
            pending_fwd: Default::default(),
            stop_request: Default::default(),
            gap_zero: Default::default(),
            full: Default::default(),
            room: Default::default(),
            covers: Default::default(),
            hold_q: Default::default(),
            lock_now: Default::default(),
            ge: Default::default(),
            slows: Default::default(),
            le: Default::default(),
            step_back: Default::default(),
            step_fwd: Default::default(),
            brake_carry: Default::default(),
            brake_borrow: Default::default(),
            reached: Default::default(),
            forward_in: Default::default(),
            counted: Default::default(),
            engaged: Default::default(),
            ratio_valid: Default::default(),
            arm_crawl: Default::default(),
            slack_negative: Default::default(),
            length_near: Default::default(),
            at_length: Default::default(),
            trigger: Default::default(),
            stop_now: Default::default(),
            stopping_now: Default::default(),
            accelerate: Default::default(),
            decelerate: Default::default(),
            brake_up: Default::default(),
            brake_down: Default::default(),
            run_over: Default::default(),
            ramp_zero: Default::default(),
            catch_up_zero: Default::default(),
            a_num: Default::default(),
            a_rate: Default::default(),
            a_catch: Default::default(),
            a_step: Default::default(),
            a_ramp: Default::default(),
            a_head: Default::default(),
            a_den: Default::default(),
            a_crawl: Default::default(),
            a_rold: Default::default(),
            a_brake: Default::default(),
            a_work_e: Default::default(),
            a_slack_e: Default::default(),
            a_len_e: Default::default(),
            a_beyond_e: Default::default(),
            a_narrow: Default::default(),
            b_rate: Default::default(),
            b_ramp: Default::default(),
            b_crawl: Default::default(),
            b_den: Default::default(),
            b_catch: Default::default(),
            b_brake: Default::default(),
            b_rold: Default::default(),
            b_step: Default::default(),
            b_work_e: Default::default(),
            b_one_e: Default::default(),
            b_two_e: Default::default(),
            b_narrow: Default::default(),
            overrunning: Default::default(),
            arm_take: Default::default(),
            arm_load: Default::default(),
            run_end: Default::default(),
            stepped: Default::default(),
            idle_now: Default::default(),
            narrow_out: Default::default(),
            step_delta: Default::default(),
            write_seq: Default::default(),
            alu_a: Default::default(),
            alu_b: Default::default(),
            alu_sub: Default::default(),
            alu_out: Default::default(),
            alu_negative: Default::default(),
            alu_zero: Default::default(),
            take: Default::default(),
            commit: Default::default(),
            abort: Default::default(),
            zero_w: konst(0),
            zero_e: konst(0),
            zero_l: konst(0),
            one_e: konst(1),
            two_e: konst(2),
            one_l: konst(1),
            all_ones_l: konst(u64::MAX >> (64 - L)),
            four_e: konst(4),
            sign_e: konst(1 << (E - 1)),
            ramp_shift: konst((E - W - 1) as u64),
            zero_seq: konst(0),
            first_seq: konst(1),
            idle_code: konst(IDLE),
            armed_code: konst(ARMED),
            ramp_in_code: konst(RAMP_IN),
            track_code: konst(TRACK),
            stopping_code: konst(STOPPING),
        }
    }
}

impl<const W: usize, const E: usize, const L: usize> Logic for ElectronicGearbox<W, E, L> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            state,
            command_stop,
            rate,
            rate_old,
            catch_up,
            to_step,
            slack,
            to_brake,
            steps,
            to_length,
            beyond_brake,
            locked_flag,
            done_flag,
            invalid_flag,
            overrun_flag,
            up_request,
            down_request,
            num,
            den,
            ramp_taken,
            headroom,
            crawl,
            has_length,
            spindle_back,
            axis_back,
            seq,
            work,
            second_half,
            operand_a,
            operand_b,
            operand_sub,
            fwd,
            eff_ramp_in,
            eff_track,
            eff_stopping,
            pending,
            pending_fwd,
            stop_request,
            gap_zero,
            full,
            room,
            covers,
            hold_q,
            lock_now,
            ge,
            slows,
            le,
            step_back,
            step_fwd,
            brake_carry,
            brake_borrow,
            reached
        );
        self.step_up.next = self.up_request.q.val();
        self.step_down.next = self.down_request.q.val();
        self.phase.next = self.state.q.val();
        self.locked.next = self.locked_flag.q.val();
        self.done.next = self.done_flag.q.val();
        self.invalid.next = self.invalid_flag.q.val();
        self.overrun.next = self.overrun_flag.q.val();
        self.position.next = self.steps.q.val();
        self.up_request.d.next = false;
        self.down_request.d.next = false;
        self.second_half.d.next = !self.second_half.q.val();
        self.seq.d.next = self.seq.q.val();
        if self.second_half.q.val() {
            self.seq.d.next = self.seq.q.val() << 1;
        }

        // The count on the pins, in the spindle's forward direction.
        self.counted.next = self.count_up.val() ^ self.count_down.val();
        self.forward_in.next = self.count_up.val() ^ self.spindle_back.q.val();
        self.engaged.next = (self.state.q.val() == self.ramp_in_code.val())
            | (self.state.q.val() == self.track_code.val())
            | (self.state.q.val() == self.stopping_code.val());

        // The arm's check of the ratio and its crawl rate, on the inputs.
        self.ratio_valid.next = (self.denominator.val() != self.zero_w.val())
            & (self.numerator.val() <= self.denominator.val())
            & ((self.ramp.val() == self.zero_w.val())
                | ((bit_cast::<E, W>(self.ramp.val()) << self.ramp_shift.val())
                    >= bit_cast::<E, W>(self.numerator.val())));
        self.arm_crawl.next = self.ramp.val();
        if (self.ramp.val() == self.zero_w.val()) | (self.ramp.val() >= self.numerator.val()) {
            self.arm_crawl.next = self.numerator.val();
        }

        // The phase a count taken now sees: a `stop` (now or while the
        // engine worked), or R <= 3 in ramp-in or track, starts the ramp-out.
        self.slack_negative.next = (self.slack.q.val() & self.sign_e.val()) != self.zero_e.val();
        self.length_near.next = ((self.beyond_brake.q.val() & self.sign_e.val())
            != self.zero_e.val())
            | (self.beyond_brake.q.val() < self.four_e.val());
        self.at_length.next = ((self.to_length.q.val() & self.sign_e.val()) != self.zero_e.val())
            | (self.to_length.q.val() == self.zero_e.val());
        self.trigger.next = self.has_length.q.val()
            & !self.command_stop.q.val()
            & ((self.state.q.val() == self.ramp_in_code.val())
                | (self.state.q.val() == self.track_code.val()))
            & self.length_near.val();
        self.stop_now.next = self.stop.val() | self.stop_request.q.val();
        self.stopping_now.next = (self.state.q.val() == self.stopping_code.val())
            | self.trigger.val()
            | self.stop_now.val();

        // The decisions the engine's flags make.
        self.ramp_zero.next = self.ramp_taken.q.val() == self.zero_w.val();
        self.catch_up_zero.next = self.catch_up.q.val() == self.zero_w.val();
        self.accelerate.next = self.covers.q.val() & self.room.q.val();
        self.decelerate.next = !self.accelerate.val() & !self.hold_q.q.val();
        self.brake_up.next = self.fwd.q.val()
            & ((self.eff_ramp_in.q.val() & !self.gap_zero.q.val())
                | (self.eff_track.q.val() & self.accelerate.val() & !self.ramp_zero.val()));
        self.brake_down.next = self.fwd.q.val() & self.eff_track.q.val() & self.decelerate.val();
        self.run_over.next = self.le.q.val()
            & (self.command_stop.q.val() | (self.has_length.q.val() & self.at_length.val()));

        // The engine's adder: alu_a + alu_b or alu_a - alu_b. Each
        // operand is an OR of its sources, each gated by its micro-steps
        // (one-hot, so at most one source is on): AND-OR, not a chain of
        // priority muxes. A value that only moves (a rate to crawl, say)
        // goes through the adder with 0, so each register has one source.
        self.a_num.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0) & self.fwd.q.val() & self.eff_ramp_in.q.val())
            | (self.seq.q.val().get_bit(3) & !self.fwd.q.val())
            | (self.seq.q.val().get_bit(5)
                & self.fwd.q.val()
                & self.eff_ramp_in.q.val()
                & self.full.q.val())
        {
            self.a_num.next = self.num.q.val();
        }
        self.a_rate.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0) & self.fwd.q.val() & self.eff_stopping.q.val())
            | (self.seq.q.val().get_bit(5)
                & self.fwd.q.val()
                & ((self.eff_ramp_in.q.val() & !self.full.q.val()) | self.eff_track.q.val()))
            | self.seq.q.val().get_bit(10)
        {
            self.a_rate.next = self.rate.q.val();
        }
        self.a_catch.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0) & self.fwd.q.val() & self.eff_track.q.val())
            | (self.seq.q.val().get_bit(6) & self.decelerate.val())
        {
            self.a_catch.next = self.catch_up.q.val();
        }
        self.a_step.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0) & !self.fwd.q.val())
            | self.seq.q.val().get_bit(11)
            | self.seq.q.val().get_bit(12)
        {
            self.a_step.next = self.to_step.q.val();
        }
        self.a_ramp.next = self.zero_w.val();
        if self.seq.q.val().get_bit(1) & self.fwd.q.val() & self.eff_ramp_in.q.val() {
            self.a_ramp.next = self.ramp_taken.q.val();
        }
        self.a_head.next = self.zero_w.val();
        if self.seq.q.val().get_bit(1) & self.fwd.q.val() & self.eff_track.q.val() {
            self.a_head.next = self.headroom.q.val();
        }
        self.a_den.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(1) & !self.fwd.q.val())
            | (self.seq.q.val().get_bit(8) & self.brake_down.val())
        {
            self.a_den.next = self.den.q.val();
        }
        self.a_crawl.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(2) & self.fwd.q.val() & self.eff_stopping.q.val())
            | (self.seq.q.val().get_bit(5)
                & self.fwd.q.val()
                & self.eff_stopping.q.val()
                & !self.slows.q.val())
        {
            self.a_crawl.next = self.crawl.q.val();
        }
        self.a_rold.next = self.zero_w.val();
        if self.seq.q.val().get_bit(7) & !self.brake_down.val() {
            self.a_rold.next = self.rate_old.q.val();
        }
        self.a_brake.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(7) & self.brake_down.val())
            | ((self.seq.q.val().get_bit(8) | self.seq.q.val().get_bit(9)) & !self.brake_down.val())
        {
            self.a_brake.next = self.to_brake.q.val();
        }
        self.a_work_e.next = self.zero_e.val();
        if (self.seq.q.val().get_bit(1) & self.fwd.q.val() & self.eff_stopping.q.val())
            | (self.seq.q.val().get_bit(2)
                & ((self.fwd.q.val() & self.eff_ramp_in.q.val()) | !self.fwd.q.val()))
            | (self.seq.q.val().get_bit(5)
                & self.fwd.q.val()
                & self.eff_stopping.q.val()
                & self.slows.q.val())
            | (self.seq.q.val().get_bit(6) & self.accelerate.val())
            | (self.seq.q.val().get_bit(9) & self.brake_down.val())
        {
            self.a_work_e.next = self.work.q.val();
        }
        self.a_slack_e.next = self.zero_e.val();
        if (self.seq.q.val().get_bit(2) & self.fwd.q.val() & self.eff_track.q.val())
            | (self.seq.q.val().get_bit(3) & self.fwd.q.val())
            | self.seq.q.val().get_bit(4)
        {
            self.a_slack_e.next = self.slack.q.val();
        }
        self.a_len_e.next = self.zero_e.val();
        if self.seq.q.val().get_bit(13) {
            self.a_len_e.next = self.to_length.q.val();
        }
        self.a_beyond_e.next = self.zero_e.val();
        if self.seq.q.val().get_bit(14) {
            self.a_beyond_e.next = self.beyond_brake.q.val();
        }
        self.a_narrow.next = self.a_num.val()
            | self.a_rate.val()
            | self.a_catch.val()
            | self.a_step.val()
            | self.a_ramp.val()
            | self.a_head.val()
            | self.a_den.val()
            | self.a_crawl.val()
            | self.a_rold.val()
            | self.a_brake.val();
        self.alu_a.next = bit_cast::<E, W>(self.a_narrow.val())
            | self.a_work_e.val()
            | self.a_slack_e.val()
            | self.a_len_e.val()
            | self.a_beyond_e.val();
        self.b_rate.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0)
            & ((self.fwd.q.val() & self.eff_ramp_in.q.val()) | !self.fwd.q.val()))
            | (self.seq.q.val().get_bit(2) & self.fwd.q.val() & self.eff_stopping.q.val())
            | (self.seq.q.val().get_bit(3) & !self.fwd.q.val())
            | (self.seq.q.val().get_bit(7) & self.brake_down.val())
            | self.seq.q.val().get_bit(11)
        {
            self.b_rate.next = self.rate.q.val();
        }
        self.b_ramp.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(0)
            & self.fwd.q.val()
            & (self.eff_track.q.val() | self.eff_stopping.q.val()))
            | (self.seq.q.val().get_bit(2) & self.fwd.q.val() & self.eff_ramp_in.q.val())
            | (self.seq.q.val().get_bit(3)
                & self.fwd.q.val()
                & self.eff_track.q.val()
                & !self.accelerate.val()
                & !self.hold_q.q.val())
            | (self.seq.q.val().get_bit(5)
                & self.fwd.q.val()
                & ((self.eff_ramp_in.q.val() & !self.full.q.val())
                    | (self.eff_track.q.val() & (self.accelerate.val() | self.decelerate.val()))))
            | (self.seq.q.val().get_bit(6) & self.decelerate.val())
        {
            self.b_ramp.next = self.ramp_taken.q.val();
        }
        self.b_crawl.next = self.zero_w.val();
        if self.seq.q.val().get_bit(1) & self.fwd.q.val() & self.eff_stopping.q.val() {
            self.b_crawl.next = self.crawl.q.val();
        }
        self.b_den.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(2) & !self.fwd.q.val() & self.step_back.q.val())
            | (self.seq.q.val().get_bit(9)
                & ((self.brake_up.val() & self.brake_carry.q.val())
                    | (self.brake_down.val() & self.brake_borrow.q.val())))
            | self.seq.q.val().get_bit(12)
        {
            self.b_den.next = self.den.q.val();
        }
        self.b_catch.next = self.zero_w.val();
        if (self.seq.q.val().get_bit(3)
            & self.fwd.q.val()
            & self.eff_track.q.val()
            & !self.accelerate.val()
            & self.hold_q.q.val())
            | (self.seq.q.val().get_bit(4) & !self.fwd.q.val() & self.eff_track.q.val())
        {
            self.b_catch.next = self.catch_up.q.val();
        }
        self.b_brake.next = self.zero_w.val();
        if self.seq.q.val().get_bit(7) & !self.brake_down.val() {
            self.b_brake.next = self.to_brake.q.val();
        }
        self.b_rold.next = self.zero_w.val();
        if self.seq.q.val().get_bit(8) & !self.brake_down.val() {
            self.b_rold.next = self.rate_old.q.val();
        }
        self.b_step.next = self.zero_w.val();
        if self.seq.q.val().get_bit(10) {
            self.b_step.next = self.to_step.q.val();
        }
        self.b_work_e.next = self.zero_e.val();
        if (self.seq.q.val().get_bit(1) & !(self.fwd.q.val() & self.eff_stopping.q.val()))
            | (self.seq.q.val().get_bit(2) & self.fwd.q.val() & self.eff_track.q.val())
            | (self.seq.q.val().get_bit(3)
                & self.fwd.q.val()
                & (self.eff_ramp_in.q.val() | self.accelerate.val()))
            | (self.seq.q.val().get_bit(4) & !(!self.fwd.q.val() & self.eff_track.q.val()))
            | (self.seq.q.val().get_bit(8) & self.brake_down.val())
        {
            self.b_work_e.next = self.work.q.val();
        }
        self.b_one_e.next = self.zero_e.val();
        if self.seq.q.val().get_bit(13)
            | (self.seq.q.val().get_bit(14)
                & ((self.fwd.q.val()
                    & ((self.step_fwd.q.val()
                        ^ (self.brake_up.val() & self.brake_carry.q.val()))
                        & !(self.brake_down.val() & self.brake_borrow.q.val())))
                    | (self.fwd.q.val()
                        & self.brake_down.val()
                        & self.brake_borrow.q.val()
                        & !self.step_fwd.q.val())
                    | (!self.fwd.q.val() & self.step_back.q.val())))
        {
            self.b_one_e.next = self.one_e.val();
        }
        self.b_two_e.next = self.zero_e.val();
        if self.seq.q.val().get_bit(14)
            & self.fwd.q.val()
            & self.step_fwd.q.val()
            & self.brake_up.val()
            & self.brake_carry.q.val()
        {
            self.b_two_e.next = self.two_e.val();
        }
        self.b_narrow.next = self.b_rate.val()
            | self.b_ramp.val()
            | self.b_crawl.val()
            | self.b_den.val()
            | self.b_catch.val()
            | self.b_brake.val()
            | self.b_rold.val()
            | self.b_step.val();
        self.alu_b.next = bit_cast::<E, W>(self.b_narrow.val())
            | self.b_work_e.val()
            | self.b_one_e.val()
            | self.b_two_e.val();
        self.alu_sub.next = (self.seq.q.val().get_bit(0)
            & self.fwd.q.val()
            & (self.eff_ramp_in.q.val() | self.eff_stopping.q.val()))
            | self.seq.q.val().get_bit(1)
            | self.seq.q.val().get_bit(2)
            | (self.seq.q.val().get_bit(3)
                & ((self.fwd.q.val()
                    & self.eff_track.q.val()
                    & (self.accelerate.val() | self.hold_q.q.val()))
                    | !self.fwd.q.val()))
            | (self.seq.q.val().get_bit(4) & !(!self.fwd.q.val() & self.eff_track.q.val()))
            | (self.seq.q.val().get_bit(5) & self.eff_track.q.val() & self.decelerate.val())
            | (self.seq.q.val().get_bit(6) & self.decelerate.val())
            | (self.seq.q.val().get_bit(7) & !self.brake_down.val())
            | self.seq.q.val().get_bit(8)
            | (self.seq.q.val().get_bit(9) & self.brake_down.val())
            | self.seq.q.val().get_bit(10)
            | self.seq.q.val().get_bit(11)
            | (self.seq.q.val().get_bit(13) & self.fwd.q.val())
            | (self.seq.q.val().get_bit(14)
                & self.fwd.q.val()
                & !(self.brake_down.val() & self.brake_borrow.q.val() & !self.step_fwd.q.val()));
        // The operands are registered: a micro-step takes two clocks, its
        // operands in the first and the adder and its writes in the second.
        self.operand_a.d.next = self.alu_a.val();
        self.operand_b.d.next = self.alu_b.val();
        self.operand_sub.d.next = self.alu_sub.val();
        if self.operand_sub.q.val() {
            self.alu_out.next = self.operand_a.q.val() - self.operand_b.q.val();
        } else {
            self.alu_out.next = self.operand_a.q.val() + self.operand_b.q.val();
        }
        self.write_seq.next = self.zero_seq.val();
        if self.second_half.q.val() {
            self.write_seq.next = self.seq.q.val();
        }
        self.alu_negative.next = (self.alu_out.val() & self.sign_e.val()) != self.zero_e.val();
        self.alu_zero.next = self.alu_out.val() == self.zero_e.val();

        // Where the results go: each register takes the adder's result
        // when its micro-step writes it, its value at the arm, or 0.
        self.take.next = (self.seq.q.val() == self.zero_seq.val())
            & self.engaged.val()
            & (self.pending.q.val() | self.counted.val());
        // A halt wins: the count it meets is dropped with the rest, not an
        // overrun.
        self.overrunning.next = (self.seq.q.val() != self.zero_seq.val())
            & self.counted.val()
            & self.pending.q.val()
            & !self.halt.val();
        self.abort.next = self.halt.val() | self.overrunning.val();
        self.commit.next = self.write_seq.val().get_bit(14) & !self.abort.val();
        self.arm_take.next = (self.state.q.val() == self.idle_code.val())
            & self.arm.val()
            & !self.stop_now.val()
            & !self.halt.val();
        self.arm_load.next = self.arm_take.val() & self.ratio_valid.val();
        self.run_end.next = self.commit.val()
            & (self.reached.q.val()
                | (self.fwd.q.val() & self.eff_stopping.q.val() & self.run_over.val()));
        self.stepped.next = (self.fwd.q.val() & self.step_fwd.q.val())
            | (!self.fwd.q.val() & self.step_back.q.val());
        self.idle_now.next = self.arm_take.val()
            | self.run_end.val()
            | (self.abort.val() & (self.state.q.val() != self.idle_code.val()));
        self.narrow_out.next = self.alu_out.val().get_bits::<W>(0);
        self.step_delta.next = self.one_l.val();
        if !self.fwd.q.val() {
            self.step_delta.next = self.all_ones_l.val();
        }

        if self.write_seq.val().get_bit(0)
            | (self.write_seq.val().get_bit(2) & self.fwd.q.val() & self.eff_ramp_in.q.val())
            | (self.write_seq.val().get_bit(3) & !self.fwd.q.val())
            | (self.write_seq.val().get_bit(7) & self.brake_down.val())
        {
            self.work.d.next = self.alu_out.val();
        }
        if self.write_seq.val().get_bit(0) {
            self.gap_zero.d.next = self.alu_zero.val();
            self.ge.d.next = !self.alu_negative.val();
        }
        if self.write_seq.val().get_bit(1) {
            self.full.d.next = !self.alu_negative.val() | self.ramp_zero.val();
            self.room.d.next = !self.alu_negative.val();
            self.slows.d.next = self.ge.q.val() & !self.alu_negative.val();
            self.step_back.d.next = self.alu_negative.val();
        }
        if self.write_seq.val().get_bit(2) {
            self.covers.d.next = !self.slack_negative.val() & !self.alu_negative.val();
            self.hold_q.d.next = self.catch_up_zero.val() | !self.slack_negative.val();
            self.lock_now.d.next = self.catch_up_zero.val()
                & !self.slack_negative.val()
                & (self.ramp_zero.val() | self.alu_negative.val());
            self.le.d.next = !self.alu_negative.val();
        }
        if (self.write_seq.val().get_bit(2) & !self.fwd.q.val())
            | (self.write_seq.val().get_bit(11) & self.fwd.q.val())
            | (self.write_seq.val().get_bit(12) & self.step_fwd.q.val())
        {
            self.to_step.d.next = self.narrow_out.val();
        }
        if (self.write_seq.val().get_bit(3)
            & self.fwd.q.val()
            & ((self.eff_ramp_in.q.val() & !self.full.q.val()) | self.eff_track.q.val()))
            | (self.write_seq.val().get_bit(4)
                & ((self.fwd.q.val() & self.eff_track.q.val() & self.accelerate.val())
                    | (!self.fwd.q.val() & !self.eff_stopping.q.val())))
        {
            self.slack.d.next = self.alu_out.val();
        }
        if self.write_seq.val().get_bit(5) & self.fwd.q.val() {
            self.rate_old.d.next = self.rate.q.val();
            self.rate.d.next = self.narrow_out.val();
        }
        if self.write_seq.val().get_bit(6)
            & self.fwd.q.val()
            & self.eff_track.q.val()
            & (self.accelerate.val() | self.decelerate.val())
        {
            self.catch_up.d.next = self.narrow_out.val();
        }
        if self.write_seq.val().get_bit(7) {
            self.brake_carry.d.next = !self.alu_negative.val();
        }
        if self.write_seq.val().get_bit(8) {
            self.brake_borrow.d.next = self.alu_negative.val();
        }
        if (self.write_seq.val().get_bit(8) & self.brake_up.val())
            | (self.write_seq.val().get_bit(9)
                & ((self.brake_up.val() & self.brake_carry.q.val()) | self.brake_down.val()))
        {
            self.to_brake.d.next = self.narrow_out.val();
        }
        if self.write_seq.val().get_bit(10) {
            self.step_fwd.d.next = self.fwd.q.val() & !self.alu_negative.val();
        }
        if self.write_seq.val().get_bit(13) {
            self.reached.d.next =
                self.stepped.val() & self.has_length.q.val() & self.alu_zero.val();
            if self.stepped.val() {
                self.to_length.d.next = self.alu_out.val();
            }
        }
        if self.commit.val() {
            self.beyond_brake.d.next = self.alu_out.val();
            if self.stepped.val() {
                self.steps.d.next = self.steps.q.val() + self.step_delta.val();
                self.up_request.d.next = self.fwd.q.val() ^ self.axis_back.q.val();
                self.down_request.d.next = !(self.fwd.q.val() ^ self.axis_back.q.val());
            }
        }

        // The engine's slot and the stop that waits for it.
        if self.seq.q.val() != self.zero_seq.val() {
            if self.counted.val() {
                self.pending.d.next = true;
                self.pending_fwd.d.next = self.forward_in.val();
            }
            if self.stop.val() {
                self.stop_request.d.next = true;
            }
        } else {
            self.stop_request.d.next = false;
            self.pending.d.next = false;
            if self.take.val() {
                self.seq.d.next = self.first_seq.val();
                self.second_half.d.next = false;
                self.fwd.d.next = self.forward_in.val();
                if self.pending.q.val() {
                    self.fwd.d.next = self.pending_fwd.q.val();
                    self.pending.d.next = self.counted.val();
                    self.pending_fwd.d.next = self.forward_in.val();
                }
                self.eff_stopping.d.next = self.stopping_now.val();
                self.eff_ramp_in.d.next =
                    !self.stopping_now.val() & (self.state.q.val() == self.ramp_in_code.val());
                self.eff_track.d.next =
                    !self.stopping_now.val() & (self.state.q.val() == self.track_code.val());
            }
            if self.engaged.val() {
                self.command_stop.d.next = self.command_stop.q.val() | self.stop_now.val();
            }
        }
        if self.overrunning.val() {
            self.overrun_flag.d.next = true;
        }

        // The phase.
        if (self.seq.q.val() == self.zero_seq.val())
            & self.engaged.val()
            & !self.take.val()
            & self.stopping_now.val()
        {
            self.state.d.next = self.stopping_code.val();
            self.locked_flag.d.next = false;
        }
        if self.state.q.val() == self.armed_code.val() {
            if self.index.val() {
                self.state.d.next = self.ramp_in_code.val();
            }
            if self.stop_now.val() {
                self.state.d.next = self.idle_code.val();
            }
        }
        if (self.state.q.val() == self.idle_code.val())
            & self.arm.val()
            & !self.stop_now.val()
            & !self.halt.val()
            & !self.ratio_valid.val()
        {
            self.invalid_flag.d.next = true;
        }
        if self.commit.val() {
            if self.eff_stopping.q.val() {
                self.state.d.next = self.stopping_code.val();
                self.locked_flag.d.next = false;
            }
            if self.fwd.q.val() & self.eff_ramp_in.q.val() & (self.rate.q.val() == self.num.q.val())
            {
                self.state.d.next = self.track_code.val();
            }
            if self.fwd.q.val() & self.eff_track.q.val() & self.lock_now.q.val() {
                self.locked_flag.d.next = true;
            }
            if self.run_end.val() & (self.reached.q.val() | !self.command_stop.q.val()) {
                self.done_flag.d.next = true;
            }
        }
        // The arm's values load on any arm in idle, valid or not: an
        // invalid one leaves the gearbox idle, and the next arm loads them
        // again. Only the phase, the flags and the position wait for the
        // ratio's check (which keeps it off the wide loads' enables).
        if self.arm_take.val() {
            self.to_step.d.next = self.denominator.val();
            self.to_brake.d.next = self.denominator.val();
            self.to_length.d.next = bit_cast::<E, L>(self.length.val());
            self.beyond_brake.d.next = bit_cast::<E, L>(self.length.val());
            self.num.d.next = self.numerator.val();
            self.den.d.next = self.denominator.val();
            self.ramp_taken.d.next = self.ramp.val();
            self.headroom.d.next = self.denominator.val() - self.numerator.val();
            self.crawl.d.next = self.arm_crawl.val();
            self.has_length.d.next = self.length.val() != self.zero_l.val();
            self.spindle_back.d.next = self.spindle_reverse.val();
            self.axis_back.d.next = self.axis_reverse.val();
        }
        if self.arm_load.val() {
            self.state.d.next = self.armed_code.val();
        }
        if self.idle_now.val() & !self.arm_load.val() {
            self.state.d.next = self.idle_code.val();
        }
        if self.abort.val() {
            self.seq.d.next = self.zero_seq.val();
            self.pending.d.next = false;
            self.stop_request.d.next = false;
            self.up_request.d.next = false;
            self.down_request.d.next = false;
        }

        // The clears (synchronous resets of their flip-flops).
        if self.reset.val() | self.arm_take.val() {
            self.command_stop.d.next = false;
            self.catch_up.d.next = self.zero_w.val();
            self.slack.d.next = self.zero_e.val();
        }
        if self.reset.val() | self.arm_load.val() {
            self.steps.d.next = self.zero_l.val();
            self.done_flag.d.next = false;
            self.invalid_flag.d.next = false;
            self.overrun_flag.d.next = false;
        }
        if self.reset.val()
            | self.idle_now.val()
            | (self.write_seq.val().get_bit(5)
                & self.fwd.q.val()
                & self.eff_stopping.q.val()
                & self.run_over.val())
        {
            self.rate.d.next = self.zero_w.val();
        }
        if self.reset.val() | self.idle_now.val() {
            self.locked_flag.d.next = false;
        }
        if self.reset.val() {
            self.state.d.next = self.idle_code.val();
            self.rate_old.d.next = self.zero_w.val();
            self.to_step.d.next = self.zero_w.val();
            self.to_brake.d.next = self.zero_w.val();
            self.to_length.d.next = self.zero_e.val();
            self.beyond_brake.d.next = self.zero_e.val();
            self.up_request.d.next = false;
            self.down_request.d.next = false;
            self.num.d.next = self.zero_w.val();
            self.den.d.next = self.zero_w.val();
            self.ramp_taken.d.next = self.zero_w.val();
            self.headroom.d.next = self.zero_w.val();
            self.crawl.d.next = self.zero_w.val();
            self.has_length.d.next = false;
            self.spindle_back.d.next = false;
            self.axis_back.d.next = false;
            self.seq.d.next = self.zero_seq.val();
            self.pending.d.next = false;
            self.stop_request.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize, const E: usize, const L: usize] ElectronicGearbox<W, E, L> {
    inputs: [
        reset, count_up, count_down, index, arm, stop, halt, spindle_reverse, axis_reverse,
        numerator, denominator, ramp, length
    ],
    outputs: [step_up, step_down, phase, locked, done, invalid, overrun, position],
});
