//! # `motion_controller`: K step/encoder axes behind a CPU register bus
//!
//! The FPGA half of a DSP/CPU + FPGA motion controller. The CPU queues each
//! interpolation period's step count per axis in a FIFO; at every period
//! boundary all axes take their next entry on the same clock edge, a fine
//! interpolator per axis (a DDA or the dual-period uniform pulse generator,
//! chosen per axis) spreads the steps over the period, and a step output
//! stage emits them with enforced drive timing. Each axis also counts the
//! steps it emitted (commanded position) and decodes an encoder (actual
//! position). The CPU is interrupted to refill the FIFOs and on every
//! fault; a watchdog stops everything when the CPU goes silent.
//!
//! Composition (per axis): [`CommandFifo`](crate::blocks::command_fifo),
//! [`UniformPulseGen`](crate::blocks::uniform_pulse_gen) (whose engine
//! also runs the axis's [`DdaIntegrator`](crate::blocks::dda_integrator),
//! in its DDA mode),
//! [`StepOutput`](crate::blocks::step_output),
//! [`PulseCounter`](crate::blocks::pulse_counter) and
//! [`QuadratureDecoder`](crate::blocks::quadrature_decoder); shared: a
//! [`FreqDivider`](crate::blocks::freq_divider) base tick, the period
//! counter, a [`Watchdog`](crate::blocks::watchdog) and an
//! [`InterruptController`](crate::blocks::interrupt_controller). The
//! register map is in [`registers`] (generated as
//! `rtl-out/motion_controller_regs.h` and `rtl-out/motion_controller_regs.md`).
//!
//! ## Ports (`K` axes; the exported `motion_controller` has K = 3 and 16-entry FIFOs)
//!
#![doc = include_str!("ports.md")]
//!
//! Every switch, alarm and E-stop input is active high at reset: with the
//! FPGA's pull-ups and normally-closed contacts to ground, an open or
//! broken wire reads as tripped. `INPUT_POLARITY` makes a class active low
//! for normally-open wiring (not `estop`: an E-stop chain must fail safe).
//! A board without a switch ties the input low in its own top, or clears
//! `IO_CONFIG.LIMIT_ENABLE` / `ALARM_ENABLE`; `estop` cannot be disabled.
//!
//! This is the synchronous register bus of
//! [`external_bus_adapter`](crate::blocks::external_bus_adapter), so a DSP's
//! asynchronous external-memory interface connects through that adapter.
//!
//! ```text
//! clock           |  c   | c+1  | c+2  |
//! bus_write       /‾‾‾‾‾‾\______________     register written at edge c+1
//! bus_read        /‾‾‾‾‾‾\______________
//! bus_read_data          |  D   ...          valid after edge c+1, held
//! ```
//!
//! ## Time base and periods
//! * The base tick is one clock in `TICK_DIVISOR` (0 stops it: everything
//!   that counts ticks pauses). An interpolation period is `PERIOD_TICKS`
//!   base ticks (16 bits, 1 to 65535; 0 acts as 1), taken at each
//!   boundary. For a 1 ms period at 100 MHz, use `TICK_DIVISOR` >= 2.
//! * Writing `CONTROL.RUN` = 1 while stopped starts: the first base tick is
//!   a boundary at which every axis pops its first entry; then a boundary
//!   comes every `PERIOD_TICKS` ticks. At each boundary all axes pop on the
//!   same clock edge, `PERIOD_COUNT` counts, and `STATUS.PERIOD_DONE` is
//!   raised (except at the first boundary after a start).
//! * An entry is the signed number of steps of that axis in that period.
//!   The interpolators take it one clock after the boundary and see every
//!   tick one clock late, so the boundary tick still belongs to the old
//!   period. DDA axes emit exactly |n| steps spread over the period's P
//!   ticks (at most one per tick: |n| <= P). Uniform axes load the dual-period
//!   generator with (P, |n|), |n| <= P/2. The uniform axes share one
//!   period planner (the divider, the clamp of |n| and the split) and take
//!   turns at it in axis order, so the j-th uniform axis
//!   (from 0) runs each period [`latency::UNIFORM_LAG`] + j *
//!   [`latency::UNIFORM_TURN`] = 24 + 18 j clocks or more after its
//!   boundary: a fixed lag for a given choice of uniform axes, at most
//!   [`latency::uniform_lag`]`(K)` (60 clocks at K = 3). A period must be
//!   longer than its axis's lag in clocks, or the generator refuses the
//!   next one (`INTERP_OVERFLOW`).
//! * The commanded position counts the steps that left each output stage,
//!   so it is exact whatever happened before.
//! * **Position range.** CMD_POSITION, ACT_POSITION and their snapshot,
//!   index and home latches are [`POSITION_BITS`] = 24 bits wide
//!   (`CONFIG.POSITION_BITS`; 32 before VERSION 0.4.0). They count modulo
//!   2^24: one step past +8388607 reads -8388608, and no count is lost.
//!   Each register word carries the sign up to bit 31. A driver either
//!   keeps the machine's travel within the range (the crate's driver
//!   refuses a path that leaves it, `PositionOutOfRange`) or extends the
//!   words itself, reading each position at least once per 2^23 counts.
//!
//! ## Bad input and faults
//! * **Underrun**: a boundary that finds any axis's FIFO empty pops
//!   nothing. Every axis stops taking steps (DDA integrands go to 0, no
//!   uniform period is loaded; steps already requested still leave, and a
//!   uniform period in progress completes), `RUN` clears, and
//!   `STATUS.UNDERRUN` is raised. Restart: refill the FIFOs, clear
//!   `STATUS.UNDERRUN` if wanted, write `RUN` = 1.
//! * **Overflow**: a `FIFO_WRITE` to a full FIFO is refused; the FIFO is
//!   unchanged and `STATUS.OVERFLOW` is raised.
//! * **Watchdog**: with `WATCHDOG_TIMEOUT` != 0, the first `WATCHDOG_KICK`
//!   arms it; if `WATCHDOG_TIMEOUT` base ticks pass without a kick, every
//!   axis is aborted (see "Machine I/O and safety": interpolators reset,
//!   output stages flushed, a pulse already high keeps its full length),
//!   `RUN` clears, `STATUS.WATCHDOG` is raised, every `drive_enable` and
//!   the `GPIO_SAFE` outputs drop, and `RUN` cannot be set until
//!   `STATUS.WATCHDOG` is written 1.
//! * **Stop**: `RUN` written 0 stops the interpolators at once; steps
//!   already requested to an output stage still leave with correct timing
//!   (a stop is not an abort: nothing is flushed). `CONTROL.FLUSH`
//!   empties every FIFO at once, so a restart does not run stale periods.
//! * **Interpolator choice** (`AXIS_CONFIG.UNIFORM`) is taken at a start,
//!   for an axis whose uniform generator is idle; an axis still finishing
//!   a uniform period keeps the generator until the next start, so no
//!   pulse is cut off. A DDA-only build (see "Build options") has no
//!   choice: `UNIFORM` reads 0 and every axis runs its DDA.
//! * **Encoder error**: A and B changing on one sample counts nothing, sets
//!   `AXIS_STATUS.ENCODER_ERROR` and raises `STATUS.ENCODER_ERROR`.
//!   `CLEAR_ENCODER_ERROR` acknowledges it and keeps `ACT_POSITION` (the
//!   next error interrupts again); `CLEAR_ENCODER` zeroes the position too.
//! * **Lost steps** (never silent): a count beyond what the interpolator
//!   can emit is clamped (`INTERP_OVERRANGE`; on a uniform axis an odd
//!   `PERIOD_TICKS` is also corrected and flagged), a uniform period
//!   refused for lack of set-up time (`INTERP_OVERFLOW`), a saturated
//!   output stage (`STEP_OVERRUN`). Each is sticky in `AXIS_STATUS` until
//!   `CLEAR_FAULTS` (a stop or a start does not clear it), each occurrence
//!   raises `STATUS.AXIS_FAULT`, and the commanded position still counts
//!   only what was emitted. A DDA axis asked for more steps per period than
//!   its output stage's timing allows is not flagged until the stage's
//!   pending count saturates at +127 or -128 steps behind
//!   (`STAGE_PENDING_BITS` = 8): up to then the steps are delayed, not lost.
//! * **Reset or a STEP_MODE change in quadrature mode** returns A/B to 00
//!   from whatever state they were in, which a drive may count as a step:
//!   change modes and reset only with the drive disabled.
//! * Writes to read-only or unused addresses are ignored; reads of unused
//!   addresses return 0.
//!
//! * **Entry too large**: |n| > 65535 is saturated to 65535 and
//!   `INTERP_OVERRANGE` is set one clock after the entry is taken (then the
//!   interpolator's own clamp applies).
//! * **Uniform clamp timing** (VERSION 0.3.1): on a uniform axis, an odd
//!   or too small `PERIOD_TICKS` sets `INTERP_OVERRANGE` 4 clocks after
//!   the boundary (3 after the entry is taken); |n| > P/2 sets it when the
//!   axis's plan arrives from the shared planner,
//!   [`latency::UNIFORM_LAG`] - 2 + j * [`latency::UNIFORM_TURN`] clocks
//!   after the boundary (22 + 18 j; j as for the lag). Before 0.3.1 both
//!   were set 4 clocks after it.
//! * **`CLEAR_POSITION` in motion**: `CMD_POSITION` becomes 0 at the first
//!   edge, from the one that ends the write on, at which no step is
//!   counted: one clock later if a step is counted on the write's own
//!   clock (steps are at least 2 clocks apart unless a quadrature output
//!   runs at one state per clock, which postpones the clear until it
//!   pauses). Each step is thus in the old count, as read before the clear
//!   takes effect, or in the new one: none is lost or counted twice.
//!
//! ## Machine I/O and safety
//! Limits, drive alarms and the E-stop act in hardware, within the clocks
//! given in [`latency`] (each measured at the pins by `tests/controller/machine_io.rs`).
//! * **Inputs.** Every switch, alarm, E-stop and general input passes an
//!   [`InputConditioner`](crate::blocks::input_conditioner): a 2-flip-flop
//!   synchronizer and a glitch filter of `INPUT_FILTER.LENGTH` samples
//!   (reset 4), one sample every `INPUT_FILTER.SAMPLE_RATE` + 1 clocks. A
//!   level held from clock c is acted on from c + [`latency::switch`]
//!   (LENGTH 4, rate 0: 5 clocks); a shorter pulse is never seen. For 3
//!   clocks after reset the inputs read inactive and `RUN` is refused
//!   (`STATE.INPUTS_READY`).
//! * **Abort** (E-stop, an enabled drive alarm, a limit cut, a home with
//!   `STOP_ON_HOME`, the watchdog): every interpolator is reset, every
//!   output stage is flushed (its pending steps dropped: they never left,
//!   so `CMD_POSITION` stays the pins' count), and no new step enters one.
//!   A pulse already high keeps its full `STEP_LEN`, and the space, hold
//!   and setup that follow still apply. `RUN` clears; `STOP_CAUSE` tells
//!   why (and which axis); the FIFOs keep their entries until
//!   `CONTROL.FLUSH`. The last step of any axis rises at most
//!   [`latency::ABORT_ALL_AXES`] = 3 clocks after the cause is seen (1 for
//!   the watchdog). While a cause is latched (`STATE.ABORTED`) every axis
//!   stays flushed and `RUN` is refused; the E-stop input itself refuses
//!   `RUN` too.
//! * **Limits** (`IO_CONFIG.LIMIT_ENABLE`, reset 1). A step toward an
//!   enabled, active limit never leaves: offered by the interpolator, in
//!   the request register or pending in the stage, it is *cut* (dropped)
//!   in the clock it is seen, and a step toward the limit can rise at most
//!   [`latency::LIMIT_OWN_AXIS`] = 1 clock after the limit's filtered level
//!   is set (a step whose pulse started in that clock). A cut sets the
//!   sticky `IO_STATUS.LIMIT_POS_TRIPPED` or `LIMIT_NEG_TRIPPED`, raises
//!   `STATUS.LIMIT` and aborts all axes. A limit that closes while its axis
//!   moves away, or stands still, cuts nothing. After
//!   `IO_COMMAND.CLEAR_LIMITS` the axis may move away from a limit still
//!   active: that is how firmware backs off a switch.
//! * **Drive alarm** (`IO_CONFIG.ALARM_ENABLE`, reset 1): an active alarm
//!   sets the sticky `ALARM_TRIPPED` (held while the alarm lasts:
//!   `CLEAR_ALARM` works only once it is gone), raises `STATUS.ALARM`,
//!   aborts all axes and drops that axis's `drive_enable`.
//! * **E-stop**: an active `estop` sets `STATE.ESTOP_LATCHED`, raises
//!   `STATUS.ESTOP`, aborts all axes and drops every `drive_enable` and the
//!   `GPIO_SAFE` outputs. Writing `STATUS.ESTOP` = 1 releases the latch once
//!   the input is inactive.
//! * **Drive enable**: `drive_enable[k]` = `IO_CONFIG.DRIVE_ENABLE` AND no
//!   E-stop latched AND no watchdog expiry AND no alarm of axis k. It falls
//!   at the edge that latches the E-stop or the alarm
//!   ([`latency::DRIVE_ENABLE`] = 1 clock after the filtered level), and one
//!   clock after the watchdog expires.
//! * **Home**: the first active edge of `home[k]` after `CLEAR_HOME` latches
//!   `HOME_CMD_POSITION` and `HOME_ACT_POSITION` as they are in the clock
//!   the edge is acted on (c + `latency::switch`: the steps whose first pin
//!   edge came before that clock), sets `HOME_SEEN` and raises
//!   `STATUS.HOME`; later edges do not overwrite it. With
//!   `IO_CONFIG.STOP_ON_HOME` the edge also aborts (homing moves) until
//!   `CLEAR_HOME`.
//! * **Probe** (VERSION 0.5.0; build option `PROBE`, on in every
//!   exported build): the `probe` input passes a conditioner
//!   like the switches' (same `INPUT_FILTER`, no polarity bit: `EDGE`
//!   chooses). Writing `PROBE_CONTROL.ARM` = 1 arms it (and clears
//!   `TRIPPED`); the first edge `PROBE_CONTROL.EDGE` selects (0 rising, 1
//!   falling) after that trips it: in the clock the edge is acted on
//!   (c + [`latency::switch`] for a pin changed at clock c, as for home),
//!   every axis's `PROBE_CMD_POSITION` and `PROBE_ACT_POSITION` take that
//!   clock's CMD_POSITION and ACT_POSITION (the steps whose first pin edge
//!   came before it; the encoder count of that clock), on the same edge
//!   for all axes. The trip sets `TRIPPED`, disarms, and raises
//!   `STATUS.PROBE` (`irq` two clocks after the trip clock, if enabled).
//!   Later edges are ignored until the next arming: the latch holds the
//!   first contact. A `PROBE_CONTROL` write takes effect in its own clock:
//!   an edge acted on in the clock of a write that arms (disarms) trips
//!   (does not). With `PROBE_CONTROL.STOP` the trip also requests the
//!   feed hold (below) in its own clock: a controlled stop along the
//!   path, not an abort; else the firmware stops the motion. The latched
//!   positions are exact whatever the feed: the error is that of the
//!   probe's own switching, not of a servo period.
//!   `PROBE_CONTROL.LEVEL` reads the filtered input (0 until the inputs
//!   are ready); reset disarms and zeroes the latches.
//! * **Feed hold** (VERSION 0.6.0; analog axes scaled from 0.6.1;
//!   [`feed_hold`], [`hold_ramp`]): a
//!   controlled stop along the path that resumes exactly where it left
//!   off. It scales time, not steps: the periods and the axes run on the
//!   base tick through a gate that passes a fraction f of the ticks (the
//!   watchdog keeps the base tick). Every interpolator still emits exactly
//!   its entry's steps per period, so the path slows along itself, the
//!   FIFOs are not flushed, and the end position equals that of the same
//!   run without the hold on every axis; no step interval becomes shorter
//!   than it was at f = 1, and no step pulse is cut.
//!   - The request is sticky. It is set by the `feed_hold` input while
//!     it is active (conditioned like the switches, `INPUT_FILTER`, with
//!     its own polarity `HOLD_CONTROL.INVERT`), by writing
//!     `HOLD_CONTROL.HOLD` = 1 (`REQUESTED` reads it), or by a probe trip with
//!     `PROBE_CONTROL.STOP`. Only a write of `HOLD_CONTROL.RELEASE` = 1
//!     clears it, and not in a clock where one of those sets it: a release
//!     while the input is still active is refused.
//!   - The factor f (17 bits, 0 to 1 in 1/65536) moves by
//!     `HOLD_CONTROL.RATE`/65536 at each base tick, toward 0 while the
//!     request is set and back to 1 after: a deceleration per base tick,
//!     chosen over one per period so that the ramp does not depend on the
//!     period length. From full speed the stop and the return take
//!     ceil(65536 / RATE) base ticks; RATE 0 (its reset value) acts as
//!     65536, an immediate stop at the next tick, which stops the axes as
//!     RUN = 0 would but keeps every count and entry. A `HOLD_CONTROL`
//!     write's RATE applies from the next clock, as the request does (the
//!     ramp follows `REQUESTED` and `RATE` as they read), so `HOLD` and
//!     `RATE` written together ramp at that rate from the first tick.
//!   - Range: the slowest stop is 65536 base ticks (RATE 1), 1.4 ms on a
//!     48 MHz base tick. A longer stop takes a longer base tick: raise
//!     `TICK_DIVISOR` and lower `PERIOD_TICKS` to keep the period, as
//!     long as each period still has a tick for every step it asks
//!     (`simulate` chooses the divisor whose RATE stops closest to the
//!     machine's stop, `host::hold_window::hold_tick_settings`). A finer
//!     RATE would widen the ramp, its gate and the soft limits' reach by
//!     the bits it adds.
//!   - The fraction of a gated tick is carried (`phase`), so after any
//!     hold 65536 x the gated ticks + phase = the sum of f over the base
//!     ticks, exactly: no tick, and so no step, is lost or invented.
//!   - Latency: a request decided in clock d (`REQUESTED` reads it from
//!     d + 1) lowers f at the first base tick from d +
//!     [`latency::HOLD_REQUEST_TO_RAMP`] on; the next base tick is the
//!     first that may be withheld ([`latency::HOLD_FIRST_REDUCED_TICK`]). d is the clock of
//!     a `HOLD_CONTROL` write or of the probe's trip; for the input,
//!     d = c + [`latency::switch`] + 1 after a pin change at clock c (its
//!     filtered level is set at c + `switch`, the request follows in the
//!     next clock). `STATUS.HELD` is set, and `irq` rises, two clocks
//!     after the clock whose tick brings f to 0.
//!   - Held time and the FIFOs: a period lasts `PERIOD_TICKS` *gated*
//!     ticks, so it lasts 1/f as many base ticks while slowed and never
//!     ends while held (f = 0): the FIFOs are consumed more slowly, no
//!     boundary comes while held, so there is no underrun and no
//!     `STATUS.PERIOD_DONE` then, and the host may keep filling them.
//!   - `STATE.HOLDING` is set while f < 1 (slowing, held, or ramping
//!     back), `STATE.HELD` while f = 0; `STATUS.HELD` is raised when f
//!     reaches 0.
//!   - A hold and a stop are independent: RUN = 0, an underrun or an abort
//!     during a hold stops as without it (the abort flushes the stages);
//!     the request and f stay as they are. RUN = 1 while held starts, and
//!     the first boundary comes with the first gated tick.
//!   - Analog axes slow with the same factor: see "Analog axes", "The
//!     feed hold scales the codes".
//!   - A soft-limit verdict (below) also sets the request, and while it
//!     stands a release is refused.
//! * **Soft limits** (VERSION 0.7.0, revised in 0.7.1; build option `SOFT_LIMITS`, on in
//!   `motion_controller`, off in `motion_controller_dda` and
//!   `motion_controller_servo`; [`soft_limits`]): a position window per
//!   axis, `SOFT_MIN` to `SOFT_MAX` (24-bit signed steps, read back
//!   sign-extended; 0 after reset), checked against the feed hold's
//!   stopping distance, so that an axis whose path would leave its window
//!   starts the controlled stop early enough to stop inside it. The hard
//!   limits and the E-stop keep their hard stops.
//!   - The windows are block RAM: a bus read of `SOFT_MIN` or `SOFT_MAX`
//!     in the clock of a write to it reads 0, where every other register
//!     reads its old value (no adapter of this crate reads and writes in
//!     one clock); a window written in the clock its axis is loaded is
//!     checked as written.
//!   - `SOFT_LIMIT.ENABLE` (bit k) enables axis k's window (reset 0). The
//!     axes are checked in turn while RUN is set, one every
//!     [`soft_limits::CHECK_CLOCKS`] = 23 clocks. A moving step axis is
//!     *beyond* when (Δ − 2) × P <= |J| × G': Δ the steps left to the
//!     bound it heads for (`SOFT_MAX` moving up, `SOFT_MIN` down) from its
//!     CMD_POSITION, |J| its steps in the running period, P =
//!     `PERIOD_TICKS`, and G' ([`soft_limits::reach_ticks`]) the most
//!     base ticks a stop from full speed at `HOLD_CONTROL.RATE` lets
//!     through, floor(N / 2) + 1 for a stop of N = ceil(65536 / RATE)
//!     ticks, plus the check's own latency
//!     ([`soft_limits::check_latency`]`(K)` = 100 at K = 3). So the
//!     axis is stopped where its present rate, continued over the stop's
//!     reach, would still leave 2 steps of the window. N is measured by a
//!     second hold ramp in the block, not computed; `SOFT_LIMIT.MEASURED`
//!     reads 0 after reset and for ceil(65536 / RATE) + 3 clocks after
//!     RATE changes, while every moving axis is judged with the longest
//!     reach (2^17 − 1 ticks) and so trips at once: write RATE, wait for
//!     MEASURED, then start.
//!   - A verdict that turns beyond raises `STATUS.SOFT_LIMIT` and records
//!     the axis and its direction in `SOFT_LIMIT.AXIS` and `NEGATIVE`;
//!     `BEYOND` (bit k) is each axis's live verdict. Any verdict beyond
//!     sets the hold's request in every clock it stands (the path stops
//!     along itself, on every axis, at `RATE`; the FIFOs keep their
//!     entries), and a `RELEASE` is refused while it stands. It stands
//!     while the held axis's entry still heads out: the host stops (RUN
//!     = 0 clears every verdict at the next edge), releases, flushes, and
//!     backs the axis in with new entries (a move back into the window is
//!     never beyond), or clears the axis's ENABLE to run on past it.
//!   - Latency: a verdict follows its axis's load by 23 clocks; the stop's
//!     request follows it by one clock, as a probe stop's does.
//!   - The guarantee: the axis stops inside its window when its rate
//!     toward the bound does not grow during the stop's reach (the check
//!     judges the running period's rate; an entry that speeds up toward
//!     the bound within G' ticks of it can carry the axis past by the
//!     extra steps). Steps still queued in an output stage (a stage whose
//!     timing is slower than the entries ask) are not in CMD_POSITION and
//!     not counted. A move that ends at a bound at speed trips within
//!     its reach of the bound: set the window outside the planner's
//!     travel by the reach at the final approach speed (a backstop, as
//!     LinuxCNC's joint limits beyond its soft limits).
//!   - Analog axes and standing axes are never beyond; an axis outside
//!     its window heading further out is beyond at once.
//! * **General I/O**: `GPIO_IN` reads the 8 filtered inputs; every edge is
//!   recorded in `GPIO_EDGES` (write 1 to clear) and the ones enabled in
//!   `GPIO_IRQ_ENABLE` raise `STATUS.GPIO`. `gpio_out` is `GPIO_OUT`; the
//!   bits of `GPIO_SAFE` are cleared, and held 0, from the edge that latches
//!   an E-stop and from the clock after a watchdog expiry (spindle,
//!   coolant): firmware must turn them on again after the recovery.
//! * Power-up without a reset: `IO_CONFIG` and `INPUT_FILTER` read their
//!   reset values (their flip-flops hold the value XOR the reset value), so
//!   limits and alarms are enabled from the first clock.
//!
//! ## Spindle encoder and electronic gearbox (VERSION 0.8.0; build option `SPINDLE`)
//! On in `motion_controller_dda_spindle` ([`MotionController3DdaSpindle`]);
//! [`spindle`], [`gear_merge`]. Threading and rigid tapping: one axis
//! is geared to the spindle's encoder, in exact ratio, from the same
//! spindle angle at every pass.
//! * **Registers**: a window at `0xE0` (`SPINDLE_*`, `GEAR_*`: see the
//!   register map), where the seventh axis window would be, so a `SPINDLE`
//!   build has at most [`registers::MAX_AXES_SPINDLE`] = 6 axes.
//! * **The encoder** (`spindle_a`, `spindle_b`, `spindle_index`) passes a
//!   [`QuadratureDecoder`](crate::blocks::quadrature_decoder) with
//!   `SPINDLE_CONFIG.FILTER`, `COUNTER_MODE` and `INDEX_INVERT` (each
//!   applied from the clock after its write), sampled every clock.
//!   `SPINDLE_POSITION` is its count (POSITION_BITS, wrapping, never
//!   cleared: the host takes differences); `SPINDLE_INDEX_POSITION` the
//!   count at the last index event; `SPINDLE_SPEED` the counts in the last
//!   window of 2^`SPEED_WINDOW` clocks (reset 20), updated at each
//!   window's end (a window ends where bit n of a free-running clock
//!   counter changes; a new n applies from the next clock, so the window
//!   in which it changes may be short). It is the position's change
//!   modulo 2^24: choose n so that fewer than 2^23 counts pass in a window.
//!   A and B changing on one sample set `GEAR_STATUS.ENCODER_ERROR`
//!   (counts lost; `GEAR_CONTROL.CLEAR_ENCODER_ERROR` clears it).
//! * **The gearbox** is an
//!   [`ElectronicGearbox`](crate::blocks::electronic_gearbox) (W = 24,
//!   E = 40, L = 24): its datasheet states the ratio, the ramp-in and the
//!   catch-up (a bang-bang law on the lost phase, at `GEAR_RAMP`/d step
//!   per count per count, so the acceleration is bounded in spindle
//!   counts), `LOCKED`, the run's length and the ramp-out, exactly. The
//!   unit feeds it each count of the encoder (one clock after the count
//!   changes), each index event, and `GEAR_CONTROL`'s strobes; its
//!   parameters are `GEAR_NUMERATOR`, `DENOMINATOR`, `RAMP` and `LENGTH`
//!   as they read in the clock of the arm.
//! * **Arming**: writing `GEAR_CONTROL.ARM` = 1 while `PHASE` reads 0
//!   arms the gearbox for the axis in that write's `AXIS`, with its
//!   `SPINDLE_REVERSE` and `AXIS_REVERSE`; it engages at the next index
//!   event, so every pass starts at the same spindle angle. `AXIS`, the
//!   directions and the ratio are kept for the run: a `GEAR_CONTROL` write
//!   while armed or engaged changes only what its strobes do. An arm with
//!   `AXIS` >= K, or with a ratio the gearbox refuses (d = 0, n > d, RAMP
//!   x 2^15 < n), sets `INVALID` and leaves the gearbox idle.
//! * **Motion**: each gearbox step joins the geared axis's steps in front
//!   of its request register ([`gear_merge`]): it shares the axis's limit
//!   gate, output stage, step timing and `CMD_POSITION` with the FIFO's
//!   steps, which add to it (tapers, retracts). An interpolator step has
//!   the clock; a gearbox step that meets one waits one clock (a hold of
//!   one). A gearbox step lost (the hold full and the interpolator
//!   stepping in each of the 31 clocks since the last: a DDA at one step a
//!   tick with `TICK_DIVISOR` 1; or the axis analog) sets the axis's
//!   `STEP_OVERRUN` and raises `STATUS.AXIS_FAULT`.
//! * **Latency**: a spindle count changes `SPINDLE_POSITION`
//!   [`latency::SPINDLE_DECODE`] = 4 clocks after its pin edge (filter 0),
//!   and the step it makes has its first pin edge
//!   [`latency::SPINDLE_COUNT_TO_STEP`] = 38 clocks after that edge (the engine's
//!   30 clocks, the merge, the request register and the output stage; one
//!   clock more when the step waited in the hold, later if the stage's
//!   timing holds it back). The gearbox takes one count per 31 clocks: a
//!   spindle faster than that (3.2 M counts/s at 100 MHz) overruns, which
//!   halts the gearbox and sets `OVERRUN`.
//! * **Independent of RUN and of the feed hold.** The gearbox steps while
//!   it is engaged, whether or not periods run, and a feed hold does not
//!   slow it: a thread cannot pause mid-pass (LinuxCNC ignores a feed hold
//!   in spindle-synchronized motion too). `GEAR_CONTROL.STOP` ramps it out
//!   to the crawl rate; a `LENGTH` ends the run exactly there.
//! * **Abort**: every abort (E-stop, limit, alarm, stop on home, watchdog)
//!   halts the gearbox in its clock (no ramp: the axis's stage is flushed
//!   as for the FIFO's steps), and it stays halted while the abort stands
//!   (an arm is refused then). `GEAR_CONTROL.HALT` does the same alone.
//! * `STATUS.SPINDLE` rises with `DONE`, `INVALID`, `OVERRUN` or
//!   `ENCODER_ERROR`.
//! * Without `SPINDLE` the three `spindle_*` pins are ignored (tie them
//!   low), the window is absent (reads 0, writes ignored), `CONFIG.SPINDLE`
//!   reads 0 and `STATUS.SPINDLE` is never set: synthesis removes the unit
//!   and every axis's merge. The ports are the same in every build.
//!
//! ## Laser PWM (VERSION 0.9.0, the register power 0.10.0; build option `LASER`)
//! On in `motion_controller_dda_laser` ([`MotionController3DdaLaser`]);
//! [`laser`]. A laser's power tied to the path: the duty of `laser_pwm`
//! is set per period from a FIFO and, in dynamic mode (grbl's M4), scaled
//! in gateware by the path's speed over the programmed feed, so that the
//! energy per millimetre holds through accelerations, corners and a feed
//! hold. The power and feed may instead be held in a register.
//! * **Registers** (see the register map): `LASER_CONTROL` (ENABLE,
//!   DYNAMIC, CLEAR_OVERFLOW, SOURCE, the plane's AXIS_A and AXIS_B),
//!   `LASER_PWM_PERIOD`, `LASER_FIFO`, `LASER_STATUS` (LEVEL, OVERFLOW,
//!   ACTIVE, BUSY), `LASER_OUTPUT` (DUTY, SPEED) and `LASER_POWER`
//!   (POWER, FEED), from `0xF0` in the
//!   spindle's window: a `LASER` build has at most
//!   [`registers::MAX_AXES_SPINDLE`] = 6 axes.
//! * **The PWM** is a [`LaserPwm`](crate::blocks::laser_pwm) (R = 16,
//!   C = 16, F = 24): period `LASER_PWM_PERIOD` clocks, glitch-free (a
//!   new duty acts in the PWM period under way; a pulse that has ended
//!   does not restart before the next wrap: a pulse under way is
//!   lengthened at once, one that has ended waits for the next PWM
//!   period), no pulse at duty 0, a steady high at a duty of
//!   the period or more, `laser_pwm` registered.
//! * **Per period from the FIFO.** Firmware writes one `LASER_FIFO` entry
//!   (POWER: clocks high per PWM period at the programmed feed; FEED: the
//!   programmed feed in 1/16 step per period, the vector length in the
//!   plane) per period, beside the axes' entries. With
//!   `LASER_CONTROL.ENABLE` = 1 when RUN starts (`LASER_STATUS.ACTIVE`)
//!   the laser FIFO takes part in the run: its head pops at every boundary
//!   with the axes', and an empty laser FIFO there is an underrun. When RUN
//!   falls the period's entry becomes 0 and ACTIVE clears. A write to a
//!   full laser FIFO (no pop freeing a slot in that clock) is refused and
//!   sets the sticky `OVERFLOW`. `CONTROL.FLUSH` empties it with the axes'.
//! * **By register.** With `LASER_CONTROL.SOURCE` = 1 the duty engine
//!   takes POWER and FEED from `LASER_POWER` (a FIFO entry's layout)
//!   instead of the period's entry, in every clock: a write reaches the
//!   duty within [`laser::LASER_LAG`] clocks, as a new period does. A run
//!   started with SOURCE = 1 leaves the laser FIFO out (ACTIVE stays 0, no
//!   pop, no underrun): the axes' FIFOs alone pace it. For constant power
//!   over a whole job, or a host that sets the power per segment and not
//!   per period. SOURCE changed during a run switches the engine's input
//!   at once; whether the FIFO pops was settled at the start.
//! * **The duty.** Constant (DYNAMIC = 0, M3): the period's POWER.
//!   Dynamic (M4): POWER x min(1, v x f / FEED), rounded to the nearest
//!   clock, where v = sqrt(a^2 + b^2) in 1/16 step is the vector speed of
//!   the running period's steps a and b on the plane's two axes (their
//!   FIFO entries' magnitudes, each saturated to 2^15 - 1; an analog axis
//!   or an AXIS >= K counts as standing, and AXIS_B equal to AXIS_A makes
//!   b = 0, a plane of that one axis; the gearbox's steps are not
//!   counted) and f the feed hold's factor. The speed window is the
//!   interpolation period: its steps are known when it starts. The engine
//!   runs free, one computation every [`ENGINE_CLOCKS`](crate::blocks::laser_pwm::model::ENGINE_CLOCKS)
//!   + 1 clocks with the period's values and the factor of its start, so
//!   a new period's duty (and a changed hold factor) is in force
//!   [`laser::LASER_LAG`] = 263 clocks after the change at most. The hold
//!   stretches the period by 1/f and the duty scales by f: the energy per
//!   millimetre holds through the hold's ramps. A period shorter than the
//!   lag still gets a duty, computed for the period that was running when
//!   its computation began.
//! * **Off.** `laser_pwm` fires only while RUN and `ENABLE`: it is low
//!   from the clock after RUN falls (its registered output follows the
//!   falling RUN, not the clock after), and ENABLE = 0 turns it off from
//!   the next clock. Every abort (E-stop, limit, alarm,
//!   stop on home: [`latency::LASER_OFF`] = 3 clocks after the filtered
//!   level, as for the steps; the watchdog: the clock after it expires)
//!   and the feed hold's stop (`STATE.HELD`: the clock after) turn it off
//!   and zero the duty in force. In dynamic mode the duty is also 0 while
//!   the plane's axes stand (v = 0) or FEED is 0, from `LASER_LAG`
//!   clocks after the period starts (the last duty holds until then).
//! * Without `LASER` the `laser_pwm` pin stays low, the registers are
//!   absent (read 0, writes ignored), `CONFIG.LASER` reads 0 and the
//!   periods never wait for the laser FIFO: synthesis removes the unit.
//!   The ports are the same in every build.
//!
//! ## Analog axes (build option `ANALOG`; on in `motion_controller_servo`)
//! An axis with `AXIS_CONFIG.ANALOG` set (taken when RUN starts) drives a
//! servo amplifier in velocity mode through its own DAC instead of
//! step/dir: the DACs are a [`DacInterface`](crate::blocks::dac_interface)
//! (AD669 style, one channel per axis, one shared data bus and LDAC).
//! * **Entries are codes.** Each FIFO entry of an analog axis is its
//!   signed 16-bit DAC code for that period (0 is 0 V; the sign is the
//!   direction: a positive code must move the axis toward `limit_pos`, with
//!   its encoder counting up). An entry outside -32768..=32767 is
//!   saturated and flagged (`INTERP_OVERRANGE`, `STATUS.AXIS_FAULT`). The
//!   axis takes no steps; its encoder stays the position feedback.
//! * **One update per period.** After each pop the codes are loaded one
//!   axis a clock, then one update writes every DAC's first rank and pulses
//!   `dac_ldac` once: every analog output changes on the same edge,
//!   [`latency::analog_ldac`] clocks after the boundary (29 at K = 3 and the
//!   reset timing), a fixed lag after the step axes' boundary. The update
//!   lasts 1 + K (S + Wd + H) + L clocks (`DAC_TIMING`; 30 at reset): a
//!   period must be longer than the lag plus that, or updates are deferred
//!   (`DAC_STATUS.DEFERRED`) and the outputs lag further.
//! * **The feed hold scales the codes.** A period's code is a velocity,
//!   and a hold stretches the period by 1/f, so the code is scaled by the
//!   hold's factor f: while f < 1 every walk loads floor(|code| x f /
//!   2^16) with the code's sign (an entry beyond 16 bits is saturated
//!   first), all axes of one update at one f, taken at the walk's start.
//!   The multiply is one shift-add a clock on registered operands, so a
//!   scaled walk takes [`SCALE_STEPS`](analog_outputs::SCALE_STEPS) + 2 =
//!   18 clocks an axis (a period's codes change
//!   [`latency::analog_scaled_ldac`] clocks after its boundary, 81 at K = 3
//!   and the reset timing, where the plain walk takes 29), and its update
//!   request waits for the DAC to be idle, so it never defers an update
//!   nor sets `DAC_STATUS.DEFERRED`. Between pops the outputs are
//!   re-walked at the factor of the moment whenever the DAC is idle, one
//!   update every [`latency::analog_rewalk`] clocks (87),
//!   and once more at f = 1 after the release: a hold ramps every velocity
//!   code down with the factor to 0 V and back to its full code, never
//!   stepping it. A ramp step lasts a base tick, so with `TICK_DIVISOR`
//!   below 87 (at K = 3) an update may skip factors: the codes then
//!   follow the ramp at the updates' pace. Re-walks run only while RUN is
//!   set and no abort is active; an abort ends any walk (the DAC forces
//!   the safe code).
//! * **Stop and underrun set 0 V.** When RUN falls by an underrun or a RUN
//!   = 0 write, every analog channel gets code 0 and an update (its LDAC
//!   3 + K (S + Wd + H) clocks later, after the running update if one
//!   runs). A velocity held through an underrun would keep the motor
//!   turning with nobody closing the loop, so the analog outputs stop as
//!   the step axes do.
//! * **Abort forces the safe code.** An abort (E-stop, watchdog, alarm,
//!   limit, stop on home) drives the DAC's `force_safe`: every output gets
//!   0 V within the DAC's [`safe_latency`](crate::blocks::dac_interface::safe_latency)
//!   (35 clocks at the reset timing) of the abort; from an E-stop pin that
//!   is at most `latency::switch` + 1 + 35 = 41 clocks (41 measured, worst
//!   case over an E-stop at every clock of an update). Codes cannot reach
//!   the DACs until the abort clears and RUN starts again.
//! * **Limits.** A code toward an enabled, active limit is cut like a step:
//!   the limit trips and everything aborts, and the update carrying the
//!   code is cut before its LDAC, so the code never reaches the output. An
//!   analog axis moving away from an active limit is allowed (after
//!   `CLEAR_LIMITS`).
//! * **Read back**: `DAC_APPLIED` (per axis) is the code at the DAC's
//!   output; `DAC_CONTROL` (the code format), `DAC_STATUS` and
//!   `DAC_TIMING` are the DAC's own registers (see its datasheet). The
//!   channel of an axis not in analog mode stays at 0 V.
//! * The servo loop's latency is the FIFO's: firmware closing a position
//!   loop keeps one or two entries queued on an analog axis.
//!
//! A board with narrower DACs (12-bit, such as the DAC7724) takes the top
//! bits of `dac_data`: a 16-bit code's upper 12 bits are the 12-bit code in
//! either format.
//!
//! ## Latency
//! A DDA step reaches the pins at the earliest 6 clocks after the base tick
//! that produced it (1 in the feed hold's gate register, 1 tick delay, 2
//! in the DDA, 1 request register, 1 in the stage); the stage's timing
//! settings may delay it further. The periods and the axes see each base
//! tick one clock late, through the gate register: a boundary comes one
//! clock after its base tick. A uniform
//! axis runs each period 24 + 18 j clocks or more behind the boundary (j:
//! the uniform axes before it, see [`latency::UNIFORM_LAG`]). `irq` follows a `STATUS` bit by
//! one clock. `CMD_POSITION` counts a step one clock after its first pin
//! edge appears; `ACT_POSITION` follows the encoder pins by the decoder's
//! latency (5 clocks with the filter off).
//!
//! ## Formal proof
//! The whole controller does not close, so its two safety rules, "no step
//! toward an enabled, active limit" and "no step after the E-stop's
//! latency", are proved on the sub-blocks that decide them, each with the
//! rest of the controller abstracted: every input of the sub-block is free
//! at every clock (reset, `abort`, the filtered switch levels, the bus),
//! and nothing is assumed of the environment. Clock t runs from edge t - 1
//! to edge t; a step "at edge t" has its first pin edge after edge t.
//! * `formal/motion_controller_axis_io.sv`, on [`axis_io::AxisIo`] (an
//!   axis's limit gate): a direction is blocked exactly when its filtered
//!   limit level is active and `IO_CONFIG.LIMIT_ENABLE` reads 1 (from
//!   power-up and after reset, else as last written); `cut` is high exactly
//!   when a step toward a blocked direction is offered to the request
//!   register, in it, or pending in the stage; a cut sets its sticky trip
//!   flag (a trip on the clock of `CLEAR_LIMITS` wins), whose OR,
//!   `limit_held`, aborts every axis.
//! * `formal/motion_controller_axis.sv`, on [`axis::MotionAxis`] (N = 2,
//!   with the uniform generator, no analog outputs, and the gearbox's step
//!   input of a `SPINDLE` build, free like every other input: an axis of
//!   the exported `motion_controller`, with a 4-entry FIFO and the
//!   [`gear_merge`]): a request the output stage
//!   takes in clock t was made in clock t - 1 with `abort` low and its
//!   direction not blocked; the stage is flushed in a clock exactly when
//!   `abort` is high or a step toward a blocked direction is pending,
//!   requested or offered; after a clock with `abort` high, neither pin
//!   rises and no step leaves at the next edge; and a step the stage
//!   reports (`emitted`: the step at the last edge) is not toward a
//!   direction that was blocked in the clock before the one that decided
//!   it. That last rule's induction takes a premise on the stage's ports
//!   (the stage's pending count is a register of a sub-block, which the
//!   property file cannot name), proved on the same stage by
//!   `formal/motion_controller_stage.sv` (`StepOutput` with T = 16, P = 8,
//!   as the axis builds it): a reported step goes the way of the pending
//!   count's sign in the clock that decided it, and the count turns
//!   forward (backward) only through a forward (backward) request at an
//!   edge without reset or flush.
//! * `formal/motion_controller_machine_io.sv`, on [`machine_io::MachineIo`]
//!   (K = 1): `STATE.ESTOP_LATCHED` is set at an edge whose clock had the
//!   filtered E-stop level high, and then holds until an edge with a
//!   `STATUS.ESTOP` clear and the level low (or reset); with
//!   `INPUT_FILTER` at its reset value (LENGTH 4, SAMPLE_RATE 0, nothing
//!   else written since the last reset or power-up), an E-stop pin held
//!   from clock c with no reset makes the filtered level high after edge
//!   c + [`latency::switch`]`(4, 0)` = c + 5, and the latch after edge c + 6.
//!
//! How they compose (the wiring between the blocks is this file's
//! `update`, read, not proved; `tests/controller/machine_io.rs` measures
//! the whole at the pins):
//! * **Limits.** The axis's `limit_forward` is the machine I/O's
//!   conditioned `limit_pos_active` of the same clock, so a limit whose
//!   filtered level is set at edge s (and enabled) blocks from clock s + 1
//!   on, and the axis proof leaves no step toward it after edge s + 1 =
//!   s + [`latency::LIMIT_OWN_AXIS`] (the step at edge s + 1 is decided in
//!   clock s + 1 from registers the limit had not reached). That is at the
//!   stage's step report; the stage's own contract
//!   (`formal/step_output.sv`, proved at T = 3, P = 3) makes the report the
//!   pin step.
//! * **E-stop.** Pin held from clock c: latched after edge c + 6 (machine
//!   I/O proof); `abort_hold` (one register, cleared by reset) after edge
//!   c + 7; `abort` (= `abort_hold` OR the watchdog's expiry, to every axis
//!   unregistered) high from clock c + 8 on; no pin rise and no step of any
//!   axis after edge c + 8 (axis proof). The last step is thus at edge
//!   c + 8 = c + `latency::switch(4, 0)` + [`latency::ABORT_ALL_AXES`], the
//!   stated bound; `tests/formal/motion_controller.rs` checks these
//!   constants.
//!
//! Not proved: the controller as a whole and the wiring above; the E-stop
//! latency at other `INPUT_FILTER` settings (the filter's counters are
//! registers of the input conditioner, a sub-block the property file cannot
//! name, so the induction must span a whole filter interval: up to 4096
//! clocks); the DDA-only and servo builds' axes (same source, with the
//! uniform generator gated off, or the analog code's direction also offered
//! to the limit gate); drive alarms, stop on home and the watchdog.
//!
//! ## Structure
//! The controller is its core and a register layer apart from it, each a
//! sub-block in its own file here (internal: their behavior is the
//! controller's, modelled by [`model`]):
//! * [`global_registers`]: the global registers' flip-flops, write strobes
//!   and read word (ID to STOP_CAUSE), fields placed by the register map;
//! * [`config_shadow`]: the axes' configuration registers read back from
//!   block RAM;
//! * [`period_sequencer`]: RUN, FLUSH, the base ticks of each period and
//!   its boundary (pop or underrun), PERIOD_COUNT;
//! * [`stop_cause`]: STOP_CAUSE, taken when RUN falls;
//! * [`entry`]: the 20-bit FIFO entry and the converter that makes it from
//!   the bus word, once for every axis;
//! * [`analog_outputs`]: the DAC, its walk over the analog axes after each
//!   pop, the 0 V update, and the DAC's registers on the bus;
//! * [`machine_io`]: switch conditioning, the E-stop latch, general I/O;
//! * [`probe_trigger`]: the probe's conditioner, `PROBE_CONTROL` and its trip;
//! * [`soft_limits`]: the windows, `SOFT_LIMIT`, the check of each axis in
//!   turn and the gauge of the stop's reach;
//! * [`spindle`]: the spindle encoder, its registers, and the electronic
//!   gearbox with its register layer; [`gear_merge`] (in each axis) joins
//!   its steps with the interpolator's;
//! * [`feed_hold`]: the feed hold's input, `HOLD_CONTROL`, its sticky
//!   request, and the [`hold_ramp`] (the velocity factor and the tick gate
//!   it drives) whose gated tick paces the periods and the axes;
//! * [`axis`] (one per axis): FIFO, DDA, uniform generator, output stage,
//!   position counter, encoder, the axis's I/O ([`axis_io`]) and its
//!   register window ([`axis_registers`]: configuration, strobes,
//!   snapshots and reads, apart from the axis's core).
//!
//! The controller's own `update()` wires these together, ORs the stop
//! causes and events, and arbitrates the uniform generators' shared
//! period planner.
//!
//! ## Resources (iCE40 HX8K, 16-entry FIFOs)
//! See `rtl-out/synthesis-report.md`, which also has K = 1 and K = 6 and
//! four other FPGA families. Each axis carries a uniform pulse generator
//! (a double-buffered period plan; the planner that computes it is shared
//! by all axes), a
//! DDA, an output stage with four 16-bit timers, a 24-bit position counter,
//! a quadrature decoder, a FIFO, its machine I/O (two 24-bit home latches)
//! and its register window with two 24-bit snapshots; `rtl-out/scaling-report.md`
//! gives the cost of an axis (K = 1, 3 and 6).
//!
//! Five things keep the per-axis cost down. Only the position width
//! changes a register (its range, VERSION 0.4.0); the others change no
//! register and no clock of the behavior above:
//! * **Entries converted once.** The FIFOs hold 20-bit entries, not the
//!   written 32-bit words: |n| saturated to 16 bits, its sign, and whether
//!   it was too large, beyond 16 bits signed, or 0 (`entry::ENTRY_BITS`).
//!   The controller converts each bus word once, before every axis's FIFO,
//!   and puts the sign back once for the DAC after its walk.
//! * **Configuration read back from block RAM.** AXIS_CONFIG, STEP_LEN,
//!   STEP_SPACE, DIR_SETUP, DIR_HOLD and ENC_SAMPLE_RATE of every axis are
//!   copied on write into one 256 x 16 block RAM (`config_shadow`), which
//!   answers their reads; the axes' read multiplexers carry only the live
//!   and captured values. A read of one of them while it is written on the
//!   same clock still returns the old value.
//! * **No read-first logic behind the FIFOs' RAMs**: each FIFO's own
//!   bypass already hides a read that collides with a write
//!   (`command_fifo`, proved).
//! * **24-bit positions** ([`POSITION_BITS`], see "Position range"): the
//!   counters, latches and snapshots hold 24 bits; the read path carries
//!   bit 23 up to bit 31 (synthesis merges the copies).
//! * **One interpolator engine per axis.** Every DDA period has all its
//!   PERIOD_TICKS ticks at one J, so the DDA's phase is 0 at each
//!   boundary and the DDA needs no accumulator: its Bresenham error
//!   e = acc + J - M, with the steps J - M and J, is the uniform
//!   generator's error with its long and short steps. The axis's DDA is
//!   the generator core's DDA mode (`UniformPulseCore`), reloaded one
//!   clock after J changes; -M is formed once for all axes. The
//!   controller's model keeps the accumulating `DdaIntegrator` model, so
//!   the lockstep tests check the phase too.
//!
//! The DDA-only build
//! (`motion_controller_dda`) and the servo build (`motion_controller_servo`:
//! the DAC and its walk) have their own rows in the synthesis report.
//!
//! ## Build options: DDA only, analog outputs, probe, soft limits, spindle, laser
//! `ANALOG` = true builds the analog outputs (see "Analog axes"); without
//! them `CONFIG.ANALOG` and `AXIS_CONFIG.ANALOG` read 0, the `DAC_*`
//! registers are absent (read 0) and the DAC pins idle (every `dac_cs_n`
//! and `dac_l1_n` high, `dac_ldac` and `dac_data` low): synthesis removes
//! the DAC. Both exports keep the same ports.
//!
//! `UNIFORM` = false builds the controller without the uniform pulse
//! generators and their shared planner: the seed design's own DDA-only
//! scheme. The two options are exported as:
//! * `motion_controller` ([`MotionController3`]): uniform generators, no
//!   analog outputs (with the board's bus adapter it nearly fills an
//!   iCE40 HX8K: the DAC does not fit beside it);
//! * `motion_controller_dda` ([`MotionController3Dda`]): DDA only, no
//!   analog outputs: the seed design's scheme for step drives;
//! * `motion_controller_servo` ([`MotionController3Servo`]): DDA only,
//!   with the analog outputs (step and AD669 servo drives): the seed
//!   card's controller (`seed_board.v`, which its placement test keeps
//!   within the 85 % of an iCE40 HX8K the card asks for).
//!
//! `SOFT_LIMITS` = true builds the soft limits (see "Soft limits"):
//! `motion_controller` has them; the two builds of the seed card
//! (`motion_controller_dda`, `motion_controller_servo`) do not, for the
//! card's 85 % budget. Without them `CONFIG.SOFT_LIMITS` reads 0,
//! `SOFT_LIMIT`, `SOFT_MIN` and `SOFT_MAX` are absent (read 0, writes
//! ignored) and `STATUS.SOFT_LIMIT` is never set; the ports are the same.
//! The scaling report places [`MotionController3NoSoftLimits`] beside
//! `motion_controller`: the row pair is their cost.
//!
//! `PROBE` = true builds the probe latch (see "Probe"); every exported
//! build has it. Without it `CONFIG.PROBE` reads 0, the `probe` pin is
//! ignored, `PROBE_CONTROL` and `PROBE_*_POSITION` are absent (read 0,
//! writes ignored) and `STATUS.PROBE` is never set: synthesis removes the
//! trigger and the 2K latches. The ports are the same. The scaling report
//! places [`MotionController3NoProbe`] (`motion_controller` without it) on
//! the seed card beside the exported builds: the row pair is the probe's
//! cost.
//!
//! `SPINDLE` = true builds the spindle encoder and the electronic gearbox
//! (see "Spindle encoder and electronic gearbox"): exported as
//! `motion_controller_dda_spindle` ([`MotionController3DdaSpindle`]: the
//! DDA-only build with the probe, without soft limits, with the spindle),
//! whose register map is `rtl-out/motion_controller_dda_spindle_regs.h`
//! and `.md`. Every build has the `spindle_*` pins.
//!
//! `LASER` = true builds the laser FIFO and PWM (see "Laser PWM"):
//! exported as `motion_controller_dda_laser`
//! ([`MotionController3DdaLaser`]: the DDA-only build with the probe,
//! without soft limits, with the laser), whose register map is
//! `rtl-out/motion_controller_dda_laser_regs.h` and `.md`. Every build
//! has the `laser_pwm` pin.
//!
//! [`MotionController3UniformServo`], uniform generators and analog
//! outputs, is not exported:
//! with the host links it does not fit the seed card's HX8K. The scaling
//! report places the seed card with it and with the three exported builds
//! ("The seed card"); a lockstep test runs it against the model.
//!
//! Without the uniform generators the ports are the same; for software:
//! * `CONFIG.DDA_ONLY` reads 1 (0 in the full build, and in cores older
//!   than the field, which all have the generators): the driver's way to
//!   tell the builds apart.
//! * `AXIS_CONFIG.UNIFORM` and `INTERLEAVED` read 0 whatever is written
//!   (write-any, read-legal); the other fields behave as in the full
//!   build. Every axis runs its DDA, so a period takes |n| <= P steps on
//!   every axis, and the uniform lag ([`latency::UNIFORM_LAG`]) never
//!   applies.
//! * `AXIS_STATUS.UNIFORM_RUNNING` and `INTERP_OVERFLOW` stay 0; `active`
//!   is `running` or an output stage busy.
//! * Everything else, pin for pin and clock for clock, is the full build
//!   with no axis uniform and the same `SOFT_LIMITS` option
//!   (`tests/controller/dda_only.rs` checks it against the full build
//!   without soft limits).
//!
//! Its register map is `rtl-out/motion_controller_dda_regs.h` and `.md`
//! (same names as the full build's, with UNIFORM and INTERLEAVED read-only).
//! The generators stay in the Rust block, but every use of their outputs,
//! and the planner's, is gated by a constant: in the DDA-only build they
//! drive nothing, and synthesis removes them.

