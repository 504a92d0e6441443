//! `DacInterface`: RTL against the model in lockstep, and an independent
//! monitor at the pins built on a behavioral bank of AD669s (two latch
//! ranks each, the seed's truth table), shown by mutation to catch broken
//! traces; directed tests of the datasheet's timing, deferral, abort and
//! reset; cross-simulation.

use motion_hdl::blocks::dac_interface::model::{DacInputs, DacModel, DacOutputs};
use motion_hdl::blocks::dac_interface::registers::{
    field_of, register_map, ADDRESS_BITS, CODE_BASE,
};
use motion_hdl::blocks::dac_interface::{safe_latency, DacInterface, DacInterface3};
use motion_hdl::blocks::width_mask;
use motion_hdl::regmap::RegisterMap;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn address(map: &RegisterMap, name: &str) -> u64 {
    map.register(name).unwrap().address as u64
}

/// Random traffic: code writes (some wider than W), update pulses and
/// `UPDATE` writes, rare format and timing changes, W1C clears, reads of
/// every address, hardware loads, aborts held for a while, rare resets. Clock 0 is a reset.
struct Traffic {
    rng: StdRng,
    map: RegisterMap,
    channels: usize,
    width: usize,
    abort_left: u32,
}

impl Traffic {
    fn new(seed: u64, channels: usize, width: usize) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            map: register_map(channels, width).unwrap(),
            channels,
            width,
            abort_left: 0,
        }
    }

    fn timing_word(&mut self) -> u64 {
        let mut word = 0;
        for lsb in [0, 8, 16, 24] {
            let value = if self.rng.gen_ratio(1, 10) {
                self.rng.gen_range(0..40)
            } else {
                self.rng.gen_range(0..7)
            };
            word |= value << lsb;
        }
        word
    }

    fn next(&mut self, clock: u64) -> DacInputs {
        let rng = &mut self.rng;
        let mut i = DacInputs {
            reset: clock == 0 || rng.gen_ratio(1, 200_000),
            bus_address: rng.gen_range(0..1 << ADDRESS_BITS),
            update: rng.gen_ratio(1, 40),
            ..Default::default()
        };
        if self.abort_left > 0 {
            self.abort_left -= 1;
            i.force_safe = true;
        } else if rng.gen_ratio(1, 3000) {
            self.abort_left = rng.gen_range(1..400);
            i.force_safe = true;
        }
        match rng.gen_range(0..100) {
            0..=11 => {
                i.bus_write = true;
                i.bus_address = CODE_BASE as u64 + rng.gen_range(0..self.channels as u64);
                i.bus_write_data = if rng.gen_ratio(1, 20) {
                    rng.gen::<u32>() as u64
                } else {
                    rng.gen_range(0..1 << 16)
                };
            }
            12..=13 => {
                i.bus_write = true;
                i.bus_address = address(&self.map, "UPDATE");
                i.bus_write_data = rng.gen_range(0..4);
            }
            14 => {
                i.bus_write = true;
                i.bus_address = address(&self.map, "STATUS");
                i.bus_write_data = rng.gen::<u32>() as u64;
            }
            15 if rng.gen_ratio(1, 20) => {
                i.bus_write = true;
                i.bus_address = address(&self.map, "CONTROL");
                i.bus_write_data = rng.gen_range(0..2);
            }
            16 if rng.gen_ratio(1, 40) => {
                i.bus_write = true;
                i.bus_address = address(&self.map, "TIMING");
                i.bus_write_data = self.timing_word();
            }
            17 if i.bus_address != address(&self.map, "TIMING") => {
                // Any other address, any data (read-only and unused
                // addresses ignore it).
                i.bus_write = true;
                i.bus_write_data = rng.gen::<u32>() as u64;
            }
            18..=40 => i.bus_read = true,
            _ => {}
        }
        // The hardware load port, alone or beside a bus write.
        if self.rng.gen_ratio(1, 25) {
            i.load = self.rng.gen_range(1..1 << self.channels);
            i.load_code = self.rng.gen_range(0..1 << self.width);
        }
        i
    }
}

/// One AD669 of the bank: CS and L1 both low make the first rank
/// transparent; LDAC high makes the second rank (the output) transparent.
#[derive(Clone, Copy, Debug, Default)]
struct Ad669 {
    first: Option<u64>,
    second: Option<u64>,
    written_since_ldac: bool,
}

