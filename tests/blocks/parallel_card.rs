//! `parallel_card`: RTL against the model on random traffic on every port
//! (rust-hdl and the compiled Verilator model), a whole period driven as
//! the DSPs drive it with the contract checked at the pins by an
//! independent monitor (every slave released on one clock, every DAC
//! output changing on one edge, an underrun or estop bringing every output
//! to 0 V), mutations the monitor must catch, cross-simulation of the
//! exported Verilog, and the C headers. Registers by name from the maps.

use motion_hdl::blocks::parallel_card::model::{CardInputs, CardOutputs, ParallelCardModel};
use motion_hdl::blocks::parallel_card::registers::{
    master_map, slave_map, ID_VALUE, JOINTS, SLAVES,
};
use motion_hdl::blocks::parallel_card::ParallelCard;
use motion_hdl::blocks::sync_fifo_bridge::model::SlaveBus;
use motion_hdl::regmap::RegisterMap;
use motion_hdl::sim::{Backend, Lockstep};
use motion_hdl::tools::cosim::{check_instance_with, Instance, ALL_CLOCKS};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The DAC pair's safe latency at the reset `DAC_TIMING` (its datasheet's
/// formula, K = 2).
const SAFE_LATENCY: usize = 27;

/// Clocks from a `period_tick` (clock t) to the first clock in which every
/// `dac_ldac` is high, at the reset `DAC_TIMING`: LDAC rises at the edge
/// ending t + 1 + K (S + Wd + H) = t + 17 (the DAC's datasheet, K = 2).
const TICK_TO_LDAC: usize = 18;

fn address(map: &RegisterMap, register: &str, index: u32) -> u64 {
    map.address_of(register, index).unwrap() as u64
}

fn pack(map: &RegisterMap, register: &str, fields: &[(&str, u64)]) -> u64 {
    map.register(register).unwrap().pack(fields).unwrap() as u64
}

fn field(map: &RegisterMap, register: &str, name: &str, word: u64) -> u64 {
    map.field(register, name)
        .unwrap()
        .extract(word as u32)
        .unwrap()
}

/// Quadrature pins of the six joints, moved one state at a time, with a
/// rare double change (an error).
struct Encoders {
    phase: [u8; JOINTS],
}

impl Encoders {
    const GRAY: [(bool, bool); 4] = [(false, false), (true, false), (true, true), (false, true)];

    fn step(&mut self, rng: &mut StdRng, rate: u32) -> (u64, u64) {
        for p in &mut self.phase {
            match rng.gen_range(0..1000) {
                0 => *p = (*p + 2) % 4,
                r if r < rate => *p = (*p + 1) % 4,
                r if r < 2 * rate => *p = (*p + 3) % 4,
                _ => {}
            }
        }
        self.pins()
    }

    fn pins(&self) -> (u64, u64) {
        self.phase
            .iter()
            .enumerate()
            .fold((0, 0), |(a, b), (j, &p)| {
                let (pa, pb) = Self::GRAY[p as usize];
                (a | (pa as u64) << j, b | (pb as u64) << j)
            })
    }
}

/// Random traffic on every port: registers chosen by name, some random
/// addresses, ticks, short DAC timings, W1C writes, estop and rare resets.
struct Traffic {
    rng: StdRng,
    master: RegisterMap,
    slave: RegisterMap,
    encoders: Encoders,
    estop: bool,
}

