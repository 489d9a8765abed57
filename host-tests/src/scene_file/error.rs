//! Errors of scene file loading: one message naming the file, the field and
//! the problem.

use std::fmt;

/// Why a scene file was rejected.
///
/// Displayed on one line as `FILE: FIELD: problem`, followed by
/// ` (line L, column C)` when the position in the TOML text is known. Errors
/// that concern no particular field (a file that cannot be read, a TOML
/// syntax error) are displayed as `FILE: problem` or
/// `FILE: line L, column C: problem`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file as given (a path, or `builtin:NAME` for a built-in
    /// scene).
    pub file: String,
    /// The offending field, e.g. `object[1].material.ks`, if any.
    pub field: Option<String>,
    /// One-based line and column in the TOML text, if known.
    pub position: Option<(usize, usize)>,
    /// What is wrong, on one line.
    pub problem: String,
}

impl SceneError {
    /// An error about `field` of `file`.
    pub fn field(file: &str, field: impl Into<String>, problem: impl Into<String>) -> Self {
        Self {
            file: file.to_owned(),
            field: Some(field.into()),
            position: None,
            problem: one_line(&problem.into()),
        }
    }

    /// An error about `file` as a whole.
    pub fn file(file: &str, problem: impl Into<String>) -> Self {
        Self {
            file: file.to_owned(),
            field: None,
            position: None,
            problem: one_line(&problem.into()),
        }
    }

    /// The same error at a position in the TOML text.
    pub(crate) fn at(mut self, position: Option<(usize, usize)>) -> Self {
        self.position = position;
        self
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file)?;
        match (&self.field, self.position) {
            (Some(field), Some((line, column))) => write!(
                f,
                "{field}: {} (line {line}, column {column})",
                self.problem
            ),
            (Some(field), None) => write!(f, "{field}: {}", self.problem),
            (None, Some((line, column))) => {
                write!(f, "line {line}, column {column}: {}", self.problem)
            }
            (None, None) => f.write_str(&self.problem),
        }
    }
}

impl std::error::Error for SceneError {}

/// Joins the lines of `s` with `; ` so that a message stays on one line.
pub(crate) fn one_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// One-based line and column of byte `offset` in `text` (columns count
/// characters). Offsets past the end or inside a character are clamped.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_forms() {
        let e = SceneError::field(
            "a.toml",
            "object[1].material.ks",
            "must be in [0, 1], got 2",
        );
        assert_eq!(
            e.to_string(),
            "a.toml: object[1].material.ks: must be in [0, 1], got 2"
        );
        let e = e.at(Some((3, 7)));
        assert_eq!(
            e.to_string(),
            "a.toml: object[1].material.ks: must be in [0, 1], got 2 (line 3, column 7)"
        );
        let e = SceneError::file("a.toml", "oops\nsecond line").at(Some((1, 2)));
        assert_eq!(e.to_string(), "a.toml: line 1, column 2: oops; second line");
        assert_eq!(SceneError::file("b", "x").to_string(), "b: x");
    }

    #[test]
    fn positions() {
        let text = "ab\ncdé\nf";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 2), (1, 3));
        assert_eq!(line_column(text, 3), (2, 1));
        // Inside 'é' (bytes 5..7): clamped back to its start.
        assert_eq!(line_column(text, 6), (2, 3));
        assert_eq!(line_column(text, 100), (3, 2));
    }
}
