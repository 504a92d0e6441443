//! The host (CPU/DSP) half of the two-level interpolator, in plain Rust:
//! G-code programs and `.path` files into toolpaths of lines and arcs,
//! velocity planning with look-ahead under per-axis limits, coarse
//! interpolation into per-period step counts, and a driver that streams
//! them into `motion_controller` over its register map.

pub mod bus;
pub mod driver;
pub mod gcode;
pub mod geometry;
pub mod hexapod;
pub mod hold_window;
pub mod interpolator;
pub mod laser_log;
pub mod laser_run;
pub mod machine;
pub mod path;
pub mod planner;
pub mod servo;
pub mod simulated_probe;
pub mod simulation;
pub mod soft_window;
pub mod spi;
pub mod spindle_run;
mod statements;
pub mod thread_log;
pub mod tool_table;
pub mod toolpath;

pub use bus::{ControllerBus, ModelBus, ProbeSurface, RecordingBus, RtlBus};
pub use driver::{Driver, DriverConfig, DriverError, LaserEntry, LaserRun, RunReport};
pub use interpolator::{interpolate, Interpolation};
pub use machine::MachineSettings;
pub use path::{Path, PathError, Segment};
pub use planner::{plan, plan_toolpath, PlannedSegment, Shape};
pub use servo::{DriveScale, FollowingError, LoopOutput, PositionLoop, ServoError, ServoGains};
pub use tool_table::{Tool, ToolTable, ToolTableError};
pub use toolpath::{Arc, Item, LaserPower, Move, MoveKind, Plane, Toolpath};
