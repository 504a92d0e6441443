//! Reference models of [`super::UniformPulseGen`]: the dual-period plan of
//! a period (both pulse orders), the single-period algorithm it replaces,
//! tick-level pulse trains of all three for plots and checks, and a
//! cycle-exact model of the RTL.

/// How the pulses of one interpolation period are laid out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PulsePlan {
    /// T: the period in ticks (even, >= 2).
    pub period: u64,
    /// N: pulses in the period, 0 <= N <= T/2.
    pub count: u64,
    /// Tp1 / 2 = floor(T / 2N): high (and low) ticks of a short pulse.
    pub half: u64,
    /// N1 = (N * Tp2 - T) / 2: short pulses.
    pub short_pulses: u64,
    /// N2 = (T - N * Tp1) / 2: long pulses (Tp2 = Tp1 + 2).
    pub long_pulses: u64,
    /// The (T, N) asked for, before correction.
    pub requested: (u64, u64),
}

impl PulsePlan {
    /// The plan for a requested (T, N), with the bad-input rules of the
    /// datasheet applied: an odd T is rounded down to even, a T below 2
    /// becomes 2, and N above T/2 is clamped to T/2. The flag tells whether
    /// any rule applied (`overrange`).
    pub fn new(period: u64, count: u64) -> (Self, bool) {
        let period = period & 0xffff_ffff;
        let count = count & 0xffff_ffff;
        let t = (period & !1).max(2);
        let half_t = t / 2;
        let n = count.min(half_t);
        let plan = if n == 0 {
            Self {
                period: t,
                requested: (period, count),
                ..Default::default()
            }
        } else {
            Self {
                period: t,
                count: n,
                half: half_t / n,
                short_pulses: n - half_t % n,
                long_pulses: half_t % n,
                requested: (period, count),
            }
        };
        let overrange = plan.period_corrected() || plan.count_clamped();
        (plan, overrange)
    }

    /// The requested T was odd or below 2, and was corrected.
    pub fn period_corrected(&self) -> bool {
        self.requested.0 != self.period
    }

    /// The requested N was above the corrected T/2, and was clamped.
    pub fn count_clamped(&self) -> bool {
        self.requested.1 != self.count
    }

    /// Tp1, the short pulse period in ticks (0 when N = 0).
    pub fn short_period(&self) -> u64 {
        2 * self.half
    }

    /// Whether pulse `i` (0-based) of the period is a long one: in paper
    /// order all N1 short pulses come first; interleaved, pulse i is long
    /// when floor((i + 1) * N2 / N) steps up (Bresenham over the index).
    pub fn is_long(&self, i: u64, interleaved: bool) -> bool {
        if interleaved {
            (i + 1) * self.long_pulses / self.count > i * self.long_pulses / self.count
        } else {
            i >= self.short_pulses
        }
    }

    /// The output level on each tick of the period (dual-period algorithm).
    pub fn train(&self, interleaved: bool) -> Vec<bool> {
        let mut levels = Vec::with_capacity(self.period as usize);
        for i in 0..self.count {
            let half = self.half + self.is_long(i, interleaved) as u64;
            levels.extend(std::iter::repeat_n(true, half as usize));
            levels.extend(std::iter::repeat_n(false, half as usize));
        }
        // N = 0: the whole period low.
        levels.resize(self.period as usize, false);
        levels
    }
}

/// The single-period algorithm the dual-period one replaces: N pulses of
/// Tp = 2 * floor(T / 2N) ticks, then idle until the period ends.
pub fn single_period_train(period: u64, count: u64) -> Vec<bool> {
    let (plan, _) = PulsePlan::new(period, count);
    let mut levels = Vec::with_capacity(plan.period as usize);
    for _ in 0..plan.count {
        levels.extend(std::iter::repeat_n(true, plan.half as usize));
        levels.extend(std::iter::repeat_n(false, plan.half as usize));
    }
    levels.resize(plan.period as usize, false);
    levels
}

