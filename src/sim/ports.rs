use rust_hdl::core::prelude::*;

/// A port value that travels through test vectors as `u64` columns: one
/// column for a port of up to 64 bits, `ceil(width / 64)` consecutive
/// columns for a wider one, least significant word first.
pub trait PortValue: Sized {
    /// Vector columns the value takes.
    const WORDS: usize = 1;
    /// The value as an unsigned integer (bit 0 = LSB; the low 64 bits of a
    /// wider port).
    fn to_vector(&self) -> u64;
    /// The value from an unsigned integer; bits above the port width are dropped.
    fn from_vector(value: u64) -> Self;
    /// Appends the value's [`PortValue::WORDS`] columns to `out`.
    fn push_words(&self, out: &mut Vec<u64>) {
        out.push(self.to_vector());
    }
    /// The value from its [`PortValue::WORDS`] columns.
    fn from_words(words: &[u64]) -> Self {
        Self::from_vector(words[0])
    }
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
    const WORDS: usize = if N > 64 { N.div_ceil(64) } else { 1 };
    fn to_vector(&self) -> u64 {
        if N <= 64 {
            self.to_u64()
        } else {
            (0..64).fold(0, |w, i| w | (self.get_bit(i) as u64) << i)
        }
    }
    fn from_vector(value: u64) -> Self {
        Self::from_words(&[value])
    }
    fn push_words(&self, out: &mut Vec<u64>) {
        if N <= 64 {
            out.push(self.to_u64());
        } else {
            for word in 0..Self::WORDS {
                let bits = word * 64..(word * 64 + 64).min(N);
                out.push(bits.fold(0, |w, i| w | (self.get_bit(i) as u64) << (i % 64)));
            }
        }
    }
    fn from_words(words: &[u64]) -> Self {
        if N <= 64 {
            let masked = words[0] & crate::blocks::width_mask(N.min(64) as u32);
            Bits::<N>::from(masked)
        } else {
            (0..N)
                .filter(|&i| words.get(i / 64).is_some_and(|w| w >> (i % 64) & 1 != 0))
                .fold(Bits::<N>::default(), |x, i| x.replace_bit(i, true))
        }
    }
}

/// The vector columns of the port `signal` selects (for [`crate::vector_ports!`]).
pub fn port_words<B, D: Direction, T: Synth + PortValue>(
    _signal: fn(&B) -> &Signal<D, T>,
) -> usize {
    T::WORDS
}

/// Sets `signal` from its columns at `*column` and moves past them (for
/// [`crate::vector_ports!`]).
pub fn set_port<T: Synth + PortValue>(
    signal: &mut Signal<In, T>,
    values: &[u64],
    column: &mut usize,
) {
    signal.next = T::from_words(&values[*column..*column + T::WORDS]);
    *column += T::WORDS;
}

/// Appends the columns of `signal`'s value to `out` (for [`crate::vector_ports!`]).
pub fn push_port<T: Synth + PortValue>(signal: &Signal<Out, T>, out: &mut Vec<u64>) {
    signal.val().push_words(out);
}

/// A block whose ports can be driven from and compared against test vectors.
///
/// The port lists must match the block's top-level ports in declaration order
/// (without `clock`); the cross-simulation checks this against the ports
/// rust-hdl reports, so a stale list fails loudly. Implement it with
/// [`crate::vector_ports!`].
pub trait VectorPorts: Block {
    /// Input port names as exported (`name__i` for element i of an array),
    /// in vector order (a port wider than 64 bits takes several columns:
    /// [`VectorPorts::input_words`]).
    fn input_names() -> Vec<String>;
    /// Output port names as exported, in vector order.
    fn output_names() -> Vec<String>;
    /// The clock input.
    fn clock_mut(&mut self) -> &mut Signal<In, Clock>;
    /// Sets every input from `values` (in `input_names` order).
    fn set_inputs(&mut self, values: &[u64]);
    /// Reads every output (in `output_names` order).
    fn outputs(&self) -> Vec<u64>;
    /// Vector columns of each input (1 up to 64 bits; see [`PortValue`]).
    fn input_words() -> Vec<usize> {
        vec![1; Self::input_names().len()]
    }
    /// Vector columns of each output.
    fn output_words() -> Vec<usize> {
        vec![1; Self::output_names().len()]
    }
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
            fn set_inputs(&mut self, values: &[u64]) {
                let mut column = 0;
                $(
                    $crate::sim::set_port(&mut self.$input, values, &mut column);
                )*
            }
            fn outputs(&self) -> Vec<u64> {
                // A count known at compile time: this runs every clock.
                let mut out = Vec::with_capacity([$(stringify!($output)),*].len());
                $(
                    $crate::sim::push_port(&self.$output, &mut out);
                )*
                out
            }
            fn input_words() -> Vec<usize> {
                vec![$($crate::sim::port_words(|b: &Self| &b.$input)),*]
            }
            fn output_words() -> Vec<usize> {
                vec![$($crate::sim::port_words(|b: &Self| &b.$output)),*]
            }
        }
    };
}