impl Traffic {
    fn new(seed: u64) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            master: master_map().unwrap(),
            slave: slave_map().unwrap(),
            encoders: Encoders { phase: [0; JOINTS] },
            estop: false,
        }
    }

    fn slave_bus(&mut self) -> SlaveBus {
        let rng = &mut self.rng;
        let s = &self.slave;
        let j = rng.gen_range(0..2);
        let timing = pack(
            s,
            "DAC_TIMING",
            &[
                ("SETUP", rng.gen_range(0..3)),
                ("WIDTH", rng.gen_range(0..3)),
                ("HOLD", rng.gen_range(0..3)),
                ("LDAC_WIDTH", rng.gen_range(0..3)),
            ],
        );
        let (address, write_data) = match rng.gen_range(0..100) {
            0..=24 => (address(s, "CMD", 0), 0),
            25..=34 => (address(s, "STATUS", 0), rng.gen::<u32>() as u64),
            35..=39 => (address(s, "LEVELS", 0), 0),
            40..=43 => (address(s, "FLAGS", 0), rng.gen_range(0..4u64)),
            44..=49 => (address(s, "COUNT", j), 0),
            50..=54 => (address(s, "LIVE", j), 0),
            55..=59 => (address(s, "ENCODER", 0), rng.gen::<u32>() as u64 & 0x303),
            60..=62 => (address(s, "CARD_STATE", 0), 0),
            63..=77 => (address(s, "DAC_CODE", j), rng.gen::<u16>() as u64),
            78..=81 => (address(s, "DAC_STATUS", 0), rng.gen::<u32>() as u64),
            82..=84 => (address(s, "DAC_TIMING", 0), timing),
            85..=86 => (address(s, "DAC_UPDATE", 0), 1),
            87..=88 => (address(s, "DAC_APPLIED", j), 0),
            89..=90 => (address(s, "DAC_CONTROL", 0), rng.gen_range(0..2)),
            _ => (rng.gen_range(0..64), rng.gen::<u32>() as u64),
        };
        let strobe = rng.gen_range(0..10);
        SlaveBus {
            address,
            write_data,
            write: (4..7).contains(&strobe) || strobe == 9,
            read: strobe < 4 || strobe == 9,
        }
    }

    fn next(&mut self) -> CardInputs {
        let slaves = [self.slave_bus(), self.slave_bus(), self.slave_bus()];
        let rng = &mut self.rng;
        let k = rng.gen_range(0..SLAVES as u32);
        let m = &self.master;
        let (m_address, m_write_data) = match rng.gen_range(0..100) {
            0..=29 => (address(m, "CMD", k), rng.gen::<u32>() as u64),
            30..=37 => (address(m, "STATUS", k), 0),
            38..=41 => (address(m, "LEVELS", k), 0),
            42..=45 => (address(m, "FLAGS", k), rng.gen_range(0..4u64) * 0x101),
            46..=57 => (address(m, "SYNC", 0), 0),
            58..=60 => (address(m, "CONTROL", 0), rng.gen_range(0..2)),
            61..=63 => (address(m, "STATE", 0), 0),
            64..=75 => (address(m, "CARD_FAULT", 0), rng.gen::<u32>() as u64),
            76..=78 => (address(m, "CARD_CONTROL", 0), rng.gen::<u32>() as u64),
            79..=86 => (address(m, "COUNT", rng.gen_range(0..JOINTS as u32)), 0),
            87..=88 => (address(m, "CARD_ID", 0), 0),
            _ => (rng.gen_range(0..512), rng.gen::<u32>() as u64),
        };
        let (m_write, m_read) = match rng.gen_range(0..20) {
            0..=8 => (true, false),
            9..=14 => (false, true),
            15 => (true, true),
            _ => (false, false),
        };
        if rng.gen_ratio(1, 3000) {
            self.estop = !self.estop;
        }
        let (enc_a, enc_b) = self.encoders.step(&mut self.rng, 60);
        CardInputs {
            reset: self.rng.gen_ratio(1, 50_000),
            m_address,
            m_write_data,
            m_write,
            m_read,
            period_tick: self.rng.gen_ratio(1, 25),
            slaves,
            enc_a,
            enc_b,
            estop: self.estop,
        }
    }
}

/// Activity of a lockstep run, read off the outputs.
#[derive(Debug, Default)]
struct Activity {
    ldac_rises: u64,
    stops: u64,
    restarts: u64,
    ready_rises: u64,
    nonzero_slave_reads: u64,
}

