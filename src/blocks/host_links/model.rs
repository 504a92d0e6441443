//! Reference model of [`super::HostLinks`], cycle-exact: the models of the
//! synchronizer, word assembler, mailbox and narrow adapter, wired as the
//! RTL.

use crate::blocks::bus_synchronizer::model::{
    BusPinInputs, BusSynchronizerModel, BusSynchronizerOutputs,
};
use crate::blocks::dpram_mailbox::model::{
    DpramMailboxInputs, DpramMailboxModel, DpramMailboxOutputs,
};
use crate::blocks::narrow_bus_adapter::model::{NarrowBusModel, NarrowBusOutputs};
use crate::blocks::width_mask;
use crate::blocks::word_assembler::model::{PartGeometry, WordAssemblerInputs, WordAssemblerModel};

/// The block's parameters as numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HostLinksGeometry {
    /// Controller register address bits (CA).
    pub register_bits: u32,
    /// Mailbox word address bits (MA); the pins have MA + 1.
    pub mailbox_bits: u32,
}

impl HostLinksGeometry {
    /// The exported `host_links`: 256 registers, 1024 mailbox words.
    pub const fn seed() -> Self {
        Self {
            register_bits: 8,
            mailbox_bits: 10,
        }
    }

    /// Pin address width of both masters (DA).
    pub const fn pin_address_bits(&self) -> u32 {
        self.mailbox_bits + 1
    }

    /// The DSP's pin address of mailbox word `word`.
    pub const fn dsp_mailbox_address(&self, word: u64) -> u64 {
        (1 << self.mailbox_bits) | word
    }

    /// The DSP's pin address of controller register `register`, half `half`.
    pub const fn dsp_register_address(&self, register: u64, half: u64) -> u64 {
        register * 2 + half
    }

    /// The PC's pin address of mailbox word `word`, byte `byte`.
    pub const fn pc_address(&self, word: u64, byte: u64) -> u64 {
        word * 2 + byte
    }

    fn registers(&self) -> PartGeometry {
        PartGeometry {
            narrow_bits: 16,
            wide_bits: 32,
            address_bits: self.register_bits,
        }
    }

    fn pc_words(&self) -> PartGeometry {
        PartGeometry {
            narrow_bits: 8,
            wide_bits: 16,
            address_bits: self.mailbox_bits,
        }
    }
}

/// Inputs of one clock, in the RTL's vector order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostLinksInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The DSP's pins (`bus_read_data` unused).
    pub dsp: BusPinInputs,
    /// The PC's pins (`bus_read_data` unused).
    pub pc: BusPinInputs,
    /// The controller's read data.
    pub reg_read_data: u64,
}

impl HostLinksInputs {
    /// The RTL's input vector.
    pub fn to_vector(&self) -> Vec<u64> {
        let pins = |p: &BusPinInputs| {
            [
                p.cs_n as u64,
                p.we_n as u64,
                p.rd_n as u64,
                p.address,
                p.data_in,
            ]
        };
        let mut v = vec![self.reset as u64];
        v.extend(pins(&self.dsp));
        v.extend(pins(&self.pc));
        v.push(self.reg_read_data);
        v
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostLinksOutputs {
    /// DSP read data.
    pub dsp_data_out: u64,
    /// Drive the DSP data pins.
    pub dsp_data_oe: bool,
    /// XREADY.
    pub dsp_ready: bool,
    /// The DSP broke a register's half order.
    pub dsp_order_error: bool,
    /// PC read data.
    pub pc_data_out: u64,
    /// Drive the PC data pins.
    pub pc_data_oe: bool,
    /// The PC's access may end.
    pub pc_ready: bool,
    /// The PC broke a mailbox word's byte order.
    pub pc_order_error: bool,
    /// Controller register address.
    pub reg_address: u64,
    /// Controller register write data.
    pub reg_write_data: u64,
    /// Controller register write strobe.
    pub reg_write: bool,
    /// Controller register read strobe.
    pub reg_read: bool,
    /// The PC wrote `MAILBOX_TO_B`.
    pub irq_dsp: bool,
    /// The DSP wrote `MAILBOX_TO_A`.
    pub irq_pc: bool,
    /// Both masters wrote one mailbox word on one clock.
    pub mailbox_collision: bool,
    /// A DSP mailbox write was refused.
    pub mailbox_overrun: bool,
}

impl HostLinksOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            dsp_data_out: v[0],
            dsp_data_oe: v[1] != 0,
            dsp_ready: v[2] != 0,
            dsp_order_error: v[3] != 0,
            pc_data_out: v[4],
            pc_data_oe: v[5] != 0,
            pc_ready: v[6] != 0,
            pc_order_error: v[7] != 0,
            reg_address: v[8],
            reg_write_data: v[9],
            reg_write: v[10] != 0,
            reg_read: v[11] != 0,
            irq_dsp: v[12] != 0,
            irq_pc: v[13] != 0,
            mailbox_collision: v[14] != 0,
            mailbox_overrun: v[15] != 0,
        }
    }
}

