//! `spi_bus_adapter`: RTL against the model under random framed traffic
//! (good, corrupted, cut short and too-fast frames, garbage pins, resets);
//! the contract at the pins checked by an independent monitor with a
//! register file behind the bus (and shown to fail on mutants); every
//! abort point and every single-bit error of a frame; cross-simulation.

use motion_hdl::blocks::spi_bus_adapter::frame::{
    self, crc8, STATUS_ABORTED, STATUS_CRC_ERROR, STATUS_MARKER, STATUS_OVERSPEED,
};
use motion_hdl::blocks::spi_bus_adapter::model::{SpiBusModel, SpiInputs, SpiOutputs};
use motion_hdl::blocks::spi_bus_adapter::{SpiBusAdapter, SNAPSHOT_ADDRESS};
use motion_hdl::host::spi::{transfer, SpiPins, SpiTiming};
use motion_hdl::sim::{stepper, Backend, Lockstep, VectorPorts};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const SNAPSHOT: u8 = SNAPSHOT_ADDRESS as u8;

/// CS high, SCLK low: the pins between frames.
const IDLE: SpiPins = SpiPins {
    sclk: false,
    cs_n: true,
    mosi: false,
};

/// The clocks at which SCLK rises in `pins`.
fn rises(pins: &[SpiPins]) -> Vec<usize> {
    (0..pins.len())
        .filter(|&k| pins[k].sclk && (k == 0 || !pins[k - 1].sclk))
        .collect()
}

#[test]
fn the_crc_is_crc8_smbus() {
    assert_eq!(crc8(b"123456789"), 0xf4);
    assert_eq!(crc8(&[]), 0);
}

/// The pins of one frame at `timing`, as the master drives them.
fn frame_pins(timing: SpiTiming, bytes: &[u8]) -> Vec<SpiPins> {
    let mut pins = Vec::new();
    transfer(timing, bytes, |p| {
        pins.push(p);
        false
    });
    pins
}

fn random_timing(rng: &mut StdRng) -> SpiTiming {
    SpiTiming {
        high: rng.gen_range(2..5),
        low: rng.gen_range(2..5),
        lead: rng.gen_range(3..6),
        lag: rng.gen_range(0..4),
        gap: rng.gen_range(2..5),
    }
}

/// A random frame's bytes: writes and reads of 1 to 16 words, some with
/// `SNAPSHOT`, a few with a wrong CRC.
fn random_frame(rng: &mut StdRng) -> Vec<u8> {
    let address = rng.gen::<u8>();
    let words = rng.gen_range(1..=16);
    let mut bytes = if rng.gen_bool(0.5) {
        let data: Vec<u32> = (0..words).map(|_| rng.gen()).collect();
        frame::write_frame(address, &data).unwrap()
    } else {
        frame::read_frame(address, words, rng.gen_bool(0.3)).unwrap()
    };
    if rng.gen_bool(0.1) {
        let k = rng.gen_range(0..bytes.len().min(3 + 4 * words));
        bytes[k] ^= 1 << rng.gen_range(0..8);
    }
    bytes
}

/// Random traffic at the pins: frames at random timings, some cut short,
/// some with one SCLK phase of a single clock, stretches of random pins,
/// and rare resets.
fn random_traffic(seed: u64, cycles: usize) -> Vec<SpiInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(cycles + 5_000);
    while out.len() < cycles {
        let mut pins = frame_pins(random_timing(&mut rng), &random_frame(&mut rng));
        match rng.gen_range(0..10) {
            // Cut short: CS rises anywhere.
            0 => {
                let keep = rng.gen_range(1..pins.len());
                pins.truncate(keep);
                pins.extend([IDLE; 3]);
            }
            // One phase a single clock long.
            1 => {
                let from = rng.gen_range(0..pins.len() - 1);
                if let Some(k) = (from..pins.len() - 1).find(|&k| pins[k].sclk != pins[k + 1].sclk)
                {
                    let run = pins[k + 1..]
                        .iter()
                        .take_while(|p| p.sclk == pins[k + 1].sclk)
                        .count();
                    if run > 1 {
                        pins.drain(k + 2..k + 1 + run);
                    }
                }
            }
            // Garbage at the pins.
            2 => {
                for _ in 0..rng.gen_range(10..300) {
                    pins.push(SpiPins {
                        sclk: rng.gen(),
                        cs_n: rng.gen_bool(0.2),
                        mosi: rng.gen(),
                    });
                }
            }
            _ => {}
        }
        let reset_at = rng.gen_bool(0.02).then(|| rng.gen_range(0..pins.len()));
        for (k, p) in pins.into_iter().enumerate() {
            out.push(SpiInputs {
                reset: Some(k) == reset_at,
                sclk: p.sclk,
                cs_n: p.cs_n,
                mosi: p.mosi,
                bus_read_data: rng.gen(),
            });
        }
    }
    out
}

