//! `dpram_mailbox`: RTL against the model in lockstep on random strobes
//! (a 16-word instance where addresses collide all the time, and the
//! exported 1024 x 16), an independent monitor of the datasheet's rules
//! driven from the pins (and shown to catch wrong rules), directed tests of
//! every interrupt, collision, read-first and write-rate rule, and
//! cross-simulation of the exported Verilog.

use motion_hdl::blocks::dpram_mailbox::model::{
    DpramMailboxInputs, DpramMailboxModel, DpramMailboxOutputs,
};
use motion_hdl::blocks::dpram_mailbox::{
    mailbox_to_a, mailbox_to_b, DpramMailbox, DpramMailbox1024x16,
};
use motion_hdl::sim::{Harness, Lockstep, VectorPorts};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

type Small = DpramMailbox<4, 16>;

/// Random strobes on both ports, in phases of light and heavy writing (up
/// to both ports writing every clock, far past the write rate), with
/// addresses drawn so that the two ports meet on the same word and on the
/// mailbox words often.
struct Stimulus {
    rng: StdRng,
    address_bits: usize,
    p_write: (f64, f64),
    p_read: (f64, f64),
}

impl Stimulus {
    fn new(seed: u64, address_bits: usize) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            address_bits,
            p_write: (0.2, 0.2),
            p_read: (0.4, 0.4),
        }
    }

    fn address(&mut self) -> u64 {
        let depth = 1u64 << self.address_bits;
        match self.rng.gen_range(0..8) {
            0 => mailbox_to_a(self.address_bits),
            1 => mailbox_to_b(self.address_bits),
            2..=5 => self.rng.gen_range(0..depth.min(8)),
            _ => self.rng.gen_range(0..depth),
        }
    }

    fn next(&mut self) -> DpramMailboxInputs {
        if self.rng.gen_ratio(1, 100) {
            const WRITES: [(f64, f64); 8] = [
                (0.1, 0.1),
                (0.3, 0.3),
                (0.5, 0.5),
                (0.9, 0.9),
                (0.3, 0.0),
                (0.0, 0.3),
                (1.0, 0.4),
                (0.45, 0.45),
            ];
            self.p_write = WRITES[self.rng.gen_range(0..WRITES.len())];
            self.p_read = (self.rng.gen_range(0.0..0.8), self.rng.gen_range(0.0..0.8));
        }
        DpramMailboxInputs {
            reset: self.rng.gen_ratio(1, 20_000),
            a_address: self.address(),
            a_write_data: self.rng.gen::<u16>() as u64,
            a_write: self.rng.gen_bool(self.p_write.0),
            a_read: self.rng.gen_bool(self.p_read.0),
            b_address: self.address(),
            b_write_data: self.rng.gen::<u16>() as u64,
            b_write: self.rng.gen_bool(self.p_write.1),
            b_read: self.rng.gen_bool(self.p_read.1),
        }
    }
}

/// How often each rule was exercised.
#[derive(Debug, Default)]
struct Counts {
    irq_a_raised: u32,
    irq_b_raised: u32,
    irq_a_cleared_by_read: u32,
    irq_a_cleared_by_write: u32,
    irq_b_cleared_by_read: u32,
    irq_b_cleared_by_write: u32,
    raise_won_a: u32,
    raise_won_b: u32,
    collisions: u32,
    overruns: u32,
    /// Reads answered from the write queue (the word had not landed).
    forwarded: u32,
    /// Reads on the clock the other port wrote the word, with a new value.
    read_first: u32,
}

impl Counts {
    /// The rules counted from the model's state before the clock:
    /// (reads forwarded from the write queue, read-first reads).
    fn model_rules(i: &DpramMailboxInputs, model: &DpramMailboxModel) -> (u32, u32) {
        let forwarded = (i.a_read && model.is_queued(i.a_address)) as u32
            + (i.b_read && model.is_queued(i.b_address)) as u32;
        let new_word = |address: u64, data: u64| model.word(address) != data;
        let read_first = (i.b_read
            && i.a_write
            && i.a_address == i.b_address
            && new_word(i.a_address, i.a_write_data)) as u32
            + (i.a_read
                && i.b_write
                && i.a_address == i.b_address
                && new_word(i.b_address, i.b_write_data)) as u32;
        (forwarded, read_first)
    }