/// The unevenness of the single-period algorithm, mu = 1 - N * Tp / T:
/// the share of the period left idle.
pub fn single_period_unevenness(period: u64, count: u64) -> f64 {
    let (plan, _) = PulsePlan::new(period, count);
    1.0 - (plan.count * plan.short_period()) as f64 / plan.period as f64
}

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UniformPulseGenInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Time base.
    pub tick: bool,
    /// T.
    pub period: u64,
    /// N.
    pub count: u64,
    /// false = paper order, true = interleaved.
    pub mode: bool,
    /// Queue (period, count, mode).
    pub load: bool,
    /// Clear the sticky flags.
    pub clear_flags: bool,
}

impl UniformPulseGenInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.tick as u64,
            self.period,
            self.count,
            self.mode as u64,
            self.load as u64,
            self.clear_flags as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UniformPulseGenOutputs {
    /// The pulse train.
    pub pulse: bool,
    /// One-clock strobe at the end of each period.
    pub period_done: bool,
    /// The next-period slot is free.
    pub ready: bool,
    /// A period is running.
    pub running: bool,
    /// Sticky: a period ended with no next period ready.
    pub underrun: bool,
    /// Sticky: an odd or too small T, or N > T/2, was corrected.
    pub overrange: bool,
    /// Sticky: a load arrived while `ready` was low and was ignored.
    pub overflow: bool,
}

impl UniformPulseGenOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            pulse: v[0] != 0,
            period_done: v[1] != 0,
            ready: v[2] != 0,
            running: v[3] != 0,
            underrun: v[4] != 0,
            overrange: v[5] != 0,
            overflow: v[6] != 0,
        }
    }
}

/// Clocks from the edge that accepts a load to the edge after which the
/// slot is complete, for a `width`-bit generator (a check and a correction
/// clock, the `width`-clock plan and its start clock, and two spare
/// clocks): a
/// period loaded at edge L can start at the first tick edge after
/// L + `load_to_ready(width)`.
pub const fn load_to_ready(width: u32) -> u32 {
    width + 6
}

/// Clocks from the edge at which the slot takes its plan (and flags a
/// clamped N) to the edge after which it is complete.
const PLAN_TO_READY: u32 = 2;

/// [`load_to_ready`] of the exported 32-bit generator.
pub const LOAD_TO_READY: u32 = load_to_ready(32);

#[derive(Clone, Copy, Debug, Default)]
struct Current {
    plan: PulsePlan,
    interleaved: bool,
    ticks_left: u64,
    /// Tick edges left in the current half pulse (1: it ends at the next).
    half_left: u64,
    pulse_index: u64,
    long: bool,
}

/// Cycle-exact model of a `uniform_pulse_gen` (32-bit by default).
#[derive(Clone, Debug)]
pub struct UniformPulseGenModel {
    /// Port width mask.
    mask: u64,
    /// [`load_to_ready`] of this width.
    load_to_ready: u32,
    /// The queued period and the clocks until it is computed.
    slot: Option<(PulsePlan, bool, u32)>,
    current: Option<Current>,
    out: UniformPulseGenOutputs,
}

impl Default for UniformPulseGenModel {
    fn default() -> Self {
        Self::new()
    }
}

impl UniformPulseGenModel {
    /// A 32-bit generator in its power-up state.
    pub fn new() -> Self {
        Self::with_width(32)
    }

