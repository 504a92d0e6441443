//! The register map of [`super::MotionController`]: the one source of truth
//! for addresses, fields and reset values. The C header
//! (`rtl-out/motion_controller_regs.h`), the Markdown table
//! (`rtl-out/motion_controller_regs.md`), the RTL's address decoder and the
//! tests (which drive the RTL through the bus with this map) all come from
//! here.
//!
//! The RTL decodes addresses with constants taken from this map. Field bit
//! positions appear in the RTL as literals (rust-hdl prints a named Rust
//! constant literally into the Verilog), so every field is exercised
//! through the bus by the tests, packed and unpacked with this map: a field
//! moved here and not in the RTL fails them.

use crate::regmap::{Access, Field, RegMapError, Register, RegisterMap};

/// `ID` register value: "MHDC".
pub const ID_VALUE: u32 = 0x4d48_4443;
/// `VERSION` register value: major 0, minor 1, patch 0.
pub const VERSION_VALUE: u32 = 0x0000_0100;

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
}

/// Word address of axis 0's register window; axis k is at
/// `AXIS_BASE + k * AXIS_STRIDE`.
pub const AXIS_BASE: u32 = 0x10;
/// Words per axis window.
pub const AXIS_STRIDE: u32 = 0x10;
/// Most axes the 8-bit address space holds.
pub const MAX_AXES: usize = 15;

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
    /// Number of interrupt sources.
    pub const COUNT: usize = 7;
}

fn field(name: &'static str, lsb: u32, width: u32, access: Access, doc: &'static str) -> Field {
    Field {
        name,
        lsb,
        width,
        access,
        reset: 0,
        doc,
    }
}

fn register(name: &'static str, address: u32, doc: &'static str, fields: Vec<Field>) -> Register {
    Register {
        name,
        address,
        count: 1,
        stride: 0,
        doc,
        fields,
    }
}

/// A read-write register whose low `width` bits hold a number.
fn number(name: &'static str, address: u32, width: u32, doc: &'static str) -> Register {
    register(name, address, doc, vec![field("VALUE", 0, width, Access::ReadWrite, doc)])
}

fn irq_fields(access: Access) -> Vec<Field> {
    vec![
        field("PERIOD_DONE", irq::PERIOD_DONE, 1, access, "a period ended and the next began"),
        field("FIFO_LOW", irq::FIFO_LOW, 1, access, "an axis FIFO level fell to FIFO_LOW_WATER or below"),
        field("UNDERRUN", irq::UNDERRUN, 1, access, "a boundary found an axis FIFO empty: all axes stopped, RUN cleared"),
        field("OVERFLOW", irq::OVERFLOW, 1, access, "a FIFO_WRITE to a full FIFO was refused (nothing overwritten)"),
        field("ENCODER_ERROR", irq::ENCODER_ERROR, 1, access, "an encoder saw A and B change together (counts lost)"),
        field("WATCHDOG", irq::WATCHDOG, 1, access, "the watchdog expired: all axes stopped, RUN cleared; clearing it re-allows RUN"),
        field("AXIS_FAULT", irq::AXIS_FAULT, 1, access, "an axis dropped or clamped steps: see AXIS_STATUS"),
    ]
}

