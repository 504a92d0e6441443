//! The register map of [`super::MotionController`]: the one source of truth
//! for addresses, fields and reset values. The C header
//! (`rtl-out/motion_controller_regs.h`), the Markdown table
//! (`rtl-out/motion_controller_regs.md`), the RTL's address decoder and the
//! tests (which drive the RTL through the bus with this map) all come from
//! here.
//!
//! The RTL decodes addresses with constants taken from this map. Field
//! positions are written once, in [`fields`], and the map is built from
//! them. The RTL takes its multi-bit fields through `field_slices!`
//! (positioned by [`fields`] when the Verilog is generated); a single bit
//! stays a literal (rust-hdl prints a named Rust constant by name into the
//! Verilog) tied to its [`fields`] constant by a compile-time assertion
//! next to the block. The tests pack and unpack every field by name with
//! this map, and `tests/tooling/regmap.rs` checks each [`fields`] constant
//! against the field it names.

use crate::regmap::{field, register, Access, Field, RegMapError, Register, RegisterMap};

/// `ID` register value: "MHDC".
pub const ID_VALUE: u32 = 0x4d48_4443;
/// `VERSION` register value: major 0, minor 10, patch 0 (minor 2: machine
/// I/O, 32-word axis windows; minor 3: analog axes, `CONFIG.ANALOG`;
/// patch 1: on a uniform axis, `INTERP_OVERRANGE` for |n| > P/2 is set
/// when the axis's period plan arrives from the shared planner, not two
/// clocks after the entry is taken). Minor 4: the position counters and
/// their latches are `CONFIG.POSITION_BITS` = 24 bits wide, not 32; their
/// words carry the sign up to bit 31 and wrap at 2^24. Minor 5: the probe
/// input (`PROBE_CONTROL`, `PROBE_*_POSITION`, `STATUS.PROBE`). Minor 6:
/// the feed hold (`feed_hold`, `HOLD_CONTROL`, `STATE.HOLDING`/`HELD`,
/// `STATUS.HELD`, `PROBE_CONTROL.STOP`); its patch 1: the hold scales the
/// analog axes' codes by its factor. Minor 7: the soft limits
/// (`SOFT_LIMIT`, `SOFT_MIN`, `SOFT_MAX`, `STATUS.SOFT_LIMIT`,
/// `CONFIG.SOFT_LIMITS`); its patch 1: the check's latency 100 clocks at
/// K = 3 (was 96), the reach floor(N/2) + 1 + latency from the stop's
/// length, a window written in an axis's load clock checked as written,
/// and a window read in the clock of a write to it reading 0. Minor 8: the
/// spindle encoder and the electronic gearbox (`SPINDLE_*`, `GEAR_*`,
/// `STATUS.SPINDLE`, `CONFIG.SPINDLE`, the `spindle_*` pins). Minor 9:
/// the laser PWM tied to the path (`LASER_*`, `CONFIG.LASER`, the
/// `laser_pwm` pin). Minor 10: the laser's power by register
/// (`LASER_POWER`, `LASER_CONTROL.SOURCE`).
pub const VERSION_VALUE: u32 = 0x0000_0a00;

/// Word addresses of the global registers.
pub mod global {
    /// Identity.
    pub const ID: u32 = 0x00;
    /// Version.
    pub const VERSION: u32 = 0x01;
    /// Build configuration.
    pub const CONFIG: u32 = 0x02;
    /// Run control.
    pub const CONTROL: u32 = 0x03;
    /// Sticky interrupt status (write 1 to clear).
    pub const STATUS: u32 = 0x04;
    /// Interrupt enable mask.
    pub const IRQ_ENABLE: u32 = 0x05;
    /// Base tick divisor.
    pub const TICK_DIVISOR: u32 = 0x06;
    /// Interpolation period in base ticks.
    pub const PERIOD_TICKS: u32 = 0x07;
    /// FIFO low-water threshold.
    pub const FIFO_LOW_WATER: u32 = 0x08;
    /// Watchdog timeout in base ticks.
    pub const WATCHDOG_TIMEOUT: u32 = 0x09;
    /// Watchdog kick.
    pub const WATCHDOG_KICK: u32 = 0x0a;
    /// Position snapshot trigger.
    pub const SNAPSHOT: u32 = 0x0b;
    /// Live state.
    pub const STATE: u32 = 0x0c;
    /// Periods started since reset.
    pub const PERIOD_COUNT: u32 = 0x0d;
    /// Switch and GPIO input filter.
    pub const INPUT_FILTER: u32 = 0x0e;
    /// Input polarity per input class.
    pub const INPUT_POLARITY: u32 = 0x0f;
    /// Cause of the last stop.
    pub const STOP_CAUSE: u32 = 0x10;
    /// General inputs, filtered.
    pub const GPIO_IN: u32 = 0x11;
    /// General outputs.
    pub const GPIO_OUT: u32 = 0x12;
    /// Outputs dropped on E-stop or watchdog expiry.
    pub const GPIO_SAFE: u32 = 0x13;
    /// General input edge interrupt enables.
    pub const GPIO_IRQ_ENABLE: u32 = 0x14;
    /// General input edges seen (write 1 to clear).
    pub const GPIO_EDGES: u32 = 0x15;
    /// The probe: arm, edge, and its state.
    pub const PROBE_CONTROL: u32 = 0x19;
    /// The feed hold: request, release, ramp rate, and the input's level.
    pub const HOLD_CONTROL: u32 = 0x1a;
    /// Soft limits: enables, verdicts, the last axis tripped.
    pub const SOFT_LIMIT: u32 = 0x1b;
    /// The analog outputs' code format (`dac_interface` CONTROL; analog builds).
    pub const DAC_CONTROL: u32 = 0x16;
    /// The analog outputs' state and flags (`dac_interface` STATUS).
    pub const DAC_STATUS: u32 = 0x17;
    /// The analog outputs' pin timing (`dac_interface` TIMING).
    pub const DAC_TIMING: u32 = 0x18;
}

/// The `dac_interface` registers an analog build forwards, by name: (the
/// controller's register, the DAC's register). The controller's bus
/// reaches them at these addresses; their fields, access and reset values
/// are the DAC's own.
pub const DAC_GLOBAL: [(&str, u32, &str); 3] = [
    ("DAC_CONTROL", global::DAC_CONTROL, "CONTROL"),
    ("DAC_STATUS", global::DAC_STATUS, "STATUS"),
    ("DAC_TIMING", global::DAC_TIMING, "TIMING"),
];

/// Width of the analog codes: the AD669's 16 bits (a narrower DAC takes
/// the top bits of `dac_data`).
pub const DAC_BITS: usize = 16;