/// The contract at the pins, from the datasheet only: a bank of AD669s on
/// the block's pins, and the register writes it sees on the bus. Fed one
/// clock at a time (that clock's inputs, and the pins after its edge).
struct Ad669Monitor {
    map: RegisterMap,
    channels: usize,
    width: u32,
    chips: Vec<Ad669>,
    clock: u64,
    /// Every staged code vector and format since the last LDAC rise, and
    /// TIMING words of the last few thousand clocks, with their clocks.
    staged: Vec<u64>,
    staged_history: Vec<(Vec<u64>, bool)>,
    offset_binary: bool,
    timing: Vec<(u64, u64)>,
    abort_prev: bool,
    /// Clocks of aborts and resets still waiting for 0 V at the outputs.
    safe_due: Vec<u64>,
    /// An abort or reset since the last all-zero LDAC: its safe update
    /// may still come (after the outputs are 0 V already).
    safe_owed: bool,
    prev: Option<DacOutputs>,
    same_for: u64,
    l1_low_for: u64,
    ldac_high_for: u64,
    since_l1_rise: u64,
    /// Figures, for the caller.
    updates: u64,
    safe_updates: u64,
    worst_safe_latency: u64,
}

impl Ad669Monitor {
    fn new(channels: usize, width: usize) -> Self {
        let map = register_map(channels, width).unwrap();
        let timing_reset = map.register("TIMING").unwrap().reset_value() as u64;
        Self {
            map,
            channels,
            width: width as u32,
            chips: vec![Ad669::default(); channels],
            clock: 0,
            staged: vec![0; channels],
            staged_history: vec![(vec![0; channels], false)],
            offset_binary: false,
            timing: vec![(0, timing_reset)],
            abort_prev: false,
            safe_due: Vec::new(),
            safe_owed: false,
            prev: None,
            same_for: 0,
            l1_low_for: 0,
            ldac_high_for: 0,
            since_l1_rise: u64::MAX,
            updates: 0,
            safe_updates: 0,
            worst_safe_latency: 0,
        }
    }

    /// TIMING fields (0 acting as 1) over the words in effect in the last
    /// `span` clocks: the floor (element-wise least) or ceiling.
    fn timing_bound(&self, span: u64, floor: bool) -> [u64; 4] {
        let from = self.clock.saturating_sub(span);
        let mut words: Vec<u64> = self
            .timing
            .iter()
            .filter(|(c, _)| *c >= from)
            .map(|(_, w)| *w)
            .collect();
        if let Some((_, w)) = self.timing.iter().rev().find(|(c, _)| *c < from) {
            words.push(*w);
        }
        let mut bound = [if floor { u64::MAX } else { 0 }; 4];
        let fields = ["SETUP", "WIDTH", "HOLD", "LDAC_WIDTH"]
            .map(|name| field_of(&self.map, "TIMING", name).clone());
        for word in words {
            for (field, b) in fields.iter().zip(bound.iter_mut()) {
                let v = field.extract(word as u32).unwrap().max(1);
                *b = if floor { (*b).min(v) } else { (*b).max(v) };
            }
        }
        bound
    }

    /// Every second rank holds 0 V in a format of the recent history.
    fn outputs_safe(&self) -> bool {
        let formats = [false, true];
        formats.iter().any(|&f| {
            self.staged_history.iter().any(|(_, hf)| *hf == f)
                && self
                    .chips
                    .iter()
                    .all(|c| c.second.map(|p| self.decode(p, f)) == Some(0))
        })
    }

    fn decode(&self, pins: u64, offset_binary: bool) -> u64 {
        pins ^ if offset_binary {
            1 << (self.width - 1)
        } else {
            0
        }
    }

    fn registers(&mut self, i: &DacInputs) {
        let code_mask = field_of(&self.map, "CODE", "VALUE").mask() as u64;
        if i.reset {
            self.staged = vec![0; self.channels];
            self.offset_binary = false;
            self.timing.push((
                self.clock,
                self.map.register("TIMING").unwrap().reset_value() as u64,
            ));
            self.safe_due = vec![self.clock];
            self.safe_owed = true;
            self.abort_prev = false;
            self.staged_history
                .push((self.staged.clone(), self.offset_binary));
            return;
        }
        if i.bus_write {
            let a = i.bus_address;
            if a == address(&self.map, "CONTROL") {
                self.offset_binary = field_of(&self.map, "CONTROL", "OFFSET_BINARY")
                    .extract(i.bus_write_data as u32)
                    .unwrap()
                    != 0;
            } else if a == address(&self.map, "TIMING") {
                self.timing.push((self.clock, i.bus_write_data));
            } else if (CODE_BASE as u64..CODE_BASE as u64 + self.channels as u64).contains(&a)
                && !i.force_safe
            {
                self.staged[(a - CODE_BASE as u64) as usize] = i.bus_write_data & code_mask;
            }
        }
        if !i.force_safe {
            for c in 0..self.channels {
                if i.load >> c & 1 == 1 {
                    self.staged[c] = i.load_code & code_mask;
                }
            }
        }
        if i.force_safe && !self.abort_prev {
            self.staged = vec![0; self.channels];
            self.safe_due.push(self.clock);
            self.safe_owed = true;
        }
        self.abort_prev = i.force_safe;
        let now = (self.staged.clone(), self.offset_binary);
        if self.staged_history.last() != Some(&now) {
            self.staged_history.push(now);
        }
    }