    fn count(
        &mut self,
        aw: usize,
        i: &DpramMailboxInputs,
        before: &DpramMailboxOutputs,
        after: &DpramMailboxOutputs,
        (forwarded, read_first): (u32, u32),
    ) {
        if i.reset {
            return;
        }
        let (to_a, to_b) = (mailbox_to_a(aw), mailbox_to_b(aw));
        let a_touches = (i.a_read || i.a_write) && i.a_address == to_a;
        let b_touches = (i.b_read || i.b_write) && i.b_address == to_b;
        let b_raises = i.b_write && i.b_address == to_a && !after.overrun;
        let a_raises = i.a_write && i.a_address == to_b;
        self.irq_a_raised += (!before.irq_a && after.irq_a) as u32;
        self.irq_b_raised += (!before.irq_b && after.irq_b) as u32;
        if before.irq_a && !after.irq_a {
            self.irq_a_cleared_by_read += i.a_read as u32;
            self.irq_a_cleared_by_write += i.a_write as u32;
        }
        if before.irq_b && !after.irq_b {
            self.irq_b_cleared_by_read += i.b_read as u32;
            self.irq_b_cleared_by_write += i.b_write as u32;
        }
        self.raise_won_a += (a_touches && b_raises && after.irq_a) as u32;
        self.raise_won_b += (b_touches && a_raises && after.irq_b) as u32;
        self.collisions += after.collision as u32;
        self.overruns += after.overrun as u32;
        self.forwarded += forwarded;
        self.read_first += read_first;
    }

    fn assert_at_least(&self, n: u32) {
        let all = [
            self.irq_a_raised,
            self.irq_b_raised,
            self.irq_a_cleared_by_read,
            self.irq_a_cleared_by_write,
            self.irq_b_cleared_by_read,
            self.irq_b_cleared_by_write,
            self.raise_won_a,
            self.raise_won_b,
            self.collisions,
            self.overruns,
            self.forwarded,
            self.read_first,
        ];
        assert!(
            all.iter().all(|&c| c >= n),
            "some rule exercised fewer than {n} times: {self:?}"
        );
    }
}

/// `cycles` random clocks of the RTL against the model and the monitor.
fn lockstep<const AW: usize>(seed: u64, cycles: usize) -> Counts
where
    DpramMailbox<AW, 16>: VectorPorts,
{
    let mut pair = Lockstep::harness(
        "dpram_mailbox",
        DpramMailbox::<AW, 16>::default(),
        DpramMailboxModel::new(AW, 16),
    );
    let mut monitor = Monitor::new(AW, Rule::Datasheet);
    let mut stimulus = Stimulus::new(seed, AW);
    let mut counts = Counts::default();
    let mut before = DpramMailboxOutputs::default();
    for cycle in 0..cycles {
        let i = stimulus.next();
        // The counts read the model before the clock (queued writes).
        let forwarding = Counts::model_rules(&i, pair.model());
        let rtl = pair.step(&i).unwrap_or_else(|e| panic!("{e}"));
        counts.count(AW, &i, &before, &rtl, forwarding);
        if let Err(e) = monitor.observe(&i, &rtl) {
            panic!("cycle {cycle}: {e}");
        }
        before = rtl;
    }
    counts
}

#[test]
fn rtl_matches_model_and_monitor_16_words_a_million_clocks() {
    let counts = lockstep::<4>(0xd9a, 1_000_000);
    eprintln!("{counts:?}");
    counts.assert_at_least(1000);
}

#[test]
fn rtl_matches_model_and_monitor_exported_1024_words() {
    let counts = lockstep::<10>(0xd9b, 200_000);
    eprintln!("{counts:?}");
    counts.assert_at_least(50);
}