/// Bit numbers (and, for the multi-bit fields the RTL slices, widths) of
/// the register fields the RTL, the models and the tests use by name. The
/// map below is built from these: they are the one place a field's
/// position is written. The RTL reads them through
/// `field_slices!` (`src/blocks/mod.rs`: slices) or at a literal bit tied to
/// them by a compile-time assertion (single bits: rust-hdl prints a named
/// constant by name); the test `fields_agree_with_the_map` checks each
/// against the map by register and field name.
pub mod fields {
    /// `CONTROL.RUN`.
    pub const CONTROL_RUN: u32 = 0;
    /// `CONTROL.FLUSH`.
    pub const CONTROL_FLUSH: u32 = 1;
    /// `INPUT_FILTER.LENGTH`: samples a level must hold.
    pub const FILTER_LENGTH: u32 = 0;
    /// Width of `INPUT_FILTER.LENGTH`.
    pub const FILTER_LENGTH_WIDTH: u32 = 4;
    /// `INPUT_FILTER.SAMPLE_RATE`: a sample every n + 1 clocks.
    pub const FILTER_SAMPLE_RATE: u32 = 8;
    /// Width of `INPUT_FILTER.SAMPLE_RATE`.
    pub const FILTER_SAMPLE_RATE_WIDTH: u32 = 8;
    /// Reset value of `INPUT_FILTER.LENGTH`.
    pub const FILTER_LENGTH_RESET: u64 = 4;
    /// `INPUT_POLARITY.LIMIT_POS`: limit_pos active low.
    pub const POLARITY_LIMIT_POS: u32 = 0;
    /// `INPUT_POLARITY.LIMIT_NEG`.
    pub const POLARITY_LIMIT_NEG: u32 = 1;
    /// `INPUT_POLARITY.HOME`.
    pub const POLARITY_HOME: u32 = 2;
    /// `INPUT_POLARITY.DRIVE_ALARM`.
    pub const POLARITY_DRIVE_ALARM: u32 = 3;
    /// `INPUT_POLARITY.GPIO`: one bit per general input.
    pub const POLARITY_GPIO: u32 = 8;
    /// Width of `INPUT_POLARITY.GPIO`, and the number of general inputs
    /// and outputs (`GPIO_IN.LEVEL`, `GPIO_OUT.LEVEL`, `GPIO_SAFE.MASK`,
    /// `GPIO_IRQ_ENABLE.RISE` and `FALL`, `GPIO_EDGES.RISE` and `FALL`).
    pub const GPIO_WIDTH: u32 = 8;
    /// `GPIO_IN.LEVEL`, `GPIO_OUT.LEVEL` and `GPIO_SAFE.MASK`.
    pub const GPIO_LEVEL: u32 = 0;
    /// `STOP_CAUSE.CAUSE` (a [`super::StopCause`]).
    pub const STOP_CAUSE_CAUSE: u32 = 0;
    /// `STOP_CAUSE.AXIS`.
    pub const STOP_CAUSE_AXIS: u32 = 8;
    /// Width of `STOP_CAUSE.CAUSE` and `STOP_CAUSE.AXIS`.
    pub const STOP_CAUSE_WIDTH: u32 = 4;
    /// `GPIO_IRQ_ENABLE.RISE` and `GPIO_EDGES.RISE` ([`GPIO_WIDTH`] bits).
    pub const GPIO_RISE: u32 = 0;
    /// `GPIO_IRQ_ENABLE.FALL` and `GPIO_EDGES.FALL` ([`GPIO_WIDTH`] bits).
    pub const GPIO_FALL: u32 = 8;
    /// `CONFIG.DDA_ONLY`: the build has no uniform pulse generators.
    pub const CONFIG_DDA_ONLY: u32 = 24;
    /// `CONFIG.ANALOG`: the build has the analog outputs.
    pub const CONFIG_ANALOG: u32 = 25;
    /// `CONFIG.PROBE`: the build has the probe latch.
    pub const CONFIG_PROBE: u32 = 26;
    /// `FIFO_STATUS.LEVEL` and `FIFO_LOW_WATER.LEVEL` (FIFO depth + 1 bits).
    pub const FIFO_LEVEL: u32 = 0;
    /// `FIFO_STATUS.EMPTY`.
    pub const FIFO_EMPTY: u32 = 16;
    /// `FIFO_STATUS.FULL`.
    pub const FIFO_FULL: u32 = 17;
    /// `FIFO_STATUS.LOW`.
    pub const FIFO_LOW: u32 = 18;
    /// `AXIS_CONFIG.UNIFORM`: the uniform pulse generator drives the axis.
    pub const AXIS_UNIFORM: u32 = 0;
    /// `AXIS_CONFIG.INTERLEAVED`: the uniform generator's order.
    pub const AXIS_INTERLEAVED: u32 = 1;
    /// `AXIS_CONFIG.STEP_MODE`: the output stage's pin mode.
    pub const AXIS_STEP_MODE: u32 = 2;
    /// Width of `AXIS_CONFIG.STEP_MODE`.
    pub const AXIS_STEP_MODE_WIDTH: u32 = 2;
    /// `AXIS_CONFIG.ENC_FILTER`: the encoder glitch filter length.
    pub const AXIS_ENC_FILTER: u32 = 4;
    /// Width of `AXIS_CONFIG.ENC_FILTER`.
    pub const AXIS_ENC_FILTER_WIDTH: u32 = 4;
    /// `AXIS_CONFIG.ENC_COUNTER_MODE`.
    pub const AXIS_ENC_COUNTER_MODE: u32 = 8;
    /// `AXIS_CONFIG.INDEX_INVERT`.
    pub const AXIS_INDEX_INVERT: u32 = 9;
    /// `AXIS_CONFIG.INDEX_CLEAR`.
    pub const AXIS_INDEX_CLEAR: u32 = 10;
    /// `AXIS_CONFIG.INDEX_LATCH`.
    pub const AXIS_INDEX_LATCH: u32 = 11;
    /// `AXIS_CONFIG.INDEX_ONCE`.
    pub const AXIS_INDEX_ONCE: u32 = 12;
    /// `AXIS_CONFIG.ANALOG`: the axis is an analog (DAC) axis.
    pub const AXIS_ANALOG: u32 = 13;
    /// `AXIS_STATUS.STEP_OVERRUN`.
    pub const STATUS_STEP_OVERRUN: u32 = 0;
    /// `AXIS_STATUS.INTERP_OVERRANGE`.
    pub const STATUS_INTERP_OVERRANGE: u32 = 1;
    /// `AXIS_STATUS.INTERP_OVERFLOW`.
    pub const STATUS_INTERP_OVERFLOW: u32 = 2;
    /// `AXIS_STATUS.ENCODER_ERROR`.
    pub const STATUS_ENCODER_ERROR: u32 = 3;
    /// `AXIS_STATUS.INDEX_SEEN`.
    pub const STATUS_INDEX_SEEN: u32 = 4;
    /// `AXIS_STATUS.STEP_BUSY`.
    pub const STATUS_STEP_BUSY: u32 = 5;
    /// `AXIS_STATUS.UNIFORM_RUNNING`.
    pub const STATUS_UNIFORM_RUNNING: u32 = 6;
    /// `AXIS_STATUS.STEP_MODE_INVALID`.
    pub const STATUS_STEP_MODE_INVALID: u32 = 7;
    /// `AXIS_COMMAND.CLEAR_FAULTS`.
    pub const CMD_CLEAR_FAULTS: u32 = 0;
    /// `AXIS_COMMAND.CLEAR_ENCODER`.
    pub const CMD_CLEAR_ENCODER: u32 = 1;
    /// `AXIS_COMMAND.REARM_INDEX`.
    pub const CMD_REARM_INDEX: u32 = 2;
    /// `AXIS_COMMAND.CLEAR_POSITION`.
    pub const CMD_CLEAR_POSITION: u32 = 3;
    /// `AXIS_COMMAND.CLEAR_ENCODER_ERROR`.
    pub const CMD_CLEAR_ENCODER_ERROR: u32 = 4;
    /// `VALUE`, the one field of a number register (`STEP_LEN`,
    /// `ENC_SAMPLE_RATE`, `PERIOD_TICKS`...).
    pub const VALUE: u32 = 0;
    /// Width of `STEP_LEN`, `STEP_SPACE`, `DIR_SETUP` and `DIR_HOLD`.
    pub const STEP_TIMING_WIDTH: u32 = 16;
    /// Width of `ENC_SAMPLE_RATE`.
    pub const ENC_SAMPLE_RATE_WIDTH: u32 = 8;
    /// `STATE.RUNNING`.
    pub const STATE_RUNNING: u32 = 0;
    /// `STATE.WATCHDOG_ARMED`.
    pub const STATE_WATCHDOG_ARMED: u32 = 1;
    /// `STATE.WATCHDOG_EXPIRED`.
    pub const STATE_WATCHDOG_EXPIRED: u32 = 2;
    /// `STATE.ESTOP_INPUT`.
    pub const STATE_ESTOP_INPUT: u32 = 3;
    /// `STATE.ESTOP_LATCHED`.
    pub const STATE_ESTOP_LATCHED: u32 = 4;
    /// `STATE.ABORTED`.
    pub const STATE_ABORTED: u32 = 5;
    /// `STATE.INPUTS_READY`.
    pub const STATE_INPUTS_READY: u32 = 6;
    /// `IO_CONFIG.LIMIT_ENABLE` (reset 1).
    pub const LIMIT_ENABLE: u32 = 0;
    /// `IO_CONFIG.ALARM_ENABLE` (reset 1).
    pub const ALARM_ENABLE: u32 = 1;
    /// `IO_CONFIG.STOP_ON_HOME`.
    pub const STOP_ON_HOME: u32 = 2;
    /// `IO_CONFIG.DRIVE_ENABLE`.
    pub const DRIVE_ENABLE: u32 = 3;
    /// Reset value of `IO_CONFIG`.
    pub const IO_CONFIG_RESET: u32 = 1 << LIMIT_ENABLE | 1 << ALARM_ENABLE;
    /// `IO_STATUS.LIMIT_POS`: live, active.
    pub const IO_LIMIT_POS: u32 = 0;
    /// `IO_STATUS.LIMIT_NEG`.
    pub const IO_LIMIT_NEG: u32 = 1;
    /// `IO_STATUS.HOME`.
    pub const IO_HOME: u32 = 2;
    /// `IO_STATUS.DRIVE_ALARM`.
    pub const IO_DRIVE_ALARM: u32 = 3;
    /// `IO_STATUS.LIMIT_POS_TRIPPED`: sticky.
    pub const IO_LIMIT_POS_TRIPPED: u32 = 8;
    /// `IO_STATUS.LIMIT_NEG_TRIPPED`: sticky.
    pub const IO_LIMIT_NEG_TRIPPED: u32 = 9;
    /// `IO_STATUS.ALARM_TRIPPED`: sticky.
    pub const IO_ALARM_TRIPPED: u32 = 10;
    /// `IO_STATUS.HOME_SEEN`: sticky.
    pub const IO_HOME_SEEN: u32 = 11;
    /// `IO_STATUS.DRIVE_ENABLE`: the pin.
    pub const IO_DRIVE_ENABLE: u32 = 16;
    /// `PROBE_CONTROL.ARM`: write 1 to arm (clears TRIPPED), 0 to disarm.
    pub const PROBE_ARM: u32 = 0;
    /// `PROBE_CONTROL.EDGE`: 0 = the rising edge of `probe`, 1 = the falling.
    pub const PROBE_EDGE: u32 = 1;
    /// `PROBE_CONTROL.TRIPPED`: read-only, sticky until re-armed.
    pub const PROBE_TRIPPED: u32 = 8;
    /// `PROBE_CONTROL.LEVEL`: read-only, the filtered `probe` level.
    pub const PROBE_LEVEL: u32 = 9;
    /// `PROBE_CONTROL.STOP`: a trip also requests the feed hold.
    pub const PROBE_STOP: u32 = 2;
    /// `HOLD_CONTROL.HOLD`: write 1 to request the hold.
    pub const HOLD_HOLD: u32 = 0;
    /// `HOLD_CONTROL.RELEASE`: write 1 to release the hold.
    pub const HOLD_RELEASE: u32 = 1;
    /// `HOLD_CONTROL.INVERT`: the `feed_hold` input is active low.
    pub const HOLD_INVERT: u32 = 2;
    /// `HOLD_CONTROL.REQUESTED`: read-only, the hold is requested.
    pub const HOLD_REQUESTED: u32 = 8;
    /// `HOLD_CONTROL.INPUT`: read-only, the filtered `feed_hold` input.
    pub const HOLD_INPUT: u32 = 9;
    /// `HOLD_CONTROL.RATE`: the factor's change per base tick.
    pub const HOLD_RATE: u32 = 16;
    /// Width of `HOLD_CONTROL.RATE`.
    pub const HOLD_RATE_WIDTH: u32 = 16;
    /// `SOFT_LIMIT.ENABLE`: one bit per axis.
    pub const SOFT_ENABLE: u32 = 0;
    /// Room of `SOFT_LIMIT.ENABLE` and `BEYOND`: 8 axes (each field is
    /// K bits wide, K axes).
    pub const SOFT_ENABLE_WIDTH: u32 = 8;
    /// `SOFT_LIMIT.BEYOND`: one bit per axis, the live verdicts.
    pub const SOFT_BEYOND: u32 = 8;
    /// `SOFT_LIMIT.AXIS`: the axis of the last verdict that turned beyond.
    pub const SOFT_AXIS: u32 = 16;
    /// Width of `SOFT_LIMIT.AXIS`.
    pub const SOFT_AXIS_WIDTH: u32 = 3;
    /// `SOFT_LIMIT.NEGATIVE`: that axis was moving down (toward SOFT_MIN).
    pub const SOFT_NEGATIVE: u32 = 19;
    /// `SOFT_LIMIT.MEASURED`: the stop's reach at the present RATE is measured.
    pub const SOFT_MEASURED: u32 = 20;
    /// `CONFIG.SOFT_LIMITS`: the build has the soft limits.
    pub const CONFIG_SOFT_LIMITS: u32 = 27;
    /// `CONFIG.SPINDLE`: the build has the spindle unit.
    pub const CONFIG_SPINDLE: u32 = 28;
    /// `CONFIG.LASER`: the build has the laser unit.
    pub const CONFIG_LASER: u32 = 29;
    /// `LASER_CONTROL.ENABLE`: the laser may fire (and, at a start, its
    /// FIFO joins the run).
    pub const LASER_ENABLE: u32 = 0;
    /// `LASER_CONTROL.DYNAMIC`: the duty scales with path speed / feed.
    pub const LASER_DYNAMIC: u32 = 1;
    /// `LASER_CONTROL.CLEAR_OVERFLOW`: write 1 to clear `LASER_STATUS.OVERFLOW`.
    pub const LASER_CLEAR_OVERFLOW: u32 = 2;
    /// `LASER_CONTROL.SOURCE`: 1 = each period's POWER and FEED come from
    /// `LASER_POWER`, and the laser FIFO stays out of the run.
    pub const LASER_SOURCE: u32 = 3;
    /// `LASER_CONTROL.AXIS_A`: the plane's first axis.
    pub const LASER_AXIS_A: u32 = 4;
    /// `LASER_CONTROL.AXIS_B`: the plane's second axis.
    pub const LASER_AXIS_B: u32 = 8;
    /// Width of `LASER_CONTROL.AXIS_A` and `AXIS_B`.
    pub const LASER_AXIS_WIDTH: u32 = 3;
    /// `LASER_FIFO.POWER`, `LASER_POWER.POWER` and `LASER_OUTPUT.DUTY`:
    /// clocks high per PWM period.
    pub const LASER_POWER: u32 = 0;
    /// `LASER_FIFO.FEED` and `LASER_POWER.FEED`: the programmed feed, 1/16
    /// step per period.
    pub const LASER_FEED: u32 = 16;
    /// Width of `LASER_FIFO.POWER`, `FEED`, `LASER_PWM_PERIOD` and
    /// `LASER_OUTPUT`'s fields.
    pub const LASER_WORD_WIDTH: u32 = 16;
    /// `LASER_STATUS.LEVEL`: entries in the laser FIFO.
    pub const LASER_LEVEL: u32 = 0;
    /// `LASER_STATUS.OVERFLOW`: sticky, a `LASER_FIFO` write was refused.
    pub const LASER_OVERFLOW: u32 = 8;
    /// `LASER_STATUS.ACTIVE`: the laser FIFO takes part in the run.
    pub const LASER_ACTIVE: u32 = 9;
    /// `LASER_STATUS.BUSY`: the duty engine is computing.
    pub const LASER_BUSY: u32 = 10;
    /// `LASER_OUTPUT.SPEED`: the last computed vector speed, steps per period.
    pub const LASER_SPEED: u32 = 16;
    /// `SPINDLE_CONFIG.FILTER`: the spindle encoder's glitch filter length.
    pub const SPINDLE_FILTER: u32 = 0;
    /// Width of `SPINDLE_CONFIG.FILTER`.
    pub const SPINDLE_FILTER_WIDTH: u32 = 4;
    /// `SPINDLE_CONFIG.COUNTER_MODE`: count rising edges of A, B = direction.
    pub const SPINDLE_COUNTER_MODE: u32 = 4;
    /// `SPINDLE_CONFIG.INDEX_INVERT`: the index is active low.
    pub const SPINDLE_INDEX_INVERT: u32 = 5;
    /// `SPINDLE_CONFIG.SPEED_WINDOW`: the speed window is 2^n clocks.
    pub const SPINDLE_SPEED_WINDOW: u32 = 8;
    /// Width of `SPINDLE_CONFIG.SPEED_WINDOW`.
    pub const SPINDLE_SPEED_WINDOW_WIDTH: u32 = 5;
    /// `SPINDLE_CONFIG.SPEED_WINDOW` after reset: 2^20 clocks.
    pub const SPINDLE_SPEED_WINDOW_RESET: u64 = 20;
    /// `GEAR_CONTROL.ARM`: write 1 to arm the gearbox.
    pub const GEAR_ARM: u32 = 0;
    /// `GEAR_CONTROL.STOP`: write 1 to ramp out and stop.
    pub const GEAR_STOP: u32 = 1;
    /// `GEAR_CONTROL.HALT`: write 1 to stop at once.
    pub const GEAR_HALT: u32 = 2;
    /// `GEAR_CONTROL.CLEAR_ENCODER_ERROR`: write 1 to clear the spindle
    /// encoder's error flag.
    pub const GEAR_CLEAR_ENCODER_ERROR: u32 = 3;
    /// `GEAR_CONTROL.SPINDLE_REVERSE`: the spindle's forward is counting down.
    pub const GEAR_SPINDLE_REVERSE: u32 = 4;
    /// `GEAR_CONTROL.AXIS_REVERSE`: a forward count steps the axis down.
    pub const GEAR_AXIS_REVERSE: u32 = 5;
    /// `GEAR_CONTROL.AXIS`: the geared axis.
    pub const GEAR_AXIS: u32 = 8;
    /// Width of `GEAR_CONTROL.AXIS`.
    pub const GEAR_AXIS_WIDTH: u32 = 3;
    /// `GEAR_STATUS.PHASE`: 0 idle, 1 armed, 2 ramp-in, 3 track, 4 stopping.
    pub const GEAR_PHASE: u32 = 0;
    /// Width of `GEAR_STATUS.PHASE`.
    pub const GEAR_PHASE_WIDTH: u32 = 3;
    /// `GEAR_STATUS.LOCKED`: tracking with the lag caught up.
    pub const GEAR_LOCKED: u32 = 3;
    /// `GEAR_STATUS.DONE`: sticky, the last run reached its length.
    pub const GEAR_DONE: u32 = 4;
    /// `GEAR_STATUS.INVALID`: sticky, an arm was refused.
    pub const GEAR_INVALID: u32 = 5;
    /// `GEAR_STATUS.OVERRUN`: sticky, a count was lost and the gearbox halted.
    pub const GEAR_OVERRUN: u32 = 6;
    /// `GEAR_STATUS.ENCODER_ERROR`: sticky, the spindle encoder lost counts.
    pub const GEAR_ENCODER_ERROR: u32 = 7;
    /// `STATE.HOLDING`: the hold's factor is below 1.
    pub const STATE_HOLDING: u32 = 7;
    /// `STATE.HELD`: the hold's factor is 0.
    pub const STATE_HELD: u32 = 8;
    /// `IO_COMMAND.CLEAR_LIMITS`.
    pub const CLEAR_LIMITS: u32 = 0;
    /// `IO_COMMAND.CLEAR_ALARM`.
    pub const CLEAR_ALARM: u32 = 1;
    /// `IO_COMMAND.CLEAR_HOME`.
    pub const CLEAR_HOME: u32 = 2;
}