pub mod analog_model;
pub mod analog_outputs;
pub mod axis;
pub mod axis_io;
pub mod axis_registers;
pub mod config_shadow;
pub mod entry;
pub mod feed_hold;
pub mod gear_merge;
pub mod global_registers;
pub mod hold_ramp;
pub mod io_model;
pub mod laser;
pub mod laser_model;
pub mod machine_io;
pub mod model;
pub mod period_sequencer;
pub mod probe_trigger;
pub mod registers;
pub mod soft_limits;
pub mod spindle;
pub mod spindle_model;
pub mod stop_cause;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::freq_divider::FreqDivider;
use crate::blocks::interrupt_controller::InterruptController;
use crate::blocks::uniform_pulse_gen::PeriodPlanner;
use crate::blocks::watchdog::Watchdog;
use analog_outputs::AnalogOutputs;
use axis::MotionAxis;
use config_shadow::{ConfigShadow, SHADOW_BITS};
use entry::EntryConverter;
use feed_hold::FeedHold;
use global_registers::{ControllerFields, GlobalRegisters};
use laser::LaserUnit;
use machine_io::MachineIo;
use period_sequencer::PeriodSequencer;
use probe_trigger::ProbeTrigger;
use registers::{fields, irq, DAC_BITS};
use soft_limits::SoftLimits;
use spindle::SpindleUnit;
use stop_cause::StopCauseRegister;

