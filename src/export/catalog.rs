//! The list of exported modules: the single place that says which blocks
//! ship in `rtl-out/`, with which parameters.

use rust_hdl::core::prelude::*;

use crate::blocks::dac_interface::{self, DacInterface3};
use crate::blocks::dda_integrator::{self, DdaIntegrator};
use crate::blocks::dda_interpolator::{self, DdaInterpolator};
use crate::blocks::dpram_mailbox::{self, DpramMailbox1024x16};
use crate::blocks::electronic_gearbox::{self, ElectronicGearbox24};
use crate::blocks::external_bus_adapter::{self, ExternalBusAdapter};
use crate::blocks::freq_divider::{self, FreqDivider};
use crate::blocks::host_links::{self, SeedHostLinks};
use crate::blocks::laser_pwm::{self, LaserPwm};
use crate::blocks::motion_controller::{
    self, MotionController1, MotionController3, MotionController3Dda, MotionController3DdaLaser,
    MotionController3DdaSpindle, MotionController3Servo, MotionController6,
};
use crate::blocks::narrow_bus_adapter::{self, ExternalBusAdapter16, ExternalBusAdapter8};
use crate::blocks::parallel_card::{self, ParallelCard};
use crate::blocks::pulse_counter::{self, PulseCounter};
use crate::blocks::quadrature_decoder::{self, QuadratureDecoder};
use crate::blocks::sequential_divider::{self, SequentialDivider};
use crate::blocks::spi_bus_adapter::{self, SpiBusAdapter};
use crate::blocks::step_channel::{self, StepChannel};
use crate::blocks::step_output::{self, StepOutput};
use crate::blocks::sync_fifo_bridge::{self, SyncFifoBridge3};
use crate::blocks::uniform_pulse_gen::{self, UniformPulseGen};

pub use crate::blocks::port_doc::PortDoc;

