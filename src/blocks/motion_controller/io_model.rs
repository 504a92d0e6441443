//! Reference models of the controller's machine I/O:
//! [`super::machine_io::MachineIo`] ([`MachineIoModel`]),
//! [`super::probe_trigger::ProbeTrigger`] ([`ProbeModel`]),
//! [`super::feed_hold::FeedHold`] ([`FeedHoldModel`]) and
//! [`super::axis_io::AxisIo`] ([`AxisIoModel`]). Cycle-exact, two-phase
//! like the rest of [`super::model`]: the combinational values of a clock
//! from the registered state, then the edge.

use super::hold_ramp::{HoldRampInputs, HoldRampModel};
use super::registers::{axis, fields, global};
use crate::blocks::input_conditioner::model::{InputConditionerInputs, InputConditionerModel};

/// The machine-I/O pins of the controller in one clock, bit k for axis k.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MachinePins {
    /// limit_pos.
    pub limit_pos: u32,
    /// limit_neg.
    pub limit_neg: u32,
    /// home.
    pub home: u32,
    /// drive_alarm.
    pub drive_alarm: u32,
    /// estop.
    pub estop: bool,
    /// gpio_in.
    pub gpio_in: u8,
    /// probe.
    pub probe: bool,
    /// feed_hold.
    pub feed_hold: bool,
}

/// One axis's conditioned switch levels in one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AxisSwitches {
    /// limit_pos active.
    pub limit_forward: bool,
    /// limit_neg active.
    pub limit_backward: bool,
    /// home active.
    pub home: bool,
    /// home rose at the last edge.
    pub home_rise: bool,
    /// drive_alarm active.
    pub alarm: bool,
}

/// The combinational values of [`MachineIoModel`] in one clock.
#[derive(Clone, Debug)]
pub struct MachineIoComb {
    /// Per axis (the first K entries; an array, so that the per-clock
    /// model allocates nothing).
    pub switches: [AxisSwitches; super::registers::MAX_AXES],
    /// The E-stop input is active.
    pub estop_active: bool,
    /// The E-stop latch.
    pub estop_latched: bool,
    /// The latch after the edge.
    pub estop_latched_next: bool,
    /// The latch rises at this edge.
    pub estop_event: bool,
    /// An enabled general-input edge.
    pub gpio_event: bool,
    /// The conditioners are primed.
    pub ready: bool,
    /// The addressed register of this block, 0 otherwise.
    pub read_data: u32,
}

/// Model of the controller-wide machine I/O of `axes` axes.
#[derive(Clone, Debug)]
pub struct MachineIoModel {
    axes: usize,
    limit_pos: InputConditionerModel,
    limit_neg: InputConditionerModel,
    home: InputConditionerModel,
    alarm: InputConditionerModel,
    estop: InputConditionerModel,
    gpio: InputConditionerModel,
    filter: u32,
    polarity: u32,
    sample_count: u8,
    estop_latch: bool,
    gpio_out: u8,
    gpio_safe: u8,
    gpio_irq_enable: u16,
    gpio_edges: u16,
}

fn bit(word: u32, n: u32) -> bool {
    word >> n & 1 != 0
}

/// All ones in a field of `width` bits.
fn ones(width: u32) -> u32 {
    crate::blocks::width_mask(width) as u32
}

impl MachineIoModel {
    /// Power-up state (the registers read their reset values).
    pub fn new(axes: usize) -> Self {
        let k = axes as u32;
        Self {
            axes,
            limit_pos: InputConditionerModel::new(k),
            limit_neg: InputConditionerModel::new(k),
            home: InputConditionerModel::new(k),
            alarm: InputConditionerModel::new(k),
            estop: InputConditionerModel::new(1),
            gpio: InputConditionerModel::new(8),
            filter: (fields::FILTER_LENGTH_RESET as u32) << fields::FILTER_LENGTH,
            polarity: 0,
            sample_count: 0,
            estop_latch: false,
            gpio_out: 0,
            gpio_safe: 0,
            gpio_irq_enable: 0,
            gpio_edges: 0,
        }
    }

    /// The gpio_out pins.
    pub fn gpio_out(&self) -> u8 {
        self.gpio_out
    }