    fn step(&mut self, i: &DacInputs, o: &DacOutputs) -> Result<(), String> {
        self.clock += 1;
        let clock = self.clock;
        self.registers(i);
        if i.reset {
            // The one input that may cut a pulse: the pins go idle at once
            // and the safe update rewrites every first rank before its LDAC.
            self.prev = Some(*o);
            self.same_for = 1;
            self.l1_low_for = 0;
            self.ldac_high_for = 0;
            self.since_l1_rise = u64::MAX;
            for chip in &mut self.chips {
                chip.written_since_ldac = false;
            }
            return Ok(());
        }
        let [setup, width, hold, ldac_width] = self.timing_bound(4000, true);
        let prev = self.prev.unwrap_or(DacOutputs {
            dac_cs_n: width_mask(self.channels as u32),
            dac_l1_n: true,
            ..*o
        });
        let l1 = !o.dac_l1_n;
        let was_l1 = !prev.dac_l1_n;
        let bus_changed = o.dac_data != prev.dac_data || o.dac_cs_n != prev.dac_cs_n;

        if (!o.dac_cs_n & width_mask(self.channels as u32)).count_ones() > 1 {
            return Err(format!(
                "clock {clock}: more than one chip selected: {:#b}",
                o.dac_cs_n
            ));
        }
        // Setup, width and hold of the first-rank writes.
        let l1_rose = !l1 && was_l1;
        self.since_l1_rise = if l1_rose {
            0
        } else {
            self.since_l1_rise.saturating_add(1)
        };
        if bus_changed {
            if l1 && was_l1 {
                return Err(format!(
                    "clock {clock}: data or CS changed while L1 was low"
                ));
            }
            if self.since_l1_rise < hold {
                return Err(format!(
                    "clock {clock}: data or CS changed {} clocks after L1 rose (hold {hold})",
                    self.since_l1_rise
                ));
            }
        }
        if l1 && !was_l1 && (self.same_for < setup || bus_changed) {
            return Err(format!(
                "clock {clock}: L1 fell {} clocks after data and CS settled (setup {setup})",
                self.same_for
            ));
        }
        if !l1 && was_l1 && self.l1_low_for < width {
            return Err(format!(
                "clock {clock}: L1 low for {} clocks (width {width})",
                self.l1_low_for
            ));
        }
        self.same_for = if bus_changed { 1 } else { self.same_for + 1 };
        self.l1_low_for = if l1 { self.l1_low_for + 1 } else { 0 };

        // The LDAC pulse: only with every first-rank write complete.
        if o.dac_ldac && (o.dac_cs_n != width_mask(self.channels as u32) || l1) {
            return Err(format!(
                "clock {clock}: LDAC high during a first-rank write"
            ));
        }
        if !o.dac_ldac && prev.dac_ldac && self.ldac_high_for < ldac_width {
            return Err(format!(
                "clock {clock}: LDAC high for {} clocks (width {ldac_width})",
                self.ldac_high_for
            ));
        }
        self.ldac_high_for = if o.dac_ldac {
            self.ldac_high_for + 1
        } else {
            0
        };

        // The bank: first ranks, then second ranks.
        for (k, chip) in self.chips.iter_mut().enumerate() {
            if o.dac_cs_n & (1 << k) == 0 && l1 {
                chip.first = Some(o.dac_data);
                chip.written_since_ldac = true;
            }
        }
        let ldac_rise = o.dac_ldac && !prev.dac_ldac;
        if ldac_rise {
            self.check_ldac_codes()?;
        }
        for chip in self.chips.iter_mut() {
            if o.dac_ldac {
                chip.second = chip.first;
            }
        }
        // An abort or reset is served once every output holds 0 V.
        if !self.safe_due.is_empty() && self.outputs_safe() {
            self.worst_safe_latency = self.worst_safe_latency.max(clock - self.safe_due[0]);
            self.safe_updates += 1;
            self.safe_due.clear();
        }
        if ldac_rise {
            self.next_update();
        }
        // The oldest due is the first to run out.
        if let Some(&due) = self.safe_due.first() {
            let [s, w, h, l] = self.timing_bound(4000, false);
            let limit = safe_latency(self.channels as u64, s, w, h, l);
            if clock - due > limit {
                return Err(format!(
                    "clock {clock}: no safe LDAC {} clocks after the abort or reset of clock {due}",
                    clock - due
                ));
            }
        }
        self.prev = Some(*o);
        Ok(())
    }

