//! Register maps: one description in Rust, from which the C header for
//! firmware, the Markdown register table and the field packing used by tests
//! and drivers are all derived, so that they cannot disagree (a driver and
//! firmware disagreeing on register packing is a known field failure).
//!
//! A [`RegisterMap`] is a list of 32-bit [`Register`]s at word addresses;
//! a register may repeat with a stride (one copy per axis). Each register is
//! made of [`Field`]s with an access type and a reset value.
//! [`RegisterMap::validate`] refuses overlapping fields or addresses, fields
//! outside the word, reset values that do not fit, and names that are not C
//! identifiers, each with an error naming the problem.

mod c_header;
mod markdown;

use bitvec::prelude::*;

pub use c_header::c_header;
pub use markdown::markdown;

/// How software may access a field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Read only; writes are ignored.
    ReadOnly,
    /// Read and write; reads return the last value written.
    ReadWrite,
    /// Read; writing 1 clears the bit, writing 0 leaves it.
    WriteOneToClear,
    /// Write only, an action (a strobe or a FIFO push); reads return 0.
    WriteOnly,
}

impl Access {
    /// The short name used in the header and the table.
    pub fn abbreviation(self) -> &'static str {
        match self {
            Access::ReadOnly => "RO",
            Access::ReadWrite => "RW",
            Access::WriteOneToClear => "W1C",
            Access::WriteOnly => "WO",
        }
    }
}

/// A bit field of a register.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// C identifier, upper case.
    pub name: &'static str,
    /// Least significant bit.
    pub lsb: u32,
    /// Width in bits (1 to 32).
    pub width: u32,
    /// Software access.
    pub access: Access,
    /// Value after reset.
    pub reset: u64,
    /// One line: what the field means.
    pub doc: &'static str,
}

impl Field {
    /// The same field with reset value `reset`.
    pub fn with_reset(self, reset: u64) -> Self {
        Self { reset, ..self }
    }

    /// All ones in the field's width.
    pub fn max_value(&self) -> u64 {
        // Clamped: an invalid width must give an error later, not a panic.
        crate::blocks::width_mask(self.width.clamp(1, 64))
    }

    /// The field's bits within the word.
    pub fn mask(&self) -> u32 {
        (self.max_value() << self.lsb) as u32
    }

    fn check_fits(&self) -> Result<(), RegMapError> {
        match self.lsb.checked_add(self.width) {
            Some(end) if self.width > 0 && end <= 32 => Ok(()),
            _ => Err(RegMapError::FieldOutOfWord {
                register: String::new(),
                field: self.name.to_string(),
                lsb: self.lsb,
                width: self.width,
            }),
        }
    }

    /// `word` with this field set to `value`.
    pub fn insert(&self, word: u32, value: u64) -> Result<u32, RegMapError> {
        self.check_fits()?;
        if value > self.max_value() {
            return Err(RegMapError::ValueTooWide {
                field: self.name.to_string(),
                value,
                width: self.width,
            });
        }
        let mut bits = BitArray::<[u32; 1], Lsb0>::new([word]);
        bits[self.lsb as usize..(self.lsb + self.width) as usize].store(value);
        Ok(bits.into_inner()[0])
    }

    /// This field's value in `word`.
    pub fn extract(&self, word: u32) -> Result<u64, RegMapError> {
        self.check_fits()?;
        let bits = BitArray::<[u32; 1], Lsb0>::new([word]);
        Ok(bits[self.lsb as usize..(self.lsb + self.width) as usize].load::<u64>())
    }
}

/// A field with reset value 0 (see [`Field::with_reset`]): the builder every
/// block's register map uses.
pub fn field(name: &'static str, lsb: u32, width: u32, access: Access, doc: &'static str) -> Field {
    Field {
        name,
        lsb,
        width,
        access,
        reset: 0,
        doc,
    }
}

/// A single register (count 1) of `fields`.
pub fn register(
    name: &'static str,
    address: u32,
    doc: &'static str,
    fields: Vec<Field>,
) -> Register {
    Register {
        name,
        address,
        count: 1,
        stride: 0,
        doc,
        fields,
    }
}