    fn class_invert(&self, polarity_bit: u32) -> u32 {
        if bit(self.polarity, polarity_bit) {
            crate::blocks::width_mask(self.axes as u32) as u32
        } else {
            0
        }
    }

    fn gpio_invert(&self) -> u32 {
        (self.polarity >> fields::POLARITY_GPIO) & ones(fields::GPIO_WIDTH)
    }

    /// This clock's filter sample strobe and `INPUT_FILTER.LENGTH`, which
    /// the probe's conditioner shares.
    pub fn filter_inputs(&self) -> (bool, u8) {
        (self.sample_count == 0, self.length())
    }

    fn length(&self) -> u8 {
        ((self.filter >> fields::FILTER_LENGTH) & ones(fields::FILTER_LENGTH_WIDTH)) as u8
    }

    fn gpio_edges_now(&self) -> u16 {
        let g = self.gpio.outputs(self.gpio_invert());
        let gpio = ones(fields::GPIO_WIDTH);
        ((g.rise & gpio) << fields::GPIO_RISE | (g.fall & gpio) << fields::GPIO_FALL) as u16
    }

    /// The combinational values of this clock.
    pub fn comb(&self, reset: bool, address: u32, estop_clear: bool) -> MachineIoComb {
        let lp = self
            .limit_pos
            .outputs(self.class_invert(fields::POLARITY_LIMIT_POS));
        let ln = self
            .limit_neg
            .outputs(self.class_invert(fields::POLARITY_LIMIT_NEG));
        let hm = self.home.outputs(self.class_invert(fields::POLARITY_HOME));
        let al = self
            .alarm
            .outputs(self.class_invert(fields::POLARITY_DRIVE_ALARM));
        let es = self.estop.outputs(0);
        let estop_active = es.active & 1 != 0;
        let mut estop_next = self.estop_latch && !estop_clear;
        if estop_active {
            estop_next = true;
        }
        if reset {
            estop_next = false;
        }
        let g = self.gpio.outputs(self.gpio_invert());
        let read_data = match address {
            global::INPUT_FILTER => self.filter,
            global::INPUT_POLARITY => self.polarity,
            global::GPIO_IN => g.active,
            global::GPIO_OUT => self.gpio_out as u32,
            global::GPIO_SAFE => self.gpio_safe as u32,
            global::GPIO_IRQ_ENABLE => self.gpio_irq_enable as u32,
            global::GPIO_EDGES => self.gpio_edges as u32,
            _ => 0,
        };
        MachineIoComb {
            switches: std::array::from_fn(|k| {
                let k = k as u32;
                AxisSwitches {
                    limit_forward: bit(lp.active, k),
                    limit_backward: bit(ln.active, k),
                    home: bit(hm.active, k),
                    home_rise: bit(hm.rise, k),
                    alarm: bit(al.active, k),
                }
            }),
            estop_active,
            estop_latched: self.estop_latch,
            estop_latched_next: estop_next,
            estop_event: estop_active && !self.estop_latch,
            gpio_event: self.gpio_edges_now() & self.gpio_irq_enable != 0,
            ready: es.ready,
            read_data,
        }
    }