#[test]
fn rtl_matches_model_under_random_framed_traffic() {
    let mut pair = Lockstep::harness(
        "spi_bus_adapter",
        SpiBusAdapter::default(),
        SpiBusModel::new(SNAPSHOT),
    );
    let traffic = random_traffic(0x5b1, 1_000_000);
    let (mut writes, mut reads, mut snapshots, mut errors) = (0, 0, 0, 0);
    pair.run_all(&traffic, |_, _, o: &SpiOutputs| {
        writes += (o.bus_write && o.bus_address != SNAPSHOT) as u32;
        snapshots += (o.bus_write && o.bus_address == SNAPSHOT) as u32;
        reads += o.bus_read as u32;
        errors += o.frame_error as u32;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        writes > 1_000 && reads > 1_300 && snapshots > 50 && errors > 1_300,
        "{writes} writes, {reads} reads, {snapshots} snapshot writes, {errors} frame errors"
    );
}

/// One clock of a device under test: the pins and the bus's read data in,
/// the outputs after the edge.
type Device<'a> = Box<dyn FnMut(SpiInputs) -> SpiOutputs + 'a>;

fn rtl_device() -> Device<'static> {
    let mut rtl = stepper(
        Backend::RustHdl,
        "spi_bus_adapter",
        SpiBusAdapter::default(),
        None,
    )
    .unwrap();
    let mut outputs = vec![0; SpiBusAdapter::output_names().len()];
    Box::new(move |i: SpiInputs| {
        rtl.step_into(&i.to_vector(), &mut outputs).unwrap();
        SpiOutputs::from_vector(&outputs)
    })
}

/// The contract at the pins: a master, a 256-register file behind the
/// bus, and what the monitor expects of each frame.
struct Bench<'a> {
    device: Device<'a>,
    /// The outputs as the register file sees them this clock.
    shown: SpiOutputs,
    read_data: u32,
    registers: [u32; 256],
    /// Bus strobes seen: (clock, write, address, data).
    strobes: Vec<(u64, bool, u8, u32)>,
    frame_errors: u32,
    clock: u64,
}

impl<'a> Bench<'a> {
    fn new(device: Device<'a>) -> Self {
        Self {
            device,
            shown: SpiOutputs::default(),
            read_data: 0,
            registers: std::array::from_fn(|k| (k as u32).wrapping_mul(0x9e37_79b9)),
            strobes: Vec::new(),
            frame_errors: 0,
            clock: 0,
        }
    }

    fn clock(&mut self, pins: SpiPins) -> bool {
        let before = self.shown;
        self.shown = (self.device)(SpiInputs {
            reset: false,
            sclk: pins.sclk,
            cs_n: pins.cs_n,
            mosi: pins.mosi,
            bus_read_data: self.read_data,
        });
        if before.bus_write {
            self.registers[before.bus_address as usize] = before.bus_write_data;
            self.strobes
                .push((self.clock, true, before.bus_address, before.bus_write_data));
        }
        if before.bus_read {
            self.read_data = self.registers[before.bus_address as usize];
            self.strobes
                .push((self.clock, false, before.bus_address, 0));
        }
        self.frame_errors += self.shown.frame_error as u32;
        self.clock += 1;
        before.miso
    }

