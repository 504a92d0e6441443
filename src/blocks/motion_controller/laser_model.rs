//! Cycle-exact model of the laser unit ([`super::laser::LaserUnit`]): the
//! laser FIFO, its registers, and the [`LaserPwmModel`] driven as the unit
//! drives the block.

use super::model::{bit_set, field_value, flag};
use super::registers::{fields, laser};
use crate::blocks::command_fifo::model::{CommandFifoModel, CommandFifoOutputs};
use crate::blocks::laser_pwm::model::{LaserInputs, LaserOutputs, LaserPwmModel};
use crate::blocks::laser_pwm::{C, F, R};

/// The unit's inputs in one clock (the bus and the run's strobes are the
/// controller's).
#[derive(Clone, Copy, Debug, Default)]
pub struct LaserUnitInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Bus word address.
    pub address: u32,
    /// Bus write strobe (only in a `LASER` build).
    pub write: bool,
    /// Bus write data.
    pub write_data: u32,
    /// RUN starts.
    pub start: bool,
    /// A boundary pops every FIFO.
    pub pop: bool,
    /// RUN falls (an underrun or a halt).
    pub stop: bool,
    /// A CONTROL.FLUSH write.
    pub flush: bool,
    /// RUN.
    pub running: bool,
    /// An abort or the hold's stop.
    pub kill: bool,
    /// The hold's factor, 1/65536.
    pub factor: u64,
    /// |entry| of the plane's axes' running periods, 16 bits.
    pub counts: (u64, u64),
}

/// Model of the laser unit of a controller with FIFOs of 2^`fifo_log2`.
#[derive(Clone, Debug)]
pub struct LaserUnitModel {
    fifo: CommandFifoModel,
    fifo_out: CommandFifoOutputs,
    engine: LaserPwmModel,
    engine_out: LaserOutputs,
    control: u32,
    pwm_period: u64,
    entry: u32,
    /// `LASER_POWER`.
    power: u32,
    active: bool,
    overflow: bool,
    busy_prev: bool,
    /// `LASER_CONTROL`'s read-write bits, from the register map.
    control_mask: u32,
}

const COUNT_MAX: u64 = 0x7fff;
const WORD: u32 = fields::LASER_WORD_WIDTH;

impl LaserUnitModel {
    /// The unit at power-up, with FIFOs of 2^`fifo_log2` entries and
    /// `LASER_CONTROL`'s read-write bits `control_mask` (the map's).
    pub fn new(fifo_log2: u32, control_mask: u32) -> Self {
        let mut fifo = CommandFifoModel::new(1 << fifo_log2);
        let fifo_out = fifo.step(true, false, 0, false, 0, false);
        Self {
            fifo,
            fifo_out,
            engine: LaserPwmModel::new(R as u32, C as u32, F as u32),
            engine_out: LaserOutputs::default(),
            control: 0,
            pwm_period: 0,
            entry: 0,
            power: 0,
            active: false,
            overflow: false,
            busy_prev: false,
            control_mask,
        }
    }

    /// `LASER_CONTROL.AXIS_A` and `AXIS_B`.
    pub fn axes(&self) -> (u32, u32) {
        (
            field_value(self.control, fields::LASER_AXIS_A, fields::LASER_AXIS_WIDTH),
            field_value(self.control, fields::LASER_AXIS_B, fields::LASER_AXIS_WIDTH),
        )
    }

    /// A boundary may pop: the FIFO is not in the run or has an entry.
    pub fn ready(&self) -> bool {
        !self.active || !self.fifo_out.empty
    }

    /// The pin `laser_pwm`.
    pub fn pwm(&self) -> bool {
        self.engine_out.pwm
    }

    /// The duty in force.
    pub fn duty(&self) -> u64 {
        self.engine_out.duty
    }

    /// The unit's registers as read (0 outside them).
    pub fn read(&self, address: u32) -> u32 {
        match address {
            laser::LASER_CONTROL => self.control,
            laser::LASER_PWM_PERIOD => self.pwm_period as u32,
            laser::LASER_STATUS => {
                self.fifo_out.level as u32
                    | flag(self.overflow, fields::LASER_OVERFLOW)
                    | flag(self.active, fields::LASER_ACTIVE)
                    | flag(self.engine_out.busy, fields::LASER_BUSY)
            }
            laser::LASER_OUTPUT => {
                self.engine_out.duty as u32 | (self.engine_out.speed as u32) << fields::LASER_SPEED
            }
            laser::LASER_POWER => self.power,
            _ => 0,
        }
    }

    fn engine_inputs(&self, i: &LaserUnitInputs) -> LaserInputs {
        let setpoint = if bit_set(self.control, fields::LASER_SOURCE) {
            self.power
        } else {
            self.entry
        };
        LaserInputs {
            reset: i.reset,
            pwm_period: self.pwm_period,
            power: field_value(setpoint, fields::LASER_POWER, WORD) as u64,
            dynamic: bit_set(self.control, fields::LASER_DYNAMIC),
            load: !self.engine_out.busy,
            commit: self.busy_prev && !self.engine_out.busy,
            count_a: i.counts.0.min(COUNT_MAX),
            count_b: i.counts.1.min(COUNT_MAX),
            feed: field_value(setpoint, fields::LASER_FEED, WORD) as u64,
            factor: i.factor,
            enable: bit_set(self.control, fields::LASER_ENABLE) && i.running && !i.stop,
            kill: i.kill,
        }
    }

    /// One clock edge.
    pub fn edge(&mut self, i: &LaserUnitInputs) {
        let write = |a: u32| i.write && i.address == a;
        let control_write = write(laser::LASER_CONTROL);
        let fifo_write = write(laser::LASER_FIFO);
        let pop = i.pop && self.active;
        let engine_in = self.engine_inputs(i);
        let mut next = self.clone();
        if control_write {
            next.control = i.write_data & self.control_mask;
        }
        if write(laser::LASER_PWM_PERIOD) {
            next.pwm_period = field_value(i.write_data, fields::LASER_POWER, WORD) as u64;
        }
        if write(laser::LASER_POWER) {
            next.power = i.write_data;
        }
        if control_write && bit_set(i.write_data, fields::LASER_CLEAR_OVERFLOW) {
            next.overflow = false;
        }
        if fifo_write && self.fifo_out.full && !pop {
            next.overflow = true;
        }
        next.fifo_out = next.fifo.step(
            i.reset || i.flush,
            fifo_write,
            i.write_data as u64,
            pop,
            0,
            false,
        );
        if i.start {
            next.active = bit_set(self.control, fields::LASER_ENABLE)
                && !bit_set(self.control, fields::LASER_SOURCE);
        }
        if pop {
            next.entry = self.fifo_out.head as u32;
        }
        if i.stop {
            next.entry = 0;
            next.active = false;
        }
        next.busy_prev = self.engine_out.busy;
        next.engine_out = next.engine.step(&engine_in);
        if i.reset {
            next.control = 0;
            next.pwm_period = 0;
            next.entry = 0;
            next.power = 0;
            next.active = false;
            next.overflow = false;
            next.busy_prev = false;
        }
        *self = next;
    }
}