    /// One edge. `comb` is this clock's [`MachineIoModel::comb`].
    pub fn edge(
        &mut self,
        reset: bool,
        pins: &MachinePins,
        write: Option<(u32, u32)>,
        comb: &MachineIoComb,
        watchdog_expired: bool,
    ) {
        let sample = self.sample_count == 0;
        let length = self.length();
        let k_mask = crate::blocks::width_mask(self.axes as u32) as u32;
        let step = |c: &mut InputConditionerModel, raw: u32| {
            c.step(InputConditionerInputs {
                reset,
                raw,
                invert: 0,
                sample,
                length,
            });
        };
        let edges_now = self.gpio_edges_now();
        step(&mut self.limit_pos, pins.limit_pos & k_mask);
        step(&mut self.limit_neg, pins.limit_neg & k_mask);
        step(&mut self.home, pins.home & k_mask);
        step(&mut self.alarm, pins.drive_alarm & k_mask);
        step(&mut self.estop, pins.estop as u32);
        step(&mut self.gpio, pins.gpio_in as u32);
        self.sample_count = if sample {
            ((self.filter >> fields::FILTER_SAMPLE_RATE) & ones(fields::FILTER_SAMPLE_RATE_WIDTH))
                as u8
        } else {
            self.sample_count.wrapping_sub(1)
        };
        let mut gpio_out = self.gpio_out;
        let safe = self.gpio_safe;
        let mut edges = self.gpio_edges;
        if let Some((address, data)) = write {
            match address {
                global::INPUT_FILTER => {
                    self.filter = data
                        & (ones(fields::FILTER_LENGTH_WIDTH) << fields::FILTER_LENGTH
                            | ones(fields::FILTER_SAMPLE_RATE_WIDTH) << fields::FILTER_SAMPLE_RATE)
                }
                global::INPUT_POLARITY => {
                    self.polarity = data
                        & (1 << fields::POLARITY_LIMIT_POS
                            | 1 << fields::POLARITY_LIMIT_NEG
                            | 1 << fields::POLARITY_HOME
                            | 1 << fields::POLARITY_DRIVE_ALARM
                            | ones(fields::GPIO_WIDTH) << fields::POLARITY_GPIO)
                }
                global::GPIO_OUT => gpio_out = data as u8,
                global::GPIO_SAFE => self.gpio_safe = data as u8,
                global::GPIO_IRQ_ENABLE => self.gpio_irq_enable = data as u16,
                global::GPIO_EDGES => edges &= !(data as u16),
                _ => {}
            }
        }
        if comb.estop_latched_next || watchdog_expired {
            gpio_out &= !safe;
        }
        self.gpio_out = gpio_out;
        self.gpio_edges = edges | edges_now;
        self.estop_latch = comb.estop_latched_next;
        if reset {
            let fresh = Self::new(self.axes);
            self.filter = fresh.filter;
            self.polarity = 0;
            self.sample_count = 0;
            self.gpio_out = 0;
            self.gpio_safe = 0;
            self.gpio_irq_enable = 0;
            self.gpio_edges = 0;
        }
    }
}

/// [`ProbeModel`]'s combinational values in one clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct ProbeComb {
    /// The probe trips in this clock: every axis latches its positions.
    pub latch: bool,
    /// The trip requests the feed hold (`PROBE_CONTROL.STOP`).
    pub stop: bool,
    /// `PROBE_CONTROL` when addressed, else 0.
    pub read_data: u32,
}

/// Model of the probe trigger: its conditioner, `PROBE_CONTROL` and the
/// trip.
#[derive(Clone, Debug)]
pub struct ProbeModel {
    conditioner: InputConditionerModel,
    armed: bool,
    falling: bool,
    stop: bool,
    tripped: bool,
}

impl Default for ProbeModel {
    fn default() -> Self {
        Self {
            conditioner: InputConditionerModel::new(1),
            armed: false,
            falling: false,
            stop: false,
            tripped: false,
        }
    }
}

impl ProbeModel {
    /// The armed state, edge and stop of this clock: a `PROBE_CONTROL`
    /// write decides them.
    fn control_now(&self, write: Option<(u32, u32)>) -> (bool, bool, bool) {
        match write {
            Some((global::PROBE_CONTROL, data)) => (
                bit(data, fields::PROBE_ARM),
                bit(data, fields::PROBE_EDGE),
                bit(data, fields::PROBE_STOP),
            ),
            _ => (self.armed, self.falling, self.stop),
        }
    }

    /// The combinational values of this clock; `write` is this clock's bus
    /// write (address, data), if any.
    pub fn comb(&self, address: u32, write: Option<(u32, u32)>) -> ProbeComb {
        let out = self.conditioner.outputs(0);
        let (armed, falling, stop) = self.control_now(write);
        let edge = if falling { out.fall } else { out.rise };
        let flag = |on: bool, n: u32| (on as u32) << n;
        let latch = armed && edge & 1 != 0;
        ProbeComb {
            latch,
            stop: latch && stop,
            read_data: if address == global::PROBE_CONTROL {
                flag(self.armed, fields::PROBE_ARM)
                    | flag(self.falling, fields::PROBE_EDGE)
                    | flag(self.stop, fields::PROBE_STOP)
                    | flag(self.tripped, fields::PROBE_TRIPPED)
                    | flag(out.active & 1 != 0, fields::PROBE_LEVEL)
            } else {
                0
            },
        }
    }