/// The machine-I/O latencies in clocks, as the tests measure them. Clock
/// c is the first clock whose inputs carry a pin's new level; "at c + n"
/// means in the outputs after the edge of clock c + n.
pub mod latency {
    /// A switch, alarm, E-stop or general input held from clock c is
    /// acted on from c + `switch(length, rate)` on (its filtered level is
    /// set then), with `INPUT_FILTER` LENGTH = `length` and SAMPLE_RATE =
    /// `rate`: 2 synchronizer clocks, then max(length, 1) samples, one every
    /// rate + 1 clocks. Exact for rate 0; at most this for rate > 0.
    pub const fn switch(length: u64, rate: u64) -> u64 {
        let samples = if length > 1 { length } else { 1 };
        1 + samples * (rate + 1) + rate
    }
    /// After the filtered limit level is set (at s = c + `switch`), the
    /// last step toward the limit on its own axis can rise at s +
    /// `LIMIT_OWN_AXIS`; later ones are cut.
    pub const LIMIT_OWN_AXIS: u64 = 1;
    /// After an abort cause is seen (a filtered E-stop or enabled alarm
    /// level at s, a cut step, a stop-on-home edge), the last step of any
    /// axis can rise at s + `ABORT_ALL_AXES`.
    pub const ABORT_ALL_AXES: u64 = 3;
    /// A spindle count changes `SPINDLE_POSITION` at c + `SPINDLE_DECODE`
    /// after its encoder edge at c (`SPINDLE_CONFIG.FILTER` 0 or 1; the
    /// decoder's synchronizer, filter and count stage).
    pub const SPINDLE_DECODE: u64 = 4;
    /// The step a spindle count makes on the geared axis has its first pin
    /// edge at c + `SPINDLE_COUNT_TO_STEP` after the count's encoder edge at
    /// c (filter 0 or 1, the step not held back by the merge or the stage):
    /// the decode, one clock to the gearbox, its engine's 30 clocks, the
    /// request register and the output stage.
    pub const SPINDLE_COUNT_TO_STEP: u64 = 38;
    /// `laser_pwm` is low at s + `LASER_OFF` after a filtered E-stop or
    /// enabled alarm level at s (the registered abort, then the PWM's
    /// registered output), and in the clock after the watchdog expires or
    /// the feed hold's factor reaches 0 (`STATE.HELD`).
    pub const LASER_OFF: u64 = 3;
    /// `drive_enable` is low from s + `DRIVE_ENABLE` after a filtered
    /// E-stop or enabled alarm level at s, and from the clock after the
    /// watchdog expires.
    pub const DRIVE_ENABLE: u64 = 1;
    /// A feed-hold request (or release) decided in clock d (the
    /// `feed_hold` input: d = c + `switch` + 1 after a pin change at c)
    /// moves the factor from the first base tick t >= d +
    /// `HOLD_REQUEST_TO_RAMP`: the ramp follows the registered request.
    pub const HOLD_REQUEST_TO_RAMP: u64 = 1;
    /// The first base tick the gate may withhold is the next one after
    /// the tick t that first lowers the factor: `HOLD_FIRST_REDUCED_TICK`
    /// ticks after t.
    pub const HOLD_FIRST_REDUCED_TICK: u64 = 1;
    /// After the watchdog expires (STATE.WATCHDOG_EXPIRED set at x), the
    /// last step of any axis can rise at x + `WATCHDOG_ALL_AXES`.
    pub const WATCHDOG_ALL_AXES: u64 = 1;
    /// A uniform axis runs each period `UNIFORM_LAG` + j * `UNIFORM_TURN`
    /// clocks after its boundary, or later (the first tick edge from then
    /// on), where j is the number of lower-numbered uniform axes that load
    /// a period at the same boundary: the axes take turns at one planner,
    /// and each turn lasts a division of `PERIOD_BITS` clocks and 2 of
    /// handover. The lag of an axis is thus fixed by which axes are uniform.
    pub const UNIFORM_LAG: u64 =
        crate::blocks::uniform_pulse_gen::load_to_ready(super::PERIOD_BITS as u32) as u64 + 2;
    /// See [`UNIFORM_LAG`].
    pub const UNIFORM_TURN: u64 = super::PERIOD_BITS as u64 + 2;
    /// The analog outputs of a period change (the DAC's `dac_ldac` rises)
    /// `analog_ldac(K, S, Wd, H)` clocks after its boundary clock (the
    /// clock the FIFOs pop), with the `DAC_TIMING` fields S, Wd, H (0 acting
    /// as 1): the codes are loaded one axis a clock after the pop, then the
    /// DAC writes K first ranks. 29 clocks at K = 3 and the reset timing.
    /// When RUN falls by an underrun or a stop (clock c), the 0 V update's
    /// `dac_ldac` rises at c + 3 + K (S + Wd + H), or after the running
    /// update's if one runs (it is deferred, not torn).
    pub const fn analog_ldac(axes: u64, setup: u64, width: u64, hold: u64) -> u64 {
        axes + 2 + axes * (at_least_1(setup) + at_least_1(width) + at_least_1(hold))
    }

