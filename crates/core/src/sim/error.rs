//! Why a world file was refused: always the file, and where toml gives it the line,
//! the field and the offending value.

use std::path::PathBuf;

/// A world file that could not be read, parsed or accepted.
#[derive(Debug, thiserror::Error)]
pub enum WorldError {
    #[error("cannot read world {path}: {}", crate::map::io::io_reason(error))]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    /// Syntax, type or unknown-field errors; toml's message carries line and column.
    #[error("world {path}: {message}")]
    Parse { path: PathBuf, message: String },
    /// A well-formed file whose content breaks a rule (ranges, bounds, duplicates).
    #[error("world {path}{}: field `{field}` = {value}: {reason}", line_note(*.line))]
    Invalid {
        path: PathBuf,
        line: Option<usize>,
        field: String,
        value: String,
        reason: String,
    },
}

impl WorldError {
    /// What is wrong, without the world file's name: for a message that names the file
    /// itself ("cannot use map X as a world: …").
    pub fn reason(&self) -> String {
        match self {
            WorldError::Read { error, .. } => {
                format!("cannot read it: {}", crate::map::io::io_reason(error))
            }
            WorldError::Parse { message, .. } => message.clone(),
            WorldError::Invalid {
                line,
                field,
                value,
                reason,
                ..
            } => crate::map::io::field_reason(*line, field, value, reason),
        }
    }
}

fn line_note(line: Option<usize>) -> String {
    line.map_or_else(String::new, |l| format!(" line {l}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_names_file_line_field_and_value() {
        let e = WorldError::Invalid {
            path: PathBuf::from("maps/x.toml"),
            line: Some(7),
            field: "markers[0].id".into(),
            value: "999".into(),
            reason: "not a marker id".into(),
        };
        assert_eq!(
            e.to_string(),
            "world maps/x.toml line 7: field `markers[0].id` = 999: not a marker id"
        );
    }
}
