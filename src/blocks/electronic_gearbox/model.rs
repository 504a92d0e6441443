//! Reference model of [`super::ElectronicGearbox`], cycle-exact. It is
//! written from the datasheet's equations in plain integers, with the
//! registers' widths applied where the datasheet says they wrap.

use crate::blocks::{signed_value, width_mask};

/// The gearbox's phase, as `phase` reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Phase {
    /// Not geared: no step.
    #[default]
    Idle = 0,
    /// Armed: waiting for the next index.
    Armed = 1,
    /// Engaged, the rate ramping in toward the ratio.
    RampIn = 2,
    /// Engaged at the ratio, catching up the ramp's lag, then locked.
    Track = 3,
    /// Engaged, the rate ramping out (a command or the length).
    Stopping = 4,
}

impl Phase {
    /// Engaged: ramp-in, track or stopping (the phases that gear counts).
    pub fn is_engaged(self) -> bool {
        matches!(self, Phase::RampIn | Phase::Track | Phase::Stopping)
    }

    /// Ramp-in or track: the phases that keep the lag and the ramp-out
    /// bound.
    fn is_tracking(self) -> bool {
        matches!(self, Phase::RampIn | Phase::Track)
    }

    /// The phase from its code (codes 5 to 7 never occur; read as Idle).
    pub fn from_code(code: u64) -> Phase {
        match code {
            1 => Phase::Armed,
            2 => Phase::RampIn,
            3 => Phase::Track,
            4 => Phase::Stopping,
            _ => Phase::Idle,
        }
    }
}

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearboxInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// A spindle count up.
    pub count_up: bool,
    /// A spindle count down.
    pub count_down: bool,
    /// A spindle index event.
    pub index: bool,
    /// Arm: engage at the next index.
    pub arm: bool,
    /// Ramp out and stop (disarm while armed).
    pub stop: bool,
    /// Stop at once, no ramp.
    pub halt: bool,
    /// 1 = `count_down` is the spindle's forward direction.
    pub spindle_reverse: bool,
    /// 1 = a forward count steps the axis down.
    pub axis_reverse: bool,
    /// Ratio numerator n (steps per count = n / d).
    pub numerator: u64,
    /// Ratio denominator d.
    pub denominator: u64,
    /// Rate change per count while ramping, in 1/d step per count.
    pub ramp: u64,
    /// Steps from the index at which the gearbox stops; 0 = no end (taken at the arm).
    pub length: u64,
}

impl GearboxInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.count_up as u64,
            self.count_down as u64,
            self.index as u64,
            self.arm as u64,
            self.stop as u64,
            self.halt as u64,
            self.spindle_reverse as u64,
            self.axis_reverse as u64,
            self.numerator,
            self.denominator,
            self.ramp,
            self.length,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearboxOutputs {
    /// One step of the axis up.
    pub step_up: bool,
    /// One step of the axis down.
    pub step_down: bool,
    /// The phase.
    pub phase: Phase,
    /// Locked: within a step behind pitch x angle, the lag caught up (set
    /// by the first forward count in track that finds it so).
    pub locked: bool,
    /// Sticky: the last run reached its length.
    pub done: bool,
    /// Sticky: an arm was refused.
    pub invalid: bool,
    /// Sticky: a count came while one was in work and another waited (the
    /// gearbox halted).
    pub overrun: bool,
    /// Net forward steps since the arm (the low L bits, two's complement).
    pub position: u64,
}

impl GearboxOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            step_up: v[0] != 0,
            step_down: v[1] != 0,
            phase: Phase::from_code(v[2]),
            locked: v[3] != 0,
            done: v[4] != 0,
            invalid: v[5] != 0,
            overrun: v[6] != 0,
            position: v[7],
        }
    }
}

/// The widths of a gearbox: `W` for the ratio, `L` for the position and
/// the length, `E` for the lag (see the datasheet).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GearboxWidths {
    /// Width of numerator, denominator and ramp.
    pub w: u32,
    /// Width of the lag and its braking distance.
    pub e: u32,
    /// Width of position and length.
    pub l: u32,
}

impl GearboxWidths {
    /// The exported gearbox's: W = 24, E = 40, L = 24.
    pub const EXPORTED: Self = Self {
        w: 24,
        e: 40,
        l: 24,
    };