/// The register map of a `motion_controller` with `axes` axes and FIFOs of
/// 2^`fifo_log2` entries. Fails, naming the problem, for more axes than the
/// address space holds or a map that does not validate.
pub fn register_map(axes: usize, fifo_log2: u32) -> Result<RegisterMap, RegMapError> {
    if axes == 0 || axes > MAX_AXES {
        return Err(RegMapError::NoCopies(format!(
            "motion_controller axes: {axes} (1 to {MAX_AXES} fit the 8-bit address space)"
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
        ],
    );
    config.fields[0].reset = axes as u64;
    config.fields[1].reset = fifo_log2 as u64;
    config.fields[2].reset = super::TIMER_BITS as u64;
    config.fields[3].reset = 32;
    let map = RegisterMap {
        name: "MC",
        address_bits: 8,
        doc: "motion_controller: K step/encoder axes behind a 32-bit word-addressed register bus",
        registers: vec![
            Register::word("ID", global::ID, ReadOnly, ID_VALUE as u64, "identity: 0x4D484443, \"MHDC\""),
            register(
                "VERSION",
                global::VERSION,
                "core version",
                vec![
                    field("PATCH", 0, 8, ReadOnly, "patch"),
                    Field { reset: 1, ..field("MINOR", 8, 8, ReadOnly, "minor") },
                    field("MAJOR", 16, 8, ReadOnly, "major"),
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
                        0,
                        1,
                        ReadWrite,
                        "write 1 to start (refused while WATCHDOG_EXPIRED); write 0 to stop at once; cleared by an underrun or the watchdog",
                    ),
                    field(
                        "FLUSH",
                        1,
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
                vec![field("LEVEL", 0, level_bits, ReadWrite, "FIFO_LOW is raised when a level falls to this or below")],
            ),
            Register::word("WATCHDOG_TIMEOUT", global::WATCHDOG_TIMEOUT, ReadWrite, 0, "base ticks allowed between kicks, taken at each kick; 0 disarms"),
            Register::word("WATCHDOG_KICK", global::WATCHDOG_KICK, WriteOnly, 0, "any write kicks (and arms) the watchdog"),
            Register::word("SNAPSHOT", global::SNAPSHOT, WriteOnly, 0, "any write latches every axis's CMD and ACT positions on the same clock"),
            register(
                "STATE",
                global::STATE,
                "live state",
                vec![
                    field("RUNNING", 0, 1, ReadOnly, "periods are running"),
                    field("WATCHDOG_ARMED", 1, 1, ReadOnly, "the watchdog is counting"),
                    field("WATCHDOG_EXPIRED", 2, 1, ReadOnly, "the watchdog expired; cleared with STATUS.WATCHDOG"),
                ],
            ),
            Register::word("PERIOD_COUNT", global::PERIOD_COUNT, ReadOnly, 0, "periods started since reset, wrapping"),
            per_axis(Register::word("FIFO_WRITE", at(axis::FIFO_WRITE), WriteOnly, 0, "push one period's signed step count (refused when full); a magnitude above 65535 is saturated and flagged")),
            per_axis(register(
                "FIFO_STATUS",
                at(axis::FIFO_STATUS),
                "FIFO level and flags",
                vec![
                    field("LEVEL", 0, level_bits, ReadOnly, "periods queued"),
                    Field { reset: 1, ..field("EMPTY", 16, 1, ReadOnly, "no period queued") },
                    field("FULL", 17, 1, ReadOnly, "no room: a write now is refused"),
                    Field { reset: 1, ..field("LOW", 18, 1, ReadOnly, "LEVEL <= FIFO_LOW_WATER") },
                ],
            )),
            per_axis(register(
                "AXIS_CONFIG",
                at(axis::AXIS_CONFIG),
                "interpolator, output mode and encoder settings",
                vec![
                    field("UNIFORM", 0, 1, ReadWrite, "0 = DDA, 1 = dual-period uniform pulse generator; taken when RUN starts and the axis's uniform generator is idle"),
                    field("INTERLEAVED", 1, 1, ReadWrite, "uniform generator order: 0 = short pulses first, 1 = interleaved"),
                    field("STEP_MODE", 2, 2, ReadWrite, "0 step/dir, 1 up/down, 2 quadrature, 3 reserved (acts as 0); taken while the output is idle"),
                    field("ENC_FILTER", 4, 4, ReadWrite, "encoder glitch filter: samples a level must hold"),
                    field("ENC_COUNTER_MODE", 8, 1, ReadWrite, "0 = 4x quadrature, 1 = step/dir input"),
                    field("INDEX_INVERT", 9, 1, ReadWrite, "index active low"),
                    field("INDEX_CLEAR", 10, 1, ReadWrite, "an index event clears ACT_POSITION"),
                    field("INDEX_LATCH", 11, 1, ReadWrite, "an index event latches ACT_POSITION into INDEX_POSITION"),
                    field("INDEX_ONCE", 12, 1, ReadWrite, "act on the first index only, until REARM_INDEX"),
                ],
            )),
            per_axis(number("STEP_LEN", at(axis::STEP_LEN), 16, "step pulse high time in clocks (0 acts as 1)")),
            per_axis(number("STEP_SPACE", at(axis::STEP_SPACE), 16, "minimum step low time in clocks (0 acts as 1)")),
            per_axis(number("DIR_SETUP", at(axis::DIR_SETUP), 16, "dir stable before a step rises, clocks (0 acts as 1)")),
            per_axis(number("DIR_HOLD", at(axis::DIR_HOLD), 16, "dir stable after a step falls, clocks (0 acts as 1)")),
            per_axis(number("ENC_SAMPLE_RATE", at(axis::ENC_SAMPLE_RATE), 8, "encoder sample every n + 1 clocks")),
            per_axis(Register::word("CMD_POSITION", at(axis::CMD_POSITION), ReadOnly, 0, "commanded position: steps emitted at the pins, signed")),
            per_axis(Register::word("ACT_POSITION", at(axis::ACT_POSITION), ReadOnly, 0, "actual position: encoder count, signed")),
            per_axis(Register::word("CMD_SNAPSHOT", at(axis::CMD_SNAPSHOT), ReadOnly, 0, "CMD_POSITION at the last SNAPSHOT write")),
            per_axis(Register::word("ACT_SNAPSHOT", at(axis::ACT_SNAPSHOT), ReadOnly, 0, "ACT_POSITION at the last SNAPSHOT write")),
            per_axis(register(
                "AXIS_STATUS",
                at(axis::AXIS_STATUS),
                "axis flags (sticky ones are cleared with AXIS_COMMAND)",
                vec![
                    field("STEP_OVERRUN", 0, 1, ReadOnly, "sticky until CLEAR_FAULTS: the output stage's pending count saturated and a step was dropped"),
                    field("INTERP_OVERRANGE", 1, 1, ReadOnly, "sticky until CLEAR_FAULTS: an entry was clamped (above 65535; DDA: above PERIOD_TICKS; uniform: above half of it, or PERIOD_TICKS odd)"),
                    field("INTERP_OVERFLOW", 2, 1, ReadOnly, "sticky until CLEAR_FAULTS: the uniform generator refused a period (a period shorter than its 24-clock set-up)"),
                    field("ENCODER_ERROR", 3, 1, ReadOnly, "sticky: illegal encoder transition; cleared with CLEAR_ENCODER_ERROR (or CLEAR_ENCODER)"),
                    field("INDEX_SEEN", 4, 1, ReadOnly, "sticky: an index event was acted on; cleared with REARM_INDEX"),
                    field("STEP_BUSY", 5, 1, ReadOnly, "the output stage has steps pending or an interval running"),
                    field("UNIFORM_RUNNING", 6, 1, ReadOnly, "the uniform generator is inside a period"),
                    field("STEP_MODE_INVALID", 7, 1, ReadOnly, "STEP_MODE is 3"),
                ],
            )),
            per_axis(Register::word("INDEX_POSITION", at(axis::INDEX_POSITION), ReadOnly, 0, "ACT_POSITION latched at the last index event")),
            per_axis(register(
                "AXIS_COMMAND",
                at(axis::AXIS_COMMAND),
                "axis commands: write 1 to act",
                vec![
                    field("CLEAR_FAULTS", 0, 1, WriteOnly, "clear STEP_OVERRUN, INTERP_OVERRANGE and INTERP_OVERFLOW"),
                    field("CLEAR_ENCODER", 1, 1, WriteOnly, "ACT_POSITION <- 0 and ENCODER_ERROR <- 0"),
                    field("REARM_INDEX", 2, 1, WriteOnly, "clear INDEX_SEEN (re-arm a once-only index)"),
                    field("CLEAR_POSITION", 3, 1, WriteOnly, "CMD_POSITION <- 0 at the first clock, from this write on, that counts no step (no step is lost)"),
                    field("CLEAR_ENCODER_ERROR", 4, 1, WriteOnly, "ENCODER_ERROR <- 0, keeping ACT_POSITION (an error on the same clock keeps it set)"),
                ],
            )),
        ],
    };
    map.validate()?;
    Ok(map)
}
