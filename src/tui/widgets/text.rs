//! Fitting text to a width: broken between words into lines, or cut with `…`.

/// `text` in lines of at most `width` columns, broken between words; a word longer than
/// a line is broken inside it.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    let mut used = 0;
    for word in text.split_whitespace() {
        let mut word: Vec<char> = word.chars().collect();
        if used > 0 && used + 1 + word.len() > width {
            lines.push(std::mem::take(&mut line));
            used = 0;
        }
        if used > 0 {
            line.push(' ');
            used += 1;
        }
        while used + word.len() > width {
            let rest = word.split_off(width - used);
            line.extend(word);
            lines.push(std::mem::take(&mut line));
            used = 0;
            word = rest;
        }
        used += word.len();
        line.extend(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// `text` wrapped as `wrap` does into at most `rows` lines, the last holding the rest,
/// cut with `…` when it does not fit.
pub fn wrap_rows(text: &str, width: usize, rows: usize) -> Vec<String> {
    let mut lines = wrap(text, width);
    if lines.len() > rows.max(1) {
        let rest = lines.split_off(rows.max(1) - 1).join(" ");
        lines.push(fit(&rest, width.max(1)));
    }
    lines
}

/// `text` as it fits in `room` columns: cut with `…` as its last column when too long.
pub fn fit(text: &str, room: usize) -> String {
    if text.chars().count() <= room {
        return text.to_string();
    }
    let mut out: String = text.chars().take(room.saturating_sub(1)).collect();
    if room > 0 {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_break_between_words_and_inside_a_word_too_long_for_one() {
        assert_eq!(wrap("one two three", 7), vec!["one two", "three"]);
        assert_eq!(wrap("abcdefghij k", 4), vec!["abcd", "efgh", "ij k"]);
        assert_eq!(wrap("", 5), Vec::<String>::new());
        assert_eq!(wrap("héllo wörld", 5), vec!["héllo", "wörld"]);
        for line in wrap("a fairly long line of words to break up", 9) {
            assert!(line.chars().count() <= 9, "{line}");
        }
    }

    #[test]
    fn wrapped_rows_end_with_the_rest_cut_to_fit() {
        assert_eq!(
            wrap_rows("drive blue block 523 into blue gate", 21, 2),
            vec!["drive blue block 523", "into blue gate"]
        );
        assert_eq!(wrap_rows("aa bb cc dd ee", 5, 2), vec!["aa bb", "cc d…"]);
        assert_eq!(wrap_rows("aa", 5, 3), vec!["aa"]);
    }

    #[test]
    fn fit_cuts_with_an_ellipsis() {
        assert_eq!(fit("abcdef", 4), "abc…");
        assert_eq!(fit("abc", 4), "abc");
        assert_eq!(fit("abc", 0), "");
    }
}