impl Activity {
    fn record(&mut self, last: &CardOutputs, now: &CardOutputs) {
        self.ldac_rises += (now.dac_ldac & !last.dac_ldac).count_ones() as u64;
        self.stops += (now.stopped && !last.stopped) as u64;
        self.restarts += (!now.stopped && last.stopped) as u64;
        self.ready_rises += (now.s_data_ready & !last.s_data_ready).count_ones() as u64;
        self.nonzero_slave_reads += now
            .s_read_data
            .iter()
            .zip(&last.s_read_data)
            .filter(|(a, b)| a != b)
            .count() as u64;
    }

    fn assert_busy(&self, cycles: u64) {
        let per = |n: u64| n * cycles / 100_000;
        assert!(
            self.ldac_rises > per(300)
                && self.stops > per(50)
                && self.restarts > per(50)
                && self.ready_rises > per(1000)
                && self.nonzero_slave_reads > per(10_000),
            "too little activity in {cycles} clocks: {self:?}"
        );
    }
}

fn lockstep(backend: Backend, seed: u64, cycles: u64) -> Activity {
    let mut pair = Lockstep::on(
        backend,
        "parallel_card",
        ParallelCard::default(),
        ParallelCardModel::power_up(),
    )
    .unwrap();
    let mut traffic = Traffic::new(seed);
    let mut first = traffic.next();
    first.reset = true;
    let mut last = pair.step(&first).unwrap_or_else(|e| panic!("{e}"));
    let mut activity = Activity::default();
    for _ in 1..cycles {
        let now = pair.step(&traffic.next()).unwrap_or_else(|e| panic!("{e}"));
        activity.record(&last, &now);
        last = now;
    }
    activity
}

/// The rust-hdl simulation against the model.
#[test]
fn rtl_matches_model_on_random_traffic() {
    let cycles = 30_000;
    lockstep(Backend::RustHdl, 0xca4d, cycles).assert_busy(cycles);
}

/// The generated Verilog, compiled by Verilator, against the model (the
/// cross-simulation proves the two RTL simulations equal).
#[test]
fn compiled_rtl_matches_model_for_300k_clocks_of_random_traffic() {
    let cycles = 300_000;
    lockstep(Backend::Verilator, 0xca4e, cycles).assert_busy(cycles);
}

/// The exported Verilog in Icarus (its first `icarus_clocks`) and
/// Verilator against rust-hdl over `clocks` of random traffic (Icarus runs
/// the card at about 400 clocks/s).
fn cross_simulate_card(clocks: usize, icarus_clocks: usize) {
    let mut traffic = Traffic::new(0xca4f);
    let mut stimulus: Vec<Vec<u64>> = (0..clocks).map(|_| traffic.next().to_vector()).collect();
    stimulus[0][0] = 1;
    check_instance_with::<ParallelCard>(
        Instance::Exported("parallel_card"),
        stimulus,
        icarus_clocks,
    );
}

/// 4,000 clocks in the suite, Icarus on the first 2,000: the Verilog
/// itself is held to the model for 300,000 clocks by the compiled lockstep
/// above.
#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    cross_simulate_card(4_000, 2_000);
}

#[test]
#[ignore = "soak: 20,000 clocks of Icarus (about 40 s)"]
fn exported_verilog_matches_rust_over_20000_clocks() {
    cross_simulate_card(20_000, ALL_CLOCKS);
}

/// The firmware of the control DSP and of the motor DSPs includes both
/// headers: together they compile as C89 and their numbers are the maps'.
#[test]
fn both_register_headers_compile_together_and_agree_with_the_maps() {
    let root = motion_hdl::tools::repo_root().join("rtl-out");
    let program = r#"#include <stdio.h>
#include "parallel_card_master_regs.h"
#include "parallel_card_slave_regs.h"
int main(void) {
    printf("%lu %lu %lu %lu %lu\n", PCARD_CARD_FAULT_INDEX, PCARD_COUNT_INDEX(5),
           PCARD_SLAVE_DAC_CODE_INDEX(1), PCARD_SLAVE_COUNT_INDEX(1), PCARD_SLAVE_ENCODER_CLEAR_MASK);
    return 0;
}
"#;
    let printed =
        motion_hdl::tools::run_c_program(&root, "c89", program).unwrap_or_else(|e| panic!("{e}"));
    let (m, s) = (master_map().unwrap(), slave_map().unwrap());
    assert_eq!(
        printed,
        format!(
            "{} {} {} {} {}\n",
            address(&m, "CARD_FAULT", 0),
            address(&m, "COUNT", 5),
            address(&s, "DAC_CODE", 1),
            address(&s, "COUNT", 1),
            s.field("ENCODER", "CLEAR").unwrap().mask()
        )
    );
}