    fn frame(&mut self, timing: SpiTiming, mosi: &[u8]) -> Vec<u8> {
        transfer(timing, mosi, |p| self.clock(p))
    }

    fn idle(&mut self, clocks: usize) {
        for _ in 0..clocks {
            self.clock(IDLE);
        }
    }

    fn pins(&mut self, pins: &[SpiPins]) -> Vec<bool> {
        pins.iter().map(|&p| self.clock(p)).collect()
    }
}

/// What the monitor found wrong, if anything.
type Verdict = Result<(u32, u32), String>;

/// 400 random frames (good, bad CRC, cut short) against the register
/// file; every outcome checked at the pins. Returns (words written, words
/// read).
fn contract_session(device: Device<'_>, seed: u64) -> Verdict {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut b = Bench::new(device);
    let mut expected = b.registers;
    let mut last_status = STATUS_MARKER;
    let (mut written, mut read, mut flagged) = (0, 0, 0);
    for n in 0..400 {
        let timing = random_timing(&mut rng);
        let address = rng.gen::<u8>();
        let words = rng.gen_range(1..=16usize);
        let write = rng.gen_bool(0.5);
        let snapshot = !write && rng.gen_bool(0.3);
        let data: Vec<u32> = (0..words).map(|_| rng.gen()).collect();
        let mut mosi = match write {
            true => frame::write_frame(address, &data).unwrap(),
            false => frame::read_frame(address, words, snapshot).unwrap(),
        };
        let crc_at = if write {
            frame::write_crc_position(words)
        } else {
            2
        };
        let corrupt = rng.gen_bool(0.15);
        // The byte whose check fails first: the header's CRC for a header
        // error, the frame's for one after it.
        let mut check_at = crc_at;
        if corrupt {
            let at = rng.gen_range(0..=crc_at);
            mosi[at] ^= 1 << rng.gen_range(0..8);
            if at <= 2 {
                check_at = 2;
            }
        }
        let cut = rng
            .gen_bool(0.1)
            .then(|| rng.gen_range(1..8 * (crc_at + 1)));
        let strobes_before = b.strobes.len();
        let start = b.clock;
        let status;
        let miso = match cut {
            Some(bits) => {
                let pins = frame_pins(timing, &mosi);
                // CS rises during bit `bits` (before its rise).
                let mut cut_pins = pins[..rises(&pins)[bits]].to_vec();
                cut_pins.extend([IDLE; 4]);
                b.pins(&cut_pins);
                status = match corrupt && bits >= 8 * (check_at + 1) {
                    true => STATUS_MARKER | STATUS_CRC_ERROR,
                    false => STATUS_MARKER | STATUS_ABORTED,
                };
                None
            }
            None => {
                let miso = b.frame(timing, &mosi);
                status = match corrupt {
                    true => STATUS_MARKER | STATUS_CRC_ERROR,
                    false => STATUS_MARKER,
                };
                Some(miso)
            }
        };
        let strobes = &b.strobes[strobes_before..];
        let fail = |what: String| Err(format!("frame {n} ({mosi:02x?}): {what}"));
        if let Some(miso) = &miso {
            if miso[0] != last_status {
                return fail(format!(
                    "first byte {:#04x}, last status {last_status:#04x}",
                    miso[0]
                ));
            }
        }
        let good = cut.is_none() && !corrupt;
        if status != STATUS_MARKER {
            flagged += 1;
        }
        last_status = status;
        if !good {
            if !strobes.is_empty() {
                return fail(format!("bus strobes of a bad frame: {strobes:?}"));
            }
            if let Some(miso) = &miso {
                let at = if write {
                    frame::write_status_position(words)
                } else {
                    3
                };
                if miso[at] != status {
                    return fail(format!("status {:#04x}, expected {status:#04x}", miso[at]));
                }
            }
            if b.registers != expected {
                return fail("a register changed".into());
            }
            continue;
        }
        let miso = miso.unwrap();
        // Strobes: consecutive clocks, the snapshot write first.
        let mut want: Vec<(bool, u8, u32)> = Vec::new();
        if snapshot {
            want.push((true, SNAPSHOT, 0));
        }
        for (k, w) in data.iter().enumerate() {
            let a = address.wrapping_add(k as u8);
            want.push(match write {
                true => (true, a, *w),
                false => (false, a, 0),
            });
        }
        let got: Vec<(bool, u8, u32)> = strobes.iter().map(|s| (s.1, s.2, s.3)).collect();
        if got != want {
            return fail(format!("strobes {got:x?}, expected {want:x?}"));
        }
        if strobes.windows(2).any(|w| w[1].0 != w[0].0 + 1) {
            return fail("strobes not on consecutive clocks".into());
        }
        if strobes[0].0 - start > (timing.frame_clocks(mosi.len()) as u64) {
            return fail("strobes after the frame".into());
        }
        if write {
            let status_at = frame::write_status_position(words);
            if miso[1..status_at]
                .iter()
                .chain(&miso[status_at + 1..])
                .any(|&m| m != 0)
            {
                return fail(format!("MISO {miso:02x?} besides the status bytes"));
            }
            for (k, w) in data.iter().enumerate() {
                expected[address.wrapping_add(k as u8) as usize] = *w;
            }
            written += words as u32;
            if miso[frame::write_status_position(words)] != STATUS_MARKER {
                return fail("a good write frame's status".into());
            }
        } else {
            if snapshot {
                expected[SNAPSHOT as usize] = 0;
            }
            let answer = frame::read_answer(&miso, words);
            let want: Vec<u32> = (0..words)
                .map(|k| expected[address.wrapping_add(k as u8) as usize])
                .collect();
            if answer.status != STATUS_MARKER || !answer.crc_ok || answer.words != want {
                return fail(format!("read {answer:x?}, expected {want:x?}"));
            }
            read += words as u32;
        }
        if b.registers != expected {
            return fail("the register file differs from the writes".into());
        }
    }
    b.pins(&[IDLE; 4]);
    if b.frame_errors != flagged {
        return Err(format!(
            "{} frame_error pulses for {flagged} flagged frames",
            b.frame_errors
        ));
    }
    Ok((written, read))
}

