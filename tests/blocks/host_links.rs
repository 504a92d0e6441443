//! `host_links`: RTL against the model in lockstep on random pins of both
//! buses (rust-hdl, and the exported Verilog compiled by Verilator for
//! 10^6 clocks); an emulated F28335 and CH365 working at the same time at
//! the minimum timing (and the DSP with XREADY), with metastable pin
//! samples: the DSP drives a register file on the controller port while
//! the two exchange messages through the mailbox, each interrupt checked
//! against its rule; cross-simulation.

use std::collections::VecDeque;

use motion_hdl::blocks::bus_synchronizer::model::BusPinInputs;
use motion_hdl::blocks::dpram_mailbox::{mailbox_to_a, mailbox_to_b};
use motion_hdl::blocks::host_links::model::{
    HostLinksGeometry, HostLinksInputs, HostLinksModel, HostLinksOutputs,
};
use motion_hdl::blocks::host_links::SeedHostLinks;
use motion_hdl::blocks::width_mask;
use motion_hdl::sim::{Backend, Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use crate::support::pin_bench::{random_pins, resolve_pins, PinWidths};

const NAME: &str = "host_links";
const G: HostLinksGeometry = HostLinksGeometry::seed();
const DSP_PINS: PinWidths = PinWidths {
    address_bits: 11,
    data_bits: 16,
};
const PC_PINS: PinWidths = PinWidths {
    address_bits: 11,
    data_bits: 8,
};
const TO_DSP: u64 = mailbox_to_b(10);
const TO_PC: u64 = mailbox_to_a(10);

/// Random pins on both buses. In the second half the addresses walk, so
/// that whole words and the mailbox words come often: the DSP over the
/// halves of 4 registers and the top 4 mailbox words (a half every 16
/// clocks), the PC over the bytes of the top 8 mailbox words.
fn random_inputs(seed: u64, cycles: usize) -> Vec<HostLinksInputs> {
    let dsp = random_pins(seed, cycles, DSP_PINS);
    let pc = random_pins(seed ^ 0x9c, cycles, PC_PINS);
    dsp.into_iter()
        .zip(pc)
        .enumerate()
        .map(|(cycle, (mut dsp, mut pc))| {
            if cycle >= cycles / 2 {
                let c = cycle as u64;
                let slot = (c / 16) % 16;
                dsp.address = if slot < 8 {
                    G.dsp_register_address(slot / 2, slot % 2)
                } else {
                    G.dsp_mailbox_address(TO_DSP - (slot - 8) / 2)
                };
                pc.address = G.pc_address(TO_DSP - (c / 32) % 8, (c / 16) % 2);
            }
            HostLinksInputs {
                reset: dsp.reset,
                reg_read_data: dsp.bus_read_data,
                dsp,
                pc,
            }
        })
        .collect()
}

/// Events seen in a lockstep run.
#[derive(Debug, Default)]
struct Seen {
    reg_writes: u32,
    reg_reads: u32,
    irq_dsp_rises: u32,
    irq_pc_rises: u32,
    dsp_order_errors: u32,
    pc_order_errors: u32,
}

fn lockstep(backend: Backend, seed: u64, cycles: usize) -> Seen {
    let model = HostLinksModel::new(G);
    let mut pair = Lockstep::on(backend, NAME, SeedHostLinks::default(), model).unwrap();
    let mut seen = Seen::default();
    let mut last = HostLinksOutputs::default();
    let inputs = random_inputs(seed, cycles);
    pair.run_all(&inputs, |_, _, &got| {
        seen.reg_writes += got.reg_write as u32;
        seen.reg_reads += got.reg_read as u32;
        seen.irq_dsp_rises += (got.irq_dsp && !last.irq_dsp) as u32;
        seen.irq_pc_rises += (got.irq_pc && !last.irq_pc) as u32;
        seen.dsp_order_errors += got.dsp_order_error as u32;
        seen.pc_order_errors += got.pc_order_error as u32;
        last = got;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    seen
}

fn assert_covered(seen: &Seen, scale: u32) {
    assert!(
        seen.reg_writes > scale
            && seen.reg_reads > 10 * scale
            && seen.irq_dsp_rises > scale / 10
            && seen.irq_pc_rises > scale / 10
            && seen.dsp_order_errors > scale
            && seen.pc_order_errors > scale,
        "{seen:?}"
    );
}

#[test]
fn rtl_matches_model_on_random_pins() {
    let seen = lockstep(Backend::RustHdl, 0x415, 200_000);
    assert_covered(&seen, 200);
}

/// The exported Verilog, compiled by Verilator, against the model for
/// 10^6 clocks (rust-hdl's simulation of the block runs about 10^5
/// clocks in a few seconds; the cross-simulation proves the two equal).
#[test]
fn compiled_rtl_matches_model_for_a_million_clocks() {
    let seen = lockstep(Backend::Verilator, 0x416, 1_000_000);
    assert_covered(&seen, 1_000);
}

/// One access by an emulated master.
#[derive(Clone, Copy, Debug)]
enum Op {
    Write { address: u64, data: u64 },
    Read { address: u64 },
}

/// How a master times its strobes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Timing {
    /// Writes of 3 or 4 clocks, reads of `read` clocks.
    Fixed { read: u32 },
    /// Every strobe held until `ready`, sampled from its third clock on.
    Ready,
}

/// A master on one bus working through a queue of accesses, one clock at
/// a time, so that both masters can run at once: zero hold after a
/// strobe (address and data change at random when it ends), 2 clocks and
/// a random 0 to 3 more between strobes.
struct Master {
    widths: PinWidths,
    timing: Timing,
    queue: VecDeque<Op>,
    /// The access under way and its clocks so far.
    current: Option<(Op, u32)>,
    /// Fixed strobe length of the current access.
    length: u32,
    gap: u32,
    pins: BusPinInputs,
    presented: BusPinInputs,
    rng: StdRng,
    resolve: bool,
    /// Read results, in order.
    reads: VecDeque<u64>,
    /// The last access finished, and how many have finished.
    last_finished: Option<Op>,
    strobes: u32,
}

impl Master {
    fn new(widths: PinWidths, timing: Timing, seed: u64, resolve: bool) -> Self {
        let idle = BusPinInputs {
            cs_n: true,
            we_n: true,
            rd_n: true,
            ..Default::default()
        };
        Self {
            widths,
            timing,
            queue: VecDeque::new(),
            current: None,
            length: 0,
            gap: 2,
            pins: idle,
            presented: idle,
            rng: StdRng::seed_from_u64(seed),
            resolve,
            reads: VecDeque::new(),
            last_finished: None,
            strobes: 0,
        }
    }

    fn idle(&self) -> bool {
        self.queue.is_empty() && self.current.is_none()
    }

    /// The pins this clock, as the FPGA's first sample may see them.
    fn present(&mut self) -> BusPinInputs {
        let shown = if self.resolve {
            resolve_pins(&mut self.rng, self.presented, self.pins, self.widths)
        } else {
            self.pins
        };
        self.presented = self.pins;
        shown
    }

    /// After the clock edge: the block's `data_out` and `ready`.
    fn after(&mut self, data_out: u64, ready: bool) {
        if let Some((op, clocks)) = &mut self.current {
            *clocks += 1;
            let done = match self.timing {
                Timing::Ready => *clocks >= 3 && ready,
                Timing::Fixed { .. } => *clocks == self.length,
            };
            assert!(*clocks < 50, "ready never rose");
            if done {
                let op = *op;
                if let Op::Read { .. } = op {
                    self.reads.push_back(data_out);
                }
                self.last_finished = Some(op);
                self.strobes += 1;
                self.current = None;
                self.pins.cs_n = true;
                self.pins.we_n = true;
                self.pins.rd_n = true;
                self.pins.address = self.rng.gen::<u64>() & width_mask(self.widths.address_bits);
                self.pins.data_in = self.rng.gen::<u64>() & width_mask(self.widths.data_bits);
                self.gap = 2 + self.rng.gen_range(0..4);
            }
            return;
        }
        if self.gap > 1 {
            self.gap -= 1;
            return;
        }
        if let Some(op) = self.queue.pop_front() {
            self.pins.cs_n = false;
            match op {
                Op::Write { address, data } => {
                    self.pins.address = address;
                    self.pins.data_in = data;
                    self.pins.we_n = false;
                    self.length = self.rng.gen_range(3..5);
                }
                Op::Read { address } => {
                    self.pins.address = address;
                    self.pins.rd_n = false;
                    if let Timing::Fixed { read } = self.timing {
                        self.length = read;
                    }
                }
            }
            self.current = Some((op, 0));
        }
    }
}

/// The two masters on the block, a register file of 256 words on the
/// controller port (answering in the clock after `reg_read`), and the
/// interrupt rules checked every clock.
struct Card {
    h: Harness<SeedHostLinks>,
    dsp: Master,
    pc: Master,
    registers: [u64; 256],
    answer: u64,
    pending_read: Option<u64>,
    reg_writes: u32,
    reg_reads: u32,
    clock: u64,
    last: HostLinksOutputs,
    order_errors: u32,
}

impl Card {
    fn new(dsp: Timing, seed: u64, resolve: bool) -> Self {
        Self {
            h: Harness::new(NAME, SeedHostLinks::default()).unwrap(),
            dsp: Master::new(DSP_PINS, dsp, seed, resolve),
            // The CH365 has no wait input: fixed timing.
            pc: Master::new(PC_PINS, Timing::Fixed { read: 7 }, seed ^ 0x365, resolve),
            registers: [0; 256],
            answer: 0,
            pending_read: None,
            reg_writes: 0,
            reg_reads: 0,
            clock: 0,
            last: HostLinksOutputs::default(),
            order_errors: 0,
        }
    }

    fn clock(&mut self) {
        let i = HostLinksInputs {
            reset: false,
            dsp: self.dsp.present(),
            pc: self.pc.present(),
            reg_read_data: self.answer,
        };
        let o = HostLinksOutputs::from_vector(&self.h.step_vector(&i.to_vector()).unwrap());
        self.clock += 1;
        if let Some(register) = self.pending_read.take() {
            self.answer = self.registers[register as usize];
        }
        if o.reg_read {
            self.pending_read = Some(o.reg_address);
            self.reg_reads += 1;
        }
        if o.reg_write {
            self.registers[o.reg_address as usize] = o.reg_write_data;
            self.reg_writes += 1;
        }
        assert!(
            !o.mailbox_overrun && !o.mailbox_collision,
            "clock {}: {o:?}",
            self.clock
        );
        self.order_errors += (o.dsp_order_error || o.pc_order_error) as u32;
        self.dsp.after(o.dsp_data_out, o.dsp_ready);
        self.pc.after(o.pc_data_out, o.pc_ready);
        // An interrupt rises only after the other side's ring: the ring is
        // the last access that side finished (a ring is always its last).
        let rang = |m: &Master, address: u64| matches!(m.last_finished, Some(Op::Write { address: a, .. }) if a == address);
        if o.irq_dsp && !self.last.irq_dsp {
            assert!(
                rang(&self.pc, G.pc_address(TO_DSP, 1)),
                "clock {}: irq_dsp without a ring",
                self.clock
            );
        }
        if o.irq_pc && !self.last.irq_pc {
            assert!(
                rang(&self.dsp, G.dsp_mailbox_address(TO_PC)),
                "clock {}: irq_pc without a ring",
                self.clock
            );
        }
        self.last = o;
    }

    /// Runs until both masters are idle and their last strobes have had
    /// 8 clocks to take effect.
    fn settle(&mut self) {
        while !(self.dsp.idle() && self.pc.idle()) {
            self.clock();
        }
        for _ in 0..8 {
            self.clock();
        }
    }

    /// Runs until `irq` holds, at most `limit` clocks.
    fn wait_for(&mut self, irq: fn(&HostLinksOutputs) -> bool, limit: u32) {
        for _ in 0..limit {
            if irq(&self.last) {
                return;
            }
            self.clock();
        }
        panic!("clock {}: interrupt never rose", self.clock);
    }
}

fn dsp_word_write(address: u64, data: u64) -> Op {
    Op::Write {
        address: G.dsp_mailbox_address(address),
        data,
    }
}

fn pc_word_write(m: &mut Master, word: u64, data: u64) {
    m.queue.push_back(Op::Write {
        address: G.pc_address(word, 0),
        data: data & 0xff,
    });
    m.queue.push_back(Op::Write {
        address: G.pc_address(word, 1),
        data: data >> 8,
    });
}

fn pc_word_read(m: &mut Master, word: u64) {
    m.queue.push_back(Op::Read {
        address: G.pc_address(word, 0),
    });
    m.queue.push_back(Op::Read {
        address: G.pc_address(word, 1),
    });
}

fn pc_words(m: &mut Master, count: usize) -> Vec<u64> {
    (0..count)
        .map(|_| {
            let low = m.reads.pop_front().unwrap();
            let high = m.reads.pop_front().unwrap();
            high << 8 | low
        })
        .collect()
}

/// `rounds` message exchanges: the PC writes a message of 1 to 8 words
/// and rings the DSP (`MAILBOX_TO_B`); the DSP, which meanwhile drives
/// random 32-bit register accesses, reads it after `irq_dsp`, answers
/// with a reply and rings the PC (`MAILBOX_TO_A`), which reads it after
/// `irq_pc`. Checks every message, reply and register read, that each
/// interrupt rises only after its ring and falls after the receiver's
/// access, and that every register write arrives once, whole.
fn session(dsp_timing: Timing, seed: u64, resolve: bool, rounds: usize) {
    let mut card = Card::new(dsp_timing, seed, resolve);
    let mut rng = StdRng::seed_from_u64(seed ^ 0xabc);
    let mut expected = [0u64; 256];
    let (mut reg_writes, mut reg_reads) = (0, 0);
    for round in 0..rounds {
        // The PC writes its message and rings; the DSP works on registers.
        let len = rng.gen_range(1..=8u64);
        let base = rng.gen_range(0..512u64);
        let message: Vec<u64> = (0..len).map(|_| rng.gen::<u16>() as u64).collect();
        for (k, &w) in message.iter().enumerate() {
            pc_word_write(&mut card.pc, base + k as u64, w);
        }
        pc_word_write(&mut card.pc, TO_DSP, 1);
        let mut dsp_reads = Vec::new();
        for _ in 0..rng.gen_range(2..8) {
            let register = rng.gen_range(0..256u64);
            if rng.gen_bool(0.5) {
                let value = rng.gen::<u32>() as u64;
                card.dsp.queue.push_back(Op::Write {
                    address: G.dsp_register_address(register, 0),
                    data: value & 0xffff,
                });
                card.dsp.queue.push_back(Op::Write {
                    address: G.dsp_register_address(register, 1),
                    data: value >> 16,
                });
                expected[register as usize] = value;
                reg_writes += 1;
            } else {
                card.dsp.queue.push_back(Op::Read {
                    address: G.dsp_register_address(register, 0),
                });
                card.dsp.queue.push_back(Op::Read {
                    address: G.dsp_register_address(register, 1),
                });
                dsp_reads.push(expected[register as usize]);
                reg_reads += 1;
            }
        }
        assert!(
            !card.last.irq_dsp,
            "round {round}: irq_dsp before the PC rang"
        );
        card.settle();
        card.wait_for(|o| o.irq_dsp, 20);
        for want in dsp_reads {
            let low = card.dsp.reads.pop_front().unwrap();
            let high = card.dsp.reads.pop_front().unwrap();
            assert_eq!(high << 16 | low, want, "round {round}: register read");
        }

        // The DSP takes the ring (clears irq_dsp), reads the message, writes
        // its reply (each word + 1, after the message) and rings the PC.
        card.dsp.queue.push_back(Op::Read {
            address: G.dsp_mailbox_address(TO_DSP),
        });
        for k in 0..len {
            card.dsp.queue.push_back(Op::Read {
                address: G.dsp_mailbox_address(base + k),
            });
        }
        for (k, &w) in message.iter().enumerate() {
            card.dsp
                .queue
                .push_back(dsp_word_write(base + len + k as u64, (w + 1) & 0xffff));
        }
        card.dsp.queue.push_back(dsp_word_write(TO_PC, 1));
        assert!(
            !card.last.irq_pc,
            "round {round}: irq_pc before the DSP rang"
        );
        card.settle();
        assert!(
            !card.last.irq_dsp,
            "round {round}: irq_dsp not cleared by the DSP's read"
        );
        card.wait_for(|o| o.irq_pc, 20);
        assert_eq!(
            card.dsp.reads.pop_front(),
            Some(1),
            "round {round}: the ring word"
        );
        let got: Vec<u64> = (0..len)
            .map(|_| card.dsp.reads.pop_front().unwrap())
            .collect();
        assert_eq!(got, message, "round {round}: message");

        // The PC takes its ring (clears irq_pc) and reads the reply.
        pc_word_read(&mut card.pc, TO_PC);
        for k in 0..len {
            pc_word_read(&mut card.pc, base + len + k);
        }
        card.settle();
        assert!(
            !card.last.irq_pc,
            "round {round}: irq_pc not cleared by the PC's read"
        );
        let got = pc_words(&mut card.pc, 1 + len as usize);
        assert_eq!(got[0], 1, "round {round}: the ring word");
        let want: Vec<u64> = message.iter().map(|w| (w + 1) & 0xffff).collect();
        assert_eq!(&got[1..], &want[..], "round {round}: reply");
    }
    assert_eq!(
        card.reg_writes, reg_writes,
        "register writes lost or doubled"
    );
    assert_eq!(card.reg_reads, reg_reads, "register reads lost or doubled");
    assert_eq!(card.registers, expected);
    assert_eq!(card.order_errors, 0);
    let strobes = (card.dsp.strobes, card.pc.strobes);
    assert!(strobes.0 + strobes.1 >= 20_000, "{strobes:?} strobes");
    println!("{strobes:?} strobes in {} clocks", card.clock);
}

#[test]
fn dsp_and_pc_exchange_messages_while_the_dsp_drives_the_registers() {
    session(Timing::Fixed { read: 6 }, 0x5eed, false, 700);
}

#[test]
fn the_exchange_survives_randomly_resolved_samples_and_xready() {
    session(Timing::Fixed { read: 7 }, 0x5eee, true, 700);
    session(Timing::Ready, 0x5eef, true, 700);
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<SeedHostLinks>(
        Instance::Exported(NAME),
        random_inputs(0x417, 40_000)
            .iter()
            .map(HostLinksInputs::to_vector),
    );
}