    /// log2 of the longest ramp in counts: `ramp` << shift must reach n.
    pub fn ramp_shift(&self) -> u32 {
        self.e - self.w - 1
    }

    /// Whether (n, d, ramp) is a ratio the gearbox takes: d >= 1, n <= d,
    /// and ramp = 0 or ramp * 2^(E - W - 1) >= n.
    pub fn valid(&self, n: u64, d: u64, ramp: u64) -> bool {
        d != 0 && n <= d && (ramp == 0 || (ramp as u128) << self.ramp_shift() >= n as u128)
    }
}

/// Whole steps and a fraction of a step in 1/d, 0 <= frac < d: the
/// axis's travel and the ramp-out bound D carry the same way.
#[derive(Clone, Copy, Debug, Default)]
struct Carried {
    whole: i64,
    frac: u64,
}

impl Carried {
    /// Adds `x` <= d; true when a whole step carried.
    fn add(&mut self, x: u64, d: u64) -> bool {
        let t = self.frac + x;
        let carried = t >= d;
        self.frac = if carried { t - d } else { t };
        self.whole += carried as i64;
        carried
    }

    /// Subtracts `x` <= d; true when a whole step was borrowed.
    fn sub(&mut self, x: u64, d: u64) -> bool {
        let borrowed = self.frac < x;
        self.frac = if borrowed {
            self.frac + d - x
        } else {
            self.frac - x
        };
        self.whole -= borrowed as i64;
        borrowed
    }
}

/// The gearbox at the level of counts: each call is one clock of a
/// gearbox that takes a count in one clock (the datasheet's equations).
/// [`GearboxModel`] wraps it in the RTL's timing.
#[derive(Clone, Debug)]
pub struct GearboxCore {
    widths: GearboxWidths,
    phase: Phase,
    command_stop: bool,
    /// Rate, 1/d step per count.
    rate: u64,
    /// Net forward steps since the arm (not wrapped: the length's; the
    /// `position` port is its low L bits) and the fraction of the next.
    travel: Carried,
    /// Lag behind n x counts, 1/d step (signed, E bits).
    lag: i128,
    /// The catch-up's braking distance S, 1/d step (E bits).
    catch_brake: u128,
    /// The ramp-out's distance bound D.
    brake: Carried,
    locked: bool,
    done: bool,
    invalid: bool,
    step_up: bool,
    step_down: bool,
    /// The ratio, ramp, length and directions taken at the arm.
    n: u64,
    d: u64,
    ramp: u64,
    length: u64,
    spindle_reverse: bool,
    axis_reverse: bool,
}

impl GearboxCore {
    /// A gearbox of these widths in its power-up state (idle, all 0).
    pub fn new(widths: GearboxWidths) -> Self {
        Self {
            widths,
            phase: Phase::Idle,
            command_stop: false,
            rate: 0,
            travel: Carried::default(),
            lag: 0,
            catch_brake: 0,
            brake: Carried::default(),
            locked: false,
            done: false,
            invalid: false,
            step_up: false,
            step_down: false,
            n: 0,
            d: 0,
            ramp: 0,
            length: 0,
            spindle_reverse: false,
            axis_reverse: false,
        }
    }

    /// The lag register's E-bit wrap.
    fn wrap_lag(&self, value: i128) -> i128 {
        signed_value(value as u64, self.widths.e) as i128
    }