/// The datasheet's rules, and wrong ones the monitor must reject.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rule {
    /// As documented.
    Datasheet,
    /// Wrong: a read sees the writes of its own clock (write-first).
    WriteFirst,
    /// Wrong: both ports writing the same word, A's data stays.
    AWinsCollision,
    /// Wrong: a clearing access on the raising clock wins.
    ClearWins,
    /// Wrong: a read answer is valid only in the clock after the read.
    NoHold,
}

/// Checks the datasheet's contract from the pins alone: a shadow memory in
/// which every write not flagged by `overrun` takes effect at its strobe
/// (A before B), read answers the clock after the read and held, the
/// mailbox rules, `collision`, and that `overrun` pulses only past the
/// documented write rate. Independent of the model and of the RTL's queue.
struct Monitor {
    rule: Rule,
    to_a: u64,
    to_b: u64,
    shadow: Vec<u64>,
    /// Words whose value a reset made uncertain (a write queued at the reset
    /// may be dropped); their reads are not checked until written again.
    uncertain: Vec<bool>,
    /// Addresses written in the last two clocks (a reset may drop them).
    recent: Vec<Vec<u64>>,
    a_read_data: u64,
    b_read_data: u64,
    irq_a: bool,
    irq_b: bool,
    /// The backlog bound: writes strobed in excess of one per clock
    /// (max over windows ending now of strobes - length); the datasheet
    /// says nothing is refused while it stays at most 2.
    excess: i64,
}

impl Monitor {
    fn new(aw: usize, rule: Rule) -> Self {
        Self {
            rule,
            to_a: mailbox_to_a(aw),
            to_b: mailbox_to_b(aw),
            shadow: vec![0; 1 << aw],
            uncertain: vec![false; 1 << aw],
            recent: vec![vec![], vec![]],
            a_read_data: 0,
            b_read_data: 0,
            irq_a: false,
            irq_b: false,
            excess: 0,
        }
    }

    /// One clock: the inputs applied and the outputs after the edge.
    fn observe(&mut self, i: &DpramMailboxInputs, o: &DpramMailboxOutputs) -> Result<(), String> {
        let check = |what: &str, got: u64, want: u64| {
            if got == want {
                Ok(())
            } else {
                Err(format!(
                    "{what}: got {got:#x}, the rules say {want:#x} ({i:?})"
                ))
            }
        };
        if i.reset {
            for address in self.recent.concat() {
                self.uncertain[address as usize] = true;
            }
            self.recent = vec![vec![], vec![]];
            (
                self.a_read_data,
                self.b_read_data,
                self.irq_a,
                self.irq_b,
                self.excess,
            ) = (0, 0, false, false, 0);
            check("a_read_data after reset", o.a_read_data, 0)?;
            check("b_read_data after reset", o.b_read_data, 0)?;
            let quiet = (o.irq_a, o.irq_b, o.collision, o.overrun) == (false, false, false, false);
            check(
                "irqs, collision and overrun low after reset",
                quiet as u64,
                1,
            )?;
            return Ok(());
        }
        // Writes of this clock, in the order they take effect.
        let b_refused = o.overrun;
        let mut writes = vec![];
        if i.a_write {
            writes.push((i.a_address, i.a_write_data));
        }
        if i.b_write && !b_refused {
            writes.push((i.b_address, i.b_write_data));
        }
        if self.rule == Rule::AWinsCollision {
            writes.reverse();
        }
        if self.rule == Rule::WriteFirst {
            self.apply(&writes);
        }
        for (read, address, held, got, port) in [
            (
                i.a_read,
                i.a_address,
                &mut self.a_read_data,
                o.a_read_data,
                "a",
            ),
            (
                i.b_read,
                i.b_address,
                &mut self.b_read_data,
                o.b_read_data,
                "b",
            ),
        ] {
            if read {
                if self.uncertain[address as usize] {
                    *held = got;
                } else {
                    *held = self.shadow[address as usize];
                }
            } else if self.rule == Rule::NoHold {
                *held = 0;
            }
            check(&format!("{port}_read_data"), got, *held)?;
        }
        if self.rule != Rule::WriteFirst {
            self.apply(&writes);
        }
        self.recent.remove(0);
        self.recent.push(writes.iter().map(|w| w.0).collect());

        // Mailboxes.
        let clear_a = (i.a_read || i.a_write) && i.a_address == self.to_a;
        let raise_a = i.b_write && !b_refused && i.b_address == self.to_a;
        let clear_b = (i.b_read || i.b_write) && i.b_address == self.to_b;
        let raise_b = i.a_write && i.a_address == self.to_b;
        let next = |irq: bool, raise: bool, clear: bool, rule: Rule| match rule {
            Rule::ClearWins => (irq || raise) && !clear,
            _ => raise || (irq && !clear),
        };
        self.irq_a = next(self.irq_a, raise_a, clear_a, self.rule);
        self.irq_b = next(self.irq_b, raise_b, clear_b, self.rule);
        check("irq_a", o.irq_a as u64, self.irq_a as u64)?;
        check("irq_b", o.irq_b as u64, self.irq_b as u64)?;
        let collision = i.a_write && i.b_write && i.a_address == i.b_address;
        check("collision", o.collision as u64, collision as u64)?;

        // The write rate: a write is refused exactly when the excess would
        // pass 2, and it is B's.
        let strobes = i.a_write as i64 + i.b_write as i64;
        self.excess = (self.excess + strobes - 1).max(0);
        if o.overrun != (self.excess > 2) {
            return Err(format!(
                "overrun {} with an excess of {}: {i:?}",
                o.overrun, self.excess
            ));
        }
        if o.overrun {
            // The refused write is gone: one fewer waits.
            self.excess -= 1;
        }
        Ok(())
    }