    /// While the feed hold's factor is below 1 a walk scales each code
    /// (`SCALE_STEPS` + 2 clocks an axis, see "Analog axes"): a period's
    /// codes then change `analog_scaled_ldac(K, S, Wd, H)` clocks after
    /// its boundary if the DAC is idle (81 at K = 3 and the reset
    /// timing), later if an update runs (the scaled walk's request waits
    /// for it, so it never defers one).
    pub const fn analog_scaled_ldac(axes: u64, setup: u64, width: u64, hold: u64) -> u64 {
        analog_ldac(axes, setup, width, hold)
            + axes * (super::analog_outputs::SCALE_STEPS as u64 + 1)
            + 1
    }

    /// While the factor is below 1 (and once more after it returns to 1)
    /// the analog outputs are re-walked at the factor of the moment: with
    /// no pop between, one update's `dac_ldac` rise follows the last's by
    /// `analog_rewalk(K, S, Wd, H, L)` clocks (87 at K = 3 and the reset
    /// timing): a re-walk is decided in the first clock the DAC is idle
    /// and starts in the next.
    pub const fn analog_rewalk(axes: u64, setup: u64, width: u64, hold: u64, ldac: u64) -> u64 {
        analog_scaled_ldac(axes, setup, width, hold) + at_least_1(ldac) + 1
    }

