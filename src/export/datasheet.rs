//! The datasheets' port tables: `src/blocks/<block>/ports.md`, generated
//! from each block's `PORT_DOCS` and checked against its RTL, then
//! included in the block's rustdoc. `motion-hdl export` writes them; a
//! test fails when a committed table differs from what it writes now.

use rust_hdl::core::prelude::*;

use super::ports::{top_ports, Port};
use crate::blocks::port_doc::{eval_width, PortDoc};
use crate::blocks::*;

/// One datasheet's port table: the block and the instance it is checked on.
pub struct DatasheetSpec {
    /// The block's folder under `src/blocks/`.
    pub block: &'static str,
    /// The block's `PORT_DOCS`.
    pub port_docs: &'static [PortDoc],
    /// The parameter values of the instance `build` makes, for the width
    /// expressions.
    pub parameters: &'static [(&'static str, usize)],
    /// Builds the instance whose ports the table is checked against.
    pub build: fn() -> Box<dyn Block>,
}

/// Why a port table does not describe its RTL.
#[derive(Debug, thiserror::Error)]
#[error("datasheet of `{block}`: {detail}")]
pub struct DatasheetError {
    /// The block.
    pub block: String,
    /// What disagrees.
    pub detail: String,
}

/// Every block with a datasheet port table, in `src/blocks/` order.
pub fn datasheets() -> Vec<DatasheetSpec> {
    vec![
        DatasheetSpec {
            block: "bus_synchronizer",
            port_docs: bus_synchronizer::PORT_DOCS,
            parameters: &[("A", 8), ("D", 16)],
            build: || Box::new(bus_synchronizer::BusSynchronizer::<8, 16>::default()),
        },
        DatasheetSpec {
            block: "carry_select_adder",
            port_docs: carry_select_adder::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(carry_select_adder::CarrySelectAdder::<32>::default()),
        },
        DatasheetSpec {
            block: "command_fifo",
            port_docs: command_fifo::PORT_DOCS,
            parameters: &[("N", 4), ("W", 32)],
            build: || Box::new(command_fifo::CommandFifo::<4, 5, 32>::default()),
        },
        DatasheetSpec {
            block: "dac_interface",
            port_docs: dac_interface::PORT_DOCS,
            parameters: &[("K", 3), ("W", 16)],
            build: || Box::new(dac_interface::DacInterface3::default()),
        },
        DatasheetSpec {
            block: "dda_integrator",
            port_docs: dda_integrator::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(dda_integrator::DdaIntegrator::<32>::default()),
        },
        DatasheetSpec {
            block: "dda_interpolator",
            port_docs: dda_interpolator::PORT_DOCS,
            parameters: &[("K", 3)],
            build: || Box::new(dda_interpolator::DdaInterpolator::<3>::default()),
        },
        DatasheetSpec {
            block: "dpram_mailbox",
            port_docs: dpram_mailbox::PORT_DOCS,
            parameters: &[("AW", 10), ("D", 16)],
            build: || Box::new(dpram_mailbox::DpramMailbox1024x16::default()),
        },
        DatasheetSpec {
            block: "external_bus_adapter",
            port_docs: external_bus_adapter::PORT_DOCS,
            parameters: &[("A", 8)],
            build: || Box::new(external_bus_adapter::ExternalBusAdapter::<8>::default()),
        },
        DatasheetSpec {
            block: "freq_divider",
            port_docs: freq_divider::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(freq_divider::FreqDivider::<32>::default()),
        },
        DatasheetSpec {
            block: "glitch_filter",
            port_docs: glitch_filter::PORT_DOCS,
            parameters: &[],
            build: || Box::new(glitch_filter::GlitchFilter::default()),
        },
        DatasheetSpec {
            block: "host_links",
            port_docs: host_links::PORT_DOCS,
            parameters: &[("CA", 8), ("DA", 11)],
            build: || Box::new(host_links::SeedHostLinks::default()),
        },
        DatasheetSpec {
            block: "input_conditioner",
            port_docs: input_conditioner::PORT_DOCS,
            parameters: &[("W", 8)],
            build: || Box::new(input_conditioner::InputConditioner::<8>::default()),
        },
        DatasheetSpec {
            block: "electronic_gearbox",
            port_docs: electronic_gearbox::PORT_DOCS,
            parameters: &[("W", 24), ("E", 40), ("L", 24)],
            build: || Box::new(electronic_gearbox::ElectronicGearbox24::default()),
        },
        DatasheetSpec {
            block: "laser_pwm",
            port_docs: laser_pwm::PORT_DOCS,
            parameters: &[("R", 16), ("C", 16), ("F", 24)],
            build: || Box::new(laser_pwm::LaserPwm::default()),
        },
        DatasheetSpec {
            block: "holding_ram",
            port_docs: holding_ram::PORT_DOCS,
            parameters: &[("D", 16), ("N", 8)],
            build: || Box::new(holding_ram::HoldingRam::<Bits<16>, 8>::default()),
        },
        DatasheetSpec {
            block: "interrupt_controller",
            port_docs: interrupt_controller::PORT_DOCS,
            parameters: &[("N", 12)],
            build: || Box::new(interrupt_controller::InterruptController::<12>::default()),
        },
        DatasheetSpec {
            block: "motion_controller",
            port_docs: motion_controller::PORT_DOCS,
            parameters: &[("K", 3)],
            build: || Box::new(motion_controller::MotionController3Servo::default()),
        },
        DatasheetSpec {
            block: "narrow_bus_adapter",
            port_docs: narrow_bus_adapter::PORT_DOCS,
            parameters: &[("A", 8), ("NA", 9), ("N", 16), ("W", 32)],
            build: || Box::new(narrow_bus_adapter::ExternalBusAdapter16::default()),
        },
        DatasheetSpec {
            block: "parallel_card",
            port_docs: parallel_card::PORT_DOCS,
            parameters: &[],
            build: || Box::new(parallel_card::ParallelCard::default()),
        },
        DatasheetSpec {
            block: "pulse_counter",
            port_docs: pulse_counter::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(pulse_counter::PulseCounter::<32>::default()),
        },
        DatasheetSpec {
            block: "quadrature_decoder",
            port_docs: quadrature_decoder::PORT_DOCS,
            parameters: &[("W", 32), ("S", 8), ("TS", 16)],
            build: || Box::new(quadrature_decoder::QuadratureDecoder::<32, 8, 16>::default()),
        },
        DatasheetSpec {
            block: "sequential_divider",
            port_docs: sequential_divider::PORT_DOCS,
            parameters: &[("N", 32), ("D", 24)],
            build: || Box::new(sequential_divider::SequentialDivider::<32, 24>::default()),
        },
        DatasheetSpec {
            block: "spi_bus_adapter",
            port_docs: spi_bus_adapter::PORT_DOCS,
            parameters: &[],
            build: || Box::new(spi_bus_adapter::SpiBusAdapter::default()),
        },
        DatasheetSpec {
            block: "step_channel",
            port_docs: step_channel::PORT_DOCS,
            parameters: &[("W", 32), ("T", 16)],
            build: || Box::new(step_channel::StepChannel::<32, 16>::default()),
        },
        DatasheetSpec {
            block: "step_output",
            port_docs: step_output::PORT_DOCS,
            parameters: &[("T", 16), ("P", 16)],
            build: || Box::new(step_output::StepOutput::<16, 16>::default()),
        },
        DatasheetSpec {
            block: "sync_fifo_bridge",
            port_docs: sync_fifo_bridge::PORT_DOCS,
            parameters: &[("K", sync_fifo_bridge::EXPORTED_SLAVES)],
            build: || Box::new(sync_fifo_bridge::SyncFifoBridge3::default()),
        },
        DatasheetSpec {
            block: "uniform_pulse_gen",
            port_docs: uniform_pulse_gen::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(uniform_pulse_gen::UniformPulseGen::<32>::default()),
        },
        DatasheetSpec {
            block: "watchdog",
            port_docs: watchdog::PORT_DOCS,
            parameters: &[("W", 32)],
            build: || Box::new(watchdog::Watchdog::<32>::default()),
        },
        DatasheetSpec {
            block: "word_assembler",
            port_docs: word_assembler::PORT_DOCS,
            parameters: &[("A", 4), ("NA", 5), ("N", 16), ("W", 32)],
            build: || Box::new(word_assembler::WordAssembler::<4, 5, 16, 32>::new()),
        },
    ]
}

