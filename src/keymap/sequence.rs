//! Key sequences for `--keys`: `wwwwddd<space><up>q`.
//!
//! A plain character is that key, `<name>` is any key name [`Key`] parses
//! (`<space>`, `<up>`, `<ctrl-c>`, `<gt>` for '>'), and `<<` is a literal '<'.

use super::key::{Key, KeyParseError};

/// Reads a whole sequence, or says which part of it is wrong.
pub fn parse_key_sequence(s: &str) -> Result<Vec<Key>, KeyParseError> {
    let mut keys = Vec::new();
    let mut rest = s;
    while let Some(c) = rest.chars().next() {
        let after = &rest[c.len_utf8()..];
        if c != '<' {
            if c.is_control() {
                return Err(KeyParseError::ControlChar(c));
            }
            keys.push(Key::char(c));
            rest = after;
        } else if let Some(tail) = after.strip_prefix('<') {
            keys.push(Key::char('<'));
            rest = tail;
        } else {
            let Some(end) = after.find('>') else {
                let column = s[..s.len() - rest.len()].chars().count() + 1;
                return Err(KeyParseError::Unterminated { column });
            };
            keys.push(after[..end].parse()?);
            rest = &after[end + 1..];
        }
    }
    Ok(keys)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::keymap::KeyCode;

    #[test]
    fn plain_characters_are_keys_and_case_matters() {
        let keys = parse_key_sequence("wWd,").unwrap();
        assert_eq!(
            keys,
            vec![
                Key::char('w'),
                Key::char('W'),
                Key::char('d'),
                Key::char(',')
            ]
        );
    }

    #[test]
    fn angle_brackets_name_keys() {
        let keys = parse_key_sequence("ww<space><up><ctrl-c>q").unwrap();
        let ctrl_c = Key {
            code: KeyCode::Char('c'),
            ctrl: true,
            alt: false,
        };
        assert_eq!(
            keys,
            vec![
                Key::char('w'),
                Key::char('w'),
                Key::char(' '),
                Key::new(KeyCode::Up),
                ctrl_c,
                Key::char('q'),
            ]
        );
    }

    #[test]
    fn doubled_bracket_is_a_literal_bracket() {
        assert_eq!(
            parse_key_sequence("a<<b>").unwrap(),
            vec![
                Key::char('a'),
                Key::char('<'),
                Key::char('b'),
                Key::char('>')
            ]
        );
    }

    #[test]
    fn an_empty_sequence_is_no_keys() {
        assert_eq!(parse_key_sequence(""), Ok(vec![]));
    }

    #[test]
    fn unknown_names_and_open_brackets_are_refused() {
        assert_eq!(
            parse_key_sequence("w<bogus>"),
            Err(KeyParseError::UnknownName("bogus".into()))
        );
        assert_eq!(parse_key_sequence("<>"), Err(KeyParseError::Empty));
        assert_eq!(
            parse_key_sequence("wé<up"),
            Err(KeyParseError::Unterminated { column: 3 })
        );
        assert_eq!(
            parse_key_sequence("w\n"),
            Err(KeyParseError::ControlChar('\n'))
        );
    }
}
