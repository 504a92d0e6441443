//! `motion_controller_dda`: the controller built without uniform pulse
//! generators (`UNIFORM` = false). Its RTL against the model built the same
//! way, its pins against the full controller's when no axis selects the
//! uniform generator, and what firmware sees of the missing generators.
//! (The build with the analog outputs, `motion_controller_servo`:
//! `analog_axes.rs`.)

use crate::bench::{Bench, ControllerUnderTest};
use crate::motion_controller::{
    chaos_run_on, configure, cross_simulate_exported, drain, queue, ALL_STATUS,
};
use motion_hdl::blocks::motion_controller::io_model::MachinePins;
use motion_hdl::blocks::motion_controller::model::ControllerOutputs;
use motion_hdl::regmap::RegisterMap;
use motion_hdl::sim::Backend;

/// The exported DDA-only configuration (`motion_controller_dda`).
type Dda3 = Bench<3, 4, 5, false, false, true, false>;
/// The full configuration with the DDA-only one's options: the exported
/// `motion_controller` without the soft limits, which the DDA-only build
/// does not have.
type Full3 = Bench<3, 4, 5, true, false, true, false>;

/// `cycles` clocks of the chaos traffic (which writes random UNIFORM and
/// INTERLEAVED bits, and junk, to every AXIS_CONFIG) on the exported
/// DDA-only controller compiled by Verilator, in lockstep with the model
/// built without uniform generators.
fn dda_chaos(seed: u64, cycles: u64) {
    let started = std::time::Instant::now();
    let run = chaos_run_on(
        Dda3::on(Backend::from_env_or(Backend::Verilator).unwrap()),
        seed,
        cycles,
    );
    assert_eq!(
        run.status_seen,
        ALL_STATUS & !(1 << motion_hdl::blocks::motion_controller::registers::irq::SOFT_LIMIT),
        "every STATUS bit but SOFT_LIMIT (not in this build) seen set: {:#x}",
        run.status_seen
    );
    run.assert_busy("K=3 DDA only", cycles / 5, cycles / 100, cycles / 4000);
    println!(
        "{cycles} lockstep cycles in {:.1} s",
        started.elapsed().as_secs_f64()
    );
}

/// 5 x 10^5 clocks (about 8 s), in the default suite (a seed whose run
/// sees every STATUS bit).
#[test]
fn dda_only_controller_matches_its_model_under_random_traffic() {
    dda_chaos(0xdda_000b, 500_000);
}

/// The soak of the same lockstep: 10^7 clocks.
#[test]
#[ignore]
fn dda_only_controller_matches_its_model_for_ten_million_cycles() {
    dda_chaos(0xdda_0002, 10_000_000);
}

/// The full and the DDA-only controller side by side, each in lockstep
/// with its own model, fed the same traffic in which no axis selects the
/// uniform generator; their pins must agree after every clock.
struct Twins {
    full: Full3,
    dda: Dda3,
    /// Every copy of AXIS_CONFIG, and its UNIFORM and INTERLEAVED bits:
    /// cleared in every write to one (INTERLEAVED too, which the full build
    /// reads back).
    axis_config: Vec<u32>,
    uniform_bits: u32,
    /// CONFIG is never read: it differs by design (`DDA_ONLY`).
    config: u32,
    cycles: u64,
}

impl Twins {
    fn new(backend: Backend) -> Self {
        let full = Full3::on(backend);
        let axis_config = full.map.register("AXIS_CONFIG").unwrap();
        Self {
            axis_config: axis_config.addresses().collect(),
            uniform_bits: axis_config
                .pack(&[("UNIFORM", 1), ("INTERLEAVED", 1)])
                .unwrap(),
            config: full.address("CONFIG", 0),
            dda: Dda3::on(backend),
            full,
            cycles: 0,
        }
    }
}

impl ControllerUnderTest for Twins {
    fn axes(&self) -> usize {
        3
    }

    fn map(&self) -> &RegisterMap {
        &self.full.map
    }

    fn set_pins(&mut self, encoders: Vec<(bool, bool, bool)>, pins: MachinePins) {
        self.dda.set_pins(encoders.clone(), pins);
        self.full.set_pins(encoders, pins);
    }

    fn step(
        &mut self,
        reset: bool,
        address: u32,
        write_data: u32,
        write: bool,
        read: bool,
    ) -> ControllerOutputs {
        let write_data = if write && self.axis_config.contains(&address) {
            write_data & !self.uniform_bits
        } else {
            write_data
        };
        let read = read && address != self.config;
        let full = self.full.step(reset, address, write_data, write, read);
        let dda = self.dda.step(reset, address, write_data, write, read);
        assert_eq!(
            full, dda,
            "cycle {}: the full and the DDA-only controller differ",
            self.cycles
        );
        self.cycles += 1;
        full
    }