/// `STOP_CAUSE.CAUSE`: why RUN last fell. When several causes meet in one
/// clock the highest value wins.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[repr(u32)]
pub enum StopCause {
    /// Not stopped since reset.
    None = 0,
    /// CONTROL.RUN written 0.
    Stop = 1,
    /// A boundary found a FIFO empty.
    Underrun = 2,
    /// The watchdog expired.
    Watchdog = 3,
    /// An axis with STOP_ON_HOME saw its home switch.
    Home = 4,
    /// A step toward an active limit was cut.
    Limit = 5,
    /// A drive alarm.
    DriveAlarm = 6,
    /// The E-stop input.
    Estop = 7,
}

impl StopCause {
    /// Every cause, by value.
    pub const ALL: [StopCause; 8] = [
        StopCause::None,
        StopCause::Stop,
        StopCause::Underrun,
        StopCause::Watchdog,
        StopCause::Home,
        StopCause::Limit,
        StopCause::DriveAlarm,
        StopCause::Estop,
    ];

    /// The cause a `STOP_CAUSE.CAUSE` value encodes (`None` for 8 to 15).
    pub fn from_code(code: u32) -> StopCause {
        Self::ALL
            .get(code as usize)
            .copied()
            .unwrap_or(StopCause::None)
    }

    /// What the cause is, for people.
    pub fn describe(self) -> &'static str {
        match self {
            StopCause::None => "not stopped since reset",
            StopCause::Stop => "RUN written 0",
            StopCause::Underrun => "FIFO underrun",
            StopCause::Watchdog => "watchdog expired",
            StopCause::Home => "home switch (stop on home)",
            StopCause::Limit => "limit switch",
            StopCause::DriveAlarm => "drive alarm",
            StopCause::Estop => "E-stop",
        }
    }
}

/// Word address of axis 0's register window; axis k is at
/// `AXIS_BASE + k * AXIS_STRIDE`.
pub const AXIS_BASE: u32 = 0x20;
/// Words per axis window: 16 for the motion core, 16 for its machine I/O.
pub const AXIS_STRIDE: u32 = 0x20;
/// log2 of [`AXIS_STRIDE`]: the window is `address >> AXIS_STRIDE_LOG2`.
pub const AXIS_STRIDE_LOG2: u32 = 5;
/// Most axes the 8-bit address space holds.
pub const MAX_AXES: usize = 7;
/// Most axes of a build with the spindle unit, whose window takes the
/// last axis window's addresses.
pub const MAX_AXES_SPINDLE: usize = 6;

/// Word addresses of the spindle unit's registers (build option
/// `SPINDLE`): a window at the last axis window's place, `0xE0`.
pub mod spindle {
    /// The window's first word.
    pub const BASE: u32 = 0xe0;
    /// The spindle encoder's count, signed, POSITION_BITS wide.
    pub const SPINDLE_POSITION: u32 = BASE;
    /// The count at the last index event.
    pub const SPINDLE_INDEX_POSITION: u32 = BASE + 0x01;
    /// Counts in the last speed window.
    pub const SPINDLE_SPEED: u32 = BASE + 0x02;
    /// Encoder filter, mode, index polarity, speed window.
    pub const SPINDLE_CONFIG: u32 = BASE + 0x03;
    /// Gearbox strobes, directions and axis.
    pub const GEAR_CONTROL: u32 = BASE + 0x04;
    /// Gearbox phase and flags.
    pub const GEAR_STATUS: u32 = BASE + 0x05;
    /// The ratio's numerator n.
    pub const GEAR_NUMERATOR: u32 = BASE + 0x06;
    /// The ratio's denominator d.
    pub const GEAR_DENOMINATOR: u32 = BASE + 0x07;
    /// The rate's change per count while ramping.
    pub const GEAR_RAMP: u32 = BASE + 0x08;
    /// Steps from the index at which a run ends.
    pub const GEAR_LENGTH: u32 = BASE + 0x09;
    /// Net steps since the arm.
    pub const GEAR_POSITION: u32 = BASE + 0x0a;
    /// Words the window decodes (`address - BASE` below this).
    pub const WORDS: u32 = 0x0b;
}

