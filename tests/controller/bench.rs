//! The motion controller test bench: the RTL and the reference model run
//! in lockstep and are compared after every clock; the bus is driven the
//! way firmware drives it, through the generated register map; each
//! axis's step pins can drive a simulated encoder on that axis's encoder
//! inputs.

use motion_hdl::blocks::motion_controller::io_model::MachinePins;
use motion_hdl::blocks::motion_controller::model::{
    ControllerInputs, ControllerOutputs, MotionControllerModel,
};
use motion_hdl::blocks::motion_controller::registers::register_map;
use motion_hdl::blocks::motion_controller::MotionController;
use motion_hdl::regmap::RegisterMap;
use motion_hdl::sim::{Backend, Lockstep, SimulatedEncoder, VectorPorts};

/// RTL and model of a K-axis controller with 2^N-entry FIFOs, with uniform
/// generators if `UNIFORM`, in lockstep.
pub struct Bench<
    const K: usize,
    const N: usize,
    const NP1: usize,
    const UNIFORM: bool,
    const ANALOG: bool,
    const PROBE: bool,
    const SOFT: bool = true,
    const SPINDLE: bool = false,
    const LASER: bool = false,
> {
    /// The RTL and the reference model.
    pair: Lockstep<MotionControllerModel>,
    /// The controller's register map.
    pub map: RegisterMap,
    /// Encoder inputs applied in the next clock.
    pub encoders: Vec<(bool, bool, bool)>,
    /// Limit, home, alarm, E-stop and general-input pins applied in the
    /// next clock.
    pub pins: MachinePins,
    /// The spindle encoder's pins (a, b, index) applied in the next clock.
    pub spindle: (bool, bool, bool),
    /// Drive each axis's encoder from its own step/dir pins.
    pub loopback: Option<Vec<SimulatedEncoder>>,
    /// Outputs after the last clock.
    pub last: ControllerOutputs,
    /// Clocks run.
    pub cycles: u64,
    /// Step edges seen at the pins while `active` (the drive enable) was low.
    pub steps_while_inactive: u64,
    /// Input vectors of every clock, when recording (for cross-simulation).
    pub recording: Option<Vec<Vec<u64>>>,
}