    /// Every chip was written since the last LDAC, and the codes are one
    /// staged set (from a single clock) in one format, or all 0 for a
    /// pending safe update.
    fn check_ldac_codes(&mut self) -> Result<(), String> {
        let clock = self.clock;
        if let Some(k) = self.chips.iter().position(|c| !c.written_since_ldac) {
            return Err(format!(
                "clock {clock}: LDAC without a first-rank write of channel {k} since the last"
            ));
        }
        let pins: Vec<u64> = self.chips.iter().map(|c| c.first.unwrap()).collect();
        let decoded =
            |offset: bool| -> Vec<u64> { pins.iter().map(|&p| self.decode(p, offset)).collect() };
        let formats: Vec<bool> = self.staged_history.iter().map(|(_, f)| *f).collect();
        let all_zero = formats.iter().any(|&f| decoded(f).iter().all(|&c| c == 0));
        if self.safe_due.iter().any(|&due| due < clock) {
            if !all_zero {
                return Err(format!(
                    "clock {clock}: LDAC of {pins:x?} while the safe code is due"
                ));
            }
        } else if all_zero && self.safe_owed {
            // The safe update of an abort whose outputs were already 0.
        } else if !self
            .staged_history
            .iter()
            .any(|(codes, f)| &decoded(*f) == codes)
        {
            return Err(format!(
                "clock {clock}: LDAC of {pins:x?}, which is no staged set of codes"
            ));
        }
        if all_zero {
            self.safe_owed = false;
        }
        Ok(())
    }

    /// After an LDAC rise: the next update's window starts.
    fn next_update(&mut self) {
        let clock = self.clock;
        self.updates += 1;
        for chip in &mut self.chips {
            chip.written_since_ldac = false;
        }
        let last = self.staged_history.last().unwrap().clone();
        self.staged_history = vec![last];
        let from = clock.saturating_sub(8000);
        if let Some(keep) = self.timing.iter().rposition(|(c, _)| *c < from) {
            self.timing.drain(..keep);
        }
    }
}

/// RTL and model in lockstep on `cycles` clocks of [`Traffic`], the pins
/// watched by the monitor. Returns the monitor for its figures.
fn lockstep<const K: usize, const W: usize>(seed: u64, cycles: u64) -> Ad669Monitor {
    let mut pair = Lockstep::harness(
        "dac_interface",
        DacInterface::<K, W>::default(),
        DacModel::new(K, W),
    );
    let mut traffic = Traffic::new(seed, K, W);
    let mut monitor = Ad669Monitor::new(K, W);
    let mut recent = std::collections::VecDeque::new();
    let stimulus = |clock, _: &DacModel| (clock < cycles).then(|| traffic.next(clock));
    let observe = |clock, inputs: &DacInputs, out: &DacOutputs| {
        let (inputs, out) = (*inputs, *out);
        recent.push_back((clock, inputs, out));
        if recent.len() > 120 {
            recent.pop_front();
        }
        if let Err(e) = monitor.step(&inputs, &out) {
            for (c, i, o) in &recent {
                eprintln!(
                    "{c:>7} rst {} a {:x} w {} r {} d {:8x} upd {} safe_in {} | data {:4x} cs {:04b} l1 {} ldac {} busy {} safe {}",
                    i.reset as u8, i.bus_address, i.bus_write as u8, i.bus_read as u8, i.bus_write_data,
                    i.update as u8, i.force_safe as u8, o.dac_data, o.dac_cs_n, o.dac_l1_n as u8, o.dac_ldac as u8,
                    o.busy as u8, o.safe as u8
                );
            }
            panic!("monitor: {e}");
        }
    };
    pair.run(stimulus, observe)
        .unwrap_or_else(|e| panic!("{e}"));
    monitor
}

#[test]
fn rtl_matches_model_and_the_ad669_bank_for_a_million_clocks() {
    let monitor = lockstep::<3, 16>(0xdac1, 1_000_000);
    println!(
        "{} LDACs, {} of them safe updates; worst abort-to-safe-LDAC {} clocks",
        monitor.updates, monitor.safe_updates, monitor.worst_safe_latency
    );
    assert!(monitor.updates > 15_000, "{} updates", monitor.updates);
    assert!(
        monitor.safe_updates > 200,
        "{} safe updates",
        monitor.safe_updates
    );
}

#[test]
fn the_12_bit_four_channel_build_matches_its_model() {
    let monitor = lockstep::<4, 12>(0xdac2, 200_000);
    assert!(monitor.updates > 2000, "{} updates", monitor.updates);
}

/// One clock of inputs and the pins after its edge.
type Trace = Vec<(DacInputs, DacOutputs)>;

fn record(seed: u64, cycles: u64) -> Trace {
    let mut rtl = Harness::new("dac_interface", DacInterface3::default()).unwrap();
    let mut traffic = Traffic::new(seed, 3, 16);
    (0..cycles)
        .map(|clock| {
            let inputs = traffic.next(clock);
            let out = DacOutputs::from_vector(&rtl.step_vector(&inputs.to_vector()).unwrap());
            (inputs, out)
        })
        .collect()
}