#[test]
fn the_contract_holds_at_the_pins_for_good_corrupted_and_cut_frames() {
    let (written, read) = contract_session(rtl_device(), 0x5b2).unwrap();
    assert!(
        written > 700 && read > 700,
        "{written} written, {read} read"
    );
}

/// A mutant: the model with one output changed once some clocks have run.
fn mutant(kind: u32) -> Device<'static> {
    let mut model = SpiBusModel::new(SNAPSHOT);
    let mut writes = 0;
    let mut clock = 0u64;
    Box::new(move |i: SpiInputs| {
        let mut o = model.step(i);
        clock += 1;
        match kind {
            // One write's data with a bit flipped.
            0 => {
                writes += o.bus_write as u32;
                if o.bus_write && writes == 500 {
                    o.bus_write_data ^= 1 << 7;
                }
            }
            // A write strobe where there was none.
            1 => {
                if clock == 200_000 && !o.bus_write && !o.bus_read {
                    o.bus_write = true;
                }
            }
            // One MISO bit inverted.
            _ => {
                if (300_000..300_040).contains(&clock) {
                    o.miso = !o.miso;
                }
            }
        }
        o
    })
}

#[test]
fn the_monitor_fails_on_mutants() {
    for kind in 0..3 {
        let found = contract_session(mutant(kind), 0x5b3).expect_err("a mutant passed");
        eprintln!("mutant {kind}: {found}");
    }
    // The model itself passes.
    let mut model = SpiBusModel::new(SNAPSHOT);
    contract_session(Box::new(move |i| model.step(i)), 0x5b3).unwrap();
}

