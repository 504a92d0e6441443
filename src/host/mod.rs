//! The host (CPU/DSP) half of the two-level interpolator, in plain Rust:
//! paths and their file format, velocity planning with look-ahead, coarse
//! interpolation into per-period step counts, and a driver that streams
//! them into `motion_controller` over its register map.

pub mod bus;
pub mod driver;
pub mod gcode;
pub mod interpolator;
pub mod path;
pub mod planner;
pub mod servo;
pub mod simulation;

pub use bus::{ControllerBus, ModelBus, RecordingBus, RtlBus};
pub use driver::{Driver, DriverConfig, DriverError, RunReport};
pub use interpolator::{interpolate, Interpolation};
pub use path::{Path, PathError, Segment};
pub use planner::{plan, PlannedSegment};
pub use servo::{DriveScale, FollowingError, LoopOutput, PositionLoop, ServoError, ServoGains, ServoMotor};