fn watch(trace: &Trace) -> Result<(), String> {
    let mut monitor = Ad669Monitor::new(3, 16);
    trace.iter().try_for_each(|(i, o)| monitor.step(i, o))
}

/// Index of the first clock after `from` where `edge(before, after)`.
fn find(trace: &Trace, from: usize, edge: impl Fn(&DacOutputs, &DacOutputs) -> bool) -> usize {
    (from.max(1)..trace.len())
        .find(|&t| edge(&trace[t - 1].1, &trace[t].1))
        .expect("edge in the trace")
}

/// The monitor is not a test that cannot fail: each broken trace (a
/// mutation of a real RTL trace) is caught, each with its own rule.
#[test]
fn the_ad669_monitor_catches_each_broken_rule() {
    let clean = record(0xdac3, 40_000);
    watch(&clean).expect("the RTL's own trace is clean");
    // The first update out of reset is the safe update at the reset timing.
    let l1_fall = find(&clean, 1, |a, b| a.dac_l1_n && !b.dac_l1_n);
    let l1_rise = find(&clean, l1_fall, |a, b| !a.dac_l1_n && b.dac_l1_n);
    let next_channel = find(&clean, l1_rise, |a, b| a.dac_cs_n != b.dac_cs_n);
    let ldac = find(&clean, 1, |a, b| !a.dac_ldac && b.dac_ldac);
    let abort = (1..clean.len())
        .find(|&t| clean[t].0.force_safe && !clean[t - 1].0.force_safe && t > ldac)
        .unwrap();
    let safe_ldac = find(&clean, abort + 1, |a, b| !a.dac_ldac && b.dac_ldac);
    let write_start = find(&clean, safe_ldac + 100, |a, b| {
        a.dac_cs_n == 0b111 && b.dac_cs_n == 0b110
    });

    let mut mutants: Vec<(&str, Trace, &str)> = Vec::new();
    let mut short_l1 = clean.clone();
    short_l1[l1_rise - 1].1.dac_l1_n = true;
    mutants.push(("L1 pulse a clock short", short_l1, "L1 low for"));
    let mut no_hold = clean.clone();
    let new_data = clean[next_channel].1.dac_data ^ 0x5a5a;
    no_hold[next_channel - 1].1.dac_data = new_data;
    mutants.push((
        "data changed a clock into the hold",
        no_hold,
        "after L1 rose",
    ));
    let mut early_ldac = clean.clone();
    early_ldac[ldac - 1].1.dac_ldac = true;
    mutants.push((
        "LDAC a clock early",
        early_ldac,
        "LDAC high during a first-rank write",
    ));
    let mut two_selected = clean.clone();
    two_selected[l1_fall].1.dac_cs_n &= !0b100;
    mutants.push(("two chips selected", two_selected, "more than one chip"));
    let mut torn = clean.clone();
    let mut t = write_start;
    while torn[t].1.dac_cs_n == 0b110 {
        torn[t].1.dac_data ^= 0x0100;
        t += 1;
    }
    mutants.push(("channel 0 given another code", torn, "no staged set"));
    let mut no_safe = clean.clone();
    let mut t = safe_ldac;
    while no_safe[t].1.dac_ldac {
        no_safe[t].1.dac_ldac = false;
        t += 1;
    }
    mutants.push(("the safe update's LDAC dropped", no_safe, "safe"));
    for (what, trace, rule) in mutants {
        let error = watch(&trace).expect_err(what);
        assert!(error.contains(rule), "{what}: caught, but as `{error}`");
    }
}

/// The exported build, clock by clock in lockstep with its model, driven
/// by register name.
struct Bench {
    rtl: Harness<DacInterface3>,
    model: DacModel,
    map: RegisterMap,
    /// The level of `force_safe` for the next clocks.
    force_safe: bool,
    last: DacOutputs,
    clock: u64,
}

impl Bench {
    /// Out of reset, with its safe update done.
    fn new() -> Self {
        let mut b = Self {
            rtl: Harness::new("dac_interface", DacInterface3::default()).unwrap(),
            model: DacModel::new(3, 16),
            map: register_map(3, 16).unwrap(),
            force_safe: false,
            last: DacOutputs::default(),
            clock: 0,
        };
        b.clock(DacInputs {
            reset: true,
            ..Default::default()
        });
        b.idle_until_quiet();
        b
    }

    fn clock(&mut self, mut inputs: DacInputs) -> DacOutputs {
        inputs.force_safe |= self.force_safe;
        let out = DacOutputs::from_vector(&self.rtl.step_vector(&inputs.to_vector()).unwrap());
        assert_eq!(
            out,
            self.model.step(inputs),
            "clock {}: RTL against the model",
            self.clock
        );
        self.clock += 1;
        self.last = out;
        out
    }

