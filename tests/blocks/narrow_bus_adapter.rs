//! `external_bus_adapter_16` and `external_bus_adapter_8`: RTL against the
//! model on random pins; emulated 16- and 8-bit masters doing random 32-bit
//! register accesses at the minimum timing (and with `ready`) against a
//! register file, with and without metastable pin samples; the tearing
//! test; cross-simulation.

use crate::support::pin_bench::{random_pins, BusView, Length, PinBench, PinWidths};
use motion_hdl::blocks::bus_synchronizer::model::BusPinInputs;
use motion_hdl::blocks::narrow_bus_adapter::model::{NarrowBusModel, NarrowBusOutputs};
use motion_hdl::blocks::narrow_bus_adapter::{
    ExternalBusAdapter16, ExternalBusAdapter8, NarrowBusAdapter,
};
use motion_hdl::blocks::word_assembler::model::PartGeometry;
use motion_hdl::sim::Lockstep;
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn view(v: &[u64]) -> BusView {
    let o = NarrowBusOutputs::from_vector(v);
    BusView {
        data_out: o.data_out,
        data_oe: o.data_oe,
        ready: Some(o.ready),
        bus_address: o.bus_address,
        bus_write_data: o.bus_write_data,
        bus_write: o.bus_write,
        bus_read: o.bus_read,
        order_error: o.order_error,
    }
}

/// One exported configuration: its name, geometry and pin widths.
#[derive(Clone, Copy)]
struct Width {
    name: &'static str,
    geometry: PartGeometry,
}

const W16: Width = Width {
    name: "external_bus_adapter_16",
    geometry: NarrowBusModel::geometry_16(),
};
const W8: Width = Width {
    name: "external_bus_adapter_8",
    geometry: NarrowBusModel::geometry_8(),
};

impl Width {
    fn pins(&self) -> PinWidths {
        PinWidths {
            address_bits: self.geometry.address_bits + self.geometry.part_bits(),
            data_bits: self.geometry.narrow_bits,
        }
    }
}

fn lockstep<const NA: usize, const N: usize>(width: Width, seed: u64, cycles: usize) {
    let mut pair = Lockstep::harness(
        width.name,
        NarrowBusAdapter::<8, NA, N, 32>::default(),
        NarrowBusModel::new(width.geometry),
    );
    let (mut writes, mut reads, mut errors) = (0, 0, 0);
    // In the second half the address walks the parts of one register in
    // order (a part every 16 clocks, a register every 1024), so that whole
    // words happen often.
    let mut pins = random_pins(seed, cycles, width.pins());
    let g = width.geometry;
    for (cycle, i) in pins.iter_mut().enumerate().skip(cycles / 2) {
        let cycle = cycle as u64;
        i.address = g.narrow_address((cycle / 1024) % 4, (cycle / 16) % g.parts());
    }
    pair.run_all(&pins, |_, _, rtl| {
        writes += rtl.bus_write as u32;
        reads += rtl.bus_read as u32;
        errors += rtl.order_error as u32;
    })
    .unwrap_or_else(|e| panic!("{}: {e}", width.name));
    assert!(
        writes > 1_000 && reads > 10_000 && errors > 10_000,
        "{}: {writes} writes, {reads} reads, {errors} order errors",
        width.name
    );
}

#[test]
fn rtl_matches_model_on_random_pins_16() {
    lockstep::<9, 16>(W16, 0x16b, 1_000_000);
}

#[test]
fn rtl_matches_model_on_random_pins_8() {
    lockstep::<10, 8>(W8, 0x8b, 1_000_000);
}

/// How the emulated master times its strobes.
#[derive(Clone, Copy, Debug)]
enum Timing {
    /// Fixed strobes: 3-4 clock writes, reads sampled after `access` clocks.
    Fixed { access: u32 },
    /// Every strobe held until `ready` is high.
    Ready,
}

/// A master of one width on the pins, a 256-register file on the bus.
struct Master<B: motion_hdl::sim::VectorPorts> {
    bench: PinBench<B>,
    width: Width,
    timing: Timing,
    rng: StdRng,
}

impl<B: motion_hdl::sim::VectorPorts> Master<B> {
    fn new(block: B, width: Width, timing: Timing, seed: u64, resolve: bool) -> Self {
        Self {
            bench: PinBench::new(
                width.name,
                block,
                view,
                width.pins(),
                256,
                resolve.then_some(seed ^ 0x5eed),
            ),
            width,
            timing,
            rng: StdRng::seed_from_u64(seed),
        }
    }

    fn write_part(&mut self, address: u64, data: u64) {
        let length = match self.timing {
            Timing::Fixed { .. } => Length::Clocks(self.rng.gen_range(3..5)),
            Timing::Ready => Length::UntilReady,
        };
        self.bench.write(&mut self.rng, address, data, length);
    }