/// A 2-word write frame cut by CS rising before each of its bits, and with
/// each of its bits flipped: never a write.
#[test]
fn no_cut_point_and_no_single_bit_error_writes() {
    let timing = SpiTiming::FASTEST;
    let mosi = frame::write_frame(0x40, &[0x1234_5678, 0x9abc_def0]).unwrap();
    let crc_bits = 8 * (frame::write_crc_position(2) + 1);
    let mut b = Bench::new(rtl_device());
    let before = b.registers;
    let pins = frame_pins(timing, &mosi);
    let rises = rises(&pins);
    let mut errors = 0;
    for bit in 0..crc_bits {
        let mut cut = pins[..rises[bit]].to_vec();
        cut.extend([IDLE; 3]);
        b.pins(&cut);
        b.idle(4);
        assert_eq!(b.frame_errors, 1 + errors, "cut before bit {bit}");
        errors = b.frame_errors;
        // CS rising one clock after the bit's rise: the bit still counts
        // (so the frame's last bit completes it).
        if bit + 1 < crc_bits {
            let mut cut = pins[..rises[bit] + 1].to_vec();
            cut.push(SpiPins {
                sclk: true,
                cs_n: true,
                mosi: false,
            });
            cut.extend([IDLE; 3]);
            b.pins(&cut);
            b.idle(4);
            assert_eq!(b.frame_errors, 1 + errors, "cut after bit {bit}");
            errors = b.frame_errors;
        }
        let mut bad = mosi.clone();
        bad[bit / 8] ^= 0x80 >> (bit % 8);
        let miso = b.frame(timing, &bad);
        b.idle(4);
        assert_eq!(b.frame_errors, 1 + errors, "bit {bit} flipped");
        errors = b.frame_errors;
        assert_eq!(miso[0], STATUS_MARKER | STATUS_ABORTED, "bit {bit}");
        assert_eq!(
            miso[frame::write_status_position(2)],
            STATUS_MARKER | STATUS_CRC_ERROR,
            "bit {bit}"
        );
    }
    assert!(b.strobes.is_empty(), "{:?}", &b.strobes[..1]);
    assert_eq!(b.registers, before);
    assert_eq!(b.frame_errors, 3 * crc_bits as u32 - 1);
    // And the frame itself, whole, writes both words.
    let miso = b.frame(timing, &mosi);
    assert_eq!(miso[0], STATUS_MARKER | STATUS_CRC_ERROR);
    assert_eq!(
        (b.registers[0x40], b.registers[0x41]),
        (0x1234_5678, 0x9abc_def0)
    );
}

