//! An emulated bus master on an adapter's pins and a register-file slave on
//! its bus, shared by the tests of every external bus adapter (32, 16 and
//! 8 bits). With `resolve`, every pin change is presented for its first
//! clock as a random per-bit mix of the old and new values, as a
//! synchronizer may resolve a sample taken while the pins switch.

use motion_hdl::blocks::bus_synchronizer::model::BusPinInputs;
use motion_hdl::blocks::width_mask;
use motion_hdl::sim::{Harness, VectorPorts};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// How a counting register changes every clock.
type RegisterUpdate = Box<dyn Fn(u64) -> u64>;

/// What the bench reads from an adapter's outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BusView {
    pub data_out: u64,
    pub data_oe: bool,
    /// `None` for an adapter without `ready`.
    pub ready: Option<bool>,
    pub bus_address: u64,
    pub bus_write_data: u64,
    pub bus_write: bool,
    pub bus_read: bool,
    pub order_error: bool,
}

/// How long the master holds a strobe.
#[derive(Clone, Copy, Debug)]
pub enum Length {
    /// A fixed number of clocks.
    Clocks(u32),
    /// Until `ready` is seen high, sampled from the third clock on.
    UntilReady,
}

/// Pin widths of the adapter under test.
#[derive(Clone, Copy, Debug)]
pub struct PinWidths {
    pub address_bits: u32,
    pub data_bits: u32,
}

pub struct PinBench<B: VectorPorts> {
    h: Harness<B>,
    view: fn(&[u64]) -> BusView,
    widths: PinWidths,
    pub pins: BusPinInputs,
    presented: BusPinInputs,
    resolve: Option<StdRng>,
    /// The slave's registers (wide words).
    pub registers: Vec<u64>,
    /// A register that the slave updates every clock with the function.
    pub counting: Option<(usize, RegisterUpdate)>,
    slave_data: u64,
    pending_read: Option<u64>,
    pub bus_writes: u32,
    pub bus_reads: u32,
    pub order_errors: u32,
    pub clocks: u64,
    pub last: BusView,
}

impl<B: VectorPorts> PinBench<B> {
    pub fn new(
        name: &str,
        block: B,
        view: fn(&[u64]) -> BusView,
        widths: PinWidths,
        registers: usize,
        resolve: Option<u64>,
    ) -> Self {
        Self {
            h: Harness::new(name, block).unwrap(),
            view,
            widths,
            pins: BusPinInputs::default(),
            presented: BusPinInputs::default(),
            resolve: resolve.map(StdRng::seed_from_u64),
            registers: vec![0; registers],
            counting: None,
            slave_data: 0,
            pending_read: None,
            bus_writes: 0,
            bus_reads: 0,
            order_errors: 0,
            clocks: 0,
            last: BusView::default(),
        }
    }

    /// The pins as a synchronizer may see them this clock.
    fn shown_pins(&mut self) -> BusPinInputs {
        let shown = match &mut self.resolve {
            Some(rng) => resolve_pins(rng, self.presented, self.pins, self.widths),
            None => self.pins,
        };
        // Whatever was shown, the pins have their new value from now on.
        self.presented = self.pins;
        shown
    }

    pub fn clock(&mut self) {
        let mut shown = self.shown_pins();
        shown.bus_read_data = self.slave_data;
        let out = (self.view)(&self.h.step_vector(&shown.to_vector()).unwrap());
        self.clocks += 1;
        // The slave registers its answer in the clock after bus_read.
        if let Some(address) = self.pending_read.take() {
            self.slave_data = self.registers[address as usize];
        }
        if let Some((register, next)) = &self.counting {
            self.registers[*register] = next(self.registers[*register]);
        }
        if out.bus_read {
            self.pending_read = Some(out.bus_address);
            self.bus_reads += 1;
        }
        if out.bus_write {
            self.registers[out.bus_address as usize] = out.bus_write_data;
            self.bus_writes += 1;
        }
        self.order_errors += out.order_error as u32;
        assert!(!(out.bus_read && out.bus_write));
        self.last = out;
    }