    fn read_part(&mut self, address: u64) -> u64 {
        let length = match self.timing {
            Timing::Fixed { access } => Length::Clocks(access),
            Timing::Ready => Length::UntilReady,
        };
        self.bench.read(&mut self.rng, address, length).0
    }

    /// A 32-bit register write: the lower parts, then the highest.
    fn write_register(&mut self, register: u64, value: u64) {
        let g = self.width.geometry;
        for part in 0..g.parts() {
            self.write_part(g.narrow_address(register, part), g.part_of(value, part));
        }
    }

    /// A 32-bit register read, lowest part first, with `gap` idle clocks
    /// between the parts.
    fn read_register(&mut self, register: u64, gap: u32) -> u64 {
        let g = self.width.geometry;
        (0..g.parts()).fold(0, |word, part| {
            if part > 0 {
                self.bench.hold(gap);
            }
            g.with_part(word, part, self.read_part(g.narrow_address(register, part)))
        })
    }
}

/// 10k random register accesses (20k strobes on a 16-bit bus, 40k on an
/// 8-bit one): every write arrives once and whole, every read returns the
/// last word written; no order error.
fn session<B: motion_hdl::sim::VectorPorts>(
    block: B,
    width: Width,
    timing: Timing,
    seed: u64,
    resolve: bool,
) -> u32 {
    let mut m = Master::new(block, width, timing, seed, resolve);
    let mut expected = [0u64; 256];
    let (mut writes, mut reads, mut wrong) = (0, 0, 0);
    for _ in 0..10_000 {
        let register = m.rng.gen_range(0..256u64);
        if m.rng.gen_bool(0.5) {
            let value = m.rng.gen::<u32>() as u64;
            m.write_register(register, value);
            expected[register as usize] = value;
            writes += 1;
        } else {
            wrong += (m.read_register(register, 0) != expected[register as usize]) as u32;
            reads += 1;
        }
    }
    m.bench.hold(10);
    assert_eq!(
        m.bench.bus_writes, writes,
        "{}: writes lost or doubled",
        width.name
    );
    assert_eq!(
        m.bench.bus_reads, reads,
        "{}: reads lost or doubled",
        width.name
    );
    assert_eq!(m.bench.order_errors, 0, "{}: order errors", width.name);
    assert_eq!(m.bench.registers[..], expected[..]);
    wrong
}

#[test]
fn masters_of_each_width_read_back_every_write_at_the_minimum_timing() {
    let fixed = Timing::Fixed { access: 6 };
    assert_eq!(
        session(ExternalBusAdapter16::default(), W16, fixed, 0x160, false),
        0
    );
    assert_eq!(
        session(ExternalBusAdapter8::default(), W8, fixed, 0x80, false),
        0
    );
}

/// Every pin change resolved randomly, bit by bit, on its first sample.
#[test]
fn accesses_of_each_width_survive_randomly_resolved_samples() {
    let fixed = Timing::Fixed { access: 7 };
    assert_eq!(
        session(ExternalBusAdapter16::default(), W16, fixed, 0x161, true),
        0
    );
    assert_eq!(
        session(ExternalBusAdapter8::default(), W8, fixed, 0x81, true),
        0
    );
}

/// A master that waits for `ready` instead of counting wait states gets
/// the same results, clean and with metastable samples.
#[test]
fn masters_that_wait_for_ready_need_no_fixed_wait_states() {
    for resolve in [false, true] {
        assert_eq!(
            session(
                ExternalBusAdapter16::default(),
                W16,
                Timing::Ready,
                0x162,
                resolve
            ),
            0
        );
        assert_eq!(
            session(
                ExternalBusAdapter8::default(),
                W8,
                Timing::Ready,
                0x82,
                resolve
            ),
            0
        );
    }
}

/// `ready` is as short as the datasheet says: 3 clocks for a write strobe,
/// 6 for a read (clean samples), and a read held only to `ready` returns
/// the right word. Sampling a fixed 5 clocks instead returns stale words.
#[test]
fn ready_timing_is_the_documented_minimum() {
    let mut rng = StdRng::seed_from_u64(7);
    let mut b = PinBench::new(
        W16.name,
        ExternalBusAdapter16::default(),
        view,
        W16.pins(),
        256,
        None,
    );
    let mut too_early_wrong = 0;
    for k in 0..200u64 {
        let register = k % 256;
        let (lo, hi) = (k * 7 + 1, k * 13 + 2);
        assert_eq!(b.write(&mut rng, register * 2, lo, Length::UntilReady), 3);
        assert_eq!(
            b.write(&mut rng, register * 2 + 1, hi, Length::UntilReady),
            3
        );
        let (data, clocks) = b.read(&mut rng, register * 2, Length::UntilReady);
        assert_eq!((data, clocks), (lo, 6));
        let (data, clocks) = b.read(&mut rng, register * 2 + 1, Length::UntilReady);
        assert_eq!((data, clocks), (hi, 6));
        b.write(&mut rng, register * 2, !lo & 0xffff, Length::Clocks(3));
        b.write(&mut rng, register * 2 + 1, !hi & 0xffff, Length::Clocks(3));
        too_early_wrong +=
            (b.read(&mut rng, register * 2, Length::Clocks(5)).0 != !lo & 0xffff) as u32;
    }
    assert!(too_early_wrong > 150, "{too_early_wrong}");
}

