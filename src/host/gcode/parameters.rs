//! The parameters LinuxCNC keeps between runs, #5161 to #5390, as far as
//! they concern an X, Y, Z machine: where G28 and G30 go, the G92 offset,
//! the active coordinate system and the origins of G54 to G59.3. They
//! come from the machine settings file (`parameter 5221 10.0`, in mm, as
//! LinuxCNC's var file holds them in machine units); a program's G10,
//! G28.1, G30.1, G54 to G59.3 and G92 change them for the rest of its run.
//!
//! | Parameters | Meaning | Default |
//! |---|---|---|
//! | 5161, 5162, 5163 | G28 position X, Y, Z, machine mm | 0 |
//! | 5181, 5182, 5183 | G30 position X, Y, Z, machine mm | 0 |
//! | 5210 | 1: the G92 offset applies; 0: it does not (G92.1, G92.2) | 0 |
//! | 5211, 5212, 5213 | G92 offset X, Y, Z, mm | 0 |
//! | 5220 | active coordinate system: 1 = G54 ... 6 = G59, 7 = G59.1, 8 = G59.2, 9 = G59.3 | 1 |
//! | 5221 + 20 (n − 1), +1, +2 | origin of system n (1 = G54 ... 9 = G59.3), X, Y, Z, machine mm | 0 |
//!
//! The A, B, C, U, V and W entries of each group (5164 to 5169 and so on)
//! and each system's rotation (5230, 5250, ... 5390) are accepted at 0:
//! this machine has no such axes and does not rotate coordinate systems,
//! so any other value is refused by name. Numbers in the range that
//! LinuxCNC does not use (5170 to 5180, 5190 to 5209) are refused.

/// The first parameter kept between runs.
pub const FIRST: u32 = 5161;
/// The last parameter kept between runs.
pub const LAST: u32 = 5390;
/// Coordinate systems: G54 to G59, G59.1 to G59.3.
pub const SYSTEMS: usize = 9;

const G28: u32 = 5161;
const G30: u32 = 5181;
const G92_ON: u32 = 5210;
const G92: u32 = 5211;
const ACTIVE_SYSTEM: u32 = 5220;
const ORIGINS: u32 = 5221;
/// Parameters from one system's origin to the next.
const SYSTEM_STRIDE: u32 = 20;

/// The G code that selects system `index` (0 = G54 ... 8 = G59.3).
pub fn system_name(index: usize) -> &'static str {
    [
        "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
    ][index]
}

/// #5161 to #5390, in mm where they are lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PersistentParameters {
    values: [f64; (LAST - FIRST + 1) as usize],
}

impl Default for PersistentParameters {
    /// Every parameter 0, but the active coordinate system G54 (#5220 = 1).
    fn default() -> Self {
        let mut p = PersistentParameters {
            values: [0.0; (LAST - FIRST + 1) as usize],
        };
        p.put(ACTIVE_SYSTEM, 1.0);
        p
    }
}

/// What a parameter number holds.
enum Meaning {
    /// An X, Y or Z length.
    Length,
    /// A length along an axis this machine does not have.
    OtherAxis,
    Rotation,
    G92On,
    ActiveSystem,
    Unused,
}

fn meaning(n: u32) -> Meaning {
    let axis_group = |first: u32| (first..first + 9).contains(&n).then(|| n - first);
    let axis = axis_group(G28)
        .or_else(|| axis_group(G30))
        .or_else(|| axis_group(G92))
        .or_else(|| {
            let offset = n.checked_sub(ORIGINS)?;
            (offset / SYSTEM_STRIDE < SYSTEMS as u32 && offset % SYSTEM_STRIDE < 10)
                .then_some(offset % SYSTEM_STRIDE)
        });
    match (n, axis) {
        (G92_ON, _) => Meaning::G92On,
        (ACTIVE_SYSTEM, _) => Meaning::ActiveSystem,
        (_, Some(0..=2)) => Meaning::Length,
        (_, Some(9)) => Meaning::Rotation,
        (_, Some(_)) => Meaning::OtherAxis,
        (_, None) => Meaning::Unused,
    }
}

impl PersistentParameters {
    /// Parameter `n`, if it is one of #5161 to #5390.
    pub fn get(&self, n: u32) -> Option<f64> {
        let index = n.checked_sub(FIRST)? as usize;
        self.values.get(index).copied()
    }