    fn apply(&mut self, writes: &[(u64, u64)]) {
        for &(address, data) in writes {
            self.shadow[address as usize] = data;
            self.uncertain[address as usize] = false;
        }
    }
}

/// The monitor is not vacuous: each wrong rule is caught on the RTL's pins
/// within a short random run.
#[test]
fn the_monitor_rejects_wrong_rules() {
    for rule in [
        Rule::WriteFirst,
        Rule::AWinsCollision,
        Rule::ClearWins,
        Rule::NoHold,
    ] {
        let mut h = Harness::new("dpram_mailbox", Small::default()).unwrap();
        let mut monitor = Monitor::new(4, rule);
        let mut stimulus = Stimulus::new(0x3a1, 4);
        let caught = (0..50_000).any(|_| {
            let i = stimulus.next();
            let o = DpramMailboxOutputs::from_vector(&h.step_vector(&i.to_vector()).unwrap());
            monitor.observe(&i, &o).is_err()
        });
        assert!(caught, "the monitor accepted the wrong rule {rule:?}");
    }
}

// ---- directed tests, on the exported 1024 x 16 ----

const TO_A: u64 = mailbox_to_a(10);
const TO_B: u64 = mailbox_to_b(10);

/// One clock's strobes, built up.
trait Strobes {
    fn a_wr(self, address: u64, data: u64) -> Self;
    fn a_rd(self, address: u64) -> Self;
    fn b_wr(self, address: u64, data: u64) -> Self;
    fn b_rd(self, address: u64) -> Self;
}

impl Strobes for DpramMailboxInputs {
    fn a_wr(mut self, address: u64, data: u64) -> Self {
        (self.a_write, self.a_address, self.a_write_data) = (true, address, data);
        self
    }
    fn a_rd(mut self, address: u64) -> Self {
        (self.a_read, self.a_address) = (true, address);
        self
    }
    fn b_wr(mut self, address: u64, data: u64) -> Self {
        (self.b_write, self.b_address, self.b_write_data) = (true, address, data);
        self
    }
    fn b_rd(mut self, address: u64) -> Self {
        (self.b_read, self.b_address) = (true, address);
        self
    }
}

fn idle() -> DpramMailboxInputs {
    DpramMailboxInputs::default()
}