/// Word offsets of the per-axis registers within an axis window.
pub mod axis {
    /// Push one period's signed step count.
    pub const FIFO_WRITE: u32 = 0x0;
    /// FIFO level and flags.
    pub const FIFO_STATUS: u32 = 0x1;
    /// Interpolator, output mode and encoder settings.
    pub const AXIS_CONFIG: u32 = 0x2;
    /// Step pulse high time.
    pub const STEP_LEN: u32 = 0x3;
    /// Step pulse minimum low time.
    pub const STEP_SPACE: u32 = 0x4;
    /// Direction setup time.
    pub const DIR_SETUP: u32 = 0x5;
    /// Direction hold time.
    pub const DIR_HOLD: u32 = 0x6;
    /// Encoder sample rate.
    pub const ENC_SAMPLE_RATE: u32 = 0x7;
    /// Commanded position (steps emitted), live.
    pub const CMD_POSITION: u32 = 0x8;
    /// Actual position (encoder count), live.
    pub const ACT_POSITION: u32 = 0x9;
    /// Commanded position at the last snapshot.
    pub const CMD_SNAPSHOT: u32 = 0xa;
    /// Actual position at the last snapshot.
    pub const ACT_SNAPSHOT: u32 = 0xb;
    /// Axis flags.
    pub const AXIS_STATUS: u32 = 0xc;
    /// Encoder count latched at the index.
    pub const INDEX_POSITION: u32 = 0xd;
    /// Axis commands.
    pub const AXIS_COMMAND: u32 = 0xe;
    /// Limit, alarm, home and drive-enable settings.
    pub const IO_CONFIG: u32 = 0x10;
    /// Switch levels and sticky trips.
    pub const IO_STATUS: u32 = 0x11;
    /// Clear the sticky trips.
    pub const IO_COMMAND: u32 = 0x12;
    /// CMD_POSITION at the home edge.
    pub const HOME_CMD_POSITION: u32 = 0x13;
    /// ACT_POSITION at the home edge.
    pub const HOME_ACT_POSITION: u32 = 0x14;
    /// The code at the axis's DAC output (analog builds).
    pub const DAC_APPLIED: u32 = 0x15;
    /// CMD_POSITION at the probe's trip.
    pub const PROBE_CMD_POSITION: u32 = 0x16;
    /// ACT_POSITION at the probe's trip.
    pub const PROBE_ACT_POSITION: u32 = 0x17;
    /// The soft window's lower end.
    pub const SOFT_MIN: u32 = 0x18;
    /// The soft window's upper end.
    pub const SOFT_MAX: u32 = 0x19;
}

/// Bit numbers of `STATUS` and `IRQ_ENABLE`, which are also the
/// [`crate::blocks::interrupt_controller::InterruptController`] event order.
pub mod irq {
    /// A period ended and the next began.
    pub const PERIOD_DONE: u32 = 0;
    /// An axis FIFO fell to the low-water level.
    pub const FIFO_LOW: u32 = 1;
    /// A period boundary found an empty FIFO: stopped.
    pub const UNDERRUN: u32 = 2;
    /// A FIFO write was refused (full).
    pub const OVERFLOW: u32 = 3;
    /// An encoder saw an illegal transition.
    pub const ENCODER_ERROR: u32 = 4;
    /// The watchdog expired: stopped.
    pub const WATCHDOG: u32 = 5;
    /// An axis lost steps (step overrun, interpolator overrange or refused load).
    pub const AXIS_FAULT: u32 = 6;
    /// A step toward an active limit was cut: stopped.
    pub const LIMIT: u32 = 7;
    /// A drive alarm: stopped.
    pub const ALARM: u32 = 8;
    /// The E-stop input: stopped, drives disabled.
    pub const ESTOP: u32 = 9;
    /// A home switch edge was latched.
    pub const HOME: u32 = 10;
    /// An enabled general-input edge.
    pub const GPIO: u32 = 11;
    /// The armed probe tripped: every axis's positions latched.
    pub const PROBE: u32 = 12;
    /// The feed hold brought the path to a stop (`STATE.HELD` rose).
    pub const HELD: u32 = 13;
    /// A soft-limit verdict turned beyond: the hold is requested.
    pub const SOFT_LIMIT: u32 = 14;
    /// The spindle unit: the gearbox's run ended at its length, an arm was
    /// refused, the gearbox overran, or the spindle encoder saw an error.
    pub const SPINDLE: u32 = 15;
    /// Number of interrupt sources.
    pub const COUNT: usize = 16;
}

/// A read-write register whose low `width` bits hold a number.
fn number(name: &'static str, address: u32, width: u32, doc: &'static str) -> Register {
    register(
        name,
        address,
        doc,
        vec![field("VALUE", fields::VALUE, width, Access::ReadWrite, doc)],
    )
}

fn irq_fields(access: Access) -> Vec<Field> {
    vec![
        field("PERIOD_DONE", irq::PERIOD_DONE, 1, access, "a period ended and the next began"),
        field("FIFO_LOW", irq::FIFO_LOW, 1, access, "an axis FIFO level fell to FIFO_LOW_WATER or below"),
        field("UNDERRUN", irq::UNDERRUN, 1, access, "a boundary found an axis FIFO empty, or the laser FIFO while it takes part in the run: all axes stopped, RUN cleared"),
        field("OVERFLOW", irq::OVERFLOW, 1, access, "a FIFO_WRITE to a full FIFO was refused (nothing overwritten)"),
        field("ENCODER_ERROR", irq::ENCODER_ERROR, 1, access, "an encoder saw A and B change together (counts lost)"),
        field("WATCHDOG", irq::WATCHDOG, 1, access, "the watchdog expired: all axes stopped, RUN cleared; clearing it re-allows RUN"),
        field("AXIS_FAULT", irq::AXIS_FAULT, 1, access, "an axis dropped or clamped steps: see AXIS_STATUS"),
        field("LIMIT", irq::LIMIT, 1, access, "a step toward an active limit was cut: all axes stopped; see IO_STATUS"),
        field("ALARM", irq::ALARM, 1, access, "a drive alarm: all axes stopped, that drive disabled; see IO_STATUS"),
        field("ESTOP", irq::ESTOP, 1, access, "E-stop: all axes stopped, every drive disabled; clearing it (with estop released) clears STATE.ESTOP_LATCHED"),
        field("HOME", irq::HOME, 1, access, "a home switch edge latched the positions; see IO_STATUS.HOME_SEEN"),
        field("GPIO", irq::GPIO, 1, access, "an enabled general-input edge; see GPIO_EDGES"),
        field("PROBE", irq::PROBE, 1, access, "the armed probe tripped: every axis's PROBE_*_POSITION latched; see PROBE_CONTROL"),
        field("HELD", irq::HELD, 1, access, "the feed hold brought the path to a stop (STATE.HELD rose); see HOLD_CONTROL"),
        field("SOFT_LIMIT", irq::SOFT_LIMIT, 1, access, "an axis's soft-limit verdict turned beyond: the feed hold is requested; see SOFT_LIMIT.AXIS"),
        field("SPINDLE", irq::SPINDLE, 1, access, "GEAR_STATUS.DONE, INVALID or OVERRUN, or SPINDLE's ENCODER_ERROR rose; see GEAR_STATUS"),
    ]
}

/// A `motion_controller`'s build options: its `UNIFORM`, `ANALOG` and
/// `PROBE` parameters (see the controller's "Build options"). Each is
/// discoverable in `CONFIG`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BuildOptions {
    /// The uniform pulse generators (`CONFIG.DDA_ONLY` reads 0).
    pub uniform: bool,
    /// The analog outputs (`CONFIG.ANALOG`).
    pub analog: bool,
    /// The probe latch (`CONFIG.PROBE`).
    pub probe: bool,
    /// The soft limits (`CONFIG.SOFT_LIMITS`).
    pub soft_limits: bool,
    /// The spindle encoder and the electronic gearbox (`CONFIG.SPINDLE`).
    pub spindle: bool,
    /// The laser PWM tied to the path (`CONFIG.LASER`).
    pub laser: bool,
}

impl BuildOptions {
    /// `motion_controller`: uniform generators, the probe and the soft limits.
    pub const MOTION_CONTROLLER: Self = Self {
        uniform: true,
        analog: false,
        probe: true,
        soft_limits: true,
        spindle: false,
        laser: false,
    };
    /// `motion_controller_dda`: DDA only, with the probe, no soft limits
    /// (the seed card's budget).
    pub const MOTION_CONTROLLER_DDA: Self = Self {
        uniform: false,
        analog: false,
        probe: true,
        soft_limits: false,
        spindle: false,
        laser: false,
    };
    /// `motion_controller_servo`: DDA only, analog outputs and the probe, no
    /// soft limits (the seed card's budget).
    pub const MOTION_CONTROLLER_SERVO: Self = Self {
        uniform: false,
        analog: true,
        probe: true,
        soft_limits: false,
        spindle: false,
        laser: false,
    };

    /// `motion_controller_dda_spindle`: the DDA-only build with the
    /// spindle encoder and the electronic gearbox (a lathe's threading and
    /// rigid tapping), the probe, no soft limits.
    pub const MOTION_CONTROLLER_DDA_SPINDLE: Self = Self {
        uniform: false,
        analog: false,
        probe: true,
        soft_limits: false,
        spindle: true,
        laser: false,
    };
    /// `motion_controller_dda_laser`: the DDA-only build with the laser
    /// PWM tied to the path (a laser engraver or cutter), the probe, no
    /// soft limits.
    pub const MOTION_CONTROLLER_DDA_LASER: Self = Self {
        uniform: false,
        analog: false,
        probe: true,
        soft_limits: false,
        spindle: false,
        laser: true,
    };

    /// The module name of this build (the exported ones' and the names
    /// the scaling report and the test benches give the others). The
    /// soft limits are the default of the full build (uniform generators,
    /// no `ANALOG`) only: a build that differs says so in its name.
    pub fn module_name(&self) -> &'static str {
        let base = match (self.uniform, self.analog, self.probe) {
            (true, false, true) => 0,
            (false, false, true) => 1,
            (false, true, true) => 2,
            (true, true, true) => 3,
            (true, false, false) => 4,
            (false, false, false) => 5,
            (false, true, false) => 6,
            (true, true, false) => 7,
        };
        const DEFAULT: [&str; 8] = [
            "motion_controller",
            "motion_controller_dda",
            "motion_controller_servo",
            "motion_controller_uniform_servo",
            "motion_controller_no_probe",
            "motion_controller_dda_no_probe",
            "motion_controller_servo_no_probe",
            "motion_controller_uniform_servo_no_probe",
        ];
        const OTHER: [&str; 8] = [
            "motion_controller_no_soft_limits",
            "motion_controller_dda_soft_limits",
            "motion_controller_servo_soft_limits",
            "motion_controller_uniform_servo_soft_limits",
            "motion_controller_no_probe_no_soft_limits",
            "motion_controller_dda_no_probe_soft_limits",
            "motion_controller_servo_no_probe_soft_limits",
            "motion_controller_uniform_servo_no_probe_soft_limits",
        ];
        let name = match self.soft_limits == (self.uniform && !self.analog) {
            true => DEFAULT[base],
            false => OTHER[base],
        };
        if self.laser {
            return match (name, self.spindle) {
                ("motion_controller_dda", false) => "motion_controller_dda_laser",
                ("motion_controller", false) => "motion_controller_laser",
                (_, true) => "motion_controller_spindle_laser",
                _ => "motion_controller_other_laser",
            };
        }
        if !self.spindle {
            return name;
        }
        // The spindle builds: the one exported and the others the tests
        // and the scaling report name.
        match name {
            "motion_controller_dda" => "motion_controller_dda_spindle",
            "motion_controller" => "motion_controller_spindle",
            "motion_controller_servo" => "motion_controller_servo_spindle",
            _ => "motion_controller_other_spindle",
        }
    }
}