/// A 32-bit register, or an array of them (one per axis).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Register {
    /// C identifier, upper case.
    pub name: &'static str,
    /// Word address of the first copy.
    pub address: u32,
    /// Copies (1 for a plain register).
    pub count: u32,
    /// Words between copies.
    pub stride: u32,
    /// One line: what the register is.
    pub doc: &'static str,
    /// The fields, in any order.
    pub fields: Vec<Field>,
}

impl Register {
    /// A register with one field filling all 32 bits.
    pub fn word(
        name: &'static str,
        address: u32,
        access: Access,
        reset: u64,
        doc: &'static str,
    ) -> Self {
        Self {
            name,
            address,
            count: 1,
            stride: 0,
            doc,
            fields: vec![Field {
                name: "VALUE",
                lsb: 0,
                width: 32,
                access,
                reset,
                doc,
            }],
        }
    }

    /// Repeats the register `count` times, `stride` words apart.
    pub fn repeated(mut self, count: u32, stride: u32) -> Self {
        self.count = count;
        self.stride = stride;
        self
    }

    /// The word address of copy `index`.
    pub fn address_of(&self, index: u32) -> Result<u32, RegMapError> {
        if index >= self.count {
            return Err(RegMapError::NoSuchCopy {
                register: self.name.to_string(),
                index,
                count: self.count,
            });
        }
        Ok(self.address + index * self.stride)
    }

    /// Every word address the register occupies.
    pub fn addresses(&self) -> impl Iterator<Item = u32> + '_ {
        // Saturating: a map whose addresses overflow fails validation.
        (0..self.count).map(move |i| {
            i.checked_mul(self.stride)
                .and_then(|o| o.checked_add(self.address))
                .unwrap_or(u32::MAX)
        })
    }

    /// The field named `name`.
    pub fn field(&self, name: &str) -> Result<&Field, RegMapError> {
        self.fields
            .iter()
            .find(|f| f.name == name)
            .ok_or_else(|| RegMapError::NoSuchField {
                register: self.name.to_string(),
                field: name.to_string(),
            })
    }

    /// The register's value after reset, as a read returns it (write-only
    /// fields read as 0 and must reset to 0).
    pub fn reset_value(&self) -> u32 {
        self.fields.iter().fold(0, |word, f| {
            f.insert(word, f.reset & f.max_value()).unwrap_or(word)
        })
    }

    /// A word with the named fields set, every other bit 0.
    pub fn pack(&self, values: &[(&str, u64)]) -> Result<u32, RegMapError> {
        values.iter().try_fold(0, |word, (name, value)| {
            self.field(name)?.insert(word, *value)
        })
    }

    /// The bits of write-one-to-clear fields.
    pub fn w1c_mask(&self) -> u32 {
        self.mask_of(Access::WriteOneToClear)
    }

    /// The bits of read-write fields.
    pub fn rw_mask(&self) -> u32 {
        self.mask_of(Access::ReadWrite)
    }

    fn mask_of(&self, access: Access) -> u32 {
        self.fields
            .iter()
            .filter(|f| f.access == access)
            .fold(0, |m, f| m | f.mask())
    }

    /// The word to write for a read-modify-write: the read-write fields of
    /// `current` kept, the named fields set, and every write-one-to-clear
    /// bit 0 unless named (so pending flags are not cleared by accident)
    /// and every write-only field 0 unless named.
    pub fn modify(&self, current: u32, values: &[(&str, u64)]) -> Result<u32, RegMapError> {
        values
            .iter()
            .try_fold(current & self.rw_mask(), |word, (name, value)| {
                self.field(name)?.insert(word, *value)
            })
    }
}

/// A named set of registers on one 32-bit bus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RegisterMap {
    /// The module the map belongs to (C prefix, upper-cased).
    pub name: &'static str,
    /// Address bits of the bus: addresses run from 0 to 2^bits - 1.
    pub address_bits: u32,
    /// One line: what the map is.
    pub doc: &'static str,
    /// The registers, in address order.
    pub registers: Vec<Register>,
}