    const fn at_least_1(v: u64) -> u64 {
        if v > 1 {
            v
        } else {
            1
        }
    }
    /// The lag of the last of `axes` uniform axes: a period must last more
    /// clocks than this, or that axis's generator refuses the next one
    /// (`INTERP_OVERFLOW`). 24 clocks at K = 1, 60 at K = 3, 114 at K = 6.
    pub const fn uniform_lag(axes: u64) -> u64 {
        UNIFORM_LAG + axes.saturating_sub(1) * UNIFORM_TURN
    }
}

/// Clocks from a motion tick until the step the DDA makes on it makes its
/// output stage busy (the tick delay, 2 in the DDA, the request register):
/// `active` stays high that long after the last tick of a run.
pub const TICK_TRAIL: usize = 4;

/// Number of interrupt sources (`STATUS` bits).
const IRQ_COUNT: usize = irq::COUNT;

/// The exported configuration (`motion_controller`): 3 axes, 16-entry
/// FIFOs, DDA and uniform pulse generator on every axis, the probe and the
/// soft limits.
pub type MotionController3 = MotionController<3, 4, 5, true, false, true, true, false, false>;

/// The exported DDA-only configuration (`motion_controller_dda`): 3 axes,
/// 16-entry FIFOs, no uniform pulse generators, no analog outputs, no soft
/// limits (see "Build options").
pub type MotionController3Dda = MotionController<3, 4, 5, false, false, true, false, false, false>;

/// The exported servo configuration (`motion_controller_servo`): the
/// DDA-only controller with the analog outputs (see "Build options").
pub type MotionController3Servo = MotionController<3, 4, 5, false, true, true, false, false, false>;

/// The exported `motion_controller` without the probe latch (`PROBE` =
/// false): measured on the seed card in the scaling report, not exported
/// (see "Build options").
pub type MotionController3NoProbe =
    MotionController<3, 4, 5, true, false, false, true, false, false>;

/// Both build options (uniform generators and analog outputs): measured on
/// the seed card in the scaling report, not exported (see "Build options").
pub type MotionController3UniformServo =
    MotionController<3, 4, 5, true, true, true, false, false, false>;

/// The exported `motion_controller` without the soft limits (`SOFT_LIMITS`
/// = false): measured beside it, not exported (see "Build options").
pub type MotionController3NoSoftLimits =
    MotionController<3, 4, 5, true, false, true, false, false, false>;

/// One axis, 16-entry FIFOs: measured in the synthesis report's scaling
/// table, not exported.
pub type MotionController1 = MotionController<1, 4, 5, true, false, true, true, false, false>;

/// Six axes (the seeds' parallel mechanism), 16-entry FIFOs: measured in
/// the synthesis report's scaling table, and the Colorlight 5A-75E board's
/// controller (`boards/colorlight-5a-75e/motion_controller_k6.v`).
pub type MotionController6 = MotionController<6, 4, 5, true, false, true, true, false, false>;

/// Four axes, 16-entry FIFOs: the Tang Nano 20K board's controller
/// (`boards/tang-nano-20k/motion_controller_k4.v`), where the header's
/// pins, not the logic, set K.
pub type MotionController4 = MotionController<4, 4, 5, true, false, true, true, false, false>;

/// The exported spindle configuration (`motion_controller_dda_spindle`):
/// the DDA-only controller with the spindle encoder and the electronic
/// gearbox (see "Spindle encoder and electronic gearbox").
pub type MotionController3DdaSpindle =
    MotionController<3, 4, 5, false, false, true, false, true, false>;

/// The exported laser configuration (`motion_controller_dda_laser`): the
/// DDA-only controller with the laser PWM tied to the path (see "Laser
/// PWM").
pub type MotionController3DdaLaser =
    MotionController<3, 4, 5, false, false, true, false, false, true>;

/// Width of the step timing registers.
pub const TIMER_BITS: u32 = 16;

/// Width of each output stage's signed pending-step count: a backlog of
/// up to +127 or -128 steps, beyond which a request is dropped and
/// `STEP_OVERRUN` is set. An axis that far behind its commands has long
/// lost its path; 8 bits rather than the standalone stage's 16 also
/// shorten the stage's emit-to-count adder, one of the top's slowest paths.
pub const STAGE_PENDING_BITS: usize = 8;

/// Width of each axis's position counters (CMD_POSITION and ACT_POSITION)
/// and of their snapshot, index and home latches. They count modulo
/// 2^POSITION_BITS; each register word carries the sign up to bit 31, and
/// the host extends the wrap (as hostmot2's driver does with its 16-bit
/// encoder counts) by reading each position at least once per
/// 2^(POSITION_BITS - 1) counts. 24 bits: +-8388608 steps, 8.4 m of
/// travel at 1 um a step; 3.4 s at 2.5 M steps/s between two reads.
pub const POSITION_BITS: usize = 24;

/// Width of `PERIOD_TICKS` and of both interpolators: a period is at most
/// 2^16 - 1 base ticks, and an axis emits at most that many steps in one.
/// (At 32 bits the uniform generators alone would not fit an HX8K at K = 3.)
pub const PERIOD_BITS: usize = 16;

/// Width of the axes' DDA error, PERIOD_BITS + 1: it lies in [-M, M) for a
/// period of M ticks (the DDA mode of
/// [`UniformPulseCore`](crate::blocks::uniform_pulse_gen::UniformPulseCore)).
pub const ERROR_BITS: usize = PERIOD_BITS + 1;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "motion controller: K step/encoder axes, command FIFOs, synchronized periods, limits, alarms, E-stop, home, GPIO, interrupt, watchdog, register bus";

/// The DDA-only build's line (`motion_controller_dda`).
pub const SUMMARY_DDA: &str =
    "motion controller, DDA interpolators only (no uniform pulse generators): K step/encoder axes, command FIFOs, synchronized periods, limits, alarms, E-stop, home, GPIO, interrupt, watchdog, register bus";

/// The spindle build's line (`motion_controller_dda_spindle`).
pub const SUMMARY_DDA_SPINDLE: &str =
    "motion controller, DDA interpolators only, with the spindle encoder and an electronic gearbox (threading, rigid tapping): K step/encoder axes, command FIFOs, synchronized periods, limits, alarms, E-stop, home, GPIO, interrupt, watchdog, register bus";

/// The laser build's line (`motion_controller_dda_laser`).
pub const SUMMARY_DDA_LASER: &str =
    "motion controller, DDA interpolators only, with a laser PWM whose duty follows the path speed each period (constant energy per mm): K step/encoder axes, command FIFOs and a laser FIFO, synchronized periods, limits, alarms, E-stop, home, GPIO, interrupt, watchdog, register bus";

/// The servo build's line (`motion_controller_servo`).
pub const SUMMARY_SERVO: &str =
    "motion controller, DDA interpolators only, with analog outputs: K step or analog (AD669 DAC, velocity servo) axes with encoders, command FIFOs, synchronized periods, limits, alarms, E-stop, home, GPIO, interrupt, watchdog, register bus";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock (the step timing and encoder sampling run on it)"),
    port("reset", "1", "synchronous, active high: every register to its documented reset value, FIFOs empty, outputs low; power-up equals reset"),
    port("bus_address", "8", "word address of `bus_write` / `bus_read` (`MC_*_INDEX` in the C header)"),
    port("bus_write_data", "32", "data of `bus_write`"),
    port("bus_write", "1", "one-clock write strobe"),
    port("bus_read", "1", "one-clock read strobe (reads have no side effects)"),
    port("bus_read_data", "32", "the addressed register, registered: valid in the clock after `bus_read`, held until the next read"),
    port("irq", "1", "level interrupt: an enabled `STATUS` bit is set; registered"),
    port("running", "1", "periods are running (`STATE.RUNNING`)"),
    port("active", "1", "`running`, a motion tick while running in the last 4 clocks (its step is still on its way to the output stage), or an output stage or uniform generator still busy: the last steps of a move leave after `running` falls, and once `active` has fallen no step of the run is left (the drives' enables are `drive_enable`)"),
    port("step_a", "K", "bit k: axis k's step (step/dir), up (up/down) or A (quadrature); registered"),
    port("step_b", "K", "bit k: axis k's dir, down or B; registered"),
    port("enc_a", "K", "bit k: axis k's encoder A, asynchronous (synchronized and filtered inside)"),
    port("enc_b", "K", "bit k: axis k's encoder B, asynchronous (synchronized and filtered inside)"),
    port("enc_index", "K", "bit k: axis k's encoder index, asynchronous (synchronized and filtered inside)"),
    port("limit_pos", "K", "bit k: hard limit switch at the positive end of axis k, 1 = tripped, asynchronous"),
    port("limit_neg", "K", "bit k: hard limit switch at the negative end of axis k, 1 = tripped, asynchronous"),
    port("home", "K", "bit k: home switch of axis k, 1 = active, asynchronous"),
    port("drive_alarm", "K", "bit k: alarm output of axis k's drive, 1 = in alarm, asynchronous"),
    port("estop", "1", "emergency stop chain, 1 = stopped, asynchronous; no polarity setting"),
    port("gpio_in", "8", "general inputs, asynchronous"),
    port("probe", "1", "touch probe or tool setter, asynchronous: the first edge `PROBE_CONTROL.EDGE` selects after arming latches every axis's positions; ignored in a build without `PROBE` (`CONFIG.PROBE` = 0)"),
    port("feed_hold", "1", "feed hold request, asynchronous, 1 = hold (`HOLD_CONTROL.INVERT` = 1: 0 = hold): while active the path decelerates along itself to a stop; it resumes on `HOLD_CONTROL.RELEASE` once the input is inactive"),
    port("spindle_a", "1", "spindle encoder A, asynchronous (synchronized and filtered inside, `SPINDLE_CONFIG`); ignored in a build without `SPINDLE` (`CONFIG.SPINDLE` = 0)"),
    port("spindle_b", "1", "spindle encoder B, asynchronous; ignored without `SPINDLE`"),
    port("spindle_index", "1", "spindle encoder index, asynchronous: an armed gearbox engages at its next event; ignored without `SPINDLE`"),
    port("drive_enable", "K", "bit k: enable (servo-on) of axis k's drive: `IO_CONFIG.DRIVE_ENABLE`, forced low by an E-stop, a watchdog expiry or that axis's alarm; registered"),
    port("gpio_out", "8", "general outputs (`GPIO_OUT`; the `GPIO_SAFE` ones drop on E-stop or watchdog expiry); registered"),
    port("dac_data", "16", "DAC data bus, shared by the analog channels (AD669 style; 0 in a build without them); registered"),
    port("dac_cs_n", "K", "bit k: chip select of axis k's DAC, active low (1 in a build without them); registered"),
    port("dac_l1_n", "1", "DAC first-rank load, active low, shared; registered"),
    port("dac_ldac", "1", "DAC second-rank load, active high, shared: every analog output changes on its rise; registered"),
    port("laser_pwm", "1", "the laser's PWM (`LASER_*`): fires only while `running` and `LASER_CONTROL.ENABLE`, low in the clock after an abort or the feed hold's stop; registered; low in a build without `LASER` (`CONFIG.LASER` = 0)"),
];

/// The motion controller: `K` axes with FIFOs of 2^`N` entries (`NP1` =
/// N + 1), with a uniform pulse generator on every axis if `UNIFORM` (else
/// DDA only), the analog outputs if `ANALOG` (K <= 8), the probe latch
/// if `PROBE` and the soft limits if `SOFT`: see "Build options". See the [module documentation](self).
#[derive(LogicBlock)]
pub struct MotionController<
    const K: usize,
    const N: usize,
    const NP1: usize,
    const UNIFORM: bool,
    const ANALOG: bool,
    const PROBE: bool,
    const SOFT: bool,
    const SPINDLE: bool,
    const LASER: bool,
> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Bus word address.
    pub bus_address: Signal<In, Bits<8>>,
    /// Bus write data.
    pub bus_write_data: Signal<In, Bits<32>>,
    /// Bus write strobe.
    pub bus_write: Signal<In, Bit>,
    /// Bus read strobe.
    pub bus_read: Signal<In, Bit>,
    /// Per axis (bit k): encoder A.
    pub enc_a: Signal<In, Bits<K>>,
    /// Per axis: encoder B.
    pub enc_b: Signal<In, Bits<K>>,
    /// Per axis: encoder index.
    pub enc_index: Signal<In, Bits<K>>,
    /// Per axis: positive-end limit switch, 1 = tripped (asynchronous).
    pub limit_pos: Signal<In, Bits<K>>,
    /// Per axis: negative-end limit switch.
    pub limit_neg: Signal<In, Bits<K>>,
    /// Per axis: home switch.
    pub home: Signal<In, Bits<K>>,
    /// Per axis: drive alarm, 1 = in alarm.
    pub drive_alarm: Signal<In, Bits<K>>,
    /// Emergency stop chain, 1 = stopped.
    pub estop: Signal<In, Bit>,
    /// General inputs.
    pub gpio_in: Signal<In, Bits<8>>,
    /// Pin: the probe.
    pub probe: Signal<In, Bit>,
    /// Pin: the feed hold request.
    pub feed_hold: Signal<In, Bit>,
    /// Pin: spindle encoder A.
    pub spindle_a: Signal<In, Bit>,
    /// Pin: spindle encoder B.
    pub spindle_b: Signal<In, Bit>,
    /// Pin: spindle encoder index.
    pub spindle_index: Signal<In, Bit>,
    /// Bus read data.
    pub bus_read_data: Signal<Out, Bits<32>>,
    /// Level interrupt.
    pub irq: Signal<Out, Bit>,
    /// Periods are running.
    pub running: Signal<Out, Bit>,
    /// Steps are still leaving (see the port table).
    pub active: Signal<Out, Bit>,
    /// Per axis: step / up / A.
    pub step_a: Signal<Out, Bits<K>>,
    /// Per axis: dir / down / B.
    pub step_b: Signal<Out, Bits<K>>,
    /// Per axis: drive enable (servo-on).
    pub drive_enable: Signal<Out, Bits<K>>,
    /// General outputs.
    pub gpio_out: Signal<Out, Bits<8>>,
    /// DAC data bus (the analog axes' codes).
    pub dac_data: Signal<Out, Bits<DAC_BITS>>,
    /// Per axis: DAC chip select, active low.
    pub dac_cs_n: Signal<Out, Bits<K>>,
    /// DAC first-rank load, active low.
    pub dac_l1_n: Signal<Out, Bit>,
    /// DAC second-rank load, active high.
    pub dac_ldac: Signal<Out, Bit>,
    /// Pin: the laser's PWM.
    pub laser_pwm: Signal<Out, Bit>,

    axes: [MotionAxis<N, NP1>; K],
    /// The global registers: the register layer apart from the core.
    registers: GlobalRegisters<NP1>,
    /// Run control and the period boundaries.
    period: PeriodSequencer,
    /// STOP_CAUSE.
    cause_register: StopCauseRegister<K>,
    /// The bus word as a FIFO entry (see [`entry`]).
    entry_converter: EntryConverter,
    /// The axes' configuration registers, read back from block RAM.
    config_shadow: ConfigShadow<K>,
    /// `shadow_bit[b]` = 1 << b: the shadow's word, zero-extended.
    shadow_bit: [Constant<Bits<32>>; SHADOW_BITS],
    tick_divider: FreqDivider<32>,
    watchdog: Watchdog<32>,
    interrupts: InterruptController<IRQ_COUNT>,
    io: MachineIo<K>,
    probe_trigger: ProbeTrigger,
    /// The soft limits (build option `SOFT_LIMITS`).
    soft_limits: SoftLimits<K>,
    /// The spindle encoder and the gearbox (build option `SPINDLE`).
    spindle: SpindleUnit<K>,
    /// `SPINDLE`: the spindle unit's steps, event and read data are used.
    has_spindle: Constant<Bit>,
    /// The spindle unit's read data, 0 without `SPINDLE`.
    spindle_read: Signal<Local, Bits<32>>,
    /// The laser FIFO and PWM (build option `LASER`).
    laser: LaserUnit<N, NP1>,
    /// `LASER`: the laser unit's pin, readiness and read data are used.
    has_laser: Constant<Bit>,
    /// The laser unit's read data, 0 without `LASER`.
    laser_read: Signal<Local, Bits<32>>,
    /// The running periods' |entry| of the laser plane's axes.
    laser_count_a: Signal<Local, Bits<DAC_BITS>>,
    laser_count_b: Signal<Local, Bits<DAC_BITS>>,
    laser_axis: [Constant<Bits<3>>; K],
    ev_spindle: Constant<Bits<IRQ_COUNT>>,
    /// `SOFT`: the soft limits' stop, event and read data are used.
    has_soft: Constant<Bit>,
    /// The soft limits' read data, 0 without `SOFT`.
    soft_read: Signal<Local, Bits<32>>,
    /// The axis the soft limits take, its values.
    soft_position: Signal<Local, Bits<POSITION_BITS>>,
    soft_magnitude: Signal<Local, Bits<DAC_BITS>>,
    soft_negative: Signal<Local, Bit>,
    soft_step_axis: Signal<Local, Bit>,
    soft_axis: [Constant<Bits<3>>; K],
    zero_position: Constant<Bits<POSITION_BITS>>,
    /// The feed hold: its input, `HOLD_CONTROL` and the gated tick.
    feed_hold_unit: FeedHold,
    /// The base tick through the feed hold's gate, registered (the gate's
    /// comparator stays out of the path from the tick to every axis): the
    /// periods and the axes run on it, one clock after the base tick.
    motion_tick: DFF<Bit>,
    /// The motion ticks of the last `TICK_TRAIL` clocks while running: a
    /// step the DDA makes on a tick is still on its way to the output
    /// stage for that long, so `active` covers it.
    tick_trail: DFF<Bits<TICK_TRAIL>>,
    /// The analog outputs: the DAC, its walk and its registers.
    analog: AnalogOutputs<K>,
    analog_axes: Signal<Local, Bits<K>>,
    /// The walked axis's entry: |entry|, beyond 16 bits signed, negative.
    walk_magnitude: Signal<Local, Bits<DAC_BITS>>,
    walk_wide: Signal<Local, Bit>,
    walk_negative: Signal<Local, Bit>,
    zero_code: Constant<Bits<DAC_BITS>>,
    read_out: Signal<Local, Bits<32>>,
    /// One planner for every axis's uniform generator: each asks for one
    /// plan per period, so they take turns (see "Time base and
    /// periods").
    planner: PeriodPlanner<PERIOD_BITS>,
    /// The axis whose plan is being computed (one-hot).
    div_owner: DFF<Bits<K>>,
    /// `UNIFORM`: the axes have uniform generators, and so the planner is
    /// used. (A const generic cannot appear in `#[hdl_gen]` code.)
    has_uniform: Constant<Bit>,
    /// `PROBE`: the probe trigger's latch, event and read data are used.
    has_probe: Constant<Bit>,
    /// A plan can start in this clock.
    div_idle: Signal<Local, Bit>,
    /// An axis was granted the planner in this clock.
    div_granted: Signal<Local, Bit>,
    /// A stop cause is held (registered OR of every latch): every axis
    /// flushed, interpolators halted.
    abort_hold: DFF<Bit>,

    read_data: DFF<Bits<32>>,
    /// Inverted, so that reset (all flip-flops 0) counts as "already low":
    /// FIFO_LOW is raised when a level falls to the low-water mark, not for
    /// the empty FIFOs after reset.
    any_low_prev_n: DFF<Bit>,
    expired_prev: DFF<Bit>,
    held_prev: DFF<Bit>,
    /// The probe trigger's read data, 0 without `PROBE`.
    probe_read: Signal<Local, Bits<32>>,

    tick: Signal<Local, Bit>,
    start: Signal<Local, Bit>,
    halt: Signal<Local, Bit>,
    all_ready: Signal<Local, Bit>,
    pop: Signal<Local, Bit>,
    underrun: Signal<Local, Bit>,
    any_low: Signal<Local, Bit>,
    any_overflow: Signal<Local, Bit>,
    any_fault: Signal<Local, Bit>,
    any_encoder_error: Signal<Local, Bit>,
    any_busy: Signal<Local, Bit>,
    axes_read: Signal<Local, Bits<32>>,
    events: Signal<Local, Bits<IRQ_COUNT>>,
    abort: Signal<Local, Bit>,
    refuse_run: Signal<Local, Bit>,
    /// Per axis: a limit / drive alarm / home stop is held.
    limit_held: Signal<Local, Bits<K>>,
    alarm_held: Signal<Local, Bits<K>>,
    home_held: Signal<Local, Bits<K>>,
    /// Some axis holds a stop cause.
    any_held: Signal<Local, Bit>,
    any_limit_event: Signal<Local, Bit>,
    any_alarm_event: Signal<Local, Bit>,
    any_home_event: Signal<Local, Bit>,
    drive_allowed: Signal<Local, Bit>,
    steps_a: Signal<Local, Bits<K>>,
    steps_b: Signal<Local, Bits<K>>,
    enables: Signal<Local, Bits<K>>,

    zero32: Constant<Bits<32>>,
    /// The event bit of each interrupt source, by name.
    ev_period_done: Constant<Bits<IRQ_COUNT>>,
    ev_fifo_low: Constant<Bits<IRQ_COUNT>>,
    ev_underrun: Constant<Bits<IRQ_COUNT>>,
    ev_overflow: Constant<Bits<IRQ_COUNT>>,
    ev_encoder_error: Constant<Bits<IRQ_COUNT>>,
    ev_watchdog: Constant<Bits<IRQ_COUNT>>,
    ev_axis_fault: Constant<Bits<IRQ_COUNT>>,
    ev_limit: Constant<Bits<IRQ_COUNT>>,
    ev_alarm: Constant<Bits<IRQ_COUNT>>,
    ev_estop: Constant<Bits<IRQ_COUNT>>,
    ev_home: Constant<Bits<IRQ_COUNT>>,
    ev_gpio: Constant<Bits<IRQ_COUNT>>,
    ev_probe: Constant<Bits<IRQ_COUNT>>,
    ev_held: Constant<Bits<IRQ_COUNT>>,
    ev_soft_limit: Constant<Bits<IRQ_COUNT>>,
    zero_ev: Constant<Bits<IRQ_COUNT>>,
    /// STATUS.WATCHDOG and STATUS.ESTOP, for their clears.
    m_status_watchdog: Constant<Bits<32>>,
    m_status_estop: Constant<Bits<32>>,
    /// Bit k of a K-bit vector.
    axis_bit: [Constant<Bits<K>>; K],
    zero_k: Constant<Bits<K>>,
    zero_trail: Constant<Bits<TICK_TRAIL>>,
    one_trail: Constant<Bits<TICK_TRAIL>>,
}

impl<
        const K: usize,
        const N: usize,
        const NP1: usize,
        const UNIFORM: bool,
        const ANALOG: bool,
        const PROBE: bool,
        const SOFT: bool,
        const SPINDLE: bool,
        const LASER: bool,
    > MotionController<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>
{
    /// This build's options, as the register map and the model take them.
    pub const BUILD: registers::BuildOptions = registers::BuildOptions {
        uniform: UNIFORM,
        analog: ANALOG,
        probe: PROBE,
        soft_limits: SOFT,
        spindle: SPINDLE,
        laser: LASER,
    };
}

impl<
        const K: usize,
        const N: usize,
        const NP1: usize,
        const UNIFORM: bool,
        const ANALOG: bool,
        const PROBE: bool,
        const SOFT: bool,
        const SPINDLE: bool,
        const LASER: bool,
    > Default for MotionController<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>
{
    fn default() -> Self {
        assert!(
            (1..=registers::MAX_AXES).contains(&K),
            "MotionController: 1 to {} axes",
            registers::MAX_AXES
        );
        assert!(
            NP1 == N + 1 && (2..=8).contains(&N),
            "MotionController: N in 2..=8, NP1 = N + 1"
        );
        let ev = |bit: u32| Constant::new((1u64 << bit).into());
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        let map = registers::register_map(K, N as u32, Self::BUILD)
            .expect("the controller's own register map validates");
        let reg = |name: &str| map.register(name).expect("the controller's own register");
        let config = reg("CONFIG").reset_value();
        let axis_config_mask = reg("AXIS_CONFIG").rw_mask();
        Self {
            clock: Default::default(),
            reset: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            enc_a: Default::default(),
            enc_b: Default::default(),
            enc_index: Default::default(),
            limit_pos: Default::default(),
            limit_neg: Default::default(),
            home: Default::default(),
            drive_alarm: Default::default(),
            estop: Default::default(),
            gpio_in: Default::default(),
            probe: Default::default(),
            feed_hold: Default::default(),
            spindle_a: Default::default(),
            spindle_b: Default::default(),
            spindle_index: Default::default(),
            bus_read_data: Default::default(),
            irq: Default::default(),
            running: Default::default(),
            active: Default::default(),
            step_a: Default::default(),
            step_b: Default::default(),
            drive_enable: Default::default(),
            gpio_out: Default::default(),
            dac_data: Default::default(),
            dac_cs_n: Default::default(),
            dac_l1_n: Default::default(),
            dac_ldac: Default::default(),
            laser_pwm: Default::default(),
            axes: array_init::array_init(|k| {
                MotionAxis::new(k, UNIFORM, ANALOG, SPINDLE, axis_config_mask)
            }),
            entry_converter: Default::default(),
            registers: GlobalRegisters::new(config),
            period: Default::default(),
            cause_register: Default::default(),
            config_shadow: ConfigShadow::new(axis_config_mask),
            shadow_bit: array_init::array_init(|b| Constant::new((1u64 << b).into())),
            analog: AnalogOutputs::new(ANALOG),
            analog_axes: Default::default(),
            walk_magnitude: Default::default(),
            walk_wide: Default::default(),
            walk_negative: Default::default(),
            zero_code: Constant::new(0u64.into()),
            read_out: Default::default(),
            tick_divider: Default::default(),
            watchdog: Default::default(),
            interrupts: Default::default(),
            io: Default::default(),
            probe_trigger: Default::default(),
            soft_limits: Default::default(),
            has_soft: Constant::new(SOFT),
            spindle: Default::default(),
            has_spindle: Constant::new(SPINDLE),
            spindle_read: Default::default(),
            laser: Default::default(),
            has_laser: Constant::new(LASER),
            laser_read: Default::default(),
            laser_count_a: Default::default(),
            laser_count_b: Default::default(),
            laser_axis: array_init::array_init(|k| Constant::new((k as u64).into())),
            ev_spindle: ev(irq::SPINDLE),
            soft_read: Default::default(),
            soft_position: Default::default(),
            soft_magnitude: Default::default(),
            soft_negative: Default::default(),
            soft_step_axis: Default::default(),
            soft_axis: array_init::array_init(|k| Constant::new((k as u64).into())),
            zero_position: Constant::new(0u64.into()),
            feed_hold_unit: Default::default(),
            motion_tick: Default::default(),
            tick_trail: Default::default(),
            planner: Default::default(),
            div_owner: Default::default(),
            has_uniform: Constant::new(UNIFORM),
            has_probe: Constant::new(PROBE),
            div_idle: Default::default(),
            div_granted: Default::default(),
            abort_hold: Default::default(),
            read_data: Default::default(),
            any_low_prev_n: Default::default(),
            expired_prev: Default::default(),
            held_prev: Default::default(),
            probe_read: Default::default(),
            tick: Default::default(),
            start: Default::default(),
            halt: Default::default(),
            all_ready: Default::default(),
            pop: Default::default(),
            underrun: Default::default(),
            any_low: Default::default(),
            any_overflow: Default::default(),
            any_fault: Default::default(),
            any_encoder_error: Default::default(),
            any_busy: Default::default(),
            axes_read: Default::default(),
            events: Default::default(),
            abort: Default::default(),
            refuse_run: Default::default(),
            any_limit_event: Default::default(),
            any_alarm_event: Default::default(),
            any_home_event: Default::default(),
            drive_allowed: Default::default(),
            steps_a: Default::default(),
            steps_b: Default::default(),
            enables: Default::default(),
            zero32: Constant::new(0u64.into()),
            ev_period_done: ev(irq::PERIOD_DONE),
            ev_fifo_low: ev(irq::FIFO_LOW),
            ev_underrun: ev(irq::UNDERRUN),
            ev_overflow: ev(irq::OVERFLOW),
            ev_encoder_error: ev(irq::ENCODER_ERROR),
            ev_watchdog: ev(irq::WATCHDOG),
            ev_axis_fault: ev(irq::AXIS_FAULT),
            ev_limit: ev(irq::LIMIT),
            ev_alarm: ev(irq::ALARM),
            ev_estop: ev(irq::ESTOP),
            ev_home: ev(irq::HOME),
            ev_gpio: ev(irq::GPIO),
            ev_probe: ev(irq::PROBE),
            ev_held: ev(irq::HELD),
            ev_soft_limit: ev(irq::SOFT_LIMIT),
            zero_ev: Constant::new(0u64.into()),
            m_status_watchdog: m32(irq::WATCHDOG),
            m_status_estop: m32(irq::ESTOP),
            limit_held: Default::default(),
            alarm_held: Default::default(),
            home_held: Default::default(),
            any_held: Default::default(),
            axis_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
            zero_k: Constant::new(0u64.into()),
            zero_trail: Constant::new(0u64.into()),
            one_trail: Constant::new(1u64.into()),
        }
    }
}