    /// One edge. `comb` is this clock's [`ProbeModel::comb`] with the same
    /// `write`; `filter` is [`MachineIoModel::filter_inputs`] of this clock.
    pub fn edge(
        &mut self,
        reset: bool,
        pin: bool,
        write: Option<(u32, u32)>,
        comb: &ProbeComb,
        filter: (bool, u8),
    ) {
        let (armed, falling, stop) = self.control_now(write);
        self.conditioner.step(InputConditionerInputs {
            reset,
            raw: pin as u32,
            invert: 0,
            sample: filter.0,
            length: filter.1,
        });
        if armed && matches!(write, Some((global::PROBE_CONTROL, _))) {
            self.tripped = false;
        }
        self.tripped |= comb.latch;
        self.armed = armed && !comb.latch;
        self.falling = falling;
        self.stop = stop;
        if reset {
            *self = Self {
                conditioner: self.conditioner.clone(),
                ..Self::default()
            };
        }
    }
}

/// [`FeedHoldModel`]'s combinational values in one clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct FeedHoldComb {
    /// The gated tick: the periods and the axes see this tick.
    pub tick: bool,
    /// The hold request of this clock (what the ramp sees).
    pub request: bool,
    /// `HOLD_CONTROL` when addressed, else 0.
    pub read_data: u32,
}

/// Model of the feed hold: its conditioner, `HOLD_CONTROL`, the sticky
/// request and the [`HoldRampModel`].
#[derive(Clone, Debug)]
pub struct FeedHoldModel {
    conditioner: InputConditionerModel,
    requested: bool,
    invert: bool,
    rate: u16,
    ramp: HoldRampModel,
}

impl Default for FeedHoldModel {
    fn default() -> Self {
        Self {
            conditioner: InputConditionerModel::new(1),
            requested: false,
            invert: false,
            rate: 0,
            ramp: HoldRampModel::default(),
        }
    }
}

impl FeedHoldModel {
    /// The ramp: its factor and phase.
    pub fn ramp(&self) -> &HoldRampModel {
        &self.ramp
    }

    /// `HOLD_CONTROL.RATE` as the ramp uses it.
    pub fn rate(&self) -> u16 {
        self.rate
    }

    /// The hold is requested (`HOLD_CONTROL.REQUESTED`).
    pub fn requested(&self) -> bool {
        self.requested
    }

    /// `STATE.HOLDING`: the factor is below 1.
    pub fn holding(&self) -> bool {
        self.ramp.factor() != super::hold_ramp::UNITY
    }

    /// `STATE.HELD`: the factor is 0.
    pub fn held(&self) -> bool {
        self.ramp.factor() == 0
    }

    /// The combinational values of this clock: `write` is this clock's
    /// bus write (address, data), `stop` a probe trip with
    /// `PROBE_CONTROL.STOP` or a soft-limit verdict beyond, `tick` the
    /// base tick.
    pub fn comb(
        &self,
        address: u32,
        write: Option<(u32, u32)>,
        stop: bool,
        tick: bool,
    ) -> FeedHoldComb {
        let input = self.conditioner.outputs(self.invert as u32).active & 1 != 0;
        let control = match write {
            Some((global::HOLD_CONTROL, data)) => Some(data),
            _ => None,
        };
        let set = input || stop || control.is_some_and(|d| bit(d, fields::HOLD_HOLD));
        let clear = control.is_some_and(|d| bit(d, fields::HOLD_RELEASE));
        let flag = |on: bool, n: u32| (on as u32) << n;
        FeedHoldComb {
            tick: self.ramp.gate(tick),
            request: set || (self.requested && !clear),
            read_data: if address == global::HOLD_CONTROL {
                (self.rate as u32) << fields::HOLD_RATE
                    | flag(self.requested, fields::HOLD_REQUESTED)
                    | flag(self.invert, fields::HOLD_INVERT)
                    | flag(input, fields::HOLD_INPUT)
            } else {
                0
            },
        }
    }