/// The tearing test: a counter register adds 1 to every part (each part
/// wrapping on its own) on every clock, so a coherent read has all parts
/// equal, and their value must be one the counter had while the read was
/// under way. Reads of every phase (random start, 0 to 40 idle clocks
/// between the parts) never combine parts of two values. Returns the
/// number of torn reads.
fn tearing<B: motion_hdl::sim::VectorPorts>(
    block: B,
    width: Width,
    seed: u64,
    high_first: bool,
) -> u32 {
    let g = width.geometry;
    let mut m = Master::new(block, width, Timing::Fixed { access: 7 }, seed, true);
    m.bench.counting = Some((
        5,
        Box::new(move |w| {
            (0..g.parts()).fold(0, |next, p| g.with_part(next, p, g.part_of(w, p) + 1))
        }),
    ));
    let counting_from = m.bench.clocks;
    let part_mask = motion_hdl::blocks::width_mask(g.narrow_bits);
    let mut torn = 0;
    for _ in 0..2_000 {
        let start = m.rng.gen_range(0..7);
        m.bench.hold(start);
        let gap = m.rng.gen_range(0..41);
        let began = m.bench.clocks - counting_from;
        let word = if high_first {
            // Broken firmware: the highest part first.
            let top = g.parts() - 1;
            let high = m.read_part(g.narrow_address(5, top));
            m.bench.hold(gap);
            let rest = m.read_register(5, gap);
            g.with_part(rest, top, high)
        } else {
            m.read_register(5, gap)
        };
        let ended = m.bench.clocks - counting_from;
        let low = g.part_of(word, 0);
        let coherent = (0..g.parts()).all(|part| g.part_of(word, part) == low);
        torn += !coherent as u32;
        if !high_first {
            let age = low.wrapping_sub(began) & part_mask;
            assert!(
                age <= ended - began,
                "{}: read a value the counter never had during the read",
                width.name
            );
        }
    }
    torn
}

#[test]
fn a_counter_read_in_parts_never_tears() {
    assert_eq!(
        tearing(ExternalBusAdapter16::default(), W16, 0x7ea, false),
        0
    );
    assert_eq!(tearing(ExternalBusAdapter8::default(), W8, 0x7eb, false), 0);
}

/// The tearing check can fail: firmware that reads the highest part first
/// gets torn words (and the adapter flags every such read).
#[test]
fn the_tearing_check_catches_high_part_first_reads() {
    let mut m = Master::new(
        ExternalBusAdapter16::default(),
        W16,
        Timing::Fixed { access: 7 },
        1,
        false,
    );
    assert!(tearing(ExternalBusAdapter16::default(), W16, 0x7ec, true) > 1_000);
    let _ = m.read_part(W16.geometry.narrow_address(5, 1));
    m.bench.hold(3);
    assert_eq!(m.bench.order_errors, 1);
}

/// Breaking the write order never writes a torn word: the highest part
/// alone, or after another register's lower part, writes nothing and
/// flags it.
#[test]
fn a_torn_write_never_reaches_the_register() {
    let g = W8.geometry;
    let mut m = Master::new(
        ExternalBusAdapter8::default(),
        W8,
        Timing::Fixed { access: 7 },
        2,
        false,
    );
    m.write_register(9, 0x1122_3344);
    m.write_part(g.narrow_address(9, 3), 0xaa);
    m.write_part(g.narrow_address(9, 0), 0x55);
    m.write_part(g.narrow_address(10, 1), 0x66);
    m.write_part(g.narrow_address(9, 3), 0xbb);
    m.bench.hold(4);
    assert_eq!(
        (m.bench.registers[9], m.bench.registers[10]),
        (0x1122_3344, 0)
    );
    assert_eq!((m.bench.bus_writes, m.bench.order_errors), (1, 3));
}

fn cosim<const NA: usize, const N: usize>(width: Width, seed: u64) {
    check_instance::<NarrowBusAdapter<8, NA, N, 32>>(
        Instance::Exported(width.name),
        random_pins(seed, 40_000, width.pins())
            .iter()
            .map(BusPinInputs::to_vector),
    );
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    cosim::<9, 16>(W16, 0x16c);
    cosim::<10, 8>(W8, 0x8c);
}
