//! The motion controller behind the external bus adapter, wired as in the
//! board example (`boards/ice40-hx8k-breakout/motion_board.v`): an
//! emulated DSP drives the asynchronous pins at the adapter's datasheet
//! minimum timing, and the controller sees only the adapter's one-clock
//! strobes. Both blocks run against their models in lockstep (the
//! controller through the shared bench), and the step pins drive simulated
//! encoders.

#[allow(dead_code)]
use crate::bench::Bench;
use motion_hdl::blocks::external_bus_adapter::model::{
    ExternalBusInputs, ExternalBusModel, ExternalBusOutputs,
};
use motion_hdl::blocks::external_bus_adapter::ExternalBusAdapter;
use motion_hdl::blocks::motion_controller::registers::ID_VALUE;
use motion_hdl::sim::{Lockstep, VectorPorts};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The adapter and the controller, registered outputs wired to inputs.
struct Board {
    /// The adapter's RTL and model.
    adapter: Lockstep<ExternalBusModel>,
    controller: Bench<3, 4, 5, true, false, true>,
    /// What the DSP drives on the pins.
    pins: ExternalBusInputs,
    /// The adapter's outputs after the last clock.
    bus: ExternalBusOutputs,
    /// Strobes the controller received.
    writes_seen: u32,
    reads_seen: u32,
    /// Garbage for the pins between accesses.
    rng: StdRng,
}

impl Board {
    fn new() -> Self {
        Self {
            adapter: Lockstep::harness(
                "external_bus_adapter",
                ExternalBusAdapter::<8>::default(),
                ExternalBusModel::new(8),
            ),
            controller: Bench::new().with_loopback(),
            pins: ExternalBusInputs::default(),
            bus: ExternalBusOutputs::default(),
            writes_seen: 0,
            reads_seen: 0,
            rng: StdRng::seed_from_u64(0xb0a2d),
        }
    }

    /// One clock edge for both blocks: each sees the other's outputs of
    /// the clock before, as the direct wiring in the board does.
    fn clock(&mut self) {
        let mut inputs = self.pins;
        inputs.bus_read_data = self.controller.last.read_data as u64;
        debug_assert_eq!(
            inputs.to_vector().len(),
            ExternalBusAdapter::<8>::input_names().len()
        );
        let out = self
            .adapter
            .step(&inputs)
            .unwrap_or_else(|e| panic!("adapter: {e}"));
        let bus = self.bus;
        self.controller.clock(
            false,
            bus.bus_address as u32,
            bus.bus_write_data as u32,
            bus.bus_write,
            bus.bus_read,
        );
        self.writes_seen += bus.bus_write as u32;
        self.reads_seen += bus.bus_read as u32;
        self.bus = out;
    }

    fn hold(&mut self, clocks: u32) {
        for _ in 0..clocks {
            self.clock();
        }
    }

    /// A write at the minimum timing: a 3-clock strobe, address and data
    /// changed the moment it ends, then the 2-clock gap.
    fn write(&mut self, name: &str, index: u32, value: u32) {
        self.pins.address = self.controller.address(name, index) as u64;
        self.pins.data_in = value as u64;
        self.pins.cs_n = false;
        self.pins.we_n = false;
        self.hold(3);
        self.pins.we_n = true;
        self.pins.cs_n = true;
        self.pins.address = self.rng.gen_range(0..256);
        self.pins.data_in = self.rng.gen::<u32>() as u64;
        self.hold(2);
    }

    /// A read sampled at the minimum access time of 6 clocks.
    fn read(&mut self, name: &str, index: u32) -> u32 {
        self.pins.address = self.controller.address(name, index) as u64;
        self.pins.cs_n = false;
        self.pins.rd_n = false;
        self.hold(6);
        assert!(
            self.bus.data_oe,
            "the adapter drives the data pins during a read"
        );
        let value = self.bus.data_out as u32;
        self.pins.rd_n = true;
        self.pins.cs_n = true;
        self.pins.address = self.rng.gen_range(0..256);
        self.hold(2);
        value
    }
}

/// A DSP configures the controller, queues random moves on three axes and
/// polls it to rest, all through the asynchronous pins. Every access
/// reaches the controller exactly once; ID, the registers written and read
/// back, and at the end each axis's commanded and actual positions (equal
/// to the sum of its queued counts) arrive at the pins. (The controller's
/// own read data is checked against its model on every clock.)
#[test]
fn a_dsp_runs_moves_through_the_bus_adapter() {
    let mut board = Board::new();
    let mut rng = StdRng::seed_from_u64(0xd5e);
    let (mut writes, mut reads) = (0u32, 0u32);
    assert_eq!(board.read("ID", 0), ID_VALUE);
    reads += 1;
    for (name, value) in [("TICK_DIVISOR", 1), ("PERIOD_TICKS", 60)] {
        board.write(name, 0, value);
        assert_eq!(board.read(name, 0), value, "{name} reads back");
        (writes, reads) = (writes + 1, reads + 1);
    }
    let mut expected = [0i64; 3];
    for axis in 0..3u32 {
        let config = board.controller.pack(
            "AXIS_CONFIG",
            &[("UNIFORM", (axis == 1) as u64), ("INTERLEAVED", 1)],
        );
        board.write("AXIS_CONFIG", axis, config);
        writes += 1;
        for timer in ["STEP_LEN", "STEP_SPACE", "DIR_SETUP", "DIR_HOLD"] {
            board.write(timer, axis, 1);
            writes += 1;
        }
        for _ in 0..12 {
            let count: i32 = rng.gen_range(-25..=25);
            board.write("FIFO_WRITE", axis, count as u32);
            expected[axis as usize] += count as i64;
            writes += 1;
        }
    }
    board.write("CONTROL", 0, 1);
    writes += 1;
    let mut polls = 0;
    loop {
        let state = board.read("STATE", 0);
        let busy = (0..3).any(|axis| {
            let status = board.read("AXIS_STATUS", axis);
            reads += 1;
            board.controller.field("AXIS_STATUS", "STEP_BUSY", status) == 1
                || board
                    .controller
                    .field("AXIS_STATUS", "UNIFORM_RUNNING", status)
                    == 1
        });
        reads += 1;
        polls += 1;
        if board.controller.field("STATE", "RUNNING", state) == 0 && !busy {
            break;
        }
        assert!(polls < 2000, "the controller did not come to rest");
    }
    board.hold(20); // encoder latency
    for axis in 0..3u32 {
        let commanded = board.read("CMD_POSITION", axis) as i32 as i64;
        let actual = board.read("ACT_POSITION", axis) as i32 as i64;
        reads += 2;
        assert_eq!(
            (commanded, actual),
            (expected[axis as usize], expected[axis as usize]),
            "axis {axis}"
        );
        assert_eq!(
            board.controller.pin_steps(axis as usize),
            expected[axis as usize]
        );
    }
    let status = board.read("STATUS", 0);
    reads += 1;
    assert_eq!(
        board.controller.field("STATUS", "UNDERRUN", status),
        1,
        "the move ends with the underrun of the empty FIFOs"
    );
    board.hold(10);
    assert_eq!(
        (board.writes_seen, board.reads_seen),
        (writes, reads),
        "strobes lost or doubled"
    );
    assert!(expected.iter().all(|&e| e != 0));
}