/// The register map of a `motion_controller` with `axes` axes, FIFOs of
/// 2^`fifo_log2` entries and the options `build`. Without the uniform
/// generators `CONFIG.DDA_ONLY` reads 1 and `AXIS_CONFIG.UNIFORM` and
/// `INTERLEAVED` are read-only 0; without the analog outputs
/// `CONFIG.ANALOG` and `AXIS_CONFIG.ANALOG` read 0 and the `DAC_*`
/// registers are absent (read 0); without the probe `CONFIG.PROBE` reads
/// 0, `PROBE_CONTROL` and `PROBE_*_POSITION` are absent (read 0) and
/// `STATUS.PROBE` is never set. Fails, naming the problem, for more axes
/// than the address space holds or a map that does not validate.
pub fn register_map(
    axes: usize,
    fifo_log2: u32,
    build: BuildOptions,
) -> Result<RegisterMap, RegMapError> {
    let BuildOptions {
        uniform,
        analog,
        probe,
        soft_limits,
        spindle,
        laser,
    } = build;
    if axes == 0 || axes > MAX_AXES {
        return Err(RegMapError::NoCopies(format!(
            "motion_controller axes: {axes} (1 to {MAX_AXES} fit the 8-bit address space)"
        )));
    }
    if (spindle || laser) && axes > MAX_AXES_SPINDLE {
        return Err(RegMapError::NoCopies(format!(
            "motion_controller axes: {axes} with the spindle or laser unit (1 to {MAX_AXES_SPINDLE}: their window takes the last axis window's addresses)"
        )));
    }
    use Access::*;
    let level_bits = fifo_log2 + 1;
    let per_axis = |r: Register| r.repeated(axes as u32, AXIS_STRIDE);
    let at = |offset: u32| AXIS_BASE + offset;
    let mut config = register(
        "CONFIG",
        global::CONFIG,
        "build configuration, for drivers to discover the core",
        vec![
            field("AXES", 0, 8, ReadOnly, "number of axes K"),
            field("FIFO_DEPTH_LOG2", 8, 4, ReadOnly, "each axis FIFO holds 2^n periods"),
            field("TIMER_BITS", 12, 6, ReadOnly, "width of the step timing registers"),
            field("POSITION_BITS", 18, 6, ReadOnly, "width of the position counters"),
            // 1 for the build without, not 0: cores from before this field
            // read 0 here, and all of them have the uniform generators.
            field(
                "DDA_ONLY",
                fields::CONFIG_DDA_ONLY,
                1,
                ReadOnly,
                "1 = no uniform pulse generators in this build: AXIS_CONFIG.UNIFORM and INTERLEAVED read 0 and ignore writes, every axis runs its DDA",
            ),
            field(
                "ANALOG",
                fields::CONFIG_ANALOG,
                1,
                ReadOnly,
                "1 = this build has the analog outputs (dac_* pins, AXIS_CONFIG.ANALOG, the DAC_* registers)",
            ),
            field(
                "PROBE",
                fields::CONFIG_PROBE,
                1,
                ReadOnly,
                "1 = this build has the probe latch (PROBE_CONTROL, PROBE_*_POSITION, STATUS.PROBE); 0: the probe pin is ignored",
            ),
            field(
                "SOFT_LIMITS",
                fields::CONFIG_SOFT_LIMITS,
                1,
                ReadOnly,
                "1 = this build has the soft limits (SOFT_LIMIT, SOFT_MIN, SOFT_MAX, STATUS.SOFT_LIMIT)",
            ),
            field(
                "SPINDLE",
                fields::CONFIG_SPINDLE,
                1,
                ReadOnly,
                "1 = this build has the spindle encoder and the electronic gearbox (SPINDLE_*, GEAR_*, STATUS.SPINDLE); 0: the spindle_* pins are ignored",
            ),
            field(
                "LASER",
                fields::CONFIG_LASER,
                1,
                ReadOnly,
                "1 = this build has the laser PWM tied to the path (LASER_*); 0: laser_pwm stays low",
            ),
        ],
    );
    config.fields[0].reset = axes as u64;
    config.fields[1].reset = fifo_log2 as u64;
    config.fields[2].reset = super::TIMER_BITS as u64;
    config.fields[3].reset = super::POSITION_BITS as u64;
    config.fields[4].reset = !uniform as u64;
    config.fields[5].reset = analog as u64;
    config.fields[6].reset = probe as u64;
    config.fields[7].reset = soft_limits as u64;
    config.fields[8].reset = spindle as u64;
    config.fields[9].reset = laser as u64;
    let analog_access = if analog { ReadWrite } else { ReadOnly };
    let analog_doc = if analog {
        "1 = analog axis, taken when RUN starts: each FIFO entry is the axis's signed 16-bit DAC code for the period (0 = 0 V), no steps; its channel goes to 0 when RUN falls"
    } else {
        "reads 0, writes ignored: this build has no analog outputs (CONFIG.ANALOG)"
    };
    // The uniform generator's fields: read-write, or read-only 0 (writes
    // ignored) in a build without the generators.
    let uniform_access = if uniform { ReadWrite } else { ReadOnly };
    let (uniform_doc, interleaved_doc) = if uniform {
        (
            "0 = DDA, 1 = dual-period uniform pulse generator; taken when RUN starts and the axis's uniform generator is idle",
            "uniform generator order: 0 = short pulses first, 1 = interleaved",
        )
    } else {
        (
            "reads 0, writes ignored: this build has no uniform pulse generator (CONFIG.DDA_ONLY), the axis always runs its DDA",
            "reads 0, writes ignored (CONFIG.DDA_ONLY)",
        )
    };
    let map_doc = match (uniform, analog) {
        (true, false) => "motion_controller: K step/encoder axes behind a 32-bit word-addressed register bus",
        (false, true) => "motion_controller_dda: K step or analog (DAC) axes with encoders, DDA interpolators only, behind a 32-bit word-addressed register bus",
        (true, true) => "motion_controller: K step or analog (DAC) axes with encoders behind a 32-bit word-addressed register bus",
        (false, false) => "motion_controller: K step/encoder axes (DDA interpolators only) behind a 32-bit word-addressed register bus",
    };
    let mut map = RegisterMap {
        name: "MC",
        address_bits: 8,
        doc: map_doc,
        registers: vec![
            Register::word("ID", global::ID, ReadOnly, ID_VALUE as u64, "identity: 0x4D484443, \"MHDC\""),
            register(
                "VERSION",
                global::VERSION,
                "core version",
                vec![
                    Field { reset: VERSION_VALUE as u64 & 0xff, ..field("PATCH", 0, 8, ReadOnly, "patch") },
                    Field { reset: (VERSION_VALUE as u64 >> 8) & 0xff, ..field("MINOR", 8, 8, ReadOnly, "minor") },
                    Field { reset: (VERSION_VALUE as u64 >> 16) & 0xff, ..field("MAJOR", 16, 8, ReadOnly, "major") },
                ],
            ),
            config,
            register(
                "CONTROL",
                global::CONTROL,
                "run control",
                vec![
                    field(
                        "RUN",
                        fields::CONTROL_RUN,
                        1,
                        ReadWrite,
                        "write 1 to start (refused while STATE.ABORTED, the E-stop input is active or the inputs are not ready); write 0 to stop at once; cleared by an underrun or an abort (STOP_CAUSE)",
                    ),
                    field(
                        "FLUSH",
                        fields::CONTROL_FLUSH,
                        1,
                        WriteOnly,
                        "write 1 to empty every FIFO at once (with RUN 0: stop and discard the queued periods)",
                    ),
                ],
            ),
            register("STATUS", global::STATUS, "sticky interrupt status, write 1 to clear", irq_fields(WriteOneToClear)),
            register("IRQ_ENABLE", global::IRQ_ENABLE, "interrupt enable mask: irq is high while an enabled STATUS bit is set", irq_fields(ReadWrite)),
            Register::word("TICK_DIVISOR", global::TICK_DIVISOR, ReadWrite, 0, "base tick = one every n clocks; 0 stops the tick (pauses everything)"),
            number("PERIOD_TICKS", global::PERIOD_TICKS, super::PERIOD_BITS as u32, "interpolation period in base ticks, taken at each boundary; 0 acts as 1"),
            register(
                "FIFO_LOW_WATER",
                global::FIFO_LOW_WATER,
                "FIFO low-water threshold",
                vec![field("LEVEL", fields::FIFO_LEVEL, level_bits, ReadWrite, "FIFO_LOW is raised when a level falls to this or below")],
            ),
            Register::word("WATCHDOG_TIMEOUT", global::WATCHDOG_TIMEOUT, ReadWrite, 0, "base ticks allowed between kicks, taken at each kick; 0 disarms"),
            Register::word("WATCHDOG_KICK", global::WATCHDOG_KICK, WriteOnly, 0, "any write kicks (and arms) the watchdog"),
            Register::word("SNAPSHOT", global::SNAPSHOT, WriteOnly, 0, "any write latches every axis's CMD and ACT positions on the same clock"),
            register(
                "STATE",
                global::STATE,
                "live state",
                vec![
                    field("RUNNING", fields::STATE_RUNNING, 1, ReadOnly, "periods are running"),
                    field("WATCHDOG_ARMED", fields::STATE_WATCHDOG_ARMED, 1, ReadOnly, "the watchdog is counting"),
                    field("WATCHDOG_EXPIRED", fields::STATE_WATCHDOG_EXPIRED, 1, ReadOnly, "the watchdog expired; cleared with STATUS.WATCHDOG"),
                    field("ESTOP_INPUT", fields::STATE_ESTOP_INPUT, 1, ReadOnly, "the E-stop input is active (filtered)"),
                    field("ESTOP_LATCHED", fields::STATE_ESTOP_LATCHED, 1, ReadOnly, "E-stop latched; cleared with STATUS.ESTOP once the input is released"),
                    field("ABORTED", fields::STATE_ABORTED, 1, ReadOnly, "a stop cause is held (E-stop, watchdog, alarm, limit or home trip): every output stage flushed (the FIFOs keep their entries), RUN refused"),
                    Field { reset: 1, ..field("INPUTS_READY", fields::STATE_INPUTS_READY, 1, ReadOnly, "the switch filters are primed: 0 for the 3 clocks after reset, in which RUN is refused") },
                    field("HOLDING", fields::STATE_HOLDING, 1, ReadOnly, "the feed hold's factor is below 1: the path is slowing, held, or ramping back to speed"),
                    field("HELD", fields::STATE_HELD, 1, ReadOnly, "the feed hold's factor is 0: no base tick reaches the periods or the axes"),
                ],
            ),
            Register::word("PERIOD_COUNT", global::PERIOD_COUNT, ReadOnly, 0, "periods started since reset, wrapping"),
            register(
                "INPUT_FILTER",
                global::INPUT_FILTER,
                "filter of the switch, alarm, E-stop and general inputs",
                vec![
                    Field { reset: fields::FILTER_LENGTH_RESET, ..field("LENGTH", fields::FILTER_LENGTH, fields::FILTER_LENGTH_WIDTH, ReadWrite, "samples a new level must hold (0 and 1: the first sample)") },
                    field("SAMPLE_RATE", fields::FILTER_SAMPLE_RATE, fields::FILTER_SAMPLE_RATE_WIDTH, ReadWrite, "a filter sample every n + 1 clocks"),
                ],
            ),
            register(
                "INPUT_POLARITY",
                global::INPUT_POLARITY,
                "1 = the input class is active low (normally-open wiring); E-stop has no polarity: it is always active high (fail-safe)",
                vec![
                    field("LIMIT_POS", fields::POLARITY_LIMIT_POS, 1, ReadWrite, "limit_pos inputs active low"),
                    field("LIMIT_NEG", fields::POLARITY_LIMIT_NEG, 1, ReadWrite, "limit_neg inputs active low"),
                    field("HOME", fields::POLARITY_HOME, 1, ReadWrite, "home inputs active low"),
                    field("DRIVE_ALARM", fields::POLARITY_DRIVE_ALARM, 1, ReadWrite, "drive_alarm inputs active low"),
                    field("GPIO", fields::POLARITY_GPIO, fields::GPIO_WIDTH, ReadWrite, "per general input: active low"),
                ],
            ),
            register(
                "STOP_CAUSE",
                global::STOP_CAUSE,
                "why RUN last fell (kept until the next stop)",
                vec![
                    field("CAUSE", fields::STOP_CAUSE_CAUSE, fields::STOP_CAUSE_WIDTH, ReadOnly, "0 none, 1 RUN written 0, 2 underrun, 3 watchdog, 4 home, 5 limit, 6 drive alarm, 7 E-stop (the highest of simultaneous causes)"),
                    field("AXIS", fields::STOP_CAUSE_AXIS, fields::STOP_CAUSE_WIDTH, ReadOnly, "home, limit, drive alarm: the lowest axis holding that cause"),
                ],
            ),
            register("GPIO_IN", global::GPIO_IN, "general inputs", vec![field("LEVEL", fields::GPIO_LEVEL, fields::GPIO_WIDTH, ReadOnly, "filtered levels, polarity applied (0 until the inputs are ready)")]),
            register("GPIO_OUT", global::GPIO_OUT, "general outputs", vec![field("LEVEL", fields::GPIO_LEVEL, fields::GPIO_WIDTH, ReadWrite, "gpio_out pins; the GPIO_SAFE ones are cleared (and held 0) while E-stop is latched or the watchdog expired")]),
            register("GPIO_SAFE", global::GPIO_SAFE, "outputs that drop on E-stop or watchdog expiry", vec![field("MASK", fields::GPIO_LEVEL, fields::GPIO_WIDTH, ReadWrite, "1 = this output drops to 0 (spindle, coolant)")]),
            register(
                "GPIO_IRQ_ENABLE",
                global::GPIO_IRQ_ENABLE,
                "general-input edges that raise STATUS.GPIO",
                vec![
                    field("RISE", fields::GPIO_RISE, fields::GPIO_WIDTH, ReadWrite, "per input: a rise (becoming active)"),
                    field("FALL", fields::GPIO_FALL, fields::GPIO_WIDTH, ReadWrite, "per input: a fall"),
                ],
            ),
            register(
                "GPIO_EDGES",
                global::GPIO_EDGES,
                "general-input edges seen since cleared, write 1 to clear (every edge, enabled or not)",
                vec![
                    field("RISE", fields::GPIO_RISE, fields::GPIO_WIDTH, WriteOneToClear, "per input: rose"),
                    field("FALL", fields::GPIO_FALL, fields::GPIO_WIDTH, WriteOneToClear, "per input: fell"),
                ],
            ),
            register(
                "HOLD_CONTROL",
                global::HOLD_CONTROL,
                "the feed hold: a controlled stop along the path that resumes where it left off (the FIFOs keep their entries)",
                vec![
                    field("HOLD", fields::HOLD_HOLD, 1, WriteOnly, "write 1 to request the hold (0: no effect)"),
                    field("RELEASE", fields::HOLD_RELEASE, 1, WriteOnly, "write 1 to release the hold: the factor ramps back to 1 (refused while the feed_hold input is active, or with HOLD = 1 in the same write)"),
                    field("INVERT", fields::HOLD_INVERT, 1, ReadWrite, "1 = the feed_hold input is active low"),
                    field("REQUESTED", fields::HOLD_REQUESTED, 1, ReadOnly, "the hold is requested (sticky until released): by HOLD, the feed_hold input, or a probe trip with PROBE_CONTROL.STOP"),
                    field("INPUT", fields::HOLD_INPUT, 1, ReadOnly, "the feed_hold input, filtered, INVERT applied (0 until the inputs are ready)"),
                    field("RATE", fields::HOLD_RATE, fields::HOLD_RATE_WIDTH, ReadWrite, "the factor's change per base tick in 1/65536 (a stop from full speed takes ceil(65536 / RATE) ticks); 0 acts as 65536: the factor goes to 0 or 1 at the next tick"),
                ],
            ),
            per_axis(Register::word("FIFO_WRITE", at(axis::FIFO_WRITE), WriteOnly, 0, "push one period's signed step count (refused when full); a magnitude above 65535 is saturated and flagged")),
            per_axis(register(
                "FIFO_STATUS",
                at(axis::FIFO_STATUS),
                "FIFO level and flags",
                vec![
                    field("LEVEL", fields::FIFO_LEVEL, level_bits, ReadOnly, "periods queued"),
                    Field { reset: 1, ..field("EMPTY", fields::FIFO_EMPTY, 1, ReadOnly, "no period queued") },
                    field("FULL", fields::FIFO_FULL, 1, ReadOnly, "no room: a write now is refused"),
                    Field { reset: 1, ..field("LOW", fields::FIFO_LOW, 1, ReadOnly, "LEVEL <= FIFO_LOW_WATER") },
                ],
            )),
            per_axis(register(
                "AXIS_CONFIG",
                at(axis::AXIS_CONFIG),
                "interpolator, output mode and encoder settings",
                vec![
                    field("UNIFORM", fields::AXIS_UNIFORM, 1, uniform_access, uniform_doc),
                    field("INTERLEAVED", fields::AXIS_INTERLEAVED, 1, uniform_access, interleaved_doc),
                    field("STEP_MODE", fields::AXIS_STEP_MODE, fields::AXIS_STEP_MODE_WIDTH, ReadWrite, "0 step/dir, 1 up/down, 2 quadrature, 3 reserved (acts as 0); taken while the output is idle"),
                    field("ENC_FILTER", fields::AXIS_ENC_FILTER, fields::AXIS_ENC_FILTER_WIDTH, ReadWrite, "encoder glitch filter: samples a level must hold"),
                    field("ENC_COUNTER_MODE", fields::AXIS_ENC_COUNTER_MODE, 1, ReadWrite, "0 = 4x quadrature, 1 = step/dir input"),
                    field("INDEX_INVERT", fields::AXIS_INDEX_INVERT, 1, ReadWrite, "index active low"),
                    field("INDEX_CLEAR", fields::AXIS_INDEX_CLEAR, 1, ReadWrite, "an index event clears ACT_POSITION"),
                    field("INDEX_LATCH", fields::AXIS_INDEX_LATCH, 1, ReadWrite, "an index event latches ACT_POSITION into INDEX_POSITION"),
                    field("INDEX_ONCE", fields::AXIS_INDEX_ONCE, 1, ReadWrite, "act on the first index only, until REARM_INDEX"),
                    field("ANALOG", fields::AXIS_ANALOG, 1, analog_access, analog_doc),
                ],
            )),
            per_axis(number("STEP_LEN", at(axis::STEP_LEN), fields::STEP_TIMING_WIDTH, "step pulse high time in clocks (0 acts as 1)")),
            per_axis(number("STEP_SPACE", at(axis::STEP_SPACE), fields::STEP_TIMING_WIDTH, "minimum step low time in clocks (0 acts as 1)")),
            per_axis(number("DIR_SETUP", at(axis::DIR_SETUP), fields::STEP_TIMING_WIDTH, "dir stable before a step rises, clocks (0 acts as 1)")),
            per_axis(number("DIR_HOLD", at(axis::DIR_HOLD), fields::STEP_TIMING_WIDTH, "dir stable after a step falls, clocks (0 acts as 1)")),
            per_axis(number("ENC_SAMPLE_RATE", at(axis::ENC_SAMPLE_RATE), fields::ENC_SAMPLE_RATE_WIDTH, "encoder sample every n + 1 clocks")),
            per_axis(Register::word("CMD_POSITION", at(axis::CMD_POSITION), ReadOnly, 0, "commanded position: steps emitted at the pins, signed, modulo 2^CONFIG.POSITION_BITS, its sign carried up to bit 31")),
            per_axis(Register::word("ACT_POSITION", at(axis::ACT_POSITION), ReadOnly, 0, "actual position: encoder count, signed, modulo 2^CONFIG.POSITION_BITS, its sign carried up to bit 31")),
            per_axis(Register::word("CMD_SNAPSHOT", at(axis::CMD_SNAPSHOT), ReadOnly, 0, "CMD_POSITION at the last SNAPSHOT write")),
            per_axis(Register::word("ACT_SNAPSHOT", at(axis::ACT_SNAPSHOT), ReadOnly, 0, "ACT_POSITION at the last SNAPSHOT write")),
            per_axis(register(
                "AXIS_STATUS",
                at(axis::AXIS_STATUS),
                "axis flags (sticky ones are cleared with AXIS_COMMAND)",
                vec![
                    field("STEP_OVERRUN", fields::STATUS_STEP_OVERRUN, 1, ReadOnly, "sticky until CLEAR_FAULTS: the output stage's pending count saturated and a step was dropped"),
                    field("INTERP_OVERRANGE", fields::STATUS_INTERP_OVERRANGE, 1, ReadOnly, "sticky until CLEAR_FAULTS: an entry was clamped (above 65535; DDA: above PERIOD_TICKS; uniform: above half of it, or PERIOD_TICKS odd)"),
                    field("INTERP_OVERFLOW", fields::STATUS_INTERP_OVERFLOW, 1, ReadOnly, "sticky until CLEAR_FAULTS: the uniform generator refused a period (a period shorter than its 24-clock set-up)"),
                    field("ENCODER_ERROR", fields::STATUS_ENCODER_ERROR, 1, ReadOnly, "sticky: illegal encoder transition; cleared with CLEAR_ENCODER_ERROR (or CLEAR_ENCODER)"),
                    field("INDEX_SEEN", fields::STATUS_INDEX_SEEN, 1, ReadOnly, "sticky: an index event was acted on; cleared with REARM_INDEX"),
                    field("STEP_BUSY", fields::STATUS_STEP_BUSY, 1, ReadOnly, "the output stage has steps pending or an interval running"),
                    field("UNIFORM_RUNNING", fields::STATUS_UNIFORM_RUNNING, 1, ReadOnly, "the uniform generator is inside a period"),
                    field("STEP_MODE_INVALID", fields::STATUS_STEP_MODE_INVALID, 1, ReadOnly, "STEP_MODE is 3"),
                ],
            )),
            per_axis(Register::word("INDEX_POSITION", at(axis::INDEX_POSITION), ReadOnly, 0, "ACT_POSITION latched at the last index event")),
            per_axis(register(
                "AXIS_COMMAND",
                at(axis::AXIS_COMMAND),
                "axis commands: write 1 to act",
                vec![
                    field("CLEAR_FAULTS", fields::CMD_CLEAR_FAULTS, 1, WriteOnly, "clear STEP_OVERRUN, INTERP_OVERRANGE and INTERP_OVERFLOW"),
                    field("CLEAR_ENCODER", fields::CMD_CLEAR_ENCODER, 1, WriteOnly, "ACT_POSITION <- 0 and ENCODER_ERROR <- 0"),
                    field("REARM_INDEX", fields::CMD_REARM_INDEX, 1, WriteOnly, "clear INDEX_SEEN (re-arm a once-only index)"),
                    field("CLEAR_POSITION", fields::CMD_CLEAR_POSITION, 1, WriteOnly, "CMD_POSITION <- 0 at the first clock, from this write on, that counts no step (no step is lost)"),
                    field("CLEAR_ENCODER_ERROR", fields::CMD_CLEAR_ENCODER_ERROR, 1, WriteOnly, "ENCODER_ERROR <- 0, keeping ACT_POSITION (an error on the same clock keeps it set)"),
                ],
            )),
            per_axis(register(
                "IO_CONFIG",
                at(axis::IO_CONFIG),
                "limit, alarm, home and drive-enable settings",
                vec![
                    Field { reset: 1, ..field("LIMIT_ENABLE", fields::LIMIT_ENABLE, 1, ReadWrite, "the limit_pos / limit_neg inputs block steps toward them") },
                    Field { reset: 1, ..field("ALARM_ENABLE", fields::ALARM_ENABLE, 1, ReadWrite, "the drive_alarm input aborts and disables this drive") },
                    field("STOP_ON_HOME", fields::STOP_ON_HOME, 1, ReadWrite, "the home edge aborts the motion (homing moves)"),
                    field("DRIVE_ENABLE", fields::DRIVE_ENABLE, 1, ReadWrite, "drive_enable pin, when no E-stop, watchdog expiry or alarm of this axis forces it low"),
                ],
            )),
            per_axis(register(
                "IO_STATUS",
                at(axis::IO_STATUS),
                "switch levels (filtered, polarity applied, 1 = active) and sticky trips",
                vec![
                    field("LIMIT_POS", fields::IO_LIMIT_POS, 1, ReadOnly, "limit_pos active"),
                    field("LIMIT_NEG", fields::IO_LIMIT_NEG, 1, ReadOnly, "limit_neg active"),
                    field("HOME", fields::IO_HOME, 1, ReadOnly, "home active"),
                    field("DRIVE_ALARM", fields::IO_DRIVE_ALARM, 1, ReadOnly, "drive_alarm active"),
                    field("LIMIT_POS_TRIPPED", fields::IO_LIMIT_POS_TRIPPED, 1, ReadOnly, "sticky: a step toward the active positive limit was cut (aborts, refuses RUN); cleared with CLEAR_LIMITS"),
                    field("LIMIT_NEG_TRIPPED", fields::IO_LIMIT_NEG_TRIPPED, 1, ReadOnly, "sticky: the same toward the negative limit"),
                    field("ALARM_TRIPPED", fields::IO_ALARM_TRIPPED, 1, ReadOnly, "sticky: the enabled drive alarm was active (aborts, refuses RUN, drive disabled); CLEAR_ALARM clears it once the alarm is gone"),
                    field("HOME_SEEN", fields::IO_HOME_SEEN, 1, ReadOnly, "sticky: a home edge latched HOME_*_POSITION (with STOP_ON_HOME: aborts, refuses RUN); cleared with CLEAR_HOME"),
                    field("DRIVE_ENABLE", fields::IO_DRIVE_ENABLE, 1, ReadOnly, "the drive_enable pin"),
                ],
            )),
            per_axis(register(
                "IO_COMMAND",
                at(axis::IO_COMMAND),
                "machine I/O commands: write 1 to act",
                vec![
                    field("CLEAR_LIMITS", fields::CLEAR_LIMITS, 1, WriteOnly, "clear LIMIT_POS_TRIPPED and LIMIT_NEG_TRIPPED (steps away from an active limit are then allowed)"),
                    field("CLEAR_ALARM", fields::CLEAR_ALARM, 1, WriteOnly, "clear ALARM_TRIPPED (stays set while the alarm is active)"),
                    field("CLEAR_HOME", fields::CLEAR_HOME, 1, WriteOnly, "clear HOME_SEEN: the next home edge latches again"),
                ],
            )),
            per_axis(Register::word("HOME_CMD_POSITION", at(axis::HOME_CMD_POSITION), ReadOnly, 0, "CMD_POSITION on the clock of the home edge")),
            per_axis(Register::word("HOME_ACT_POSITION", at(axis::HOME_ACT_POSITION), ReadOnly, 0, "ACT_POSITION on the clock of the home edge")),
        ],
    };
    if probe {
        map.registers.push(register(
            "PROBE_CONTROL",
            global::PROBE_CONTROL,
            "the probe input: the first selected edge after arming latches every axis's positions on one clock",
            vec![
                field("ARM", fields::PROBE_ARM, 1, ReadWrite, "write 1 to arm (clears TRIPPED), 0 to disarm; reads 1 while armed; the trip disarms"),
                field("EDGE", fields::PROBE_EDGE, 1, ReadWrite, "0 = trip on a rising edge of probe (contact made, for a normally-open probe), 1 = on a falling edge"),
                field("TRIPPED", fields::PROBE_TRIPPED, 1, ReadOnly, "sticky: the armed probe tripped and PROBE_*_POSITION hold the positions of that clock; cleared by arming"),
                field("STOP", fields::PROBE_STOP, 1, ReadWrite, "1 = the trip also requests the feed hold (HOLD_CONTROL.HOLD): a controlled stop along the path, not an abort"),
                field("LEVEL", fields::PROBE_LEVEL, 1, ReadOnly, "the probe input, filtered (1 = high; 0 until the inputs are ready)"),
            ],
        ));
        map.registers.push(per_axis(Register::word(
            "PROBE_CMD_POSITION",
            at(axis::PROBE_CMD_POSITION),
            ReadOnly,
            0,
            "CMD_POSITION on the clock of the probe's trip",
        )));
        map.registers.push(per_axis(Register::word(
            "PROBE_ACT_POSITION",
            at(axis::PROBE_ACT_POSITION),
            ReadOnly,
            0,
            "ACT_POSITION on the clock of the probe's trip",
        )));
    }
    if soft_limits {
        map.registers.push(register(
            "SOFT_LIMIT",
            global::SOFT_LIMIT,
            "soft limits: a position window per axis, checked against the feed hold's stopping distance, that requests the hold early enough to stop inside it",
            vec![
                field("ENABLE", fields::SOFT_ENABLE, axes as u32, ReadWrite, "bit k: axis k's window (SOFT_MIN, SOFT_MAX) is checked"),
                field("BEYOND", fields::SOFT_BEYOND, axes as u32, ReadOnly, "bit k: axis k's last verdict: its stop's reach meets the bound it heads for (requests the hold, refuses RELEASE); cleared when RUN falls or the axis is disabled"),
                field("AXIS", fields::SOFT_AXIS, fields::SOFT_AXIS_WIDTH, ReadOnly, "the axis of the last verdict that turned beyond (STATUS.SOFT_LIMIT)"),
                field("NEGATIVE", fields::SOFT_NEGATIVE, 1, ReadOnly, "that axis was moving down, toward SOFT_MIN (0: up, toward SOFT_MAX)"),
                Field { reset: 1, ..field("MEASURED", fields::SOFT_MEASURED, 1, ReadOnly, "the stop's reach at the present HOLD_CONTROL.RATE is measured: 0 for the 3 clocks after reset and for ceil(65536 / RATE) + 3 clocks after RATE changes, while every moving axis is judged with the longest reach (start motion once it reads 1)") },
            ],
        ));
        for (name, offset, doc, value_doc) in [
            (
                "SOFT_MIN",
                axis::SOFT_MIN,
                "the soft window's lower end in steps, signed, POSITION_BITS wide",
                "the lower end, signed",
            ),
            (
                "SOFT_MAX",
                axis::SOFT_MAX,
                "the soft window's upper end in steps, signed, POSITION_BITS wide",
                "the upper end, signed",
            ),
        ] {
            map.registers.push(per_axis(signed_position(
                name,
                at(offset),
                ReadWrite,
                doc,
                value_doc,
            )));
        }
    }
    if spindle {
        map.registers.extend(spindle_registers());
    }
    if laser {
        map.registers.extend(laser_registers(level_bits));
    }
    if analog {
        let dac = crate::blocks::dac_interface::registers::register_map(axes, DAC_BITS)?;
        for (name, address, dac_name) in DAC_GLOBAL {
            let mut r = dac.register(dac_name)?.clone();
            r.name = name;
            r.address = address;
            map.registers.push(r);
        }
        let applied = dac.register("APPLIED")?;
        map.registers.push(per_axis(register(
            "DAC_APPLIED",
            at(axis::DAC_APPLIED),
            "the code at this axis's DAC output (the last LDAC), signed; 0 after reset, an abort or a stop",
            applied.fields.clone(),
        )));
    }
    map.validate()?;
    Ok(map)
}