/// What is wrong with a register map or an access through it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RegMapError {
    /// A name is not an upper-case C identifier.
    #[error("`{0}` is not an upper-case C identifier")]
    BadName(String),
    /// Two registers, or two fields of one register, share a name.
    #[error("the name `{0}` is used twice")]
    DuplicateName(String),
    /// A field does not fit in 32 bits.
    #[error("field {register}.{field} (bits {lsb}..{lsb}+{width}) does not fit in 32 bits")]
    FieldOutOfWord {
        /// Register name.
        register: String,
        /// Field name.
        field: String,
        /// Its least significant bit.
        lsb: u32,
        /// Its width.
        width: u32,
    },
    /// Two fields of one register share a bit.
    #[error("fields {register}.{first} and {register}.{second} overlap")]
    FieldOverlap {
        /// Register name.
        register: String,
        /// One field.
        first: String,
        /// The other.
        second: String,
    },
    /// A reset value does not fit its field.
    #[error("reset value {value:#x} of {register}.{field} does not fit its {width} bits")]
    ResetTooWide {
        /// Register name.
        register: String,
        /// Field name.
        field: String,
        /// The value.
        value: u64,
        /// The field width.
        width: u32,
    },
    /// Two registers share an address.
    #[error("registers {first} and {second} both use address {address:#x}")]
    AddressOverlap {
        /// One register.
        first: String,
        /// The other.
        second: String,
        /// The shared word address.
        address: u32,
    },
    /// An address is beyond the bus.
    #[error("register {register} uses address {address:#x}, beyond the {bits}-bit bus")]
    AddressOutOfRange {
        /// Register name.
        register: String,
        /// The address.
        address: u32,
        /// Bus address bits.
        bits: u32,
    },
    /// A value does not fit the field it is written to.
    #[error("value {value:#x} does not fit field {field} ({width} bits)")]
    ValueTooWide {
        /// Field name.
        field: String,
        /// The value.
        value: u64,
        /// The field width.
        width: u32,
    },
    /// No register of that name.
    #[error("no register named `{0}`")]
    NoSuchRegister(String),
    /// The bus address width is outside 1..=32.
    #[error("a register bus of {0} address bits is not supported (1 to 32)")]
    BadAddressBits(u32),
    /// A register with no copies.
    #[error("register {0} has a count of 0")]
    NoCopies(String),
    /// A repeated register whose copies all sit at one address.
    #[error("register {0} repeats with a stride of 0")]
    ZeroStride(String),
    /// A write-only field with a non-zero reset value (it reads as 0).
    #[error("write-only field {register}.{field} must reset to 0 (it reads as 0)")]
    WriteOnlyReset {
        /// Register name.
        register: String,
        /// Field name.
        field: String,
    },
    /// A description that would break the header or the table.
    #[error("the description of {0} contains a newline, `*/` or `|`")]
    BadDoc(String),
    /// Two generated C macros would have the same name.
    #[error("two generated C macros are both named {0}")]
    MacroCollision(String),
    /// No field of that name in the register.
    #[error("register {register} has no field `{field}`")]
    NoSuchField {
        /// Register name.
        register: String,
        /// The missing field.
        field: String,
    },
    /// An array index beyond the register's copies.
    #[error("register {register} has {count} copies; there is no copy {index}")]
    NoSuchCopy {
        /// Register name.
        register: String,
        /// The index asked for.
        index: u32,
        /// Copies.
        count: u32,
    },
}

fn check_doc(owner: &str, doc: &str) -> Result<(), RegMapError> {
    if doc.contains('\n') || doc.contains("*/") || doc.contains('|') {
        Err(RegMapError::BadDoc(owner.to_string()))
    } else {
        Ok(())
    }
}