/// The exported block with the model and the monitor checking every clock.
struct Bench {
    h: Harness<DpramMailbox1024x16>,
    model: DpramMailboxModel,
    monitor: Monitor,
}

impl Bench {
    fn new() -> Self {
        Self {
            h: Harness::new("dpram_mailbox", DpramMailbox1024x16::default()).unwrap(),
            model: DpramMailboxModel::new(10, 16),
            monitor: Monitor::new(10, Rule::Datasheet),
        }
    }

    /// One clock; the outputs after its edge.
    fn clock(&mut self, i: DpramMailboxInputs) -> DpramMailboxOutputs {
        let o = DpramMailboxOutputs::from_vector(&self.h.step_vector(&i.to_vector()).unwrap());
        assert_eq!(o, self.model.step(i), "{i:?}");
        self.monitor.observe(&i, &o).unwrap();
        o
    }

    fn idle(&mut self, clocks: usize) -> DpramMailboxOutputs {
        (0..clocks).map(|_| self.clock(idle())).last().unwrap()
    }

    /// Reads `address` on both ports; the answers.
    fn read_both(&mut self, address: u64) -> (u64, u64) {
        let o = self.clock(idle().a_rd(address).b_rd(address));
        (o.a_read_data, o.b_read_data)
    }
}

#[test]
fn a_writing_mailbox_to_b_raises_irq_b_and_a_b_read_clears_it() {
    let mut b = Bench::new();
    let o = b.clock(idle().a_wr(TO_B, 1));
    assert!(o.irq_b && !o.irq_a, "irq_b rises the clock after the write");
    // A's own accesses to it do not clear irq_b.
    assert!(b.clock(idle().a_rd(TO_B)).irq_b);
    assert!(b.idle(5).irq_b);
    let o = b.clock(idle().b_rd(TO_B));
    assert!(!o.irq_b, "a B read clears irq_b the clock after it");
    assert_eq!(o.b_read_data, 1, "and returns the message");
    // Other words do not raise it.
    b.clock(idle().a_wr(TO_A, 1).b_wr(TO_B - 2, 1));
    assert!(!b.idle(2).irq_b);
}

#[test]
fn a_b_write_of_mailbox_to_b_clears_irq_b() {
    let mut b = Bench::new();
    assert!(b.clock(idle().a_wr(TO_B, 1)).irq_b);
    let o = b.clock(idle().b_wr(TO_B, 0));
    assert!(!o.irq_b, "B writing 0 (done) clears irq_b");
    assert_eq!(b.read_both(TO_B), (0, 0));
}

#[test]
fn b_writing_mailbox_to_a_raises_irq_a_and_an_a_read_or_write_clears_it() {
    let mut b = Bench::new();
    let o = b.clock(idle().b_wr(TO_A, 1));
    assert!(o.irq_a && !o.irq_b);
    assert!(
        b.clock(idle().b_rd(TO_A)).irq_a,
        "B's own read does not clear it"
    );
    let o = b.clock(idle().a_rd(TO_A));
    assert!(!o.irq_a);
    assert_eq!(o.a_read_data, 1);
    assert!(b.clock(idle().b_wr(TO_A, 1)).irq_a);
    assert!(
        !b.clock(idle().a_wr(TO_A, 0)).irq_a,
        "an A write clears it too"
    );
}

#[test]
fn a_raise_and_a_clear_on_the_same_clock_the_raise_wins() {
    let mut b = Bench::new();
    // irq_b low, then A writes while B reads: it rises, B's read returns the
    // old word (read-first), and the next B read clears it and returns the new.
    let o = b.clock(idle().a_wr(TO_B, 7).b_rd(TO_B));
    assert!(o.irq_b);
    assert_eq!(o.b_read_data, 0);
    let o = b.clock(idle().b_rd(TO_B));
    assert!(!o.irq_b);
    assert_eq!(o.b_read_data, 7);
    // irq_b high, a second message while B writes "done": still high.
    assert!(b.clock(idle().a_wr(TO_B, 1)).irq_b);
    let o = b.clock(idle().a_wr(TO_B, 1).b_wr(TO_B, 0));
    assert!(o.irq_b && o.collision);
    // The mirror image for irq_a.
    let o = b.clock(idle().b_wr(TO_A, 3).a_rd(TO_A));
    assert!(o.irq_a);
    assert_eq!(o.a_read_data, 0);
    assert!(b.clock(idle().b_wr(TO_A, 4).a_wr(TO_A, 0)).irq_a);
    assert!(!b.clock(idle().a_rd(TO_A)).irq_a);
}