/// The card driven as its DSPs drive it, on the model-checked RTL, with
/// the master's and the slaves' register accesses by name.
struct Card {
    pair: Lockstep<ParallelCardModel>,
    master: RegisterMap,
    slave: RegisterMap,
    i: CardInputs,
    trace: Vec<CardOutputs>,
}

impl Card {
    fn new() -> Self {
        let mut card = Self {
            pair: Lockstep::harness(
                "parallel_card",
                ParallelCard::default(),
                ParallelCardModel::power_up(),
            ),
            master: master_map().unwrap(),
            slave: slave_map().unwrap(),
            i: CardInputs::default(),
            trace: Vec::new(),
        };
        card.i.reset = true;
        card.clock();
        card
    }

    fn clock(&mut self) -> CardOutputs {
        let out = self.pair.step(&self.i).unwrap_or_else(|e| panic!("{e}"));
        self.i.reset = false;
        self.i.m_write = false;
        self.i.m_read = false;
        self.i.period_tick = false;
        for s in &mut self.i.slaves {
            s.write = false;
            s.read = false;
        }
        self.trace.push(out.clone());
        out
    }

    fn idle(&mut self, clocks: usize) {
        for _ in 0..clocks {
            self.clock();
        }
    }

    fn m_write(&mut self, register: &str, index: u32, data: u64) {
        self.i.m_address = address(&self.master, register, index);
        self.i.m_write_data = data;
        self.i.m_write = true;
        self.clock();
    }

    fn m_read(&mut self, register: &str, index: u32) -> u64 {
        self.i.m_address = address(&self.master, register, index);
        self.i.m_read = true;
        self.clock();
        self.clock().m_read_data
    }

    fn s_write(&mut self, k: usize, register: &str, index: u32, data: u64) {
        self.i.slaves[k] = SlaveBus {
            address: address(&self.slave, register, index),
            write_data: data,
            write: true,
            read: false,
        };
        self.clock();
    }

    fn s_read(&mut self, k: usize, register: &str, index: u32) -> u64 {
        self.i.slaves[k].address = address(&self.slave, register, index);
        self.i.slaves[k].read = true;
        self.clock();
        self.clock().s_read_data[k]
    }

    /// Tick mode, one command per slave, SYNC, and the fault flags cleared.
    fn prime(&mut self, commands: [u64; SLAVES]) {
        let tick_mode = pack(&self.master, "CONTROL", &[("TICK_MODE", 1)]);
        self.m_write("CONTROL", 0, tick_mode);
        for (k, &c) in commands.iter().enumerate() {
            self.m_write("CMD", k as u32, c);
        }
        self.m_write("SYNC", 0, 0);
        self.m_write("CARD_FAULT", 0, 0x7);
    }

    fn tick(&mut self) {
        self.i.period_tick = true;
        self.clock();
    }
}