    fn outputs(&self) -> GearboxOutputs {
        GearboxOutputs {
            step_up: self.step_up,
            step_down: self.step_down,
            phase: self.phase,
            locked: self.locked,
            done: self.done,
            invalid: self.invalid,
            overrun: false,
            position: self.travel.whole as u64 & width_mask(self.widths.l),
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: GearboxInputs) -> GearboxOutputs {
        let w = self.widths;
        let wmask = width_mask(w.w);
        self.step_up = false;
        self.step_down = false;
        if i.reset {
            *self = Self::new(w);
            return self.outputs();
        }
        let net_up = i.count_up && !i.count_down;
        let net_down = i.count_down && !i.count_up;
        let forward = if self.spindle_reverse {
            net_down
        } else {
            net_up
        };
        let backward = if self.spindle_reverse {
            net_up
        } else {
            net_down
        };
        match self.phase {
            Phase::Idle => {
                if i.arm && !i.stop && !i.halt {
                    let (n, d, ramp) = (i.numerator & wmask, i.denominator & wmask, i.ramp & wmask);
                    if w.valid(n, d, ramp) {
                        *self = Self::new(w);
                        self.phase = Phase::Armed;
                        (self.n, self.d, self.ramp) = (n, d, ramp);
                        self.length = i.length & width_mask(w.l);
                        self.spindle_reverse = i.spindle_reverse;
                        self.axis_reverse = i.axis_reverse;
                    } else {
                        self.invalid = true;
                    }
                }
            }
            Phase::Armed => {
                if i.halt || i.stop {
                    self.phase = Phase::Idle;
                } else if i.index {
                    self.phase = Phase::RampIn;
                }
            }
            Phase::RampIn | Phase::Track | Phase::Stopping => {
                if i.halt {
                    self.phase = Phase::Idle;
                    self.rate = 0;
                    self.locked = false;
                } else {
                    self.engaged(i.stop, forward, backward);
                }
            }
        }
        self.outputs()
    }

    fn engaged(&mut self, stop: bool, forward: bool, backward: bool) {
        let (n, d, ramp, axis_reverse) = (self.n, self.d, self.ramp, self.axis_reverse);
        let length = self.length;
        let position = self.travel.whole as i128;
        // The ramp-out's start: the position, the bound on the ramp-out's
        // steps and a margin of 3 reach the length.
        let trigger = length != 0
            && !self.command_stop
            && self.phase.is_tracking()
            && position + self.brake.whole as i128 + 3 >= length as i128;
        let mut phase = if trigger { Phase::Stopping } else { self.phase };
        if stop {
            self.command_stop = true;
            phase = Phase::Stopping;
        }
        let crawl = if ramp == 0 || ramp >= n { n } else { ramp };
        let old = self.rate;
        // The lock: a forward count in track finds the rate at n and the
        // lag caught up (0 <= e < ramp, or 0 with ramp 0).
        let lock_now = forward
            && phase == Phase::Track
            && old == n
            && self.lag >= 0
            && (ramp == 0 || self.lag < ramp as i128);
        let mut end = false;
        if forward {
            let new = match phase {
                Phase::RampIn => {
                    let up = old + ramp;
                    if ramp == 0 || up >= n {
                        n
                    } else {
                        up
                    }
                }
                Phase::Track => {
                    let u = old - n;
                    let s = self.catch_brake;
                    let a = s + u as u128 + ramp as u128;
                    let lag = self.lag;
                    if lag >= 0 && a <= lag as u128 && old + ramp <= d {
                        self.catch_brake = a;
                        old + ramp
                    } else if u == 0 || (lag >= 0 && s <= lag as u128) {
                        old
                    } else {
                        self.catch_brake = s - u as u128;
                        old - ramp
                    }
                }
                _ => {
                    if old <= crawl
                        && (self.command_stop || (length != 0 && position >= length as i128))
                    {
                        end = true;
                        0
                    } else if old >= crawl + ramp {
                        old - ramp
                    } else {
                        crawl
                    }
                }
            };
            if phase.is_tracking() {
                if new > old {
                    self.brake.add(old, d);
                } else if new < old {
                    self.brake.sub(new, d);
                }
                self.lag = self.wrap_lag(self.lag + n as i128 - new as i128);
                if phase == Phase::RampIn && new == n {
                    phase = Phase::Track;
                }
            }
            self.rate = new;
            if self.travel.add(new, d) {
                self.emit(true, axis_reverse);
            }
        } else if backward {
            if phase.is_tracking() {
                self.lag = self.wrap_lag(self.lag - (n as i128 - old as i128));
            }
            if self.travel.sub(old, d) {
                self.emit(false, axis_reverse);
            }
        }
        let reached =
            length != 0 && (self.step_up || self.step_down) && self.travel.whole == length as i64;
        if reached || (end && !self.command_stop) {
            self.done = true;
        }
        self.phase = if end || reached { Phase::Idle } else { phase };
        if self.phase == Phase::Idle {
            self.rate = 0;
        }
        if lock_now {
            self.locked = true;
        }
        if self.phase != Phase::Track {
            self.locked = false;
        }
    }

    fn emit(&mut self, forward: bool, axis_reverse: bool) {
        if forward != axis_reverse {
            self.step_up = true;
        } else {
            self.step_down = true;
        }
    }
}

/// Clocks the engine takes for a count after the clock that takes it:
/// the count's step and its effects show in the outputs after the
/// `ENGINE_CLOCKS`-th edge after the take.
pub const ENGINE_CLOCKS: u32 = 30;

/// Cycle-exact model of [`super::ElectronicGearbox`]: the count-level
/// [`GearboxCore`] in the RTL's timing. The engine takes a count in a
/// clock where it is idle and the gearbox engaged (a pending count first),
/// works on it for [`ENGINE_CLOCKS`] clocks while the outputs hold, and
/// shows its results (and its step) after the last. A count that arrives
/// while it works waits in a slot of one; a second is an overrun (the
/// gearbox halts, `overrun`). A `stop` that arrives while it works is
/// applied at the next clock it is idle. `halt` and `reset` act at once.
#[derive(Clone, Debug)]
pub struct GearboxModel {
    core: GearboxCore,
    /// Clocks until the count in work shows; 0 = idle.
    remaining: u32,
    /// The waiting count: Some(true) = `count_up`.
    pending: Option<bool>,
    stop_request: bool,
    overrun: bool,
    /// The outputs the count in work will show.
    in_work: GearboxOutputs,
    /// The core before the count in work (a halt or an overrun drops it).
    before_take: GearboxCore,
    visible: GearboxOutputs,
}

impl GearboxModel {
    /// A gearbox of these widths in its power-up state.
    pub fn new(widths: GearboxWidths) -> Self {
        Self {
            core: GearboxCore::new(widths),
            remaining: 0,
            pending: None,
            stop_request: false,
            overrun: false,
            in_work: GearboxOutputs::default(),
            before_take: GearboxCore::new(widths),
            visible: GearboxOutputs::default(),
        }
    }

