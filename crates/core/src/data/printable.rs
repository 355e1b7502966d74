//! Text from files made safe for a terminal: control characters (an escape sequence could
//! retitle the terminal or move its cursor) are written as visible `\u{..}` escapes, and
//! lines can be cut to a length.

/// `text` with every control character but newline and tab escaped, and, when `max_line`
/// is given, each line cut to that many characters with `…`.
pub fn printable(text: &str, max_line: Option<usize>) -> String {
    let mut out = String::with_capacity(text.len());
    for (k, line) in text.split('\n').enumerate() {
        if k > 0 {
            out.push('\n');
        }
        let mut used = 0;
        for c in line.chars() {
            if max_line.is_some_and(|m| used >= m) {
                out.push('…');
                break;
            }
            if c.is_control() && c != '\t' {
                let escaped = format!("\\u{{{:x}}}", u32::from(c));
                used += escaped.chars().count();
                out.push_str(&escaped);
            } else {
                out.push(c);
                used += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escape_sequences_are_made_visible_and_long_lines_cut() {
        let title = "arena\u{1b}]2;owned\u{7}";
        assert_eq!(printable(title, None), "arena\\u{1b}]2;owned\\u{7}");
        assert_eq!(printable("a\nb\tc\r", None), "a\nb\tc\\u{d}");
        assert_eq!(printable(&"x".repeat(10), Some(4)), "xxxx…");
        assert_eq!(printable("short\nlines", Some(5)), "short\nlines");
    }
}