// `update()` reads CONTROL's bits at literals (rust-hdl prints a named
// constant by name): each is tied to the map's constant here.
const _: () = {
    assert!(fields::CONTROL_RUN == 0);
    assert!(fields::CONTROL_FLUSH == 1);
};

impl<
        const K: usize,
        const N: usize,
        const NP1: usize,
        const UNIFORM: bool,
        const ANALOG: bool,
        const PROBE: bool,
        const SOFT: bool,
        const SPINDLE: bool,
        const LASER: bool,
    > Logic for MotionController<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            read_data,
            any_low_prev_n,
            expired_prev,
            held_prev,
            motion_tick,
            tick_trail,
            abort_hold,
            div_owner
        );
        clock!(
            self,
            clock,
            registers,
            period,
            cause_register,
            tick_divider,
            watchdog,
            interrupts,
            io,
            probe_trigger,
            soft_limits,
            spindle,
            laser,
            feed_hold_unit,
            planner,
            analog
        );

        // The register layer: the global registers' flip-flops, strobes and
        // read word.
        self.registers.reset.next = self.reset.val();
        self.registers.address.next = self.bus_address.val();
        self.registers.write_data.next = self.bus_write_data.val();
        self.registers.write.next = self.bus_write.val();
        self.registers.running.next = self.period.running.val();
        self.registers.status.next = self.interrupts.status.val();
        self.registers.watchdog_armed.next = self.watchdog.armed.val();
        self.registers.watchdog_expired.next = self.watchdog.expired.val();
        self.registers.estop_input.next = self.io.estop_active.val();
        self.registers.estop_latched.next = self.io.estop_latched.val();
        self.registers.inputs_ready.next = self.io.ready.val();
        self.registers.period_count.next = self.period.period_count.val();
        self.registers.stop_cause.next = self.cause_register.stop_cause.val();

        // Base tick.
        self.tick_divider.reset.next = self.reset.val();
        self.tick_divider.enable.next = true;
        self.tick_divider.divisor.next = self.registers.tick_divisor.val();
        self.tick.next = self.tick_divider.strobe.val();

        // Watchdog: kicked by a KICK write, cleared with STATUS.WATCHDOG.
        self.watchdog.reset.next = self.reset.val();
        self.watchdog.tick.next = self.tick.val();
        self.watchdog.timeout.next = self.registers.watchdog_timeout.val();
        self.watchdog.kick.next = self.registers.kick.val();
        self.watchdog.clear.next = self.registers.status_write.val()
            & ((self.bus_write_data.val() & self.m_status_watchdog.val()) != self.zero32.val());

        // Machine I/O: switch conditioning, E-stop latch, general I/O.
        self.io.reset.next = self.reset.val();
        self.io.limit_pos.next = self.limit_pos.val();
        self.io.limit_neg.next = self.limit_neg.val();
        self.io.home.next = self.home.val();
        self.io.drive_alarm.next = self.drive_alarm.val();
        self.io.estop.next = self.estop.val();
        self.io.gpio_in.next = self.gpio_in.val();
        self.io.address.next = self.bus_address.val();
        self.io.write.next = self.bus_write.val();
        self.io.write_data.next = self.bus_write_data.val();
        self.io.estop_clear.next = self.registers.status_write.val()
            & ((self.bus_write_data.val() & self.m_status_estop.val()) != self.zero32.val());
        self.io.watchdog_expired.next = self.watchdog.expired.val();
        self.gpio_out.next = self.io.gpio_out.val();
        self.drive_allowed.next = !self.io.estop_latched_next.val() & !self.watchdog.expired.val();
        self.probe_trigger.reset.next = self.reset.val();
        self.probe_trigger.probe.next = self.probe.val();
        self.probe_trigger.sample.next = self.io.filter_sample.val();
        self.probe_trigger.length.next = self.io.filter_length.val();
        self.probe_trigger.address.next = self.bus_address.val();
        self.probe_trigger.write.next = self.bus_write.val();
        self.probe_trigger.write_data.next = self.bus_write_data.val().get_bits::<3>(0);

        // The feed hold gates the base tick of the periods and the axes
        // (the watchdog keeps the base tick: a hold does not stretch it).
        self.feed_hold_unit.reset.next = self.reset.val();
        self.feed_hold_unit.feed_hold.next = self.feed_hold.val();
        self.feed_hold_unit.sample.next = self.io.filter_sample.val();
        self.feed_hold_unit.length.next = self.io.filter_length.val();
        self.feed_hold_unit.address.next = self.bus_address.val();
        self.feed_hold_unit.write.next = self.bus_write.val();
        self.feed_hold_unit.write_data.next = self.bus_write_data.val();
        self.feed_hold_unit.probe_stop.next = self.probe_trigger.stop.val() & self.has_probe.val();
        self.feed_hold_unit.soft_stop.next = self.soft_limits.stop.val() & self.has_soft.val();
        self.feed_hold_unit.tick.next = self.tick.val();
        self.motion_tick.d.next = self.feed_hold_unit.tick_out.val();
        self.registers.holding.next = self.feed_hold_unit.holding.val();
        self.registers.held.next = self.feed_hold_unit.held.val();

        // Stop causes held by the axes, and the axes' summaries. Bits of
        // the K-bit vectors by mask, not bit select: at K = 1 rust-hdl
        // declares them without a range, where `x[0]` is illegal Verilog.
        self.limit_held.next = self.zero_k.val();
        self.alarm_held.next = self.zero_k.val();
        self.home_held.next = self.zero_k.val();
        self.any_limit_event.next = false;
        self.any_alarm_event.next = false;
        self.any_home_event.next = false;
        self.all_ready.next = true;
        self.any_low.next = false;
        self.any_overflow.next = false;
        self.any_fault.next = false;
        self.any_encoder_error.next = false;
        self.any_busy.next = false;
        for i in 0..K {
            if self.axes[i].limit_held.val() {
                self.limit_held.next = self.limit_held.val() | self.axis_bit[i].val();
            }
            if self.axes[i].alarm_held.val() {
                self.alarm_held.next = self.alarm_held.val() | self.axis_bit[i].val();
            }
            if self.axes[i].home_held.val() {
                self.home_held.next = self.home_held.val() | self.axis_bit[i].val();
            }
            self.any_limit_event.next = self.any_limit_event.val() | self.axes[i].limit_event.val();
            self.any_alarm_event.next = self.any_alarm_event.val() | self.axes[i].alarm_event.val();
            self.any_home_event.next = self.any_home_event.val() | self.axes[i].home_event.val();
            self.any_busy.next = self.any_busy.val() | self.axes[i].busy.val();
            self.all_ready.next = self.all_ready.val() & !self.axes[i].empty.val();
        }
        // The laser FIFO, when it takes part in the run (`LASER`).
        if self.has_laser.val() & !self.laser.ready.val() {
            self.all_ready.next = false;
        }
        for i in 0..K {
            self.any_low.next = self.any_low.val() | self.axes[i].low.val();
            self.any_overflow.next = self.any_overflow.val() | self.axes[i].overflow_event.val();
            self.any_fault.next = self.any_fault.val() | self.axes[i].fault_event.val();
            self.any_encoder_error.next =
                self.any_encoder_error.val() | self.axes[i].encoder_error_event.val();
        }
        self.any_held.next = (self.limit_held.val() != self.zero_k.val())
            | (self.alarm_held.val() != self.zero_k.val())
            | (self.home_held.val() != self.zero_k.val());
        // Registered, so that the OR of every latch is not in front of the
        // halt and flush logic of every axis: one clock of latency.
        self.abort_hold.d.next = self.io.estop_latched.val() | self.any_held.val();
        if self.reset.val() {
            self.abort_hold.d.next = false;
        }
        self.abort.next = self.abort_hold.q.val() | self.watchdog.expired.val();
        self.registers.aborted.next = self.abort.val();
        // RUN is refused on the latches themselves, not on the registered
        // hold, so no clock slips between a latch and the refusal.
        self.refuse_run.next = self.period.running.val()
            | self.watchdog.expired.val()
            | self.io.estop_active.val()
            | self.io.estop_latched.val()
            | self.any_held.val()
            | !self.io.ready.val();

        // Run control and the period boundary. CONTROL.RUN, CONTROL.FLUSH:
        // literal bits, asserted above.
        self.period.reset.next = self.reset.val();
        self.period.tick.next = self.motion_tick.q.val();
        self.period.control_write.next = self.registers.control_write.val();
        self.period.run_bit.next = self.bus_write_data.val().get_bit(0);
        self.period.flush_bit.next = self.bus_write_data.val().get_bit(1);
        self.period.refuse_run.next = self.refuse_run.val();
        self.period.abort.next = self.abort.val();
        self.period.all_ready.next = self.all_ready.val();
        self.period.period_ticks.next = self.registers.period_ticks.val();
        self.start.next = self.period.start.val();
        self.halt.next = self.period.halt.val();
        self.pop.next = self.period.pop.val();
        self.underrun.next = self.period.underrun.val();
        self.running.next = self.period.running.val();
        self.tick_trail.d.next = self.tick_trail.q.val() << 1;
        if self.motion_tick.q.val() & self.period.running.val() {
            self.tick_trail.d.next = (self.tick_trail.q.val() << 1) | self.one_trail.val();
        }
        self.active.next = self.period.running.val()
            | self.any_busy.val()
            | (self.tick_trail.q.val() != self.zero_trail.val());

        // STOP_CAUSE: taken when RUN falls.
        self.cause_register.reset.next = self.reset.val();
        self.cause_register.limit_held.next = self.limit_held.val();
        self.cause_register.alarm_held.next = self.alarm_held.val();
        self.cause_register.home_held.next = self.home_held.val();
        self.cause_register.estop_latched.next = self.io.estop_latched.val();
        self.cause_register.abort_hold.next = self.abort_hold.q.val();
        self.cause_register.watchdog_expired.next = self.watchdog.expired.val();
        self.cause_register.running.next = self.period.running.val();
        self.cause_register.underrun.next = self.underrun.val();
        self.cause_register.halt.next = self.halt.val();

        // The shared planner: the lowest-numbered axis that asks gets it
        // when it is idle (a start in its `done` clock would hand the
        // owner's request, still high then, a second plan). Without
        // uniform generators it is never started and its results reach no
        // axis, so synthesis removes it (the axes' requests are already 0,
        // but that is not visible across the axis's module boundary).
        self.planner.reset.next = self.reset.val() | self.halt.val();
        self.div_idle.next =
            !self.planner.busy.val() & !self.planner.done.val() & self.has_uniform.val();
        self.div_granted.next = false;
        self.planner.start.next = false;
        self.planner.dividend.next = self.axes[0].div_dividend.val();
        self.planner.divisor.next = self.axes[0].div_divisor.val();
        for i in 0..K {
            if self.div_idle.val() & !self.div_granted.val() & self.axes[i].div_request.val() {
                self.div_granted.next = true;
                self.planner.start.next = true;
                self.planner.dividend.next = self.axes[i].div_dividend.val();
                self.planner.divisor.next = self.axes[i].div_divisor.val();
                self.div_owner.d.next = self.axis_bit[i].val();
            }
            // One assignment each, no default-then-override: these nets
            // and the axes' requests form a cycle of always blocks, and a
            // glitch on both sides keeps Icarus re-evaluating forever.
            self.axes[i].div_done.next = self.has_uniform.val()
                & self.planner.done.val()
                & ((self.div_owner.q.val() & self.axis_bit[i].val()) != self.zero_k.val());
            self.axes[i].div_half.next = self.planner.half.val();
            self.axes[i].div_long_pulses.next = self.planner.long_pulses.val();
            self.axes[i].div_short_negated.next = self.planner.short_negated.val();
            self.axes[i].div_half_is_one.next = self.planner.half_is_one.val();
            self.axes[i].div_has_pulses.next = self.planner.has_pulses.val();
            self.axes[i].div_clamped.next = self.planner.clamped.val();
        }
        if self.reset.val() {
            self.div_owner.d.next = self.zero_k.val();
        }

        // Axes.
        self.axes_read.next = self.zero32.val();
        self.steps_a.next = self.zero_k.val();
        self.steps_b.next = self.zero_k.val();
        self.enables.next = self.zero_k.val();
        // The FIFO entry every axis stores, converted once for all.
        self.entry_converter.word.next = self.bus_write_data.val();
        // Bits of the K-bit ports by mask, not bit select: at K = 1 rust-hdl
        // declares them without a range, where `x[0]` is illegal Verilog.
        for i in 0..K {
            self.axes[i].clock.next = self.clock.val();
            self.axes[i].reset.next = self.reset.val();
            self.axes[i].tick.next = self.motion_tick.q.val();
            self.axes[i].start.next = self.start.val();
            self.axes[i].flush.next = self.period.flush.val();
            self.axes[i].halt.next = self.halt.val();
            self.axes[i].abort.next = self.abort.val();
            self.axes[i].gear_step.next =
                (self.spindle.step.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].gear_forward.next = self.spindle.step_forward.val();
            self.axes[i].pop.next = self.pop.val();
            self.axes[i].underrun.next = self.underrun.val();
            self.axes[i].period_active.next = self.period.period_active.val();
            self.axes[i].modulus_negated.next = self.period.modulus_negated.val();
            self.axes[i].snapshot.next = self.registers.snapshot.val();
            self.axes[i].low_water.next = self.registers.low_water.val();
            self.axes[i].address.next = self.bus_address.val();
            self.axes[i].write.next = self.bus_write.val();
            self.axes[i].write_data.next = self.bus_write_data.val();
            self.axes[i].fifo_entry.next = self.entry_converter.entry.val();
            self.axes[i].enc_a.next =
                (self.enc_a.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].enc_b.next =
                (self.enc_b.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].enc_index.next =
                (self.enc_index.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].limit_forward.next =
                (self.io.limit_pos_active.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].limit_backward.next =
                (self.io.limit_neg_active.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].home.next =
                (self.io.home_active.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].home_rise.next =
                (self.io.home_rise.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].alarm.next =
                (self.io.alarm_active.val() & self.axis_bit[i].val()) != self.zero_k.val();
            self.axes[i].drive_allowed.next = self.drive_allowed.val();
            self.axes[i].probe_latch.next = self.probe_trigger.latch.val() & self.has_probe.val();
            if self.axes[i].out_a.val() {
                self.steps_a.next = self.steps_a.val() | self.axis_bit[i].val();
            }
            if self.axes[i].out_b.val() {
                self.steps_b.next = self.steps_b.val() | self.axis_bit[i].val();
            }
            if self.axes[i].drive_enable.val() {
                self.enables.next = self.enables.val() | self.axis_bit[i].val();
            }
            self.axes_read.next = self.axes_read.val() | self.axes[i].read_data.val();
        }
        self.step_a.next = self.steps_a.val();
        self.step_b.next = self.steps_b.val();
        self.drive_enable.next = self.enables.val();

        // The spindle unit: its encoder, registers and gearbox; an abort
        // halts the gearbox. Without SPINDLE it drives nothing (the axes
        // gate its steps), and synthesis removes it.
        self.spindle.reset.next = self.reset.val();
        self.spindle.spindle_a.next = self.spindle_a.val();
        self.spindle.spindle_b.next = self.spindle_b.val();
        self.spindle.spindle_index.next = self.spindle_index.val();
        self.spindle.address.next = self.bus_address.val();
        self.spindle.write.next = self.bus_write.val() & self.has_spindle.val();
        self.spindle.write_data.next = self.bus_write_data.val().get_bits::<POSITION_BITS>(0);
        self.spindle.abort.next = self.abort.val();

        // The laser unit: the running periods' |entry| of its plane's two
        // axes (an analog axis counts as standing; AXIS_B equal to AXIS_A
        // is a plane of that one axis, not the axis twice), the hold's
        // factor; an
        // abort or the hold's stop kills the PWM. Without LASER it drives
        // nothing, and synthesis removes it.
        self.laser_count_a.next = self.zero_code.val();
        self.laser_count_b.next = self.zero_code.val();
        for i in 0..K {
            if (self.laser.axis_a.val() == self.laser_axis[i].val()) & !self.axes[i].analog.val() {
                self.laser_count_a.next = self.axes[i].dac_code.val();
            }
            if (self.laser.axis_b.val() == self.laser_axis[i].val())
                & (self.laser.axis_b.val() != self.laser.axis_a.val())
                & !self.axes[i].analog.val()
            {
                self.laser_count_b.next = self.axes[i].dac_code.val();
            }
        }
        self.laser.reset.next = self.reset.val();
        self.laser.address.next = self.bus_address.val();
        self.laser.write.next = self.bus_write.val() & self.has_laser.val();
        self.laser.write_data.next = self.bus_write_data.val();
        self.laser.start.next = self.start.val();
        self.laser.pop.next = self.pop.val();
        self.laser.stop.next = self.underrun.val() | self.halt.val();
        self.laser.flush.next = self.period.flush.val();
        self.laser.running.next = self.period.running.val();
        self.laser.kill.next = self.abort.val() | self.feed_hold_unit.held.val();
        self.laser.factor.next = self.feed_hold_unit.factor.val();
        self.laser.count_a.next = self.laser_count_a.val();
        self.laser.count_b.next = self.laser_count_b.val();
        self.laser_pwm.next = self.laser.pwm.val() & self.has_laser.val();

        // Soft limits: the axis they take in turn, its position and entry.
        self.soft_position.next = self.zero_position.val();
        self.soft_magnitude.next = self.zero_code.val();
        self.soft_negative.next = false;
        self.soft_step_axis.next = false;
        for i in 0..K {
            if self.soft_limits.select.val() == self.soft_axis[i].val() {
                self.soft_position.next = self.axes[i].cmd_position.val();
                self.soft_magnitude.next = self.axes[i].dac_code.val();
                self.soft_negative.next = self.axes[i].code_negative.val();
                self.soft_step_axis.next = !self.axes[i].analog.val();
            }
        }
        self.soft_limits.reset.next = self.reset.val();
        self.soft_limits.address.next = self.bus_address.val();
        self.soft_limits.write.next = self.bus_write.val() & self.has_soft.val();
        self.soft_limits.read.next = self.bus_read.val() & self.has_soft.val();
        self.soft_limits.write_data.next = self.bus_write_data.val().get_bits::<POSITION_BITS>(0);
        self.soft_limits.running.next = self.period.running.val();
        self.soft_limits.rate.next = self.feed_hold_unit.rate_out.val();
        self.soft_limits.period.next = self.registers.period_ticks.val();
        self.soft_limits.position.next = self.soft_position.val();
        self.soft_limits.magnitude.next = self.soft_magnitude.val();
        self.soft_limits.negative.next = self.soft_negative.val();
        self.soft_limits.step_axis.next = self.soft_step_axis.val();

        // Analog outputs. After each pop the analog axes' codes are loaded
        // into the DAC one axis a clock, then one update writes every
        // channel and pulses LDAC once. When RUN falls, not by an abort,
        // every analog channel gets 0 (an underrun or a stop must not leave
        // a velocity command on); an abort forces the DAC's safe code.
        self.analog_axes.next = self.zero_k.val();
        self.walk_magnitude.next = self.zero_code.val();
        self.walk_wide.next = false;
        self.walk_negative.next = false;
        for i in 0..K {
            if self.axes[i].analog.val() {
                self.analog_axes.next = self.analog_axes.val() | self.axis_bit[i].val();
            }
            if (self.analog.walk.val() & self.axis_bit[i].val()) != self.zero_k.val() {
                self.walk_magnitude.next = self.axes[i].dac_code.val();
                self.walk_wide.next = self.axes[i].code_out_of_range.val();
                self.walk_negative.next = self.axes[i].code_negative.val();
            }
        }
        self.analog.reset.next = self.reset.val();
        self.analog.bus_address.next = self.bus_address.val();
        self.analog.bus_write_data.next = self.bus_write_data.val();
        self.analog.bus_write.next = self.bus_write.val();
        self.analog.bus_read.next = self.bus_read.val();
        self.analog.pop.next = self.pop.val();
        self.analog.stop_zero.next =
            self.period.running.val() & (self.underrun.val() | self.halt.val()) & !self.abort.val();
        self.analog.abort.next = self.abort.val();
        self.analog.running.next = self.period.running.val();
        self.analog.slowed_in.next = self.feed_hold_unit.holding.val();
        self.analog.factor.next = self.feed_hold_unit.factor_fraction.val();
        self.analog.analog_axes.next = self.analog_axes.val();
        self.analog.code_magnitude.next = self.walk_magnitude.val();
        self.analog.code_negative.next = self.walk_negative.val();
        self.analog.code_wide.next = self.walk_wide.val();
        self.dac_data.next = self.analog.dac_data.val();
        self.dac_cs_n.next = self.analog.dac_cs_n.val();
        self.dac_l1_n.next = self.analog.dac_l1_n.val();
        self.dac_ldac.next = self.analog.dac_ldac.val();

        // Interrupts: pulses, so that a write-1-to-clear always clears.
        self.any_low_prev_n.d.next = !self.any_low.val();
        self.expired_prev.d.next = self.watchdog.expired.val();
        self.held_prev.d.next = self.feed_hold_unit.held.val();
        self.events.next = self.zero_ev.val();
        if self.period.period_done.val() {
            self.events.next = self.events.val() | self.ev_period_done.val();
        }
        if self.any_low.val() & self.any_low_prev_n.q.val() {
            self.events.next = self.events.val() | self.ev_fifo_low.val();
        }
        if self.underrun.val() {
            self.events.next = self.events.val() | self.ev_underrun.val();
        }
        if self.any_overflow.val() {
            self.events.next = self.events.val() | self.ev_overflow.val();
        }
        if self.any_encoder_error.val() {
            self.events.next = self.events.val() | self.ev_encoder_error.val();
        }
        if self.watchdog.expired.val() & !self.expired_prev.q.val() {
            self.events.next = self.events.val() | self.ev_watchdog.val();
        }
        if self.any_fault.val() {
            self.events.next = self.events.val() | self.ev_axis_fault.val();
        }
        if self.any_limit_event.val() {
            self.events.next = self.events.val() | self.ev_limit.val();
        }
        if self.any_alarm_event.val() {
            self.events.next = self.events.val() | self.ev_alarm.val();
        }
        if self.io.estop_event.val() {
            self.events.next = self.events.val() | self.ev_estop.val();
        }
        if self.any_home_event.val() {
            self.events.next = self.events.val() | self.ev_home.val();
        }
        if self.io.gpio_event.val() {
            self.events.next = self.events.val() | self.ev_gpio.val();
        }
        if self.probe_trigger.latch.val() & self.has_probe.val() {
            self.events.next = self.events.val() | self.ev_probe.val();
        }
        if self.feed_hold_unit.held.val() & !self.held_prev.q.val() {
            self.events.next = self.events.val() | self.ev_held.val();
        }
        if self.soft_limits.tripped.val() & self.has_soft.val() {
            self.events.next = self.events.val() | self.ev_soft_limit.val();
        }
        if self.spindle.cause.val() & self.has_spindle.val() {
            self.events.next = self.events.val() | self.ev_spindle.val();
        }
        self.interrupts.reset.next = self.reset.val();
        self.interrupts.events.next = self.events.val();
        self.interrupts.clear.next = self.registers.status_write.val();
        self.interrupts.clear_bits.next = self.bus_write_data.val().get_value_irq_bits();
        self.interrupts.enable.next = self.registers.irq_enable.val();
        self.irq.next = self.interrupts.irq.val();

        // Reads: the global registers, the machine I/O's, the feed hold's
        // and the axes'. Without PROBE the trigger drives nothing, and
        // synthesis removes it.
        self.probe_read.next = self.zero32.val();
        if self.has_probe.val() {
            self.probe_read.next = self.probe_trigger.read_data.val();
        }
        self.soft_read.next = self.zero32.val();
        if self.has_soft.val() {
            self.soft_read.next = self.soft_limits.read_data.val();
        }
        self.spindle_read.next = self.zero32.val();
        if self.has_spindle.val() {
            self.spindle_read.next = self.spindle.read_data.val();
        }
        self.laser_read.next = self.zero32.val();
        if self.has_laser.val() {
            self.laser_read.next = self.laser.read_data.val();
        }
        if self.bus_read.val() {
            self.read_data.d.next = self.registers.read_data.val()
                | self.io.read_data.val()
                | self.probe_read.val()
                | self.soft_read.val()
                | self.spindle_read.val()
                | self.laser_read.val()
                | self.feed_hold_unit.read_data.val()
                | self.axes_read.val();
        }
        // The DAC's read data is registered like ours: the same clock.
        self.read_out.next = self.read_data.q.val();
        if self.analog.read_selected.val() {
            self.read_out.next = self.analog.read_data.val();
        }
        // The soft-limit windows come from block RAM too (0 unless the
        // last read addressed one).
        if self.has_soft.val() {
            self.read_out.next = self.read_out.val() | self.soft_limits.window_data.val();
        }
        // The axes' configuration registers come from the shadow RAM, whose
        // word is 0 for every other read (also registered at the read).
        self.config_shadow.clock.next = self.clock.val();
        self.config_shadow.reset.next = self.reset.val();
        self.config_shadow.address.next = self.bus_address.val();
        self.config_shadow.write.next = self.bus_write.val();
        self.config_shadow.write_data.next = self.bus_write_data.val().get_bits::<SHADOW_BITS>(0);
        self.config_shadow.read.next = self.bus_read.val();
        for b in 0..SHADOW_BITS {
            if self.config_shadow.read_data.val().get_bit(b) {
                self.read_out.next = self.read_out.val() | self.shadow_bit[b].val();
            }
        }
        self.bus_read_data.next = self.read_out.val();

        if self.reset.val() {
            self.read_data.d.next = self.zero32.val();
            self.any_low_prev_n.d.next = false;
            self.expired_prev.d.next = false;
            self.held_prev.d.next = false;
            self.motion_tick.d.next = false;
            self.tick_trail.d.next = self.zero_trail.val();
        }
    }
}

crate::vector_ports!(impl[const K: usize, const N: usize, const NP1: usize, const UNIFORM: bool, const ANALOG: bool, const PROBE: bool, const SOFT: bool, const SPINDLE: bool, const LASER: bool] MotionController<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER> {
    inputs: [reset, bus_address, bus_write_data, bus_write, bus_read, enc_a, enc_b, enc_index,
        limit_pos, limit_neg, home, drive_alarm, estop, gpio_in, probe, feed_hold,
        spindle_a, spindle_b, spindle_index],
    outputs: [bus_read_data, irq, running, active, step_a, step_b, drive_enable, gpio_out,
        dac_data, dac_cs_n, dac_l1_n, dac_ldac, laser_pwm],
});