    /// One edge. `comb` is this clock's [`FeedHoldModel::comb`] with the
    /// same `write` and `tick`; `filter` is
    /// [`MachineIoModel::filter_inputs`] of this clock.
    pub fn edge(
        &mut self,
        reset: bool,
        pin: bool,
        write: Option<(u32, u32)>,
        comb: &FeedHoldComb,
        filter: (bool, u8),
        tick: bool,
    ) {
        self.conditioner.step(InputConditionerInputs {
            reset,
            raw: pin as u32,
            invert: self.invert as u32,
            sample: filter.0,
            length: filter.1,
        });
        // The ramp follows the registered request and rate: this edge's
        // ramp step sees them as they were before it.
        self.ramp.step(HoldRampInputs {
            reset,
            tick,
            hold: self.requested,
            rate: self.rate,
        });
        if let Some((global::HOLD_CONTROL, data)) = write {
            self.invert = bit(data, fields::HOLD_INVERT);
            self.rate = (data >> fields::HOLD_RATE) as u16;
        }
        self.requested = comb.request;
        if reset {
            *self = Self {
                conditioner: self.conditioner.clone(),
                ..Self::default()
            };
        }
    }
}

/// The axis's step path as [`AxisIoModel`] sees it in one clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct StepPath {
    /// The stage's next step is forward.
    pub pending_forward: bool,
    /// The stage's next step is backward.
    pub pending_backward: bool,
    /// The stage takes a request now.
    pub request: bool,
    /// Its direction.
    pub request_forward: bool,
    /// The interpolator offers a step now.
    pub pulse: bool,
    /// Its direction.
    pub pulse_forward: bool,
}

/// The combinational values of [`AxisIoModel`] in one clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct AxisIoComb {
    /// Forward steps blocked.
    pub block_forward: bool,
    /// Backward steps blocked.
    pub block_backward: bool,
    /// Cut toward the forward limit.
    pub cut_forward: bool,
    /// Cut toward the backward limit.
    pub cut_backward: bool,
    /// A limit trip flag rises.
    pub limit_event: bool,
    /// The alarm trip flag rises.
    pub alarm_event: bool,
    /// HOME_SEEN rises.
    pub home_event: bool,
    /// The alarm flag after the edge.
    pub alarm_next: bool,
}

impl AxisIoComb {
    /// A cut in either direction: the stage is flushed.
    pub fn cut(&self) -> bool {
        self.cut_forward || self.cut_backward
    }
}

/// Model of one axis's machine I/O.
#[derive(Clone, Debug)]
pub struct AxisIoModel {
    io_config: u32,
    limit_forward_tripped: bool,
    limit_backward_tripped: bool,
    alarm_tripped: bool,
    home_seen: bool,
    home_cmd: u32,
    home_act: u32,
    probe_cmd: u32,
    probe_act: u32,
    drive_enable: bool,
}

impl Default for AxisIoModel {
    fn default() -> Self {
        Self {
            io_config: fields::IO_CONFIG_RESET,
            limit_forward_tripped: false,
            limit_backward_tripped: false,
            alarm_tripped: false,
            home_seen: false,
            home_cmd: 0,
            home_act: 0,
            probe_cmd: 0,
            probe_act: 0,
            drive_enable: false,
        }
    }
}

impl AxisIoModel {
    fn config(&self, field: u32) -> bool {
        bit(self.io_config, field)
    }

    /// The drive_enable pin.
    pub fn drive_enable(&self) -> bool {
        self.drive_enable
    }

    /// A limit trip is held.
    pub fn limit_held(&self) -> bool {
        self.limit_forward_tripped || self.limit_backward_tripped
    }

    /// An alarm trip is held.
    pub fn alarm_held(&self) -> bool {
        self.alarm_tripped
    }

    /// A home stop is held.
    pub fn home_held(&self) -> bool {
        self.home_seen && self.config(fields::STOP_ON_HOME)
    }

