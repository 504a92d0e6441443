//! RS-274/NGC's values as LinuxCNC reads them: numbers, parameters
//! (`#12`, `#[1+2]`, `##3`, `#<name>`), `[expressions]` and functions,
//! parsed from a line and evaluated when the block runs.
//!
//! Binary operators, from the tightest: `**`; `*`, `/`, `MOD`; `+`, `-`;
//! `EQ`, `NE`, `GT`, `GE`, `LT`, `LE`; `AND`, `OR`, `XOR`; left to right
//! within a level (LinuxCNC's precedence). EQ and NE compare within 1e-6;
//! comparisons and logic give 1 or 0, and a non-zero operand is true. MOD's
//! result has the divisor's sign... as LinuxCNC's: `a - b * floor(a / b)`.
//! Functions: `ABS ACOS ASIN COS EXP FIX FUP ROUND LN SIN SQRT TAN`
//! (angles in degrees), `ATAN[y]/[x]`, `EXISTS[#<name>]`. Names are read
//! in either case, spaces inside them ignored.

/// An unevaluated value.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A number as written.
    Number(f64),
    /// A parameter's value.
    Param(Box<Param>),
    /// `-x` (unary plus is dropped).
    Negate(Box<Expr>),
    /// A one-argument function.
    Function(Function, Box<Expr>),
    /// `ATAN[y]/[x]`, in degrees.
    Atan(Box<Expr>, Box<Expr>),
    /// `EXISTS[#<name>]`: 1 when the named parameter is set.
    Exists(String),
    /// A binary operation.
    Binary(Op, Box<Expr>, Box<Expr>),
}

/// A parameter reference.
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    /// `#n`, `#[expr]`, `##n`: the number is itself a value.
    Numbered(Expr),
    /// `#<name>`, lower case, without spaces.
    Named(String),
}

/// One-argument functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum Function {
    Abs,
    Acos,
    Asin,
    Cos,
    Exp,
    Fix,
    Fup,
    Round,
    Ln,
    Sin,
    Sqrt,
    Tan,
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum Op {
    Power,
    Times,
    Divide,
    Modulo,
    Plus,
    Minus,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

impl Op {
    /// Tighter binds first: 5 for `**` down to 1 for the logic.
    fn precedence(self) -> u8 {
        match self {
            Op::Power => 5,
            Op::Times | Op::Divide | Op::Modulo => 4,
            Op::Plus | Op::Minus => 3,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 2,
            Op::And | Op::Or | Op::Xor => 1,
        }
    }
}

/// The words of the operators and functions, as LinuxCNC spells them.
const OPS: &[(&str, Op)] = &[
    ("**", Op::Power),
    ("*", Op::Times),
    ("/", Op::Divide),
    ("MOD", Op::Modulo),
    ("+", Op::Plus),
    ("-", Op::Minus),
    ("EQ", Op::Eq),
    ("NE", Op::Ne),
    ("GT", Op::Gt),
    ("GE", Op::Ge),
    ("LT", Op::Lt),
    ("LE", Op::Le),
    ("AND", Op::And),
    ("OR", Op::Or),
    ("XOR", Op::Xor),
];

const FUNCTIONS: &[(&str, Function)] = &[
    ("ABS", Function::Abs),
    ("ACOS", Function::Acos),
    ("ASIN", Function::Asin),
    ("COS", Function::Cos),
    ("EXP", Function::Exp),
    ("FIX", Function::Fix),
    ("FUP", Function::Fup),
    ("ROUND", Function::Round),
    ("LN", Function::Ln),
    ("SIN", Function::Sin),
    ("SQRT", Function::Sqrt),
    ("TAN", Function::Tan),
];

/// A cursor over a line's bytes; spaces are skipped everywhere, as
/// RS-274/NGC allows.
pub(super) struct Cursor<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) at: usize,
}

