//! The SPI frame of [`super::SpiBusAdapter`]: the one place its layout is
//! written. The RTL, the model, the host's [`crate::host::spi::SpiBus`] (and `simulate --bus spi`) and
//! the tests take the command bits, the status bits, the byte positions and
//! the CRC from here.
//!
//! Bytes go MSB first, words most significant byte first.
//!
//! | byte (MOSI) | write frame | read frame |
//! |---|---|---|
//! | 0 | command: `WRITE` = 1, count - 1 | command: `WRITE` = 0, `SNAPSHOT`, count - 1 |
//! | 1 | register address | register address |
//! | 2 | header CRC: CRC-8 of bytes 0, 1 | header CRC: CRC-8 of bytes 0, 1 |
//! | 3 .. 3 + 4N | N words | any: the turnaround, then the answer |
//! | 3 + 4N | CRC-8 of bytes 0 .. 3 + 4N | |
//! | 4 + 4N | any: MISO answers the status | |
//!
//! | byte (MISO) | write frame | read frame |
//! |---|---|---|
//! | 0 | the last frame's status | the last frame's status |
//! | 1 .. 4 + 4N | 0 | 1, 2: 0 |
//! | 4 + 4N | this frame's status | |
//! | 3 | | this frame's status |
//! | 4 .. 4 + 4N | | the N words |
//! | 4 + 4N | | CRC-8 of the status and the words |
//!
//! The header has a CRC of its own so that a corrupted command (a count
//! or a direction changed) is caught before the adapter lays the rest of
//! the frame out by it. Once a frame has failed a check (either CRC, or
//! `OVERSPEED` by the time of the check), every later MISO byte of the
//! frame is its status, so the host finds the flag wherever it looks.
//! Every byte after those is 0 on MISO and ignored on MOSI.

/// Command bit 7: a write frame (else a read frame).
pub const COMMAND_WRITE: u8 = 0x80;
/// Command bit 6, read frames: write the controller's `SNAPSHOT` register
/// in the clock before the first read, so that the burst reads positions
/// latched on one clock (ignored in a write frame).
pub const COMMAND_SNAPSHOT: u8 = 0x40;
/// Command bits 3..0: the number of words, minus 1 (1 to 16 words).
pub const COMMAND_COUNT_MASK: u8 = 0x0f;
/// The longest burst, in words (the adapter's buffer).
pub const MAX_WORDS: usize = 16;

/// Status bits 7..4: always `1010`, so that a stuck MISO (0x00 or 0xff)
/// never reads as a status.
pub const STATUS_MARKER: u8 = 0xa0;
/// Status bit 0: the frame's CRC did not match; nothing was written or read.
pub const STATUS_CRC_ERROR: u8 = 0x01;
/// Status bit 1: an SCLK phase shorter than 2 clocks was seen in the frame;
/// nothing was written or read (when seen before the CRC byte ended).
pub const STATUS_OVERSPEED: u8 = 0x02;
/// Status bit 2 (the last frame's status only): CS rose before the frame's
/// CRC byte ended; nothing was written or read.
pub const STATUS_ABORTED: u8 = 0x04;

/// The CRC-8 of the frame: polynomial x^8 + x^2 + x + 1 (0x07), initial
/// value 0, MSB first, no final XOR (CRC-8/SMBUS; "123456789" gives 0xf4).
pub fn crc8(bytes: &[u8]) -> u8 {
    bytes
        .iter()
        .flat_map(|byte| (0..8).rev().map(move |k| byte >> k & 1 != 0))
        .fold(0, crc8_bit)
}

/// One bit into the CRC-8, as the RTL does at every SCLK rise.
pub fn crc8_bit(crc: u8, bit: bool) -> u8 {
    let feedback = (crc >> 7 != 0) ^ bit;
    (crc << 1) ^ if feedback { 0x07 } else { 0 }
}

/// Why a frame cannot be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    /// A burst of 0 or more than [`MAX_WORDS`] words.
    #[error("an SPI burst carries 1 to {MAX_WORDS} words, not {0}")]
    Count(usize),
}

fn command(write: bool, snapshot: bool, words: usize) -> Result<u8, FrameError> {
    if !(1..=MAX_WORDS).contains(&words) {
        return Err(FrameError::Count(words));
    }
    let mut c = (words - 1) as u8;
    if write {
        c |= COMMAND_WRITE;
    }
    if snapshot {
        c |= COMMAND_SNAPSHOT;
    }
    Ok(c)
}

/// The MOSI bytes of a write frame of `words` from `address` on, with the
/// status byte's slot at the end (the byte is the host's to clock; its
/// MOSI value is ignored).
pub fn write_frame(address: u8, words: &[u32]) -> Result<Vec<u8>, FrameError> {
    let mut frame = vec![command(true, false, words.len())?, address];
    frame.push(crc8(&frame));
    for w in words {
        frame.extend_from_slice(&w.to_be_bytes());
    }
    frame.push(crc8(&frame));
    frame.push(0);
    Ok(frame)
}

/// The MOSI bytes of a read frame of `words` words from `address` on: the
/// header and its CRC, then the slots of the status, the words and their
/// CRC (zeros on MOSI).
pub fn read_frame(address: u8, words: usize, snapshot: bool) -> Result<Vec<u8>, FrameError> {
    let mut frame = vec![command(false, snapshot, words)?, address];
    frame.push(crc8(&frame));
    frame.resize(3 + 1 + 4 * words + 1, 0);
    Ok(frame)
}

/// What a read frame brought back on MISO.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadAnswer {
    /// The last frame's status (MISO byte 0).
    pub last_status: u8,
    /// This frame's status.
    pub status: u8,
    /// The words.
    pub words: Vec<u32>,
    /// The CRC-8 the adapter sent matches the status and the words.
    pub crc_ok: bool,
}

/// Splits the MISO bytes of a read frame of `words` words.
pub fn read_answer(miso: &[u8], words: usize) -> ReadAnswer {
    let byte = |k: usize| miso.get(k).copied().unwrap_or(0);
    let body: Vec<u8> = (3..4 + 4 * words).map(byte).collect();
    ReadAnswer {
        last_status: byte(0),
        status: byte(3),
        words: (0..words)
            .map(|w| u32::from_be_bytes([0, 1, 2, 3].map(|b| byte(4 + 4 * w + b))))
            .collect(),
        crc_ok: crc8(&body) == byte(4 + 4 * words),
    }
}

/// A status byte that reports no fault.
pub fn status_ok(status: u8) -> bool {
    status == STATUS_MARKER
}

/// The position of the MISO status byte in a write frame of `words` words.
pub fn write_status_position(words: usize) -> usize {
    4 + 4 * words
}

/// The position of a write frame's last CRC byte.
pub fn write_crc_position(words: usize) -> usize {
    3 + 4 * words
}
