//! The command sequence the control-level DSP writes to each motor-control
//! DSP every period through the card's FIFOs (`parallel_card`, `CMD[k]`):
//! the platform's pose, twist and acceleration at the period's end, in
//! 32-bit fixed point. Every slave gets the same point and runs the inverse
//! kinematics of its own two legs.
//!
//! | word | content | unit (LSB) | range |
//! |---|---|---|---|
//! | 0 | header: 0xA5 in bits 31..24, [`WORDS`] in 23..16, the period's sequence number in 15..0 | - | - |
//! | 1..=3 | X, Y, Z | 1 nm | ±2.147 m |
//! | 4..=6 | A, B, C | 1 µdeg | ±2147° |
//! | 7..=9 | X, Y, Z velocity | 1 µm/s | ±2147 m/s |
//! | 10..=12 | A, B, C angular velocity | 1 µdeg/s | ±2147 °/s |
//! | 13..=15 | X, Y, Z acceleration | 1 µm/s² | ±2147 m/s² |
//! | 16..=18 | A, B, C angular acceleration | 1 µdeg/s² | ±2147 °/s² |
//!
//! Values are two's complement, rounded to the nearest LSB. A value that is
//! not finite or does not fit is an error naming it, never a wrapped word.
//! The header lets a slave tell a point from a word read off an empty FIFO
//! (the bridge returns 0 and sets `CMD_UNDERFLOW`) or from a sequence it
//! entered in the middle.

use super::Pose;

/// Words of one period's point.
pub const WORDS: usize = 19;
/// The header's mark, bits 31..24.
pub const HEADER_MARK: u32 = 0xA5;
/// Points a 64-word command FIFO holds: the master can run this many
/// periods ahead of the slaves.
pub const POINTS_PER_FIFO: usize = 64 / WORDS;

// The card's FIFOs hold 64 words; at least two points must fit.
const _: () = assert!(POINTS_PER_FIFO >= 2);

/// The names of words 1 to 18, for errors.
#[doc(hidden)]
pub const FIELDS: [&str; WORDS - 1] = [
    "X",
    "Y",
    "Z",
    "A",
    "B",
    "C",
    "X velocity",
    "Y velocity",
    "Z velocity",
    "A velocity",
    "B velocity",
    "C velocity",
    "X acceleration",
    "Y acceleration",
    "Z acceleration",
    "A acceleration",
    "B acceleration",
    "C acceleration",
];

/// Units per LSB of words 1 to 18, in mm, degrees and seconds.
const LSB: [f64; WORDS - 1] = [
    1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-3, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-3, 1e-6,
    1e-6, 1e-6,
];

/// One period's point: where the platform is to be at the period's end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodPoint {
    /// The period's number (wraps at 2^16).
    pub sequence: u16,
    /// X Y Z in mm, A B C in degrees.
    pub pose: Pose,
    /// X Y Z in mm/s, A B C in degrees/s.
    pub velocity: [f64; 6],
    /// X Y Z in mm/s², A B C in degrees/s².
    pub acceleration: [f64; 6],
}

/// Why a point cannot be written or read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CommandError {
    /// A value is not finite or does not fit its word.
    #[error(
        "period point: {field} = {value} does not fit its word ({lsb} a count, 32 bits signed)"
    )]
    OutOfRange {
        /// The value's name.
        field: &'static str,
        /// The value, in mm, degrees and seconds.
        value: f64,
        /// Its unit per count.
        lsb: f64,
    },
    /// Not [`WORDS`] words.
    #[error("period point: {0} words, a point has {WORDS}")]
    Length(usize),
    /// The first word is 0: read off an empty FIFO.
    #[error("period point: the header is 0, read off an empty command FIFO (underflow)")]
    Underflow,
    /// The first word is not a header.
    #[error("period point: {0:#010x} is not a point header (0xA5, {WORDS} words)")]
    Header(u32),
}

impl PeriodPoint {
    /// Words 1 to 18's values in their order: position, angles, velocity,
    /// acceleration.
    pub fn values(&self) -> [f64; WORDS - 1] {
        let mut v = [0.0; WORDS - 1];
        v[0..3].copy_from_slice(&self.pose.position);
        v[3..6].copy_from_slice(&self.pose.angles);
        v[6..12].copy_from_slice(&self.velocity);
        v[12..18].copy_from_slice(&self.acceleration);
        v
    }

    /// The words the master writes, header first.
    pub fn encode(&self) -> Result<[u32; WORDS], CommandError> {
        let mut words = [0u32; WORDS];
        words[0] = HEADER_MARK << 24 | (WORDS as u32) << 16 | self.sequence as u32;
        for (i, value) in self.values().into_iter().enumerate() {
            let counts = (value / LSB[i]).round();
            if !counts.is_finite() || counts < i32::MIN as f64 || counts > i32::MAX as f64 {
                return Err(CommandError::OutOfRange {
                    field: FIELDS[i],
                    value,
                    lsb: LSB[i],
                });
            }
            words[i + 1] = counts as i32 as u32;
        }
        Ok(words)
    }

    /// The point a slave reads, from its [`WORDS`] words.
    pub fn decode(words: &[u32]) -> Result<Self, CommandError> {
        if words.len() != WORDS {
            return Err(CommandError::Length(words.len()));
        }
        match words[0] {
            0 => return Err(CommandError::Underflow),
            h if h >> 16 != HEADER_MARK << 8 | WORDS as u32 => return Err(CommandError::Header(h)),
            _ => {}
        }
        let v: Vec<f64> = (0..WORDS - 1)
            .map(|i| words[i + 1] as i32 as f64 * LSB[i])
            .collect();
        Ok(Self {
            sequence: words[0] as u16,
            pose: Pose {
                position: [v[0], v[1], v[2]],
                angles: [v[3], v[4], v[5]],
            },
            velocity: std::array::from_fn(|i| v[6 + i]),
            acceleration: std::array::from_fn(|i| v[12 + i]),
        })
    }

    /// The largest error of a value after [`Self::encode`] and
    /// [`Self::decode`]: half its LSB (0.5 nm, 0.5 µdeg, 0.5 µm/s ...),
    /// value by value.
    pub fn resolution() -> [f64; WORDS - 1] {
        LSB.map(|lsb| lsb / 2.0)
    }
}
