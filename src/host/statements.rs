//! The line format shared by path files and machine settings files: one
//! statement a line, a keyword and its words, `#` to the end of the line a
//! comment, blank lines skipped. Every error names the file's line.

use super::path::PathError;

/// One statement: its 1-based line, keyword and the words after it.
pub(crate) struct Statement<'a> {
    /// The 1-based line of the file.
    pub line: usize,
    /// The first word.
    pub keyword: &'a str,
    /// The words after the keyword.
    pub words: Vec<&'a str>,
}

/// The statements of `text`, comments and blank lines left out.
pub(crate) fn statements(text: &str) -> impl Iterator<Item = Statement<'_>> {
    text.lines().enumerate().filter_map(|(index, raw)| {
        let mut words = raw.split('#').next().unwrap_or("").split_whitespace();
        let keyword = words.next()?;
        Some(Statement {
            line: index + 1,
            keyword,
            words: words.collect(),
        })
    })
}

/// A statement's words read as numbers.
pub(crate) struct Numbers<'s> {
    statement: &'s Statement<'s>,
    /// The values, in order.
    pub values: Vec<f64>,
}

impl<'a> Statement<'a> {
    /// An error at this statement's line.
    pub fn error(&self, message: String) -> PathError {
        PathError::Syntax {
            line: self.line,
            message,
        }
    }

    /// Every word after the keyword as a finite number.
    pub fn numbers(&self) -> Result<Numbers<'_>, PathError> {
        let values = self
            .words
            .iter()
            .map(|w| {
                w.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| self.error(format!("`{w}` is not a number")))
            })
            .collect::<Result<_, _>>()?;
        Ok(Numbers {
            statement: self,
            values,
        })
    }
}

impl Numbers<'_> {
    /// Exactly `N` numbers, or an error naming the keyword and the count.
    pub fn exactly<const N: usize>(&self) -> Result<[f64; N], PathError> {
        <[f64; N]>::try_from(self.values.as_slice()).map_err(|_| {
            self.statement.error(format!(
                "`{}` takes {N} number(s), found {}",
                self.statement.keyword,
                self.values.len()
            ))
        })
    }
}