    /// Sets parameter `n`, checking that it is one this machine keeps and
    /// that its value means something here; the error says why not.
    pub fn set(&mut self, n: u32, value: f64) -> Result<(), String> {
        if !(FIRST..=LAST).contains(&n) {
            return Err(format!(
                "#{n} is not a parameter LinuxCNC keeps between runs (#{FIRST} to #{LAST})"
            ));
        }
        if !value.is_finite() {
            return Err(format!("#{n} = {value} is not a finite number"));
        }
        match meaning(n) {
            Meaning::Length => {}
            Meaning::OtherAxis if value == 0.0 => {}
            Meaning::OtherAxis => {
                return Err(format!(
                    "#{n} = {value} is an offset along an A, B, C, U, V or W axis; this machine has X, Y and Z only"
                ))
            }
            Meaning::Rotation if value == 0.0 => {}
            Meaning::Rotation => {
                return Err(format!(
                    "#{n} = {value} rotates a coordinate system, which is not supported"
                ))
            }
            Meaning::G92On if value == 0.0 || value == 1.0 => {}
            Meaning::G92On => {
                return Err(format!(
                    "#{n} = {value}: it is 1 when the G92 offset applies and 0 when not"
                ))
            }
            Meaning::ActiveSystem if (1.0..=9.0).contains(&value) && value.fract() == 0.0 => {}
            Meaning::ActiveSystem => {
                return Err(format!(
                    "#{n} = {value} is not a coordinate system: 1 (G54) to 9 (G59.3)"
                ))
            }
            Meaning::Unused => {
                return Err(format!("#{n} is a parameter LinuxCNC does not use"))
            }
        }
        self.put(n, value);
        Ok(())
    }

    fn put(&mut self, n: u32, value: f64) {
        self.values[(n - FIRST) as usize] = value;
    }

    fn xyz(&self, first: u32) -> [f64; 3] {
        [0, 1, 2].map(|k| self.values[(first - FIRST) as usize + k])
    }

    fn put_xyz(&mut self, first: u32, xyz: [f64; 3]) {
        for (k, value) in xyz.into_iter().enumerate() {
            self.put(first + k as u32, value);
        }
    }

    /// The stored G28 (`second` false) or G30 position, machine mm.
    pub fn home(&self, second: bool) -> [f64; 3] {
        self.xyz(if second { G30 } else { G28 })
    }

    pub(super) fn set_home(&mut self, second: bool, machine_mm: [f64; 3]) {
        self.put_xyz(if second { G30 } else { G28 }, machine_mm);
    }

    /// The active coordinate system, 0 (G54) to 8 (G59.3).
    pub fn active_system(&self) -> usize {
        // set() keeps it a whole number from 1 to 9.
        (self.values[(ACTIVE_SYSTEM - FIRST) as usize] as usize).clamp(1, SYSTEMS) - 1
    }

    pub(super) fn select_system(&mut self, index: usize) {
        self.put(ACTIVE_SYSTEM, (index + 1) as f64);
    }

    /// The origin of system `index` (0 = G54), machine mm.
    pub fn origin(&self, index: usize) -> [f64; 3] {
        self.xyz(ORIGINS + SYSTEM_STRIDE * index as u32)
    }

    pub(super) fn set_origin(&mut self, index: usize, origin: [f64; 3]) {
        self.put_xyz(ORIGINS + SYSTEM_STRIDE * index as u32, origin);
    }

    /// The G92 offset as stored (#5211 to #5213), applied or not.
    pub fn g92_stored(&self) -> [f64; 3] {
        self.xyz(G92)
    }

    /// The G92 offset in force: the stored one when #5210 is 1, else 0.
    pub fn g92(&self) -> [f64; 3] {
        if self.values[(G92_ON - FIRST) as usize] == 1.0 {
            self.g92_stored()
        } else {
            [0.0; 3]
        }
    }

    /// Stores `offset` and applies it (`on`) or not.
    pub fn set_g92(&mut self, offset: [f64; 3], on: bool) {
        self.put_xyz(G92, offset);
        self.put(G92_ON, f64::from(u8::from(on)));
    }
}