#[test]
fn both_ports_writing_the_same_word_on_the_same_clock_b_stays_and_collision_pulses() {
    let mut b = Bench::new();
    let o = b.clock(idle().a_wr(5, 0xaaaa).b_wr(5, 0xbbbb));
    assert!(o.collision && !o.overrun);
    // B's write is still queued on the next clock: both ports see it anyway.
    let o = b.clock(idle().a_rd(5).b_rd(5));
    assert!(!o.collision, "one clock only");
    assert_eq!((o.a_read_data, o.b_read_data), (0xbbbb, 0xbbbb));
    b.idle(3);
    assert_eq!(b.read_both(5), (0xbbbb, 0xbbbb));
    // Different words on the same clock: both land, no collision.
    assert!(!b.clock(idle().a_wr(6, 1).b_wr(7, 2)).collision);
    assert_eq!(b.read_both(6), (1, 1));
    assert_eq!(b.read_both(7), (2, 2));
}

#[test]
fn a_read_on_the_clock_the_other_port_writes_returns_the_old_word() {
    let mut b = Bench::new();
    b.clock(idle().a_wr(9, 0x1111));
    let o = b.clock(idle().a_wr(9, 0x2222).b_rd(9));
    assert_eq!(o.b_read_data, 0x1111, "read-first");
    assert_eq!(
        b.clock(idle().b_rd(9)).b_read_data,
        0x2222,
        "new on the next clock"
    );
    let o = b.clock(idle().b_wr(9, 0x3333).a_rd(9));
    assert_eq!(o.a_read_data, 0x2222);
    assert_eq!(b.clock(idle().a_rd(9)).a_read_data, 0x3333);
    // A port's own write on the clock it reads: old word too.
    let o = b.clock(idle().a_wr(9, 0x4444).a_rd(9));
    assert_eq!(o.a_read_data, 0x3333);
    // The answer is held until the next read.
    assert_eq!(b.idle(4).a_read_data, 0x3333);
    assert_eq!(b.clock(idle().a_rd(9)).a_read_data, 0x4444);
}

#[test]
fn back_to_back_writes_up_to_the_write_rate_are_never_refused() {
    let mut b = Bench::new();
    // Both ports on two clocks in a row (4 writes in 2 clocks): queued,
    // readable at once, nothing refused.
    let o = b.clock(idle().a_wr(1, 10).b_wr(2, 20));
    assert!(!o.overrun);
    let o = b.clock(idle().a_wr(3, 30).b_wr(4, 40));
    assert!(!o.overrun);
    for (address, data) in [(1, 10), (2, 20), (3, 30), (4, 40)] {
        assert_eq!(b.read_both(address), (data, data));
    }
    // Each port every other clock, interleaved, for a long time: no refusal.
    for k in 0..1000u64 {
        let o = if k % 2 == 0 {
            b.clock(
                idle()
                    .a_wr(k % 16, k)
                    .b_wr(16 + k % 16, k + 1)
                    .a_rd(16 + (k + 7) % 16),
            )
        } else {
            b.clock(idle().b_rd(k % 16))
        };
        assert!(!o.overrun, "clock {k}");
    }
    // One port writing every clock, the other on two clocks in a row: the
    // queue fills to 2 and, while A keeps writing every clock, stays full.
    for k in 0..1000u64 {
        let mut i = idle().a_wr(k % 32, k);
        if k == 500 || k == 501 {
            i = i.b_wr(32 + k % 32, k + 7);
        }
        assert!(!b.clock(i).overrun, "clock {k}");
    }
    b.idle(2);
    for k in 968..1000u64 {
        assert_eq!(b.read_both(k % 32), (k, k));
    }
    assert_eq!(b.read_both(32 + 500 % 32), (507, 507));
    assert_eq!(b.read_both(32 + 501 % 32), (508, 508));
}

