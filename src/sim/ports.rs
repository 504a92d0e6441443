use rust_hdl::core::prelude::*;

/// A port value that travels through test vectors as a `u64`.
pub trait PortValue {
    /// The value as an unsigned integer (bit 0 = LSB).
    fn to_vector(&self) -> u64;
    /// The value from an unsigned integer; bits above the port width are dropped.
    fn from_vector(value: u64) -> Self;
}

impl PortValue for bool {
    fn to_vector(&self) -> u64 {
        *self as u64
    }
    fn from_vector(value: u64) -> Self {
        value & 1 != 0
    }
}

impl<const N: usize> PortValue for Bits<N> {
    fn to_vector(&self) -> u64 {
        self.to_u64()
    }
    fn from_vector(value: u64) -> Self {
        let masked = value & crate::blocks::width_mask(N.min(64) as u32);
        Bits::<N>::from(masked)
    }
}

/// A block whose ports can be driven from and compared against test vectors.
///
/// The port lists must match the block's top-level ports in declaration order
/// (without `clock`); the cross-simulation checks this against the ports
/// rust-hdl reports, so a stale list fails loudly. Implement it with
/// [`crate::vector_ports!`].
pub trait VectorPorts: Block {
    /// Input port names as exported (`name__i` for element i of an array),
    /// in vector column order.
    fn input_names() -> Vec<String>;
    /// Output port names as exported, in vector column order.
    fn output_names() -> Vec<String>;
    /// The clock input.
    fn clock_mut(&mut self) -> &mut Signal<In, Clock>;
    /// Sets every input from `values` (in `input_names` order).
    fn set_inputs(&mut self, values: &[u64]);
    /// Reads every output (in `output_names` order).
    fn outputs(&self) -> Vec<u64>;
}

/// Implements [`VectorPorts`] for a block with a `clock` field.
///
/// ```ignore
/// vector_ports!(impl[const W: usize] FreqDivider<W> {
///     inputs: [reset, enable, divisor],
///     outputs: [strobe],
/// });
/// ```
#[macro_export]
macro_rules! vector_ports {
    (impl[$($generics:tt)*] $ty:ty { inputs: [$($input:ident),* $(,)?], outputs: [$($output:ident),* $(,)?] $(,)? }) => {
        impl<$($generics)*> $crate::sim::VectorPorts for $ty {
            fn input_names() -> Vec<String> {
                vec![$(stringify!($input).to_string()),*]
            }
            fn output_names() -> Vec<String> {
                vec![$(stringify!($output).to_string()),*]
            }
            fn clock_mut(&mut self) -> &mut ::rust_hdl::core::prelude::Signal<::rust_hdl::core::prelude::In, ::rust_hdl::core::prelude::Clock> {
                &mut self.clock
            }
            #[allow(unused_assignments)]
            fn set_inputs(&mut self, values: &[u64]) {
                let mut column = 0;
                $(
                    self.$input.next = $crate::sim::PortValue::from_vector(values[column]);
                    column += 1;
                )*
            }
            fn outputs(&self) -> Vec<u64> {
                vec![$($crate::sim::PortValue::to_vector(&self.$output.val())),*]
            }
        }
    };
}