/// The RTL ports a documented port stands for: the port itself, or every
/// element of a `name__i` array.
pub(crate) fn documented_ports<'a>(doc: &PortDoc, ports: &'a [Port]) -> Vec<&'a Port> {
    ports
        .iter()
        .filter(|p| array_index(doc.name, &p.name).is_some())
        .collect()
}

/// The element index when `port` is covered by the documented name `doc`
/// (`name__i` covers `name__0`, `name__1`, ...): `Some(None)` for a plain
/// match.
pub(crate) fn array_index(doc: &str, port: &str) -> Option<Option<String>> {
    if doc == port {
        return Some(None);
    }
    let prefix = doc.strip_suffix("__i")?;
    let index = port.strip_prefix(prefix)?.strip_prefix("__")?;
    (!index.is_empty() && index.chars().all(|c| c.is_ascii_digit()))
        .then(|| Some(index.to_string()))
}

/// The RTL ports that no entry of `docs` documents.
pub(crate) fn undocumented_ports<'a>(docs: &[PortDoc], ports: &'a [Port]) -> Vec<&'a str> {
    ports
        .iter()
        .filter(|p| !docs.iter().any(|d| array_index(d.name, &p.name).is_some()))
        .map(|p| p.name.as_str())
        .collect()
}

/// `src/blocks/<block>/ports.md` for one datasheet, after checking every
/// port against the RTL: each documented, none unknown, each width equal
/// to the RTL's.
pub fn port_table(spec: &DatasheetSpec) -> Result<String, DatasheetError> {
    let error = |detail: String| DatasheetError {
        block: spec.block.to_string(),
        detail,
    };
    let block = (spec.build)();
    let ports = top_ports(block.as_ref());
    let undocumented = undocumented_ports(spec.port_docs, &ports);
    if !undocumented.is_empty() {
        return Err(error(format!("undocumented ports {undocumented:?}")));
    }
    let mut md = String::from(
        "<!-- Generated from PORT_DOCS (motion_hdl::export::datasheet). Do not edit. -->\n\n\
         | port | dir | width | meaning |\n|---|---|---|---|\n",
    );
    for doc in spec.port_docs {
        let rtl = documented_ports(doc, &ports);
        let Some(first) = rtl.first() else {
            return Err(error(format!("`{}` is not a port of the RTL", doc.name)));
        };
        let width = eval_width(doc.width, spec.parameters).map_err(|e| error(e.to_string()))?;
        if let Some(port) = rtl.iter().find(|p| p.width != width) {
            return Err(error(format!(
                "`{}` is documented as {} = {width} bits, the RTL has {}",
                port.name, doc.width, port.width
            )));
        }
        md.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            doc.name,
            first.direction.as_str(),
            doc.width,
            doc.meaning
        ));
    }
    Ok(md)
}