/// The contract at the pins, checked on a trace by an independent AD669
/// emulation: (1) every slave's data_ready rises on one clock at each
/// release; (2) the three pairs' LDAC rise on one clock while running;
/// (3) after `stopped` rises, every DAC's output is 0 within the pair's
/// safe latency and stays 0 while stopped. Returns the outputs of the six DACs after the trace.
fn monitor(trace: &[CardOutputs]) -> Result<[i16; JOINTS], String> {
    let mut first_rank = [0u16; JOINTS];
    let mut output = [0i16; JOINTS];
    let mut stopped_since: Option<usize> = None;
    let mut last_rise: Option<usize> = None;
    for (c, w) in trace.windows(2).enumerate() {
        let (last, now) = (&w[0], &w[1]);
        // Releases are ticks apart: rises on consecutive clocks are one
        // release seen by the slaves on different edges.
        let ready_rises = now.s_data_ready & !last.s_data_ready;
        if ready_rises != 0 {
            if last_rise == Some(c.wrapping_sub(1)) {
                return Err(format!(
                    "clock {c}: data_ready rose for {ready_rises:03b} a clock after the others"
                ));
            }
            last_rise = Some(c);
        }
        let ldac_rises = now.dac_ldac & !last.dac_ldac;
        if !now.stopped && ldac_rises != 0 && ldac_rises != 0x7 {
            return Err(format!(
                "clock {c}: LDAC rose for pairs {ldac_rises:03b} only"
            ));
        }
        for j in 0..JOINTS {
            let k = j / 2;
            // AD669: the first rank follows the data while CS and L1 are low.
            if now.dac_cs_n >> j & 1 == 0 && now.dac_l1_n >> k & 1 == 0 {
                first_rank[j] = (now.dac_data >> (16 * k)) as u16;
            }
            if now.dac_ldac >> k & 1 != 0 {
                output[j] = first_rank[j] as i16;
            }
        }
        if now.stopped && !last.stopped {
            stopped_since = Some(c);
        }
        if !now.stopped {
            stopped_since = None;
        }
        if let Some(s) = stopped_since {
            if c > s + SAFE_LATENCY && output.iter().any(|&v| v != 0) {
                return Err(format!(
                    "clock {c}: stopped since {s} but the outputs are {output:?}"
                ));
            }
        }
    }
    Ok(output)
}

/// Three periods as the DSPs run them: every slave reads its command and
/// its joints' counts, writes both codes; the next tick puts all six out
/// on one edge. Then a period with no command for slave 1: the underrun
/// stops every joint, and the master sees which slave.
#[test]
fn a_period_runs_on_one_edge_and_an_underrun_stops_every_joint() {
    let mut card = Card::new();
    assert_eq!(card.m_read("CARD_ID", 0), ID_VALUE as u64);
    card.idle(40);
    card.prime([11, 22, 33]);
    let mut codes = [0i16; JOINTS];
    for period in 1..=3i16 {
        card.tick();
        card.clock();
        assert_eq!(
            card.trace.last().unwrap().s_data_ready,
            0x7,
            "period {period}: all released"
        );
        for k in 0..SLAVES {
            let command = card.s_read(k, "CMD", 0);
            assert_eq!(
                command,
                if period == 1 {
                    11 * (k as u64 + 1)
                } else {
                    100 * period as u64 - 100 + k as u64
                }
            );
            for j in 0..2 {
                let code = period * 1000 + (2 * k + j) as i16;
                card.s_write(k, "DAC_CODE", j as u32, code as u16 as u64);
                codes[2 * k + j] = code;
            }
        }
        for k in 0..SLAVES {
            card.m_write("CMD", k as u32, 100 * period as u64 + k as u64);
        }
        card.m_write("SYNC", 0, 0);
        card.idle(30);
        assert!(!card.trace.last().unwrap().stopped);
    }
    let tick = card.trace.len();
    card.tick();
    card.idle(40);
    let ldac = card.trace[tick..]
        .iter()
        .position(|o| o.dac_ldac == 0x7)
        .unwrap();
    assert_eq!(ldac + 1, TICK_TO_LDAC, "clocks from the tick to LDAC high");
    let out = monitor(&card.trace).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out, codes, "the last period's codes are out");

    // Slave 1 gets no command for the next period.
    for k in 0..SLAVES {
        card.s_read(k, "CMD", 0);
    }
    card.m_write("CMD", 0, 7);
    card.m_write("CMD", 2, 7);
    card.m_write("SYNC", 0, 0);
    let tick = card.trace.len();
    card.tick();
    card.idle(45);
    let stop = card.trace[tick..].iter().position(|o| o.stopped).unwrap();
    assert_eq!(stop + 1, 2, "stopped from the second clock after the tick");
    let fault = card.m_read("CARD_FAULT", 0);
    assert_eq!(field(&card.master, "CARD_FAULT", "UNDERRUN", fault), 0b010);
    let state = card.s_read(0, "CARD_STATE", 0);
    assert_eq!(field(&card.slave, "CARD_STATE", "STOPPED", state), 1);
    let out = monitor(&card.trace).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out, [0; JOINTS], "every joint at 0 V");
}