impl<
        const K: usize,
        const N: usize,
        const NP1: usize,
        const UNIFORM: bool,
        const ANALOG: bool,
        const PROBE: bool,
        const SOFT: bool,
        const SPINDLE: bool,
        const LASER: bool,
    > Bench<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>
{
    /// A bench in the power-up state, on the backend `MOTION_HDL_BACKEND`
    /// names (by default Verilator: the exported Verilog is the product, and
    /// it runs far faster).
    pub fn new() -> Self {
        Self::on(Backend::from_env_or(Backend::Verilator).unwrap())
    }

    /// A bench in the power-up state with the RTL on `backend`.
    pub fn on(backend: Backend) -> Self {
        let build =
            MotionController::<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>::BUILD;
        let map = register_map(K, N as u32, build).unwrap();
        let model = MotionControllerModel::new(K, N as u32, build).unwrap();
        let module = build.module_name();
        let pair = Lockstep::on(
            backend,
            module,
            MotionController::<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>::default(),
            model,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        Self {
            pair,
            map,
            encoders: vec![(false, false, false); K],
            pins: MachinePins::default(),
            spindle: (false, false, false),
            loopback: None,
            last: ControllerOutputs {
                steps: vec![(false, false); K],
                ..Default::default()
            },
            cycles: 0,
            recording: None,
            steps_while_inactive: 0,
        }
    }

    /// The reference model, as it is after the last clock.
    pub fn model(&self) -> &MotionControllerModel {
        self.pair.model()
    }

    /// Turns on the step-to-encoder loopback on every axis.
    pub fn with_loopback(mut self) -> Self {
        self.loopback = Some(vec![SimulatedEncoder::default(); K]);
        self
    }

    /// Word address of copy `index` of register `name`.
    pub fn address(&self, name: &str, index: u32) -> u32 {
        self.map.register(name).unwrap().address_of(index).unwrap()
    }

    /// Packs fields of register `name`.
    pub fn pack(&self, name: &str, fields: &[(&str, u64)]) -> u32 {
        self.map.register(name).unwrap().pack(fields).unwrap()
    }

    /// Unpacks field `field` of register `name` from `word`.
    pub fn field(&self, name: &str, field: &str, word: u32) -> u64 {
        self.map
            .register(name)
            .unwrap()
            .field(field)
            .unwrap()
            .extract(word)
            .unwrap()
    }

    /// The bits of `word` outside every field of register `name` (they
    /// must read 0).
    pub fn unused_bits(&self, name: &str, word: u32) -> u32 {
        let defined = self
            .map
            .register(name)
            .unwrap()
            .fields
            .iter()
            .fold(0u64, |m, f| m | (((1u64 << f.width) - 1) << f.lsb));
        word & !(defined as u32)
    }

    /// One clock with these bus inputs, on the RTL and the model; panics
    /// where they disagree.
    pub fn clock(
        &mut self,
        reset: bool,
        address: u32,
        write_data: u32,
        write: bool,
        read: bool,
    ) -> &ControllerOutputs {
        let inputs = ControllerInputs {
            reset,
            address,
            write_data,
            write,
            read,
            encoders: self.encoders.clone(),
            pins: self.pins,
            spindle: self.spindle,
        };
        let got = self.pair.step(&inputs).unwrap_or_else(|e| panic!("{e}"));
        debug_assert_eq!(
            self.pair.input_vector().len(),
            MotionController::<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>::input_names()
                .len()
        );
        if let Some(recording) = self.recording.as_mut() {
            recording.push(self.pair.input_vector().to_vec());
        }
        self.cycles += 1;
        if let Some(encoders) = self.loopback.as_mut() {
            for (i, encoder) in encoders.iter_mut().enumerate() {
                let before = encoder.total;
                self.encoders[i] = encoder.follow(got.steps[i]);
                if encoder.total != before && !got.active {
                    self.steps_while_inactive += 1;
                }
            }
        }
        self.last = got;
        &self.last
    }

    /// A clock with the bus idle.
    pub fn idle(&mut self, clocks: u64) {
        for _ in 0..clocks {
            self.clock(false, 0, 0, false, false);
        }
    }

    /// Writes copy `index` of register `name`.
    pub fn write(&mut self, name: &str, index: u32, value: u32) {
        let address = self.address(name, index);
        self.clock(false, address, value, true, false);
    }

    /// Reads copy `index` of register `name` (two clocks).
    pub fn read(&mut self, name: &str, index: u32) -> u32 {
        let address = self.address(name, index);
        self.clock(false, address, 0, false, true);
        self.clock(false, 0, 0, false, false).read_data
    }

    /// Net steps seen on the step/dir pins of `axis` (loopback only).
    pub fn pin_steps(&self, axis: usize) -> i64 {
        self.loopback.as_ref().expect("loopback")[axis].net
    }

    /// Idles `clocks` clocks; returns the interrupt after them.
    pub fn idle_then_irq(&mut self, clocks: u64) -> bool {
        self.idle(clocks);
        self.last.irq
    }

    /// Pulses reset for one clock.
    pub fn reset(&mut self) {
        self.clock(true, 0, 0, false, false);
    }
}

/// Random switch activity on one K-bit pin word: each of the `axes` pins
/// flips with probability 1/`active` per clock while active (1) and
/// 1/`inactive` while inactive: the mean clocks it stays in each level.
pub fn toggle_pins(
    rng: &mut impl rand::Rng,
    word: &mut u32,
    axes: usize,
    active: u32,
    inactive: u32,
) {
    for k in 0..axes {
        let rate = if *word >> k & 1 != 0 {
            active
        } else {
            inactive
        };
        if rng.gen_ratio(1, rate) {
            *word ^= 1 << k;
        }
    }
}

/// A controller under test that a random-traffic driver clocks: one
/// [`Bench`], or several driven alike and compared.
pub trait ControllerUnderTest {
    /// Number of axes.
    fn axes(&self) -> usize;
    /// The register map the traffic is addressed with.
    fn map(&self) -> &RegisterMap;
    /// Encoder and machine pins applied in the next clock.
    fn set_pins(&mut self, encoders: Vec<(bool, bool, bool)>, pins: MachinePins);
    /// One clock with these bus inputs; the outputs after it. Panics where
    /// an RTL and its model (or two RTLs) disagree.
    fn step(
        &mut self,
        reset: bool,
        address: u32,
        write_data: u32,
        write: bool,
        read: bool,
    ) -> ControllerOutputs;
    /// Outputs after the last clock.
    fn last(&self) -> &ControllerOutputs;
}

impl<
        const K: usize,
        const N: usize,
        const NP1: usize,
        const UNIFORM: bool,
        const ANALOG: bool,
        const PROBE: bool,
        const SOFT: bool,
        const SPINDLE: bool,
        const LASER: bool,
    > ControllerUnderTest for Bench<K, N, NP1, UNIFORM, ANALOG, PROBE, SOFT, SPINDLE, LASER>
{
    fn axes(&self) -> usize {
        K
    }

    fn map(&self) -> &RegisterMap {
        &self.map
    }

    fn set_pins(&mut self, encoders: Vec<(bool, bool, bool)>, pins: MachinePins) {
        self.encoders = encoders;
        self.pins = pins;
    }

    fn step(
        &mut self,
        reset: bool,
        address: u32,
        write_data: u32,
        write: bool,
        read: bool,
    ) -> ControllerOutputs {
        self.clock(reset, address, write_data, write, read).clone()
    }

    fn last(&self) -> &ControllerOutputs {
        &self.last
    }
}
