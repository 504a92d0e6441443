//! `external_bus_adapter`: RTL against the model on random pin activity, an
//! emulated DSP doing random reads and writes at the datasheet's minimum
//! timing against a register-file slave, and cross-simulation.

use motion_hdl::blocks::external_bus_adapter::model::{
    ExternalBusInputs, ExternalBusModel, ExternalBusOutputs,
};
use motion_hdl::blocks::external_bus_adapter::ExternalBusAdapter;
use motion_hdl::sim::Harness;
use motion_hdl::tools::cosim::{cross_simulate, CosimDesign};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

type Adapter = ExternalBusAdapter<8>;

/// Pins that change at random, strobes of every width from one clock
/// (including the illegal ones), reads and writes overlapping.
fn random_pins(seed: u64, cycles: usize) -> Vec<ExternalBusInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut i = ExternalBusInputs::default();
    (0..cycles)
        .map(|_| {
            if rng.gen_ratio(1, 4) {
                i.cs_n = rng.gen_ratio(1, 3);
            }
            if rng.gen_ratio(1, 3) {
                i.we_n = !i.we_n;
            }
            if rng.gen_ratio(1, 3) {
                i.rd_n = !i.rd_n;
            }
            if rng.gen_ratio(1, 2) {
                i.address = rng.gen_range(0..256);
            }
            if rng.gen_ratio(1, 2) {
                i.data_in = rng.gen::<u32>() as u64;
            }
            i.bus_read_data = rng.gen::<u32>() as u64;
            i.reset = rng.gen_ratio(1, 50_000);
            i
        })
        .collect()
}

#[test]
fn rtl_matches_model_on_random_pins() {
    let mut h = Harness::new("external_bus_adapter", Adapter::default()).unwrap();
    let mut model = ExternalBusModel::new(8);
    let (mut writes, mut reads) = (0, 0);
    for (cycle, i) in random_pins(0xb05, 1_000_000).iter().enumerate() {
        let rtl = ExternalBusOutputs::from_vector(&h.step_vector(&i.to_vector()).unwrap());
        assert_eq!(rtl, model.step(*i), "cycle {cycle}: {i:?}");
        writes += rtl.bus_write as u32;
        reads += rtl.bus_read as u32;
    }
    assert!(
        writes > 10_000 && reads > 10_000,
        "{writes} writes, {reads} reads"
    );
}

/// A DSP on the pins, a register file on the bus. With `resolve`, every
/// pin change is presented for its first clock as a random per-bit mix of
/// the old and new values, as a synchronizer may resolve a sample taken
/// while the pins switch.
struct System {
    h: Harness<Adapter>,
    pins: ExternalBusInputs,
    presented: ExternalBusInputs,
    resolve: Option<StdRng>,
    registers: [u64; 256],
    slave_data: u64,
    pending_read: Option<u64>,
    bus_writes: u32,
    bus_reads: u32,
    last: ExternalBusOutputs,
}

impl System {
    fn new(resolve: Option<u64>) -> Self {
        Self {
            h: Harness::new("external_bus_adapter", Adapter::default()).unwrap(),
            pins: ExternalBusInputs::default(),
            presented: ExternalBusInputs::default(),
            resolve: resolve.map(StdRng::seed_from_u64),
            registers: [0; 256],
            slave_data: 0,
            pending_read: None,
            bus_writes: 0,
            bus_reads: 0,
            last: ExternalBusOutputs::default(),
        }
    }

    fn clock(&mut self) {
        let mut shown = self.pins;
        if let Some(rng) = &mut self.resolve {
            let (old, new) = (self.presented, self.pins);
            let mix = |rng: &mut StdRng, old: u64, new: u64| {
                let take_new = rng.gen::<u64>();
                (old & !take_new) | (new & take_new)
            };
            shown.address = mix(rng, old.address, new.address) & 0xff;
            shown.data_in = mix(rng, old.data_in, new.data_in) & 0xffff_ffff;
            for (o, n, s) in [
                (old.cs_n, new.cs_n, &mut shown.cs_n),
                (old.we_n, new.we_n, &mut shown.we_n),
                (old.rd_n, new.rd_n, &mut shown.rd_n),
            ] {
                *s = if o != n && rng.gen_bool(0.5) { o } else { n };
            }
        }
        // Whatever was shown, the pins have their new value from now on.
        self.presented = self.pins;
        shown.bus_read_data = self.slave_data;
        let out = ExternalBusOutputs::from_vector(&self.h.step_vector(&shown.to_vector()).unwrap());
        // The slave registers its answer in the clock after bus_read.
        if let Some(address) = self.pending_read.take() {
            self.slave_data = self.registers[address as usize];
        }
        if out.bus_read {
            self.pending_read = Some(out.bus_address);
            self.bus_reads += 1;
        }
        if out.bus_write {
            self.registers[out.bus_address as usize] = out.bus_write_data;
            self.bus_writes += 1;
        }
        assert!(!(out.bus_read && out.bus_write));
        self.last = out;
    }