    /// A `width`-bit generator (4 to 32) in its power-up state.
    pub fn with_width(width: u32) -> Self {
        Self {
            mask: crate::blocks::width_mask(width),
            load_to_ready: load_to_ready(width),
            slot: None,
            current: None,
            out: UniformPulseGenOutputs {
                ready: true,
                ..Default::default()
            },
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: UniformPulseGenInputs) -> UniformPulseGenOutputs {
        // A divider of its own is always idle when the slot asks.
        self.step_with_divider(i, true)
    }

    /// The slot waits for its division: T/2 / N starts at the next edge
    /// if the divider is granted then ([`super::UniformPulseCore`]'s
    /// `div_request`, before its division has started).
    pub fn wants_division(&self) -> bool {
        matches!(self.slot, Some((_, _, left)) if left == self.load_to_ready - 2)
    }

    /// One rising clock edge of a [`super::UniformPulseCore`] whose
    /// division port is answered by a divider shared with others: `granted`
    /// tells whether its division starts at this edge (it waits while
    /// [`Self::wants_division`] and not granted). Its result comes `width`
    /// clocks later, as from a divider of its own.
    pub fn step_with_divider(
        &mut self,
        i: UniformPulseGenInputs,
        granted: bool,
    ) -> UniformPulseGenOutputs {
        if i.reset {
            *self = Self::with_width(self.mask.count_ones());
            return self.out;
        }
        // A waiting slot is never full, so the start below leaves it.
        let waits_for_division = self.wants_division();
        // Sticky flags: a clear and a new event on the same clock leave the
        // flag set (the event is not lost).
        if i.clear_flags {
            self.out.underrun = false;
            self.out.overrange = false;
            self.out.overflow = false;
        }
        let slot_full = matches!(self.slot, Some((_, _, 0)));
        let was_ready = self.slot.is_none();
        let mut start = false;
        self.out.period_done = false;
        if i.tick {
            match &mut self.current {
                Some(c) if c.ticks_left == 1 => {
                    // The period's T ticks have elapsed; the last pulse
                    // ends on this same edge.
                    assert!(c.plan.count == 0 || (!self.out.pulse && c.half_left == 1));
                    self.out.period_done = true;
                    if slot_full {
                        start = true;
                    } else {
                        self.current = None;
                        self.out.underrun = true;
                    }
                }
                Some(c) => {
                    c.ticks_left -= 1;
                    if c.plan.count > 0 {
                        if c.half_left == 1 {
                            if self.out.pulse {
                                self.out.pulse = false;
                            } else {
                                c.pulse_index += 1;
                                c.long = c.plan.is_long(c.pulse_index, c.interleaved);
                                self.out.pulse = true;
                            }
                            c.half_left = c.plan.half + c.long as u64;
                        } else {
                            c.half_left -= 1;
                        }
                    }
                }
                None => start = slot_full,
            }
        }
        if start {
            let (plan, interleaved, _) = self.slot.take().expect("a full slot");
            self.current = Some(Current {
                plan,
                interleaved,
                ticks_left: plan.period,
                half_left: plan.half,
                pulse_index: 0,
                long: false,
            });
            self.out.pulse = plan.count > 0;
        }
        if let Some((plan, _, left)) = &mut self.slot {
            if *left == self.load_to_ready - 1 {
                // The correction of T, two clocks after the load.
                self.out.overrange |= plan.period_corrected();
            }
            if *left == PLAN_TO_READY + 1 {
                // The plan arrives: N above the corrected T/2 was clamped.
                self.out.overrange |= plan.count_clamped();
            }
            if !waits_for_division || granted {
                *left = left.saturating_sub(1);
            }
        }
        if i.load {
            if was_ready {
                let (period, count) = (i.period & self.mask, i.count & self.mask);
                let (mut plan, _) = PulsePlan::new(period, count);
                plan.requested = (period, count);
                self.slot = Some((plan, i.mode, self.load_to_ready));
            } else {
                self.out.overflow = true;
            }
        }
        if self.current.is_none() {
            self.out.pulse = false;
        }
        self.out.ready = self.slot.is_none();
        self.out.running = self.current.is_some();
        self.out
    }
}

crate::lockstep_model!(UniformPulseGenModel {
    inputs: UniformPulseGenInputs,
    outputs: UniformPulseGenOutputs,
    step: |model, inputs| model.step(*inputs),
});
