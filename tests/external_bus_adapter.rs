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

fn vector(i: &ExternalBusInputs) -> Vec<u64> {
    vec![
        i.reset as u64,
        i.cs_n as u64,
        i.we_n as u64,
        i.rd_n as u64,
        i.address,
        i.data_in,
        i.bus_read_data,
    ]
}

fn outputs(v: &[u64]) -> ExternalBusOutputs {
    ExternalBusOutputs {
        data_out: v[0],
        data_oe: v[1] != 0,
        bus_address: v[2],
        bus_write_data: v[3],
        bus_write: v[4] != 0,
        bus_read: v[5] != 0,
    }
}

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
        let rtl = outputs(&h.step_vector(&vector(i)).unwrap());
        assert_eq!(rtl, model.step(*i), "cycle {cycle}: {i:?}");
        writes += rtl.bus_write as u32;
        reads += rtl.bus_read as u32;
    }
    assert!(
        writes > 10_000 && reads > 10_000,
        "{writes} writes, {reads} reads"
    );
}

/// A DSP on the pins, a register file on the bus.
struct System {
    h: Harness<Adapter>,
    pins: ExternalBusInputs,
    registers: [u64; 256],
    slave_data: u64,
    pending_read: Option<u64>,
    bus_writes: u32,
    bus_reads: u32,
    last: ExternalBusOutputs,
}

impl System {
    fn clock(&mut self) {
        self.pins.bus_read_data = self.slave_data;
        let out = outputs(&self.h.step_vector(&vector(&self.pins)).unwrap());
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

/// Random writes and reads with random timing at or above every minimum
/// of the datasheet: each write reaches the register file exactly once, and
/// each read returns the last word written to its address.
#[test]
fn an_emulated_dsp_reads_back_every_write_at_minimum_timing() {
    let mut rng = StdRng::seed_from_u64(0xd5b);
    let mut sys = System {
        h: Harness::new("external_bus_adapter", Adapter::default()).unwrap(),
        pins: ExternalBusInputs::default(),
        registers: [0; 256],
        slave_data: 0,
        pending_read: None,
        bus_writes: 0,
        bus_reads: 0,
        last: ExternalBusOutputs::default(),
    };
    let mut expected = [0u64; 256];
    let (mut writes, mut reads) = (0, 0);
    for _ in 0..40_000 {
        let address = rng.gen_range(0..256u64);
        sys.pins.address = address;
        if rng.gen_bool(0.5) {
            let data = rng.gen::<u32>() as u64;
            sys.pins.data_in = data;
            sys.hold(rng.gen_range(0..2));
            sys.pins.cs_n = false;
            sys.pins.we_n = false;
            // The data is stable for the whole strobe: at least 2 clocks.
            sys.hold(rng.gen_range(2..5));
            sys.pins.we_n = true;
            sys.pins.cs_n = true;
            // Zero hold: the DSP may change address and data right away.
            sys.pins.data_in = rng.gen::<u32>() as u64;
            sys.pins.address = rng.gen_range(0..256);
            expected[address as usize] = data;
            writes += 1;
        } else {
            sys.hold(1);
            sys.pins.cs_n = false;
            sys.pins.rd_n = false;
            let access = rng.gen_range(6..9);
            sys.hold(access);
            assert!(sys.last.data_oe);
            assert_eq!(
                sys.last.data_out, expected[address as usize],
                "read of {address} after {access} clocks"
            );
            sys.pins.rd_n = true;
            sys.pins.cs_n = true;
            reads += 1;
        }
        sys.hold(rng.gen_range(2..4));
    }
    sys.hold(10);
    assert_eq!(sys.bus_writes, writes, "writes lost or doubled");
    assert_eq!(sys.bus_reads, reads, "reads lost or doubled");
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus: Vec<Vec<u64>> = random_pins(0xb06, 40_000).iter().map(vector).collect();
    cross_simulate(
        &CosimDesign::exported("external_bus_adapter"),
        Adapter::default(),
        &stimulus,
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