    fn last(&self) -> &ControllerOutputs {
        &self.full.last
    }
}

/// Without the uniform generator selected, the DDA-only build is the full
/// controller: the same pins (and bus reads) in every clock under the chaos
/// traffic, each build also in lockstep with its model.
#[test]
fn dda_only_and_full_controller_have_the_same_pins_when_no_axis_is_uniform() {
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    // 1.5 x 10^5 clocks, about 6 s: two RTLs and two models per clock.
    let run = chaos_run_on(Twins::new(backend), 0xdda_0004, 150_000);
    run.assert_busy("twins", 150_000 / 5, 150_000 / 100, 150_000 / 4000);
}

/// What firmware sees: `CONFIG.DDA_ONLY` tells the builds apart;
/// `AXIS_CONFIG.UNIFORM` and `INTERLEAVED` read 0 whatever is written in the
/// DDA-only build (the other fields as written), and an axis asked for the
/// uniform generator runs its DDA: the same pins, clock for clock, as a DDA
/// axis of the full build, with counts above half the period (which a
/// uniform generator would clamp) emitted in full.
#[test]
fn dda_only_build_reads_the_uniform_bits_as_0_and_runs_its_dda() {
    let mut full = Full3::new();
    let mut dda = Dda3::new().with_loopback();
    let config = full.read("CONFIG", 0);
    assert_eq!(
        full.field("CONFIG", "DDA_ONLY", config),
        0,
        "the full build has the uniform generators"
    );
    let config = dda.read("CONFIG", 0);
    assert_eq!(
        dda.field("CONFIG", "DDA_ONLY", config),
        1,
        "CONFIG.DDA_ONLY of the DDA-only build"
    );

    let others = [("ENC_FILTER", 5), ("INDEX_ONCE", 1)];
    let written = full.pack(
        "AXIS_CONFIG",
        &[("UNIFORM", 1), ("INTERLEAVED", 1), others[0], others[1]],
    );
    let kept = full.pack("AXIS_CONFIG", &others);
    for axis in 0..3 {
        full.write("AXIS_CONFIG", axis, written);
        dda.write("AXIS_CONFIG", axis, written);
        assert_eq!(
            full.read("AXIS_CONFIG", axis),
            written,
            "axis {axis}: the full build keeps the uniform bits"
        );
        assert_eq!(
            dda.read("AXIS_CONFIG", axis),
            kept,
            "axis {axis}: the DDA-only build reads them 0"
        );
    }

    // Every axis of the DDA-only build asks for the uniform generator,
    // every axis of the full build for its DDA.
    let period = 40;
    configure(&mut full, period, [false; 3]);
    configure(&mut dda, period, [true; 3]);
    let counts: [&[i32]; 3] = [&[30, -35, 40, 7], &[-40, 21, 0, 33], &[39, 39, -1, -25]];
    let mut expected = [0i64; 3];
    for (axis, counts) in counts.iter().enumerate() {
        queue(&mut full, axis as u32, counts);
        expected[axis] = queue(&mut dda, axis as u32, counts);
    }
    full.write("CONTROL", 0, 1);
    dda.write("CONTROL", 0, 1);
    for clock in 0..(counts[0].len() as u64 + 2) * period as u64 {
        full.idle(1);
        dda.idle(1);
        assert_eq!(full.last.steps, dda.last.steps, "clock {clock}: step pins");
    }
    drain(&mut dda);
    for axis in 0..3u32 {
        assert_eq!(
            dda.pin_steps(axis as usize),
            expected[axis as usize],
            "axis {axis}: steps at the pins"
        );
        assert_eq!(
            dda.read("CMD_POSITION", axis) as i32 as i64,
            expected[axis as usize],
            "axis {axis}"
        );
        let status = dda.read("AXIS_STATUS", axis);
        assert_eq!(
            dda.field("AXIS_STATUS", "INTERP_OVERRANGE", status),
            0,
            "axis {axis}: nothing clamped"
        );
    }
}

/// The exported `motion_controller_dda.v` in Icarus and Verilator, cycle for
/// cycle against the Rust simulation.
#[test]
fn exported_dda_only_verilog_matches_rust_in_icarus_and_verilator() {
    cross_simulate_exported::<false, false, true, false>(
        "motion_controller_dda",
        crate::motion_controller::SUITE_CHAOS_CLOCKS,
        crate::motion_controller::SUITE_ICARUS_CLOCKS,
    );
}
