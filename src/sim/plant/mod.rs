//! Plant models: what hangs on the FPGA's pins in a simulation, driven by
//! the RTL's outputs and feeding its inputs. The quadrature encoder on a
//! step/dir axis, the AD669 DAC bank on the analog outputs, and the servo
//! drive and motor those DACs command, and the spindle with its encoder.

mod ad669;
mod encoder;
mod servo_motor;
mod spindle_motor;

pub use ad669::Ad669Bank;
pub use encoder::{quadrature_state, SimulatedEncoder};
pub use servo_motor::ServoMotor;
pub use spindle_motor::SpindleMotor;