impl Cursor<'_> {
    fn skip_spaces(&mut self) {
        while self
            .bytes
            .get(self.at)
            .is_some_and(|b| b.is_ascii_whitespace())
        {
            self.at += 1;
        }
    }

    pub(super) fn peek(&mut self) -> Option<u8> {
        self.skip_spaces();
        self.bytes.get(self.at).copied()
    }

    fn eat(&mut self, byte: u8) -> bool {
        if self.peek() == Some(byte) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    /// Whether the letters of `word` come next (either case, spaces
    /// between them allowed); consumes them if so.
    fn eat_word(&mut self, word: &str) -> bool {
        let start = self.at;
        for expected in word.bytes() {
            match self.peek() {
                Some(b) if b.to_ascii_uppercase() == expected => self.at += 1,
                _ => {
                    self.at = start;
                    return false;
                }
            }
        }
        true
    }

    /// A plain number: a sign, digits and points (spaces between removed).
    pub(super) fn number_text(&mut self) -> String {
        let mut number = String::new();
        loop {
            match self.peek() {
                Some(b) if (b == b'+' || b == b'-') && number.is_empty() => number.push(b as char),
                Some(b) if b.is_ascii_digit() || b == b'.' => number.push(b as char),
                _ => return number,
            }
            self.at += 1;
        }
    }

    /// A parameter after its `#`.
    pub(super) fn param(&mut self) -> Result<Param, String> {
        if self.eat(b'<') {
            let mut name = String::new();
            loop {
                match self.bytes.get(self.at) {
                    Some(b'>') => {
                        self.at += 1;
                        break;
                    }
                    Some(b) if b.is_ascii_whitespace() => self.at += 1,
                    Some(&b) => {
                        name.push(b.to_ascii_lowercase() as char);
                        self.at += 1;
                    }
                    None => return Err(format!("parameter name `#<{name}` has no closing `>`")),
                }
            }
            if name.is_empty() {
                return Err("parameter name `#<>` is empty".into());
            }
            return Ok(Param::Named(name));
        }
        Ok(Param::Numbered(self.value()?))
    }

    /// A value: a number, a parameter, `[expression]` or a function, with
    /// an optional sign.
    pub(super) fn value(&mut self) -> Result<Expr, String> {
        match self.peek() {
            Some(b'-') => {
                self.at += 1;
                Ok(Expr::Negate(Box::new(self.value()?)))
            }
            Some(b'+') => {
                self.at += 1;
                self.value()
            }
            Some(b'[') => {
                self.at += 1;
                let e = self.expression()?;
                if !self.eat(b']') {
                    return Err("`[` is not closed by `]`".into());
                }
                Ok(e)
            }
            Some(b'#') => {
                self.at += 1;
                Ok(Expr::Param(Box::new(self.param()?)))
            }
            Some(b) if b.is_ascii_digit() || b == b'.' => {
                let text = self.number_text();
                let digits = text.matches(|c: char| c.is_ascii_digit()).count();
                text.parse()
                    .ok()
                    .filter(|_| digits > 0)
                    .map(Expr::Number)
                    .ok_or_else(|| format!("`{text}` is not a number"))
            }
            Some(b) if b.is_ascii_alphabetic() => self.function(),
            Some(b) => Err(format!("`{}` cannot start a value", b as char)),
            None => Err("a value is missing at the end of the line".into()),
        }
    }

    fn function(&mut self) -> Result<Expr, String> {
        if self.eat_word("ATAN") {
            let y = self.bracketed("ATAN")?;
            if !self.eat(b'/') {
                return Err("ATAN needs `/[x]` after `[y]`".into());
            }
            let x = self.bracketed("ATAN")?;
            return Ok(Expr::Atan(Box::new(y), Box::new(x)));
        }
        if self.eat_word("EXISTS") {
            let start = self.at;
            if !(self.eat(b'[') && self.eat(b'#')) {
                self.at = start;
                return Err("EXISTS needs `[#<name>]`".into());
            }
            let Param::Named(name) = self.param()? else {
                return Err("EXISTS takes a named parameter, `[#<name>]`".into());
            };
            if !self.eat(b']') {
                return Err("EXISTS needs `[#<name>]`".into());
            }
            return Ok(Expr::Exists(name));
        }
        for &(word, f) in FUNCTIONS {
            // ASIN before SIN, ACOS before COS: the table lists them first.
            if self.eat_word(word) {
                return Ok(Expr::Function(f, Box::new(self.bracketed(word)?)));
            }
        }
        let rest: String = self.bytes[self.at..]
            .iter()
            .take_while(|b| b.is_ascii_alphabetic())
            .map(|&b| b.to_ascii_uppercase() as char)
            .collect();
        Err(format!("`{rest}` is not a function"))
    }

    fn bracketed(&mut self, function: &str) -> Result<Expr, String> {
        if !self.eat(b'[') {
            return Err(format!("{function} needs its argument in `[ ]`"));
        }
        let e = self.expression()?;
        if !self.eat(b']') {
            return Err(format!("{function}'s `[` is not closed by `]`"));
        }
        Ok(e)
    }

    fn operator(&mut self) -> Option<Op> {
        OPS.iter()
            .find(|(word, _)| self.eat_word(word))
            .map(|&(_, op)| op)
    }

    /// Values and operators up to the closing `]`, by precedence.
    fn expression(&mut self) -> Result<Expr, String> {
        let mut values = vec![self.value()?];
        let mut ops: Vec<Op> = Vec::new();
        while self.peek() != Some(b']') {
            let op = self.operator().ok_or_else(|| match self.peek() {
                Some(b) => format!("`{}` is not an operator", b as char),
                None => "`[` is not closed by `]`".to_string(),
            })?;
            while ops
                .last()
                .is_some_and(|top| top.precedence() >= op.precedence())
            {
                reduce(&mut values, &mut ops);
            }
            ops.push(op);
            values.push(self.value()?);
        }
        while !ops.is_empty() {
            reduce(&mut values, &mut ops);
        }
        Ok(values.pop().unwrap_or(Expr::Number(0.0)))
    }
}