/// Cycle-exact model of the host links.
#[derive(Clone, Debug)]
pub struct HostLinksModel {
    geometry: HostLinksGeometry,
    dsp: BusSynchronizerModel,
    registers: WordAssemblerModel,
    mailbox: DpramMailboxModel,
    pc: NarrowBusModel,
    /// Registered outputs of the parts, as shown this clock.
    dsp_shown: BusSynchronizerOutputs,
    pc_shown: NarrowBusOutputs,
    mailbox_shown: DpramMailboxOutputs,
    answer_from_mailbox: bool,
}

impl HostLinksModel {
    /// The block in its power-up state (every mailbox word 0).
    pub fn new(geometry: HostLinksGeometry) -> Self {
        Self {
            geometry,
            dsp: BusSynchronizerModel::new(geometry.pin_address_bits(), 16),
            registers: WordAssemblerModel::new(geometry.registers()),
            mailbox: DpramMailboxModel::new(geometry.mailbox_bits as usize, 16),
            pc: NarrowBusModel::new(geometry.pc_words()),
            dsp_shown: BusSynchronizerOutputs::default(),
            pc_shown: NarrowBusOutputs::default(),
            mailbox_shown: DpramMailboxOutputs::default(),
            answer_from_mailbox: false,
        }
    }

    /// The mailbox word a read strobed now would return.
    pub fn mailbox_word(&self, word: u64) -> u64 {
        self.mailbox.word(word)
    }

    fn to_mailbox(&self) -> bool {
        self.dsp_shown.bus_address >> self.geometry.mailbox_bits != 0
    }

    fn assembler_inputs(&self, i: &HostLinksInputs) -> WordAssemblerInputs {
        let to_registers = !self.to_mailbox();
        WordAssemblerInputs {
            reset: i.reset,
            narrow_address: self.dsp_shown.bus_address
                & width_mask(self.geometry.register_bits + 1),
            narrow_write_data: self.dsp_shown.bus_write_data,
            narrow_write: self.dsp_shown.bus_write && to_registers,
            narrow_read: self.dsp_shown.bus_read && to_registers,
            bus_read_data: i.reg_read_data,
        }
    }

    fn mailbox_inputs(&self, i: &HostLinksInputs) -> DpramMailboxInputs {
        let to_mailbox = self.to_mailbox();
        DpramMailboxInputs {
            reset: i.reset,
            a_address: self.pc_shown.bus_address,
            a_write_data: self.pc_shown.bus_write_data,
            a_write: self.pc_shown.bus_write,
            a_read: self.pc_shown.bus_read,
            b_address: self.dsp_shown.bus_address & width_mask(self.geometry.mailbox_bits),
            b_write_data: self.dsp_shown.bus_write_data,
            b_write: self.dsp_shown.bus_write && to_mailbox,
            b_read: self.dsp_shown.bus_read && to_mailbox,
        }
    }

    /// One rising clock edge; returns the outputs after it (the
    /// combinational `data_oe`, `ready` and `reg_*` with this clock's
    /// inputs still applied).
    pub fn step(&mut self, i: HostLinksInputs) -> HostLinksOutputs {
        // Everything the parts see before the edge.
        let words_in = self.assembler_inputs(&i);
        let mailbox_in = self.mailbox_inputs(&i);
        let dsp_answer = if self.answer_from_mailbox {
            self.mailbox_shown.b_read_data
        } else {
            self.registers.outputs(&words_in).narrow_read_data
        };
        let answer_from_mailbox = if i.reset {
            false
        } else if self.dsp_shown.bus_read {
            self.to_mailbox()
        } else {
            self.answer_from_mailbox
        };

        // The edge.
        self.dsp_shown = self.dsp.step(BusPinInputs {
            reset: i.reset,
            bus_read_data: dsp_answer,
            ..i.dsp
        });
        self.pc_shown = self.pc.step(BusPinInputs {
            reset: i.reset,
            bus_read_data: self.mailbox_shown.a_read_data,
            ..i.pc
        });
        self.registers.clock(&words_in);
        self.mailbox_shown = self.mailbox.step(mailbox_in);
        self.answer_from_mailbox = answer_from_mailbox;

        let words = self.registers.outputs(&self.assembler_inputs(&i));
        HostLinksOutputs {
            dsp_data_out: self.dsp_shown.data_out,
            dsp_data_oe: self.dsp_shown.data_oe,
            dsp_ready: self.dsp_shown.ready,
            dsp_order_error: words.order_error,
            pc_data_out: self.pc_shown.data_out,
            pc_data_oe: self.pc_shown.data_oe,
            pc_ready: self.pc_shown.ready,
            pc_order_error: self.pc_shown.order_error,
            reg_address: words.bus_address,
            reg_write_data: words.bus_write_data,
            reg_write: words.bus_write,
            reg_read: words.bus_read,
            irq_dsp: self.mailbox_shown.irq_b,
            irq_pc: self.mailbox_shown.irq_a,
            mailbox_collision: self.mailbox_shown.collision,
            mailbox_overrun: self.mailbox_shown.overrun,
        }
    }
}

crate::lockstep_model!(HostLinksModel {
    inputs: HostLinksInputs,
    outputs: HostLinksOutputs,
    step: |model, inputs| model.step(*inputs),
});
