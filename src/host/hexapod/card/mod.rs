//! # The parallel-machine card run by its DSPs (#36 step 3)
//!
//! `parallel_card` between a control-level DSP and three motor-control
//! DSPs, each driving two legs of the hexapod through a DAC pair, a
//! velocity drive and a motor whose encoder the card counts:
//!
//! ```text
//! CartesianMotion ─> ControlDsp ─master port─> parallel_card ─slave port k─> MotorDsp k
//!   (pose, twist,      point/period,              │  period_tick: release,      IK of legs 2k, 2k+1,
//!    acceleration)     SYNC, CARD_FAULT            │  latch counts, DAC update   PID, DAC_CODE
//!                                                  ├─ dac pins ─> AD669 ─> drive ─> motor ─┐
//!                                                  └─ enc_a/enc_b <──── encoder <───────────┘
//! ```
//!
//! | Item | What |
//! |---|---|
//! | [`CartesianMotion`], [`Helix`] | the path: pose, velocity and acceleration at any time |
//! | [`ControlDsp`] | primes the card (tick mode, filter, point 0, SYNC, faults cleared); after each tick writes the next point to every slave, SYNC, and reads `CARD_FAULT` |
//! | [`MotorDsp`] | on its `data_ready` rise: reads the point and its latched counts, IK, PID ([`GainSchedule`]), writes both `DAC_CODE`s |
//! | [`run_card`] | the whole card clock by clock on rust-hdl or Verilator ([`CardSettings`], [`CardRun`]) |
//!
//! ## Timing
//! Point n is the pose for tick n + [`LEAD_PERIODS`]. The control DSP
//! writes it after tick n − 1 and the tick n releases it. The motor DSP reads it
//! with the counts latched at tick n. It compares those counts with the
//! point for tick n (released two ticks before), and writes codes that go
//! out at tick n + 1 and drive until tick n + 2, the point's time. The
//! velocity command is the point's mean leg velocity over that period, plus
//! the drive's lag times the leg's acceleration (the IK of velocity and
//! acceleration: J q̈ + J̇ q̇). The DSPs' arithmetic takes no clocks here: a
//! DSP's compute time shortens the period the card leaves it, and does
//! not change what the card does.
//!
//! ## Faults
//! Every point is checked before the first clock ([`crate::host::hexapod::check_pose`]
//! and its words): a bad one is a [`CardError`] naming its period. A slave
//! with no point at a tick stops every joint (the card's rule), and the
//! control DSP reads which slave and which period ([`Underrun`]). A motor
//! DSP that reads a bad or out-of-order point writes 0 V and stops
//! ([`MotorDspError`]).

mod bus;
mod control_dsp;
mod motor_dsp;
mod program;
mod run;
mod trajectory;

pub use bus::{Access, BusAgent, BusPins};
pub use control_dsp::{ControlDsp, Underrun};
pub use motor_dsp::{GainSchedule, MotorDsp, MotorDspError, MotorDspSettings};
pub use program::{PlanError, PoseLimits, PosePlan, MAX_PROGRAM_SECONDS};
pub use run::{run_card, CardError, CardRun, CardSettings, LegPlant};
pub use trajectory::{CartesianMotion, Helix, MotionSample};

/// Periods between a point's release and its pose's tick.
pub const LEAD_PERIODS: u64 = 2;