    fn hold(&mut self, clocks: u32) {
        for _ in 0..clocks {
            self.clock();
        }
    }
}

/// Random writes and reads at the datasheet's minimum timing: 3-clock
/// write strobes with data set up 2 clocks before their end and changed
/// the moment they end, reads sampled `access` clocks after rd_n falls,
/// 2-clock gaps. Returns the number of reads that returned a wrong word;
/// checks that every write and read reached the bus exactly once.
fn dsp_session(seed: u64, resolve: bool, access: std::ops::Range<u32>) -> u32 {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut sys = System::new(resolve.then_some(seed + 1));
    let mut expected = [0u64; 256];
    let (mut writes, mut reads, mut wrong) = (0, 0, 0);
    for _ in 0..20_000 {
        let address = rng.gen_range(0..256u64);
        sys.pins.address = address;
        if rng.gen_bool(0.5) {
            let data = rng.gen::<u32>() as u64;
            sys.pins.data_in = data;
            sys.pins.cs_n = false;
            sys.pins.we_n = false;
            sys.hold(rng.gen_range(3..5));
            sys.pins.we_n = true;
            sys.pins.cs_n = true;
            // Zero hold: address and data change as the strobe ends.
            sys.pins.data_in = rng.gen::<u32>() as u64;
            sys.pins.address = rng.gen_range(0..256);
            expected[address as usize] = data;
            writes += 1;
        } else {
            sys.pins.cs_n = false;
            sys.pins.rd_n = false;
            sys.hold(rng.gen_range(access.clone()));
            assert!(sys.last.data_oe);
            wrong += (sys.last.data_out != expected[address as usize]) as u32;
            sys.pins.rd_n = true;
            sys.pins.cs_n = true;
            sys.pins.address = rng.gen_range(0..256);
            reads += 1;
        }
        sys.hold(2);
    }
    sys.hold(10);
    assert_eq!(sys.bus_writes, writes, "writes lost or doubled");
    assert_eq!(sys.bus_reads, reads, "reads lost or doubled");
    wrong
}

/// At the exact minimum: 6 clocks from rd_n to sampling, with every pin
/// change seen cleanly. Each write arrives once, each read returns the
/// last word written.
#[test]
fn an_emulated_dsp_reads_back_every_write_at_the_minimum_timing() {
    assert_eq!(dsp_session(0xd5b, false, 6..7), 0);
}

/// Every pin change resolved randomly, bit by bit, on its first sample
/// (metastability): still exactly one bus access per strobe and the right
/// data, with one more clock of read access for the late first sample.
#[test]
fn accesses_survive_randomly_resolved_samples_at_every_pin_change() {
    assert_eq!(dsp_session(0xd5c, true, 7..9), 0);
}

/// The read access minimum is tight: sampling after 5 clocks returns stale
/// words.
#[test]
fn five_clocks_of_read_access_are_not_enough() {
    assert!(dsp_session(0xd5d, false, 5..6) > 1000);
}

/// A runt strobe (one active sample) is not an access.
#[test]
fn a_one_sample_runt_is_ignored() {
    let mut sys = System::new(None);
    for pins in [(false, false, true), (false, true, false)] {
        (sys.pins.cs_n, sys.pins.we_n, sys.pins.rd_n) = pins;
        sys.hold(1);
        (sys.pins.cs_n, sys.pins.we_n, sys.pins.rd_n) = (true, true, true);
        sys.hold(10);
    }
    assert_eq!((sys.bus_writes, sys.bus_reads), (0, 0));
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus: Vec<Vec<u64>> = random_pins(0xb06, 40_000).iter().map(ExternalBusInputs::to_vector).collect();
    cross_simulate(
        &CosimDesign::exported("external_bus_adapter"),
        Adapter::default(),
        &stimulus,
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