/// Encoder counts: live, latched on the tick, cleared, and readable by the
/// master; an estop stops every joint and its release lets them run.
#[test]
fn counts_latch_on_the_tick_and_estop_stops_every_joint() {
    let mut card = Card::new();
    card.prime([0; SLAVES]);
    let mut encoders = Encoders { phase: [0; JOINTS] };
    // Joint j moves j + 1 states forward.
    for step in 0..JOINTS {
        for (j, p) in encoders.phase.iter_mut().enumerate() {
            if step <= j {
                *p = (*p + 1) % 4;
            }
        }
        (card.i.enc_a, card.i.enc_b) = encoders.pins();
        card.idle(12);
    }
    card.tick();
    for j in 0..JOINTS {
        assert_eq!(
            card.m_read("COUNT", j as u32),
            j as u64 + 1,
            "joint {j} live at the master"
        );
    }
    // One more state on joint 0 after the tick: LIVE moves, COUNT does not.
    encoders.phase[0] = (encoders.phase[0] + 1) % 4;
    (card.i.enc_a, card.i.enc_b) = encoders.pins();
    card.idle(12);
    assert_eq!(card.s_read(0, "COUNT", 0), 1);
    assert_eq!(card.s_read(0, "LIVE", 0), 2);
    assert_eq!(card.s_read(2, "COUNT", 1), 6);
    let clear = pack(&card.slave, "ENCODER", &[("CLEAR", 0b01)]);
    card.s_write(0, "ENCODER", 0, clear);
    assert_eq!(card.s_read(0, "LIVE", 0), 0);
    assert_eq!(card.s_read(0, "LIVE", 1), 2);

    card.i.estop = true;
    card.clock();
    assert!(!card.trace.last().unwrap().stopped);
    card.clock();
    assert!(card.trace.last().unwrap().stopped, "stopped from c + 2");
    let fault = card.m_read("CARD_FAULT", 0);
    assert_eq!(field(&card.master, "CARD_FAULT", "ESTOP", fault), 1);
    card.i.estop = false;
    card.idle(3);
    assert!(!card.trace.last().unwrap().stopped);
    monitor(&card.trace).unwrap_or_else(|e| panic!("{e}"));
}

/// The monitor fails traces that break the contract: a slave released a
/// clock late, one pair's LDAC alone, a DAC left at its code after a stop.
#[test]
fn the_monitor_catches_a_broken_contract() {
    let mut card = Card::new();
    card.prime([1, 2, 3]);
    card.s_write(0, "DAC_CODE", 0, 500);
    card.tick();
    card.idle(40);
    let good = card.trace.clone();
    monitor(&good).unwrap();

    let rise = good.iter().position(|o| o.s_data_ready == 0x7).unwrap();
    let mut late = good.clone();
    late[rise].s_data_ready = 0b011;
    assert!(monitor(&late).unwrap_err().contains("data_ready"));

    let ldac = good
        .iter()
        .position(|o| o.dac_ldac == 0x7 && !o.stopped)
        .unwrap();
    let mut alone = good.clone();
    alone[ldac].dac_ldac = 0b001;
    assert!(monitor(&alone).unwrap_err().contains("LDAC"));

    // A stop the DACs ignore: the outputs keep 500.
    let mut ignored = good.clone();
    let n = ignored.len();
    let mut tail: Vec<CardOutputs> = (0..50).map(|_| ignored[n - 1].clone()).collect();
    for o in &mut tail {
        o.stopped = true;
    }
    ignored.append(&mut tail);
    assert!(monitor(&ignored).unwrap_err().contains("stopped"));
}