    /// The combinational values of this clock. `command` is the
    /// IO_COMMAND data written in this clock, if any.
    pub fn comb(
        &self,
        reset: bool,
        s: &AxisSwitches,
        path: &StepPath,
        command: Option<u32>,
    ) -> AxisIoComb {
        let limits = self.config(fields::LIMIT_ENABLE);
        let block_forward = s.limit_forward && limits;
        let block_backward = s.limit_backward && limits;
        let cut_forward = block_forward
            && (path.pending_forward
                || (path.request && path.request_forward)
                || (path.pulse && path.pulse_forward));
        let cut_backward = block_backward
            && (path.pending_backward
                || (path.request && !path.request_forward)
                || (path.pulse && !path.pulse_forward));
        let alarm_now = s.alarm && self.config(fields::ALARM_ENABLE);
        let clear_alarm = command.is_some_and(|c| bit(c, fields::CLEAR_ALARM));
        let alarm_next = !reset && (alarm_now || (self.alarm_tripped && !clear_alarm));
        AxisIoComb {
            block_forward,
            block_backward,
            cut_forward,
            cut_backward,
            limit_event: (cut_forward && !self.limit_forward_tripped)
                || (cut_backward && !self.limit_backward_tripped),
            alarm_event: alarm_now && !self.alarm_tripped,
            home_event: s.home_rise && !self.home_seen,
            alarm_next,
        }
    }

    /// The I/O register at `offset` (0x10 to 0x1f) of the window.
    pub fn read(&self, offset: u32, s: &AxisSwitches) -> u32 {
        match offset {
            axis::IO_CONFIG => self.io_config,
            axis::IO_STATUS => {
                (s.limit_forward as u32) << fields::IO_LIMIT_POS
                    | (s.limit_backward as u32) << fields::IO_LIMIT_NEG
                    | (s.home as u32) << fields::IO_HOME
                    | (s.alarm as u32) << fields::IO_DRIVE_ALARM
                    | (self.limit_forward_tripped as u32) << fields::IO_LIMIT_POS_TRIPPED
                    | (self.limit_backward_tripped as u32) << fields::IO_LIMIT_NEG_TRIPPED
                    | (self.alarm_tripped as u32) << fields::IO_ALARM_TRIPPED
                    | (self.home_seen as u32) << fields::IO_HOME_SEEN
                    | (self.drive_enable as u32) << fields::IO_DRIVE_ENABLE
            }
            axis::HOME_CMD_POSITION => self.home_cmd,
            axis::HOME_ACT_POSITION => self.home_act,
            axis::PROBE_CMD_POSITION => self.probe_cmd,
            axis::PROBE_ACT_POSITION => self.probe_act,
            _ => 0,
        }
    }

    /// One edge. `write` is an I/O register write to this axis
    /// (offset, data); `positions` are (commanded, actual) of this clock;
    /// `probe_latch`, the probe's trip in this clock.
    pub fn edge(
        &mut self,
        reset: bool,
        write: Option<(u32, u32)>,
        comb: &AxisIoComb,
        positions: (u32, u32),
        drive_allowed: bool,
        probe_latch: bool,
    ) {
        let drive_enable = self.config(fields::DRIVE_ENABLE) && drive_allowed && !comb.alarm_next;
        let command = match write {
            Some((axis::IO_COMMAND, data)) => Some(data),
            _ => None,
        };
        if let Some((axis::IO_CONFIG, data)) = write {
            self.io_config = data
                & (1 << fields::LIMIT_ENABLE
                    | 1 << fields::ALARM_ENABLE
                    | 1 << fields::STOP_ON_HOME
                    | 1 << fields::DRIVE_ENABLE);
        }
        if command.is_some_and(|c| bit(c, fields::CLEAR_LIMITS)) {
            self.limit_forward_tripped = false;
            self.limit_backward_tripped = false;
        }
        self.limit_forward_tripped |= comb.cut_forward;
        self.limit_backward_tripped |= comb.cut_backward;
        self.alarm_tripped = comb.alarm_next;
        if command.is_some_and(|c| bit(c, fields::CLEAR_HOME)) {
            self.home_seen = false;
        }
        // The first edge since CLEAR_HOME latches (and wins over a clear).
        if comb.home_event {
            self.home_seen = true;
            (self.home_cmd, self.home_act) = positions;
        }
        if probe_latch {
            (self.probe_cmd, self.probe_act) = positions;
        }
        self.drive_enable = drive_enable;
        if reset {
            *self = Self::default();
        }
    }
}