#[test]
fn past_the_write_rate_b_writes_are_refused_and_flagged() {
    let mut b = Bench::new();
    // Three clocks in a row with both ports writing: 6 writes in 3 clocks
    // is one more than n + 2, so the third B write is refused.
    assert!(!b.clock(idle().a_wr(1, 1).b_wr(2, 2)).overrun);
    assert!(!b.clock(idle().a_wr(3, 3).b_wr(4, 4)).overrun);
    let o = b.clock(idle().a_wr(5, 5).b_wr(TO_A, 6));
    assert!(o.overrun, "B's third write is refused");
    assert!(!o.irq_a, "and raises no irq");
    assert!(!b.clock(idle()).overrun, "one clock only");
    b.idle(3);
    for (address, data) in [(1, 1), (2, 2), (3, 3), (4, 4), (5, 5), (TO_A, 0)] {
        assert_eq!(b.read_both(address), (data, data), "word {address}");
    }
    // Both ports writing every clock: from the third clock on, every B write is refused.
    let refused: Vec<bool> = (0..10)
        .map(|k| {
            b.clock(idle().a_wr(k, 100 + k).b_wr(k + 16, 200 + k))
                .overrun
        })
        .collect();
    assert_eq!(
        refused,
        [false, false, true, true, true, true, true, true, true, true]
    );
    b.idle(3);
    for k in 0..10 {
        let (a, _) = b.read_both(k);
        assert_eq!(a, 100 + k, "A's writes all land");
    }
    // While A writes every clock the queue does not drain: after two B
    // writes fill it, the next B write is refused however late it comes.
    b.clock(idle().a_wr(0, 0).b_wr(20, 20));
    b.clock(idle().a_wr(0, 0).b_wr(21, 21));
    for _ in 0..100 {
        assert!(!b.clock(idle().a_wr(0, 0)).overrun);
    }
    assert!(b.clock(idle().a_wr(0, 0).b_wr(22, 22)).overrun);
    assert!(
        !b.clock(idle().b_wr(22, 22)).overrun,
        "with A quiet, it is taken"
    );
}

#[test]
fn reset_lowers_irqs_and_read_data_drops_queued_writes_and_keeps_the_ram() {
    let mut b = Bench::new();
    b.clock(idle().a_wr(1, 0x11));
    b.clock(idle().a_wr(TO_B, 1).b_wr(TO_A, 1));
    b.idle(3);
    let o = b.clock(idle().a_rd(1).b_rd(1));
    assert!(o.irq_a && o.irq_b);
    assert_eq!((o.a_read_data, o.b_read_data), (0x11, 0x11));
    // Two writes queued behind A's when the reset comes: dropped.
    b.clock(idle().a_wr(2, 0x22).b_wr(3, 0x33));
    b.clock(idle().a_wr(4, 0x44).b_wr(5, 0x55));
    let o = b.clock(DpramMailboxInputs {
        reset: true,
        ..idle()
    });
    assert_eq!(o, DpramMailboxOutputs::default());
    // Landed: 1, 2 (A's, on its clock), 3 (the queue head, on the next). Dropped: 4, 5.
    for (address, data) in [
        (1, 0x11),
        (2, 0x22),
        (3, 0x33),
        (4, 0),
        (5, 0),
        (TO_B, 1),
        (TO_A, 1),
    ] {
        assert_eq!(b.read_both(address), (data, data), "word {address}");
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut stimulus = Stimulus::new(0xd9c, 10);
    check_instance::<DpramMailbox1024x16>(
        Instance::Exported("dpram_mailbox"),
        (0..40_000).map(|_| stimulus.next().to_vector()),
    );
}