fn check_name(name: &str) -> Result<(), RegMapError> {
    let mut chars = name.chars();
    let first_ok = chars.next().is_some_and(|c| c.is_ascii_uppercase());
    if first_ok && chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') {
        Ok(())
    } else {
        Err(RegMapError::BadName(name.to_string()))
    }
}

impl RegisterMap {
    /// Checks every rule of a well-formed map (see the module docs).
    pub fn validate(&self) -> Result<(), RegMapError> {
        check_name(self.name)?;
        if !(1..=32).contains(&self.address_bits) {
            return Err(RegMapError::BadAddressBits(self.address_bits));
        }
        check_doc(self.name, self.doc)?;
        let mut names = std::collections::HashSet::new();
        let mut used = std::collections::HashMap::new();
        for r in &self.registers {
            check_name(r.name)?;
            check_doc(r.name, r.doc)?;
            if !names.insert(r.name) {
                return Err(RegMapError::DuplicateName(r.name.to_string()));
            }
            if r.count == 0 {
                return Err(RegMapError::NoCopies(r.name.to_string()));
            }
            if r.count > 1 && r.stride == 0 {
                return Err(RegMapError::ZeroStride(r.name.to_string()));
            }
            for address in r.addresses() {
                if address == u32::MAX || u64::from(address) >= 1u64 << self.address_bits {
                    return Err(RegMapError::AddressOutOfRange {
                        register: r.name.to_string(),
                        address,
                        bits: self.address_bits,
                    });
                }
                if let Some(first) = used.insert(address, r.name) {
                    return Err(RegMapError::AddressOverlap {
                        first: first.to_string(),
                        second: r.name.to_string(),
                        address,
                    });
                }
            }
            let mut field_names = std::collections::HashSet::new();
            let mut claimed = bitarr![u32, Lsb0; 0; 32];
            for f in &r.fields {
                check_name(f.name)?;
                check_doc(f.name, f.doc)?;
                if !field_names.insert(f.name) {
                    return Err(RegMapError::DuplicateName(format!("{}.{}", r.name, f.name)));
                }
                if f.check_fits().is_err() {
                    return Err(RegMapError::FieldOutOfWord {
                        register: r.name.to_string(),
                        field: f.name.to_string(),
                        lsb: f.lsb,
                        width: f.width,
                    });
                }
                if f.access == Access::WriteOnly && f.reset != 0 {
                    return Err(RegMapError::WriteOnlyReset {
                        register: r.name.to_string(),
                        field: f.name.to_string(),
                    });
                }
                if f.reset > f.max_value() {
                    return Err(RegMapError::ResetTooWide {
                        register: r.name.to_string(),
                        field: f.name.to_string(),
                        value: f.reset,
                        width: f.width,
                    });
                }
                let bits = f.lsb as usize..(f.lsb + f.width) as usize;
                if claimed[bits.clone()].any() {
                    let other = r
                        .fields
                        .iter()
                        .find(|o| o.name != f.name && o.mask() & f.mask() != 0)
                        .map_or("?", |o| o.name);
                    return Err(RegMapError::FieldOverlap {
                        register: r.name.to_string(),
                        first: other.to_string(),
                        second: f.name.to_string(),
                    });
                }
                claimed[bits].fill(true);
            }
        }
        let mut macros = std::collections::HashSet::new();
        for name in c_header::macro_names(self) {
            if !macros.insert(name.clone()) {
                return Err(RegMapError::MacroCollision(name));
            }
        }
        Ok(())
    }

    /// Field `field` of register `register`.
    pub fn field(&self, register: &str, field: &str) -> Result<&Field, RegMapError> {
        self.register(register)?.field(field)
    }

    /// The word address of copy `index` of register `name`.
    pub fn address_of(&self, name: &str, index: u32) -> Result<u32, RegMapError> {
        self.register(name)?.address_of(index)
    }

    /// The register named `name`.
    pub fn register(&self, name: &str) -> Result<&Register, RegMapError> {
        self.registers
            .iter()
            .find(|r| r.name == name)
            .ok_or_else(|| RegMapError::NoSuchRegister(name.to_string()))
    }
}