    fn idle(&mut self) -> DacOutputs {
        self.clock(DacInputs::default())
    }

    fn idle_until_quiet(&mut self) {
        while self.idle().busy {}
    }

    fn write(&mut self, name: &str, index: u32, value: u64) {
        let address = self.map.address_of(name, index).unwrap() as u64;
        self.clock(DacInputs {
            bus_address: address,
            bus_write_data: value,
            bus_write: true,
            ..Default::default()
        });
    }

    fn read(&mut self, name: &str, index: u32) -> u64 {
        let address = self.map.address_of(name, index).unwrap() as u64;
        self.clock(DacInputs {
            bus_address: address,
            bus_read: true,
            ..Default::default()
        });
        self.idle().bus_read_data
    }

    fn status(&mut self, field: &str) -> u64 {
        let word = self.read("STATUS", 0);
        field_of(&self.map, "STATUS", field)
            .extract(word as u32)
            .unwrap()
    }

    /// Pulses `update` and returns the pins of the clocks until the
    /// update's LDAC has fallen, starting with the request's clock.
    fn update(&mut self) -> Vec<DacOutputs> {
        let mut pins = vec![self.clock(DacInputs {
            update: true,
            ..Default::default()
        })];
        while self.last.busy {
            pins.push(self.idle());
        }
        pins
    }
}

/// The edges of an update at the reset timing, as the datasheet's table
/// states them, and APPLIED reads back the codes.
#[test]
fn an_update_follows_the_datasheet_edges_at_the_reset_timing() {
    let mut b = Bench::new();
    let codes = [0x1234, 0x8001, 0xffff];
    for (k, code) in codes.iter().enumerate() {
        b.write("CODE", k as u32, *code);
    }
    let pins = b.update();
    let (s, w, h, l) = (1, 5, 2, 5);
    let edge = |what: &dyn Fn(&DacOutputs) -> bool| pins.iter().position(what).unwrap();
    for (k, code) in codes.iter().enumerate() {
        let start = 1 + k * (s + w + h);
        assert_eq!(
            edge(&|p: &DacOutputs| p.dac_cs_n == 0b111 ^ (1 << k)),
            start,
            "channel {k}: CS falls"
        );
        assert_eq!(pins[start].dac_data, *code, "channel {k}: data");
        let l1 = (start..).find(|&t| !pins[t].dac_l1_n).unwrap();
        assert_eq!(l1, start + s, "channel {k}: L1 falls");
        assert_eq!(
            (l1..).find(|&t| pins[t].dac_l1_n).unwrap(),
            l1 + w,
            "channel {k}: L1 rises"
        );
        let deselect = (start..)
            .find(|&t| pins[t].dac_cs_n & (1 << k) != 0)
            .unwrap();
        assert_eq!(deselect, start + s + w + h, "channel {k}: CS rises");
    }
    let ldac = edge(&|p: &DacOutputs| p.dac_ldac);
    assert_eq!(ldac, 1 + 3 * (s + w + h), "LDAC rises");
    assert_eq!(
        pins.len(),
        ldac + l + 1,
        "LDAC high {l} clocks, then busy falls with it"
    );
    assert_eq!(
        pins.len() - 1,
        30,
        "the update's length at the reset timing"
    );
    for (k, code) in codes.iter().enumerate() {
        assert_eq!(b.read("APPLIED", k as u32), *code, "APPLIED[{k}]");
    }
    assert_eq!(b.status("SAFE"), 0, "a normal update applied");
}

/// Clock by clock, as the datasheet shows it (`timing.txt`, included in
/// the rustdoc): an update at the reset timing after reset.
fn timing_diagram() -> String {
    let mut b = Bench::new();
    for k in 0..3 {
        b.write("CODE", k, 0x100 * (k as u64 + 1));
    }
    let pins = b.update();
    let row = |f: &dyn Fn(&DacOutputs) -> bool| -> String {
        pins.iter().map(|p| if f(p) { '#' } else { '_' }).collect()
    };
    let ruler: String = (0..pins.len())
        .map(|c| char::from_digit(c as u32 % 10, 10).unwrap())
        .collect();
    let data: String = pins
        .iter()
        .map(|p| match p.dac_cs_n {
            0b110 => '0',
            0b101 => '1',
            0b011 => '2',
            _ => '.',
        })
        .collect();
    format!(
        "```text\nclock      {ruler}\nupdate     #\ndac_data   {data}   (k: channel k's code while its CS is low)\ndac_cs_n   {}\ndac_l1_n   {}\ndac_ldac   {}\nbusy       {}\n```\n",
        row(&|p| p.dac_cs_n == 0b111),
        row(&|p| p.dac_l1_n),
        row(&|p| p.dac_ldac),
        row(&|p| p.busy),
    )
}