/// The spindle unit's registers (build option `SPINDLE`; see the
/// controller's "Spindle encoder and electronic gearbox").
fn spindle_registers() -> Vec<Register> {
    use Access::*;
    let signed = |name: &'static str, address: u32, access: Access, doc: &'static str| {
        signed_position(name, address, access, doc, doc)
    };
    vec![
        signed("SPINDLE_POSITION", spindle::SPINDLE_POSITION, ReadOnly, "the spindle encoder's count, signed, wrapping at 2^POSITION_BITS (never cleared: the host takes differences)"),
        signed("SPINDLE_INDEX_POSITION", spindle::SPINDLE_INDEX_POSITION, ReadOnly, "SPINDLE_POSITION at the last index event (before that event's own count)"),
        signed("SPINDLE_SPEED", spindle::SPINDLE_SPEED, ReadOnly, "counts in the last speed window of 2^SPEED_WINDOW clocks, signed (the position's change, modulo 2^POSITION_BITS)"),
        register(
            "SPINDLE_CONFIG",
            spindle::SPINDLE_CONFIG,
            "the spindle encoder's options and the speed window",
            vec![
                field("FILTER", fields::SPINDLE_FILTER, fields::SPINDLE_FILTER_WIDTH, ReadWrite, "encoder glitch filter: clocks a level of A, B or index must hold (0 and 1: synchronizer only)"),
                field("COUNTER_MODE", fields::SPINDLE_COUNTER_MODE, 1, ReadWrite, "0 = 4x quadrature, 1 = count rising edges of A, B high = up"),
                field("INDEX_INVERT", fields::SPINDLE_INDEX_INVERT, 1, ReadWrite, "1 = the index is active low"),
                Field { reset: fields::SPINDLE_SPEED_WINDOW_RESET, ..field("SPEED_WINDOW", fields::SPINDLE_SPEED_WINDOW, fields::SPINDLE_SPEED_WINDOW_WIDTH, ReadWrite, "n: SPINDLE_SPEED is measured over windows of 2^n clocks (reset 20: 10.5 ms at 100 MHz)") },
            ],
        ),
        register(
            "GEAR_CONTROL",
            spindle::GEAR_CONTROL,
            "the electronic gearbox's strobes, directions and axis; SPINDLE_REVERSE, AXIS_REVERSE and AXIS are written only while GEAR_STATUS.PHASE is 0 (idle)",
            vec![
                field("ARM", fields::GEAR_ARM, 1, WriteOnly, "write 1 to arm (idle only): take GEAR_NUMERATOR, DENOMINATOR, RAMP, LENGTH and this write's directions and axis, zero GEAR_POSITION, clear DONE, INVALID and OVERRUN, and engage at the next index; refused with INVALID for a ratio that is not valid or AXIS >= K"),
                field("STOP", fields::GEAR_STOP, 1, WriteOnly, "write 1 to ramp out to the crawl rate and stop; disarms while armed"),
                field("HALT", fields::GEAR_HALT, 1, WriteOnly, "write 1 to stop at once, no ramp (an abort halts too)"),
                field("CLEAR_ENCODER_ERROR", fields::GEAR_CLEAR_ENCODER_ERROR, 1, WriteOnly, "write 1 to clear GEAR_STATUS.ENCODER_ERROR (the count is kept)"),
                field("SPINDLE_REVERSE", fields::GEAR_SPINDLE_REVERSE, 1, ReadWrite, "1 = the spindle's forward direction counts SPINDLE_POSITION down"),
                field("AXIS_REVERSE", fields::GEAR_AXIS_REVERSE, 1, ReadWrite, "1 = a forward spindle count steps the axis down"),
                field("AXIS", fields::GEAR_AXIS, fields::GEAR_AXIS_WIDTH, ReadWrite, "the geared axis k: its steps join that axis's FIFO steps (a step axis; an arm with AXIS >= K is refused)"),
            ],
        ),
        register(
            "GEAR_STATUS",
            spindle::GEAR_STATUS,
            "the electronic gearbox's phase and flags",
            vec![
                field("PHASE", fields::GEAR_PHASE, fields::GEAR_PHASE_WIDTH, ReadOnly, "0 idle, 1 armed (waiting for the index), 2 ramp-in, 3 track, 4 stopping"),
                field("LOCKED", fields::GEAR_LOCKED, 1, ReadOnly, "tracking at the ratio with the lag caught up: the axis 0 or 1 step behind floor(n x counts / d) since the index"),
                field("DONE", fields::GEAR_DONE, 1, ReadOnly, "sticky: the last run reached GEAR_LENGTH; cleared by an arm"),
                field("INVALID", fields::GEAR_INVALID, 1, ReadOnly, "sticky: an arm was refused (d = 0, n > d, RAMP too small for n, or AXIS >= K); cleared by an accepted arm"),
                field("OVERRUN", fields::GEAR_OVERRUN, 1, ReadOnly, "sticky: spindle counts came faster than the gearbox takes them (one per 31 clocks): one was lost and the gearbox halted; cleared by an arm"),
                field("ENCODER_ERROR", fields::GEAR_ENCODER_ERROR, 1, ReadOnly, "sticky: the spindle encoder saw A and B change together (counts lost); cleared by CLEAR_ENCODER_ERROR"),
            ],
        ),
        number("GEAR_NUMERATOR", spindle::GEAR_NUMERATOR, GEAR_BITS, "n: the axis moves n / d steps per spindle count, n <= d; taken at the arm"),
        number("GEAR_DENOMINATOR", spindle::GEAR_DENOMINATOR, GEAR_BITS, "d >= 1; taken at the arm"),
        number("GEAR_RAMP", spindle::GEAR_RAMP, GEAR_BITS, "the rate's change per spindle count while ramping and catching up, in 1/d step per count; 0 = engage and stop at full rate; RAMP x 2^15 >= n; taken at the arm"),
        number("GEAR_LENGTH", spindle::GEAR_LENGTH, GEAR_BITS, "steps from the index at which a run ends, ramped out to reach it exactly; 0 = no end; taken at the arm"),
        signed("GEAR_POSITION", spindle::GEAR_POSITION, ReadOnly, "net steps the gearbox requested since the arm, forward positive, signed, wrapping"),
    ]
}