    pub fn hold(&mut self, clocks: u32) {
        for _ in 0..clocks {
            self.clock();
        }
    }

    /// A write strobe of `length`, with zero hold: address and data change
    /// to random values the moment it ends. Then the 2-clock gap. Returns
    /// the strobe's length in clocks.
    pub fn write(&mut self, rng: &mut StdRng, address: u64, data: u64, length: Length) -> u32 {
        self.pins.address = address;
        self.pins.data_in = data;
        self.pins.cs_n = false;
        self.pins.we_n = false;
        let clocks = self.hold_strobe(length);
        self.end_strobe(rng);
        clocks
    }

    /// A read strobe of `length`; returns `data_out` at its end and the
    /// strobe's length in clocks.
    pub fn read(&mut self, rng: &mut StdRng, address: u64, length: Length) -> (u64, u32) {
        self.pins.address = address;
        self.pins.cs_n = false;
        self.pins.rd_n = false;
        let clocks = self.hold_strobe(length);
        assert!(self.last.data_oe);
        let data = self.last.data_out;
        self.end_strobe(rng);
        (data, clocks)
    }

    fn hold_strobe(&mut self, length: Length) -> u32 {
        match length {
            Length::Clocks(clocks) => {
                self.hold(clocks);
                clocks
            }
            Length::UntilReady => self.wait_ready(),
        }
    }

    fn wait_ready(&mut self) -> u32 {
        let mut clocks = 0;
        loop {
            self.clock();
            clocks += 1;
            assert!(clocks < 50, "ready never rose");
            if clocks >= 3 && self.last.ready == Some(true) {
                return clocks;
            }
        }
    }

    fn end_strobe(&mut self, rng: &mut StdRng) {
        self.pins.we_n = true;
        self.pins.rd_n = true;
        self.pins.cs_n = true;
        self.pins.address = rng.gen::<u64>() & width_mask(self.widths.address_bits);
        self.pins.data_in = rng.gen::<u64>() & width_mask(self.widths.data_bits);
        self.hold(2);
    }
}

/// The pins `new` as a synchronizer may sample them on the first clock
/// after they changed from `old`: every changed bit resolved at random.
pub fn resolve_pins(
    rng: &mut StdRng,
    old: BusPinInputs,
    new: BusPinInputs,
    widths: PinWidths,
) -> BusPinInputs {
    let mix = |rng: &mut StdRng, old: u64, new: u64| {
        let take_new = rng.gen::<u64>();
        (old & !take_new) | (new & take_new)
    };
    let mut shown = new;
    shown.address = mix(rng, old.address, new.address) & width_mask(widths.address_bits);
    shown.data_in = mix(rng, old.data_in, new.data_in) & width_mask(widths.data_bits);
    for (o, n, s) in [
        (old.cs_n, new.cs_n, &mut shown.cs_n),
        (old.we_n, new.we_n, &mut shown.we_n),
        (old.rd_n, new.rd_n, &mut shown.rd_n),
    ] {
        *s = if o != n && rng.gen_bool(0.5) { o } else { n };
    }
    shown
}

/// Pins that change at random, strobes of every width from one clock
/// (including the illegal ones), reads and writes overlapping, a random
/// slave answer every clock and a rare reset.
pub fn random_pins(seed: u64, cycles: usize, widths: PinWidths) -> Vec<BusPinInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut i = BusPinInputs::default();
    (0..cycles)
        .map(|_| {
            if rng.gen_ratio(1, 4) {
                i.cs_n = rng.gen_ratio(1, 3);
            }
            if rng.gen_ratio(1, 3) {
                i.we_n = !i.we_n;
            }
            if rng.gen_ratio(1, 3) {
                i.rd_n = !i.rd_n;
            }
            if rng.gen_ratio(1, 2) {
                i.address = rng.gen::<u64>() & width_mask(widths.address_bits);
            }
            if rng.gen_ratio(1, 2) {
                i.data_in = rng.gen::<u64>() & width_mask(widths.data_bits);
            }
            i.bus_read_data = rng.gen::<u32>() as u64;
            i.reset = rng.gen_ratio(1, 50_000);
            i
        })
        .collect()
}
