//! The hardware blocks. Each block lives in its own folder: `mod.rs` holds
//! the rust-hdl implementation and its datasheet, `model.rs` the plain-Rust
//! reference model the RTL is proven against (in `tests/blocks/<block>.rs`).

/// Named slices of a register word for `#[hdl_gen]` code, placed by the
/// register map's field constants.
///
/// In `#[hdl_gen]` code `x.get_bits::<W>(OFFSET)` prints `OFFSET` by name,
/// which is broken Verilog. But rust-hdl turns a method call
/// `x.get_value_f()` into the part-select `x[(offset)+:(width)]`, with
/// `offset = x.get_my_offset_f()` and `width = x.get_my_width_f()`
/// evaluated when the Verilog is generated (its mechanism for
/// `LogicStruct` fields). This macro defines a trait, implemented for every
/// `Bits<N>`, with those three methods for each field. The offset is an
/// `i32`, which prints as `32'h..` like the literal offset of a
/// `get_bits`, so the Verilog text is the same as with literals.
///
/// A single bit has no such form (`get_bit(n)` prints an index, a
/// one-bit slice prints `[(n)+:(1)]`): there the literal stays, tied to
/// the field constant by a compile-time assertion.
macro_rules! field_slices {
    (
        $(#[$meta:meta])*
        $vis:vis trait $name:ident {
            $(
                $(#[$fmeta:meta])*
                $value:ident / $offset:ident / $width:ident = ($lsb:expr, $bits:expr);
            )*
        }
    ) => {
        $(#[$meta])*
        $vis trait $name {
            $(
                $(#[$fmeta])*
                fn $value(&self) -> rust_hdl::prelude::Bits<{ ($bits) as usize }>;
                /// The field's least significant bit, as rust-hdl prints it.
                fn $offset(&self) -> i32;
                /// The field's width.
                fn $width(&self) -> usize;
            )*
        }
        impl<const N: usize> $name for rust_hdl::prelude::Bits<N> {
            $(
                fn $value(&self) -> rust_hdl::prelude::Bits<{ ($bits) as usize }> {
                    self.get_bits::<{ ($bits) as usize }>(($lsb) as usize)
                }
                fn $offset(&self) -> i32 {
                    ($lsb) as i32
                }
                fn $width(&self) -> usize {
                    ($bits) as usize
                }
            )*
        }
    };
}

pub mod bus_synchronizer;
pub mod carry_select_adder;
pub mod command_fifo;
pub mod dac_interface;
pub mod dda_integrator;
pub mod dda_interpolator;
pub mod dpram_mailbox;
pub mod electronic_gearbox;
pub mod external_bus_adapter;
pub mod freq_divider;
pub mod glitch_filter;
pub mod holding_ram;
pub mod host_links;
pub mod input_conditioner;
pub mod interrupt_controller;
pub mod laser_pwm;
pub mod motion_controller;
pub mod narrow_bus_adapter;
pub mod parallel_card;
pub mod port_doc;
pub mod pulse_counter;
pub mod quadrature_decoder;
pub mod sequential_divider;
pub mod spi_bus_adapter;
pub mod step_channel;
pub mod step_output;
pub mod sync_fifo_bridge;
pub mod uniform_pulse_gen;
pub mod watchdog;
pub mod word_assembler;

/// A `Constant` of any width, for blocks' `Default` (rust-hdl prints it
/// as a `localparam`).
pub(crate) fn konst<const N: usize>(
    value: u64,
) -> rust_hdl::prelude::Constant<rust_hdl::prelude::Bits<N>> {
    rust_hdl::prelude::Constant::new(value.into())
}

/// All ones in the low `width` bits (1 to 64): the value range of a
/// `width`-bit port, for models and stimulus.
pub fn width_mask(width: u32) -> u64 {
    assert!((1..=64).contains(&width), "width must be 1..=64");
    u64::MAX >> (64 - width)
}

/// The low `width` bits (1 to 64) of `value` as a two's-complement number:
/// a signed `width`-bit port's value, for models.
pub fn signed_value(value: u64, width: u32) -> i64 {
    assert!((1..=64).contains(&width), "width must be 1..=64");
    let shift = 64 - width;
    ((value << shift) as i64) >> shift
}