#[test]
fn datasheet_timing_diagram_is_the_simulation() {
    crate::support::timing_diagram::assert_timing_diagram_is("dac_interface", &timing_diagram());
}

/// A request during an update is deferred, flagged, and served next with
/// the codes staged by then; the running update is not torn.
#[test]
fn a_request_during_an_update_is_deferred_with_the_latest_codes() {
    let mut b = Bench::new();
    let first = [0x0101, 0x0202, 0x0303];
    let latest = [0x7001, 0x7002, 0x7003];
    for (k, code) in first.iter().enumerate() {
        b.write("CODE", k as u32, *code);
    }
    b.clock(DacInputs {
        update: true,
        ..Default::default()
    });
    for _ in 0..3 {
        b.idle();
    }
    for (k, code) in latest.iter().enumerate() {
        b.write("CODE", k as u32, 0x6000 + *code);
        b.write("UPDATE", 0, 1);
        b.write("CODE", k as u32, *code);
    }
    assert_eq!(b.status("PENDING"), 1, "the request waits");
    assert_eq!(b.status("DEFERRED"), 1, "and is flagged");
    let mut ldac_rises = 0;
    let mut first_applied = None;
    for _ in 0..200 {
        let before = b.last;
        let out = b.idle();
        ldac_rises += (out.dac_ldac && !before.dac_ldac) as u32;
        if !out.dac_ldac && before.dac_ldac && first_applied.is_none() {
            assert!(out.busy, "the deferred update starts as LDAC falls");
            // Until the deferred update's LDAC, 25 clocks on, APPLIED holds
            // the first update's codes: the writes during it did not tear it.
            first_applied = Some((0..3).map(|k| b.read("APPLIED", k)).collect::<Vec<_>>());
        }
    }
    assert_eq!(
        first_applied,
        Some(first.to_vec()),
        "the first update's codes"
    );
    assert_eq!(ldac_rises, 2, "one deferred update, however many requests");
    for (k, code) in latest.iter().enumerate() {
        assert_eq!(
            b.read("APPLIED", k as u32),
            *code,
            "the deferred update has the latest codes"
        );
    }
    b.write(
        "STATUS",
        0,
        field_of(&b.map, "STATUS", "DEFERRED").mask() as u64,
    );
    assert_eq!(b.status("DEFERRED"), 0, "W1C");
}

/// Abort at every clock of an update (and while idle): the safe LDAC comes
/// within the stated latency, every code is 0, and while abort is high
/// codes and updates are refused.
#[test]
fn an_abort_at_any_clock_reaches_the_safe_code_within_the_stated_latency() {
    let bound = safe_latency(3, 1, 5, 2, 5);
    assert_eq!(bound, 35, "the datasheet's figure");
    let mut worst = 0;
    for offset in 0..=31 {
        let mut b = Bench::new();
        for k in 0..3 {
            b.write("CODE", k, 0x4000 + k as u64);
        }
        b.clock(DacInputs {
            update: true,
            ..Default::default()
        });
        for _ in 0..offset {
            b.idle();
        }
        b.force_safe = true;
        let before = b.last;
        let mut latency = None;
        let mut prev = before;
        for t in 0..100u64 {
            let out = b.idle();
            if out.dac_ldac && !prev.dac_ldac && t > 0 {
                latency.get_or_insert(t + 1);
            }
            prev = out;
        }
        let latency = latency.unwrap_or_else(|| panic!("offset {offset}: no safe LDAC"));
        assert!(latency <= bound, "offset {offset}: {latency} clocks");
        for k in 0..3 {
            assert_eq!(
                b.read("APPLIED", k),
                0,
                "offset {offset}: channel {k} at 0 V"
            );
        }
        worst = worst.max(latency);
        // Refused while abort is high.
        b.write("CODE", 0, 0x1111);
        b.write("UPDATE", 0, 1);
        let pins = b.update();
        assert!(
            pins.iter().all(|p| p.dac_cs_n == 0b111 && !p.dac_ldac),
            "offset {offset}: no write during the abort"
        );
        assert_eq!(b.status("REFUSED"), 1);
        assert_eq!(b.read("CODE", 0), 0, "the staged code is the safe one");
        b.force_safe = false;
        for _ in 0..50 {
            assert!(
                !b.idle().busy,
                "offset {offset}: nothing happens as abort falls"
            );
        }
        assert_eq!(b.status("SAFE"), 1);
    }
    println!("worst abort-to-safe-LDAC latency: {worst} clocks (bound {bound})");
    assert!(
        worst + 8 >= bound,
        "the bound is near the worst case: {worst} of {bound}"
    );
}