/// One fixed parameter of an exported module: name, value, meaning.
pub type ParamDoc = (&'static str, &'static str, &'static str);

/// An exported module: what `motion-hdl export` writes as `<name>.v`.
pub struct ModuleSpec {
    /// Verilog module name (snake_case); also the file name.
    pub name: &'static str,
    /// The block's folder under `src/blocks/` (its datasheet is `mod.rs`).
    pub block: &'static str,
    /// One line: what the block is.
    pub summary: &'static str,
    /// Parameters fixed in this export.
    pub parameters: &'static [ParamDoc],
    /// Every top-level port, documented.
    pub port_docs: &'static [PortDoc],
    /// The Fmax goal on iCE40 HX8K from the block's issue, in MHz (reported, not enforced).
    pub fmax_target_mhz: f64,
    /// The LUT4 budget on iCE40 HX8K from the block's issue, if it sets one.
    pub lut4_budget: Option<u32>,
    /// The logic-cell budget on iCE40 HX8K from the block's issue, if it sets one.
    pub logic_cell_budget: Option<u32>,
    /// Builds the block with the exported parameters.
    pub build: fn() -> Box<dyn Block>,
}

/// Every exported module, in the order of `rtl-out/README.md`.
pub fn catalog() -> Vec<ModuleSpec> {
    vec![
        ModuleSpec {
            name: "freq_divider",
            block: "freq_divider",
            summary: freq_divider::SUMMARY,
            parameters: &[("W", "32", "divisor width")],
            port_docs: freq_divider::PORT_DOCS,
            fmax_target_mhz: 125.0,
            lut4_budget: Some(80),
            logic_cell_budget: None,
            build: || Box::new(FreqDivider::<32>::default()),
        },
        ModuleSpec {
            name: "pulse_counter",
            block: "pulse_counter",
            summary: pulse_counter::SUMMARY,
            parameters: &[("W", "32", "count width")],
            port_docs: pulse_counter::PORT_DOCS,
            fmax_target_mhz: 125.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(PulseCounter::<32>::default()),
        },
        ModuleSpec {
            name: "sequential_divider",
            block: "sequential_divider",
            summary: sequential_divider::SUMMARY,
            parameters: &[
                ("N", "32", "dividend and quotient width"),
                ("D", "32", "divisor and remainder width"),
            ],
            port_docs: sequential_divider::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(SequentialDivider::<32, 32>::default()),
        },
        ModuleSpec {
            name: "dda_integrator",
            block: "dda_integrator",
            summary: dda_integrator::SUMMARY,
            parameters: &[("W", "32", "integrand, modulus and accumulator width")],
            port_docs: dda_integrator::PORT_DOCS,
            fmax_target_mhz: 110.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(DdaIntegrator::<32>::default()),
        },
        ModuleSpec {
            name: "dda_interpolator",
            block: "dda_interpolator",
            summary: dda_interpolator::SUMMARY,
            parameters: &[
                ("K", "3", "axes"),
                (
                    "P",
                    "24",
                    "period length width in ticks (next_period is 32 bits; P >= 2^24 is refused)",
                ),
                ("delta", "32", "per-axis steps per period, signed Q16.16"),
            ],
            port_docs: dda_interpolator::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(DdaInterpolator::<3>::default()),
        },
        ModuleSpec {
            name: "uniform_pulse_gen",
            block: "uniform_pulse_gen",
            summary: uniform_pulse_gen::SUMMARY,
            parameters: &[
                ("T", "32", "period width in ticks"),
                ("N", "32", "count width"),
            ],
            port_docs: uniform_pulse_gen::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(UniformPulseGen::<32>::default()),
        },
        ModuleSpec {
            name: "quadrature_decoder",
            block: "quadrature_decoder",
            summary: quadrature_decoder::SUMMARY,
            parameters: &[
                ("W", "32", "count and index_count width"),
                ("S", "8", "sample_rate width"),
                ("TS", "16", "timestamp and count_time width"),
            ],
            port_docs: quadrature_decoder::PORT_DOCS,
            fmax_target_mhz: 150.0,
            lut4_budget: Some(130),
            logic_cell_budget: None,
            build: || Box::new(QuadratureDecoder::<32, 8, 16>::default()),
        },
        ModuleSpec {
            name: "electronic_gearbox",
            block: "electronic_gearbox",
            summary: electronic_gearbox::SUMMARY,
            parameters: &[
                ("W", "24", "numerator, denominator and ramp width"),
                ("E", "40", "lag width: a ramp-in of up to 2^(E - W - 1) = 32768 counts"),
                ("L", "24", "position and length width"),
            ],
            port_docs: electronic_gearbox::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(ElectronicGearbox24::default()),
        },
        ModuleSpec {
            name: "laser_pwm",
            block: "laser_pwm",
            summary: laser_pwm::SUMMARY,
            parameters: &[
                ("R", "16", "PWM period, power and duty width"),
                ("C", "16", "step count width"),
                ("F", "24", "feed width"),
            ],
            port_docs: laser_pwm::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(LaserPwm::default()),
        },
        ModuleSpec {
            name: "step_output",
            block: "step_output",
            summary: step_output::SUMMARY,
            parameters: &[
                (
                    "T",
                    "16",
                    "timer width (step_len, step_space, dir_setup, dir_hold)",
                ),
                (
                    "P",
                    "16",
                    "signed pending-step count width (-32768 to 32767)",
                ),
            ],
            port_docs: step_output::PORT_DOCS,
            fmax_target_mhz: 125.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(StepOutput::<16, 16>::default()),
        },
        ModuleSpec {
            name: "external_bus_adapter",
            block: "external_bus_adapter",
            summary: external_bus_adapter::SUMMARY,
            parameters: &[
                ("A", "8", "word address width"),
                ("data", "32", "data width"),
            ],
            port_docs: external_bus_adapter::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(ExternalBusAdapter::<8>::default()),
        },
        ModuleSpec {
            name: "external_bus_adapter_16",
            block: "narrow_bus_adapter",
            summary: narrow_bus_adapter::SUMMARY_16,
            parameters: &[
                ("A", "8", "register (32-bit word) address width"),
                ("NA", "9", "pin address width: 2 pin addresses per register"),
                ("N", "16", "pin data width"),
                ("W", "32", "register width"),
            ],
            port_docs: narrow_bus_adapter::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(ExternalBusAdapter16::default()),
        },
        ModuleSpec {
            name: "external_bus_adapter_8",
            block: "narrow_bus_adapter",
            summary: narrow_bus_adapter::SUMMARY_8,
            parameters: &[
                ("A", "8", "register (32-bit word) address width"),
                ("NA", "10", "pin address width: 4 pin addresses per register"),
                ("N", "8", "pin data width"),
                ("W", "32", "register width"),
            ],
            port_docs: narrow_bus_adapter::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(ExternalBusAdapter8::default()),
        },
        ModuleSpec {
            name: "spi_bus_adapter",
            block: "spi_bus_adapter",
            summary: spi_bus_adapter::SUMMARY,
            parameters: &[
                ("A", "8", "register (32-bit word) address width"),
                ("MAX_WORDS", "16", "longest burst, in words (the frame buffer)"),
                ("SNAPSHOT", "0x0b", "the register a read frame's SNAPSHOT bit writes"),
            ],
            port_docs: spi_bus_adapter::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(SpiBusAdapter::default()),
        },
        ModuleSpec {
            name: "dpram_mailbox",
            block: "dpram_mailbox",
            summary: dpram_mailbox::SUMMARY,
            parameters: &[
                ("AW", "10", "word address width: 2^AW = 1024 words"),
                ("D", "16", "data width"),
                ("MAILBOX_TO_B", "1023", "port A writes it to raise irq_b (2^AW - 1)"),
                ("MAILBOX_TO_A", "1022", "port B writes it to raise irq_a (2^AW - 2)"),
            ],
            port_docs: dpram_mailbox::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(DpramMailbox1024x16::default()),
        },
        ModuleSpec {
            name: "step_channel",
            block: "step_channel",
            summary: step_channel::SUMMARY,
            parameters: &[
                ("W", "32", "DDA width (integrand, modulus, accumulator)"),
                (
                    "T",
                    "16",
                    "timer width (step_len, step_space, dir_setup, dir_hold)",
                ),
            ],
            port_docs: step_channel::PORT_DOCS,
            fmax_target_mhz: 110.0,
            // #19 withdrew the 232-LUT4 budget (hostmot2's DDS has no
            // modulus); about 430 LUT4 is accepted for the modulus DDA.
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(StepChannel::<32, 16>::default()),
        },
        ModuleSpec {
            name: "motion_controller",
            block: "motion_controller",
            summary: motion_controller::SUMMARY,
            parameters: &[
                ("K", "3", "axes"),
                ("N", "4", "FIFO depth 2^N = 16 periods per axis"),
                ("T", "16", "step timing register width"),
                ("P", "8", "each output stage's pending-step count width: +127 / -128 steps"),
            ],
            port_docs: motion_controller::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            // #19: at most 4000 logic cells at K = 3 (the seed's FPGA class
            // with room for the host links, DAC and mailbox).
            logic_cell_budget: Some(4000),
            build: || Box::new(MotionController3::default()),
        },
        ModuleSpec {
            name: "motion_controller_dda",
            block: "motion_controller",
            summary: motion_controller::SUMMARY_DDA,
            parameters: &[
                ("K", "3", "axes"),
                ("N", "4", "FIFO depth 2^N = 16 periods per axis"),
                ("T", "16", "step timing register width"),
                ("P", "8", "each output stage's pending-step count width: +127 / -128 steps"),
                ("UNIFORM", "false", "no uniform pulse generators: every axis runs its DDA (CONFIG.DDA_ONLY = 1)"),
            ],
            port_docs: motion_controller::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(MotionController3Dda::default()),
        },
        ModuleSpec {
            name: "motion_controller_dda_spindle",
            block: "motion_controller",
            summary: motion_controller::SUMMARY_DDA_SPINDLE,
            parameters: &[
                ("K", "3", "axes"),
                ("N", "4", "FIFO depth 2^N = 16 periods per axis"),
                ("T", "16", "step timing register width"),
                ("P", "8", "each output stage's pending-step count width: +127 / -128 steps"),
                ("UNIFORM", "false", "no uniform pulse generators: every axis runs its DDA (CONFIG.DDA_ONLY = 1)"),
                ("SPINDLE", "true", "the spindle encoder and the electronic gearbox (CONFIG.SPINDLE = 1)"),
            ],
            port_docs: motion_controller::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(MotionController3DdaSpindle::default()),
        },
        ModuleSpec {
            name: "motion_controller_dda_laser",
            block: "motion_controller",
            summary: motion_controller::SUMMARY_DDA_LASER,
            parameters: &[
                ("K", "3", "axes"),
                ("N", "4", "FIFO depth 2^N = 16 periods per axis and for the laser"),
                ("T", "16", "step timing register width"),
                ("P", "8", "each output stage's pending-step count width: +127 / -128 steps"),
                ("UNIFORM", "false", "no uniform pulse generators: every axis runs its DDA (CONFIG.DDA_ONLY = 1)"),
                ("LASER", "true", "the laser FIFO and the PWM tied to the path (CONFIG.LASER = 1)"),
            ],
            port_docs: motion_controller::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(MotionController3DdaLaser::default()),
        },
        ModuleSpec {
            name: "motion_controller_servo",
            block: "motion_controller",
            summary: motion_controller::SUMMARY_SERVO,
            parameters: &[
                ("K", "3", "axes"),
                ("N", "4", "FIFO depth 2^N = 16 periods per axis"),
                ("T", "16", "step timing register width"),
                ("P", "8", "each output stage's pending-step count width: +127 / -128 steps"),
                ("UNIFORM", "false", "no uniform pulse generators: every axis runs its DDA (CONFIG.DDA_ONLY = 1)"),
                ("ANALOG", "true", "analog outputs: an AD669 per axis, AXIS_CONFIG.ANALOG (CONFIG.ANALOG = 1)"),
            ],
            port_docs: motion_controller::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(MotionController3Servo::default()),
        },
        ModuleSpec {
            name: "sync_fifo_bridge",
            block: "sync_fifo_bridge",
            summary: sync_fifo_bridge::SUMMARY,
            parameters: &[
                ("K", "3", "slave ports"),
                ("N", "6", "FIFO depth 2^N = 64 words, for each of the 2 K FIFOs (command and status per slave)"),
                ("master address", "8", "master bus word address width (register map SFB)"),
                ("slave address", "4", "each slave bus's word address width (register map SFB_SLAVE)"),
            ],
            port_docs: sync_fifo_bridge::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(SyncFifoBridge3::default()),
        },
        ModuleSpec {
            name: "host_links",
            block: "host_links",
            summary: host_links::SUMMARY,
            parameters: &[
                ("CA", "8", "controller register address width (256 registers of 32 bits)"),
                ("CNA", "9", "DSP half-word address width of the register window (2 per register)"),
                ("MA", "10", "mailbox word address width: 1024 x 16"),
                ("DA", "11", "DSP and PC pin address width: the DSP's top bit selects the mailbox"),
            ],
            port_docs: host_links::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(SeedHostLinks::default()),
        },
        ModuleSpec {
            name: "dac_interface",
            block: "dac_interface",
            summary: dac_interface::SUMMARY,
            parameters: &[
                ("K", "3", "channels (three AD669s)"),
                ("W", "16", "code width"),
            ],
            port_docs: dac_interface::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(DacInterface3::default()),
        },
        ModuleSpec {
            name: "parallel_card",
            block: "parallel_card",
            summary: parallel_card::SUMMARY,
            parameters: &[
                ("K", "3", "slave ports (motor-control DSPs), 2 joints each"),
                ("N", "6", "FIFO depth 2^N = 64 words (the bridge's)"),
                ("joints", "6", "quadrature decoders (32-bit counts) and DAC channels (16-bit codes, a pair per slave)"),
                ("master address", "9", "register map PCARD"),
                ("slave address", "6", "register map PCARD_SLAVE"),
            ],
            port_docs: parallel_card::PORT_DOCS,
            fmax_target_mhz: 100.0,
            lut4_budget: None,
            logic_cell_budget: None,
            build: || Box::new(ParallelCard::default()),
        },
    ]
}

/// The catalog entry named `name`.
pub fn find(name: &str) -> Option<ModuleSpec> {
    catalog().into_iter().find(|spec| spec.name == name)
}

/// A motion-controller configuration measured for the report's scaling
/// table (#19): synthesized from a work folder, not exported.
pub struct ScalingVariant {
    /// K, the number of axes.
    pub axes: usize,
    /// Builds the controller.
    pub build: fn() -> Box<dyn Block>,
}

/// The controller at K = 1, 3 (the exported configuration) and 6, all with
/// 16-entry FIFOs.
pub fn controller_scaling() -> Vec<ScalingVariant> {
    vec![
        ScalingVariant {
            axes: 1,
            build: || Box::new(MotionController1::default()),
        },
        ScalingVariant {
            axes: 3,
            build: || Box::new(MotionController3::default()),
        },
        ScalingVariant {
            axes: 6,
            build: || Box::new(MotionController6::default()),
        },
    ]
}