/// The laser unit's registers (build option `LASER`; see the
/// controller's "Laser PWM").
fn laser_registers(level_bits: u32) -> Vec<Register> {
    use Access::*;
    let word = fields::LASER_WORD_WIDTH;
    let axis = fields::LASER_AXIS_WIDTH;
    vec![
        register(
            "LASER_CONTROL",
            laser::LASER_CONTROL,
            "the laser's enable, mode and plane",
            vec![
                field("ENABLE", fields::LASER_ENABLE, 1, ReadWrite, "1 = laser_pwm may fire while RUN; at a start with SOURCE = 0, 1 also makes the laser FIFO part of the run (one entry popped per period, an empty one is an underrun); 0 = laser_pwm low from the next clock"),
                field("DYNAMIC", fields::LASER_DYNAMIC, 1, ReadWrite, "1 = the duty is the period's POWER x min(1, path speed x hold factor / FEED) (M4); 0 = POWER (M3)"),
                field("CLEAR_OVERFLOW", fields::LASER_CLEAR_OVERFLOW, 1, WriteOnly, "write 1 to clear LASER_STATUS.OVERFLOW"),
                field("SOURCE", fields::LASER_SOURCE, 1, ReadWrite, "where the duty engine takes POWER and FEED: 0 = the running period's laser FIFO entry; 1 = LASER_POWER (a write reaches the duty within LASER_LAG clocks), and a run started with SOURCE = 1 leaves the laser FIFO out"),
                field("AXIS_A", fields::LASER_AXIS_A, axis, ReadWrite, "the plane's first axis (an axis >= K counts as standing)"),
                field("AXIS_B", fields::LASER_AXIS_B, axis, ReadWrite, "the plane's second axis (equal to AXIS_A: one axis only is counted)"),
            ],
        ),
        number("LASER_PWM_PERIOD", laser::LASER_PWM_PERIOD, word, "the PWM period in clocks (frequency = clock / period); below 2: laser_pwm low"),
        register(
            "LASER_FIFO",
            laser::LASER_FIFO,
            "write one entry per period, in step with the axes' FIFO entries (refused when full: LASER_STATUS.OVERFLOW)",
            vec![
                field("POWER", fields::LASER_POWER, word, WriteOnly, "the period's power: clocks high per PWM period at the programmed feed (at or above LASER_PWM_PERIOD: steady on)"),
                field("FEED", fields::LASER_FEED, word, WriteOnly, "the period's programmed feed, 1/16 step per period (vector length in the plane); 0: a dynamic duty of 0"),
            ],
        ),
        register(
            "LASER_STATUS",
            laser::LASER_STATUS,
            "the laser FIFO's level and flags",
            vec![
                field("LEVEL", fields::LASER_LEVEL, level_bits, ReadOnly, "entries in the laser FIFO"),
                field("OVERFLOW", fields::LASER_OVERFLOW, 1, ReadOnly, "sticky: a LASER_FIFO write found it full and was refused; cleared by LASER_CONTROL.CLEAR_OVERFLOW; raises no interrupt (STATUS.OVERFLOW is the axes' FIFOs'): firmware that streams the laser reads it with the FIFO level"),
                field("ACTIVE", fields::LASER_ACTIVE, 1, ReadOnly, "the laser FIFO takes part in the running periods (ENABLE = 1 and SOURCE = 0 at the start)"),
                field("BUSY", fields::LASER_BUSY, 1, ReadOnly, "the duty engine is computing: it runs free, so BUSY reads 1 in all but one clock of every ENGINE_CLOCKS + 1 (a diagnostic, not a handshake)"),
            ],
        ),
        register(
            "LASER_OUTPUT",
            laser::LASER_OUTPUT,
            "the laser's duty and speed",
            vec![
                field("DUTY", fields::LASER_POWER, word, ReadOnly, "the duty in force, clocks high per PWM period"),
                field("SPEED", fields::LASER_SPEED, word, ReadOnly, "the vector speed of the last computed period, steps per period"),
            ],
        ),
        register(
            "LASER_POWER",
            laser::LASER_POWER,
            "the power and feed by register, in force while LASER_CONTROL.SOURCE = 1 (the layout of a LASER_FIFO entry)",
            vec![
                field("POWER", fields::LASER_POWER, word, ReadWrite, "clocks high per PWM period at the programmed feed (at or above LASER_PWM_PERIOD: steady on)"),
                field("FEED", fields::LASER_FEED, word, ReadWrite, "the programmed feed, 1/16 step per period (vector length in the plane); 0: a dynamic duty of 0"),
            ],
        ),
    ]
}