fn reduce(values: &mut Vec<Expr>, ops: &mut Vec<Op>) {
    if let (Some(op), Some(right), Some(left)) = (ops.pop(), values.pop(), values.pop()) {
        values.push(Expr::Binary(op, Box::new(left), Box::new(right)));
    }
}

/// What an expression reads its parameters from.
pub trait Parameters {
    /// Parameter `n`'s value; an error for a number out of range.
    fn numbered(&self, n: f64) -> Result<f64, String>;
    /// A named parameter's value, `None` when unset.
    fn named(&self, name: &str) -> Option<f64>;
}

impl Expr {
    /// The value, reading parameters from `params`.
    pub fn evaluate(&self, params: &dyn Parameters) -> Result<f64, String> {
        let v = match self {
            Expr::Number(v) => *v,
            Expr::Param(p) => match p.as_ref() {
                Param::Numbered(n) => params.numbered(n.evaluate(params)?)?,
                Param::Named(name) => params.named(name).ok_or_else(|| {
                    format!(
                        "#<{name}> is not set (LinuxCNC: Named parameter #<{name}> not defined)"
                    )
                })?,
            },
            Expr::Negate(e) => -e.evaluate(params)?,
            Expr::Exists(name) => f64::from(u8::from(params.named(name).is_some())),
            Expr::Atan(y, x) => y.evaluate(params)?.atan2(x.evaluate(params)?).to_degrees(),
            Expr::Function(f, e) => {
                let x = e.evaluate(params)?;
                match f {
                    Function::Abs => x.abs(),
                    Function::Acos | Function::Asin if !(-1.0..=1.0).contains(&x) => {
                        return Err(format!(
                            "{}[{x}]: the argument must be from -1 to 1 (LinuxCNC: Argument to {} out of range)",
                            if *f == Function::Acos { "ACOS" } else { "ASIN" },
                            if *f == Function::Acos { "acos" } else { "asin" }
                        ))
                    }
                    Function::Acos => x.acos().to_degrees(),
                    Function::Asin => x.asin().to_degrees(),
                    Function::Cos => x.to_radians().cos(),
                    Function::Exp => x.exp(),
                    Function::Fix => x.floor(),
                    Function::Fup => x.ceil(),
                    Function::Round => x.round(),
                    Function::Ln if x <= 0.0 => {
                        return Err(format!(
                            "LN[{x}]: the argument must be above 0 (LinuxCNC: Zero or negative argument to ln)"
                        ))
                    }
                    Function::Ln => x.ln(),
                    Function::Sin => x.to_radians().sin(),
                    Function::Sqrt if x < 0.0 => {
                        return Err(format!(
                            "SQRT[{x}]: the argument must be 0 or more (LinuxCNC: Negative argument to sqrt)"
                        ))
                    }
                    Function::Sqrt => x.sqrt(),
                    Function::Tan => x.to_radians().tan(),
                }
            }
            Expr::Binary(op, a, b) => {
                let (a, b) = (a.evaluate(params)?, b.evaluate(params)?);
                let truth = |t: bool| f64::from(u8::from(t));
                match op {
                    Op::Power => a.powf(b),
                    Op::Times => a * b,
                    Op::Divide if b == 0.0 => {
                        return Err("division by zero (LinuxCNC: Attempt to divide by zero)".into())
                    }
                    Op::Divide => a / b,
                    Op::Modulo if b == 0.0 => {
                        return Err("MOD by zero (LinuxCNC: Attempt to divide by zero)".into())
                    }
                    Op::Modulo => a - b * (a / b).floor(),
                    Op::Plus => a + b,
                    Op::Minus => a - b,
                    Op::Eq => truth((a - b).abs() < 1e-6),
                    Op::Ne => truth((a - b).abs() >= 1e-6),
                    Op::Gt => truth(a > b),
                    Op::Ge => truth(a >= b),
                    Op::Lt => truth(a < b),
                    Op::Le => truth(a <= b),
                    Op::And => truth(a != 0.0 && b != 0.0),
                    Op::Or => truth(a != 0.0 || b != 0.0),
                    Op::Xor => truth((a != 0.0) != (b != 0.0)),
                }
            }
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(format!("the value is not a finite number ({v})"))
        }
    }
}
