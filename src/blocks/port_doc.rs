//! A port's documentation: the one place its meaning is written.
//!
//! Every block's `PORT_DOCS` lists its ports with a width and a meaning.
//! Everything else is generated from it: the datasheet's port table
//! (`src/blocks/<block>/ports.md`, included in the block's rustdoc), the
//! port table in the header of each exported `rtl-out/<module>.v`, and
//! `rtl-out/README.md`. The export checks the list against the RTL: every
//! port documented, no documented port missing, and every width equal to
//! the RTL's for the parameters the datasheet is drawn for.

/// One documented port of a block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PortDoc {
    /// Port name as in Rust and Verilog. An array of signals is documented
    /// once as `name__i`; its element n is the port `name__n`, and "axis i"
    /// in the meaning reads "axis n" in the tables of exported modules.
    pub name: &'static str,
    /// Width in bits: a number, a block parameter (`W`), a sum (`N+1`) or
    /// a product with a number written first (`4K`). The direction is read
    /// from the RTL.
    pub width: &'static str,
    /// What the port means, for a datasheet reader: the one place this is
    /// written.
    pub meaning: &'static str,
}

/// A documented port: `port("strobe", "1", "one-clock pulse, registered")`.
pub const fn port(name: &'static str, width: &'static str, meaning: &'static str) -> PortDoc {
    PortDoc {
        name,
        width,
        meaning,
    }
}

impl PortDoc {
    /// The port `name` of another block's documentation, for a block that
    /// passes that block's port through: the meaning stays written once.
    /// Fails to compile when `docs` has no port `name`.
    pub const fn same_as(docs: &'static [PortDoc], name: &'static str) -> PortDoc {
        let mut i = 0;
        while i < docs.len() {
            if str_eq(docs[i].name, name) {
                return docs[i];
            }
            i += 1;
        }
        panic!("PortDoc::same_as: no such port in that block's PORT_DOCS");
    }

    /// The same port with another width expression (a block that names
    /// the width's parameter differently).
    pub const fn with_width(self, width: &'static str) -> PortDoc {
        PortDoc { width, ..self }
    }

    /// The same port with another meaning (a block that narrows it).
    pub const fn with_meaning(self, meaning: &'static str) -> PortDoc {
        PortDoc { meaning, ..self }
    }
}

const fn str_eq(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// Why a width expression does not evaluate.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("width `{expression}`: {reason}")]
pub struct WidthError {
    /// The expression as written.
    pub expression: String,
    /// What is wrong with it.
    pub reason: String,
}

/// Evaluates a width expression (`32`, `T`, `N+1`, `4K`, `32K`) with the
/// given parameter values.
pub fn eval_width(expression: &str, parameters: &[(&str, usize)]) -> Result<usize, WidthError> {
    let error = |reason: String| WidthError {
        expression: expression.to_string(),
        reason,
    };
    let mut total = 0;
    for term in expression.split('+').map(str::trim) {
        if term.is_empty() {
            return Err(error("an empty term".to_string()));
        }
        let digits = term.len() - term.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        let (factor, name) = term.split_at(digits);
        let factor = if factor.is_empty() {
            1
        } else {
            factor
                .parse::<usize>()
                .map_err(|e| error(format!("`{factor}`: {e}")))?
        };
        let value = if name.is_empty() {
            1
        } else {
            parameters
                .iter()
                .find(|(p, _)| *p == name)
                .map(|(_, v)| *v)
                .ok_or_else(|| error(format!("no value for parameter `{name}`")))?
        };
        total += factor * value;
    }
    if total == 0 {
        return Err(error("a width of 0".to_string()));
    }
    Ok(total)
}