/// A register holding a signed POSITION_BITS-wide number (`VALUE`),
/// its sign copied up to bit 31 (`SIGN`).
fn signed_position(
    name: &'static str,
    address: u32,
    access: Access,
    doc: &'static str,
    value_doc: &'static str,
) -> Register {
    let position_bits = super::POSITION_BITS as u32;
    register(
        name,
        address,
        doc,
        vec![
            field("VALUE", fields::VALUE, position_bits, access, value_doc),
            field(
                "SIGN",
                position_bits,
                32 - position_bits,
                Access::ReadOnly,
                "copies of VALUE's sign bit (writes ignored)",
            ),
        ],
    )
}

/// Word addresses of the laser unit's registers (build option `LASER`):
/// in the same window as the spindle's, from `0xF0`.
pub mod laser {
    /// The unit's first word.
    pub const BASE: u32 = 0xf0;
    /// Enable, mode, plane.
    pub const LASER_CONTROL: u32 = BASE;
    /// The PWM's period in clocks.
    pub const LASER_PWM_PERIOD: u32 = BASE + 0x01;
    /// The laser FIFO: one entry (power, feed) per period.
    pub const LASER_FIFO: u32 = BASE + 0x02;
    /// The FIFO's level and flags.
    pub const LASER_STATUS: u32 = BASE + 0x03;
    /// The duty in force and the last computed speed.
    pub const LASER_OUTPUT: u32 = BASE + 0x04;
    /// The power and feed by register (`LASER_CONTROL.SOURCE` = 1).
    pub const LASER_POWER: u32 = BASE + 0x05;
    /// Words the unit decodes (`address - BASE` below this).
    pub const WORDS: u32 = 0x06;
}

/// Width of `GEAR_NUMERATOR`, `GEAR_DENOMINATOR`, `GEAR_RAMP` and
/// `GEAR_LENGTH`: the exported gearbox's W and L.
pub const GEAR_BITS: u32 = 24;