/// A write frame whose header CRC fails writes nothing, even when its
/// frame CRC matches the bytes as received: a bad header CRC with a frame
/// CRC recomputed over it, and a count corrupted from 2 words to 1 (the
/// frame then laid out one word short, its CRC byte on a data byte that
/// happens to match). Before the fix the formal proof found, the second
/// check at the frame CRC passed both and wrote them. RTL and model.
#[test]
fn a_bad_header_crc_writes_nothing_even_when_the_frame_crc_then_matches() {
    let good = frame::write_frame(0x30, &[0x0102_0304, 0x0506_0708]).unwrap();
    let mut bad_header = good.clone();
    bad_header[2] ^= 0x10;
    let crc_at = frame::write_crc_position(2);
    bad_header[crc_at] = crc8(&bad_header[..crc_at]);
    // The count cut to 1 word; the header CRC still the 2-word one; the
    // frame CRC of the 1-word layout (byte 7) made to match.
    let mut bad_count = good.clone();
    bad_count[0] = good[0] & !frame::COMMAND_COUNT_MASK;
    let crc_at_1 = frame::write_crc_position(1);
    bad_count[crc_at_1] = crc8(&bad_count[..crc_at_1]);
    let devices: [(&str, Device<'static>); 2] = [
        ("rtl", rtl_device()),
        ("model", {
            let mut model = SpiBusModel::new(SNAPSHOT);
            Box::new(move |i| model.step(i))
        }),
    ];
    for (name, device) in devices {
        let mut b = Bench::new(device);
        for (case, mosi, status_at) in [
            (
                "bad header CRC",
                &bad_header,
                frame::write_status_position(2),
            ),
            ("count 2 -> 1", &bad_count, frame::write_status_position(1)),
        ] {
            let miso = b.frame(SpiTiming::FASTEST, mosi);
            b.idle(4);
            assert!(b.strobes.is_empty(), "{name}, {case}: {:?}", b.strobes);
            assert_eq!(
                miso[status_at],
                STATUS_MARKER | STATUS_CRC_ERROR,
                "{name}, {case}: {miso:02x?}"
            );
        }
        assert_eq!(b.frame_errors, 2, "{name}");
        // The good frame still writes both words.
        b.frame(SpiTiming::FASTEST, &good);
        b.idle(4);
        assert_eq!(b.strobes.len(), 2, "{name}");
    }
}

/// One SCLK phase of a single clock, anywhere up to the CRC byte: no
/// write, `OVERSPEED` in the status. After the CRC byte: the write stands,
/// and the next frame's first byte tells.
#[test]
fn a_too_fast_sclk_writes_nothing() {
    let timing = SpiTiming::FASTEST;
    let mosi = frame::write_frame(0x20, &[0xdead_beef]).unwrap();
    let pins = frame_pins(timing, &mosi);
    let mut b = Bench::new(rtl_device());
    let edges: Vec<usize> = (1..pins.len())
        .filter(|&k| pins[k].sclk != pins[k - 1].sclk && !pins[k].cs_n)
        .collect();
    // The CRC byte's last rise: rise r is edges[2 r].
    let crc_end = edges[2 * (8 * (frame::write_crc_position(1) + 1) - 1)];
    let mut wrote_after = 0;
    // Each phase between two edges, the last (ended by CS) aside.
    for &e in &edges[1..edges.len() - 1] {
        let mut fast = pins.clone();
        fast.remove(e + 1);
        let before = b.strobes.len();
        b.pins(&fast);
        let writes = b.strobes.len() - before;
        let next = b.frame(timing, &frame::read_frame(0x00, 1, false).unwrap());
        assert_eq!(next[0] & STATUS_OVERSPEED, STATUS_OVERSPEED, "edge at {e}");
        if e < crc_end {
            assert_eq!(writes, 0, "edge at {e}: a write");
        } else {
            assert_eq!(writes, 1, "edge at {e}: no write");
            wrote_after += 1;
        }
    }
    assert!(wrote_after > 0);
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<SpiBusAdapter>(
        Instance::Exported("spi_bus_adapter"),
        random_traffic(0x5b4, 40_000)
            .iter()
            .map(SpiInputs::to_vector),
    );
}

/// The datasheet's latencies at the fastest SCLK: a write's first
/// `bus_write` and a read's first `bus_read` (after the `SNAPSHOT` write)
/// come `WRITE_LATENCY` clocks after the CRC byte's last SCLK rise at the
/// pins, one a clock.
#[test]
fn strobe_latencies_are_the_datasheets() {
    const WRITE_LATENCY: u64 = 4;
    let timing = SpiTiming::FASTEST;
    let last_rise = |pins: &[SpiPins], bytes: usize| rises(pins)[8 * bytes - 1] as u64;
    let mut b = Bench::new(rtl_device());
    for (mosi, crc_bytes, first_strobe) in [
        (
            frame::write_frame(0x10, &[1, 2, 3]).unwrap(),
            frame::write_crc_position(3) + 1,
            0,
        ),
        (frame::read_frame(0x10, 3, false).unwrap(), 3, 0),
        (frame::read_frame(0x10, 3, true).unwrap(), 3, 1),
    ] {
        let start = b.clock;
        let before = b.strobes.len();
        b.frame(timing, &mosi);
        let rise = start + last_rise(&frame_pins(timing, &mosi), crc_bytes);
        let strobes = &b.strobes[before..];
        assert_eq!(strobes[0].0 - rise, WRITE_LATENCY, "{mosi:02x?}");
        assert_eq!(
            strobes[first_strobe].1,
            first_strobe == 0 && mosi[0] & 0x80 != 0
        );
        assert_eq!(
            strobes.last().unwrap().0 - strobes[0].0,
            strobes.len() as u64 - 1
        );
    }
}
