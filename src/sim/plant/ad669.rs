//! A behavioral bank of AD669-style DACs on one shared data bus, for
//! simulations that hang DACs on a block's pins (the controller's analog
//! axes, `dac_interface`): each chip's first rank is transparent while its
//! chip select and the shared L1 are both low; every second rank (the
//! output) is transparent while the shared LDAC is high.

/// K chips, their codes as the pins carry them (two's complement).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Ad669Bank {
    first: Vec<u64>,
    second: Vec<u64>,
    ldac: bool,
}

impl Ad669Bank {
    /// `chips` DACs, both ranks 0.
    pub fn new(chips: usize) -> Self {
        Self {
            first: vec![0; chips],
            second: vec![0; chips],
            ldac: false,
        }
    }

    /// One clock of pins: `data`, the chip selects `cs_n` (bit k for chip
    /// k, active low), `l1_n` (active low) and `ldac`. True on an LDAC rise.
    pub fn clock(&mut self, data: u64, cs_n: u64, l1_n: bool, ldac: bool) -> bool {
        for (k, first) in self.first.iter_mut().enumerate() {
            if cs_n >> k & 1 == 0 && !l1_n {
                *first = data;
            }
        }
        if ldac {
            self.second.clone_from(&self.first);
        }
        let rise = ldac && !self.ldac;
        self.ldac = ldac;
        rise
    }

    /// Chip k's output as a signed 16-bit code.
    pub fn code(&self, k: usize) -> i64 {
        self.second[k] as u16 as i16 as i64
    }
}