/// Offset binary: the pins carry the code with its MSB inverted, so the
/// safe code is mid-scale; the registers stay signed.
#[test]
fn offset_binary_pins_and_the_safe_code_at_mid_scale() {
    let mut b = Bench::new();
    b.write(
        "CONTROL",
        0,
        field_of(&b.map, "CONTROL", "OFFSET_BINARY").mask() as u64,
    );
    for (k, code) in [0xffff, 0x0000, 0x7fff].iter().enumerate() {
        b.write("CODE", k as u32, *code);
    }
    let pins = b.update();
    let on_pins: Vec<u64> = (0..3).map(|k| pins[1 + k * 8].dac_data).collect();
    assert_eq!(on_pins, vec![0x7fff, 0x8000, 0xffff]);
    assert_eq!(b.read("APPLIED", 0), 0xffff, "APPLIED is signed");
    b.force_safe = true;
    let mut safe_pins = Vec::new();
    for _ in 0..40 {
        let out = b.idle();
        if !out.dac_l1_n {
            safe_pins.push(out.dac_data);
        }
    }
    assert!(
        !safe_pins.is_empty() && safe_pins.iter().all(|&d| d == 0x8000),
        "{safe_pins:x?}"
    );
}

/// Reset starts the safe update on the first clock out of reset, and the
/// registers read their reset values from the map.
#[test]
fn reset_writes_the_safe_code_first_and_registers_read_their_reset_values() {
    let mut b = Bench::new();
    for k in 0..3 {
        b.write("CODE", k, 0x2222);
    }
    b.update();
    b.write("TIMING", 0, 0x0303_0303);
    b.clock(DacInputs {
        reset: true,
        ..Default::default()
    });
    let first = b.idle();
    assert!(first.busy && first.safe, "the safe update starts at once");
    let mut t = 1;
    while !b.last.dac_ldac {
        assert!(
            b.last.dac_l1_n || b.last.dac_data == 0,
            "only code 0 is written"
        );
        b.idle();
        t += 1;
    }
    // As if requested in the first clock out of reset: 1 + 1 + K (S + Wd + H).
    assert_eq!(t, 2 + 3 * 8, "its LDAC at the reset timing");
    b.idle_until_quiet();
    for register in b.map.registers.clone() {
        for index in 0..register.count {
            let expected = register.reset_value() as u64;
            let name = register.name;
            let value = b.read(name, index);
            let wanted = if name == "STATUS" {
                field_of(&b.map, "STATUS", "SAFE").mask() as u64
            } else {
                expected
            };
            assert_eq!(value, wanted, "{name}[{index}]");
        }
    }
}

/// The exported Verilog, and a 4 x 12-bit instance, in Icarus and
/// Verilator against the Rust simulation.
#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut traffic = Traffic::new(0xdac4, 3, 16);
    let stimulus: Vec<Vec<u64>> = (0..30_000).map(|c| traffic.next(c).to_vector()).collect();
    check_instance::<DacInterface3>(Instance::Exported("dac_interface"), stimulus);
    let mut traffic = Traffic::new(0xdac5, 4, 12);
    let stimulus: Vec<Vec<u64>> = (0..20_000).map(|c| traffic.next(c).to_vector()).collect();
    check_instance::<DacInterface<4, 12>>(Instance::Generated("dac_interface_k4_w12"), stimulus);
}

/// The committed C header (`rtl-out/dac_interface_regs.h`) is today's,
/// compiles as C89 without a warning, and gives the map's numbers.
#[test]
fn the_committed_c_header_compiles_and_agrees_with_the_map() {
    let map = register_map(3, 16).unwrap();
    let rtl = motion_hdl::tools::repo_root().join("rtl-out");
    let header = std::fs::read_to_string(rtl.join("dac_interface_regs.h")).unwrap();
    assert_eq!(
        header,
        motion_hdl::regmap::c_header(&map, &motion_hdl::export::generator()),
        "rtl-out/dac_interface_regs.h is stale: run `cargo run --release -- export`"
    );
    let printed = motion_hdl::tools::run_c_program(
        &rtl,
        "c89",
        r#"#include <stdio.h>
#include "dac_interface_regs.h"
int main(void) {
    printf("%lu %lu %lu %lu\n", (unsigned long)DAC_CODE_INDEX(2), (unsigned long)DAC_TIMING_RESET,
           (unsigned long)DAC_STATUS_REFUSED_MASK, (unsigned long)DAC_APPLIED_INDEX(0));
    return 0;
}
"#,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let f = |r: &str, name: &str| field_of(&map, r, name).mask();
    assert_eq!(
        printed,
        format!(
            "{} {} {} {}\n",
            map.address_of("CODE", 2).unwrap(),
            map.register("TIMING").unwrap().reset_value(),
            f("STATUS", "REFUSED"),
            map.address_of("APPLIED", 0).unwrap()
        )
    );
}