    fn quiet(mut o: GearboxOutputs) -> GearboxOutputs {
        o.step_up = false;
        o.step_down = false;
        o
    }

    fn show(&mut self, o: GearboxOutputs) -> GearboxOutputs {
        self.visible = GearboxOutputs {
            overrun: self.overrun,
            ..o
        };
        self.visible
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: GearboxInputs) -> GearboxOutputs {
        let count = match (i.count_up, i.count_down) {
            (true, false) => Some(true),
            (false, true) => Some(false),
            _ => None,
        };
        let bare = GearboxInputs {
            count_up: false,
            count_down: false,
            ..i
        };
        if i.reset {
            *self = Self::new(self.core.widths);
            return self.visible;
        }
        if i.halt || (self.remaining > 0 && count.is_some() && self.pending.is_some()) {
            if !i.halt {
                self.overrun = true;
            }
            if self.remaining > 0 {
                self.core = self.before_take.clone();
            }
            self.remaining = 0;
            self.pending = None;
            self.stop_request = false;
            let o = self.core.step(GearboxInputs { halt: true, ..bare });
            return self.show(Self::quiet(o));
        }
        if self.remaining > 0 {
            if count.is_some() {
                self.pending = count;
            }
            self.stop_request |= i.stop;
            self.remaining -= 1;
            if self.remaining == 0 {
                let o = self.in_work;
                return self.show(o);
            }
            return self.show(Self::quiet(self.visible));
        }
        let engaged = self.core.phase.is_engaged();
        let take = if engaged {
            match self.pending.take() {
                Some(waiting) => {
                    self.pending = count;
                    Some(waiting)
                }
                None => count,
            }
        } else {
            self.pending = None;
            None
        };
        let stop = i.stop || self.stop_request;
        self.stop_request = false;
        let before = self.core.phase;
        if engaged && take.is_some() {
            self.before_take = self.core.clone();
        }
        let o = self.core.step(GearboxInputs {
            count_up: take == Some(true),
            count_down: take == Some(false),
            stop,
            ..bare
        });
        if before == Phase::Idle && o.phase == Phase::Armed {
            self.overrun = false;
        }
        if engaged && take.is_some() {
            self.remaining = ENGINE_CLOCKS;
            self.in_work = o;
            return self.show(Self::quiet(self.visible));
        }
        self.show(Self::quiet(o))
    }
}

crate::lockstep_model!(GearboxModel {
    inputs: GearboxInputs,
    outputs: GearboxOutputs,
    step: |model, inputs| model.step(*inputs),
});
