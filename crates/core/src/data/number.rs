//! Numbers in messages, printed short. A value read from a file or the command line may
//! be 1e308, whose plain `{}` is 309 digits: every range message prints its value and
//! bounds with `short` (at most six significant digits, whole numbers as whole numbers,
//! an exponent for the very large and very small) or, where a fixed number of decimals
//! reads better (metres to the millimetre), with `fixed`.

/// Below this magnitude a whole number is printed with all its digits (`18446744073709`):
/// exactly representable in an f64 and still short enough to read.
const WHOLE_LIMIT: f64 = 1e15;
/// `fixed` prints this magnitude and above as `short` does: more digits say nothing more.
const FIXED_LIMIT: f64 = 1e9;
/// The most decimals `distinct` prints: a nanometre in metres, beyond any arm's accuracy.
const MOST_DECIMALS: usize = 12;

/// `v` in a short general form: `1e308`, `0.25`, `-3`, `1.5e-300`, `NaN`, `inf`.
pub fn short(v: f64) -> String {
    significant(v, 6)
}

/// `v` to `digits` significant digits (1 to 17), trailing zeros dropped; plain decimals
/// from 1e-4 up to 1e6, an exponent outside that; a whole number below 1e15 in full.
pub fn significant(v: f64, digits: usize) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.into();
    }
    if v == 0.0 {
        return "0".into();
    }
    if v.fract() == 0.0 && v.abs() < WHOLE_LIMIT {
        return format!("{v:.0}");
    }
    let scientific = format!("{:.*e}", digits.clamp(1, 17) - 1, v);
    let (mantissa, exponent) = scientific.split_once('e').unwrap_or((&scientific, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (-4..6).contains(&exponent) {
        // The rounded value's shortest form: 0.30000 is "0.3".
        let rounded: f64 = scientific.parse().unwrap_or(v);
        return format!("{rounded}");
    }
    let mantissa = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    };
    format!("{mantissa}e{exponent}")
}

/// `v` with `places` decimals (`0.404`), or as `short` when it is not finite or a billion
/// or more; never `-0.000`.
pub fn fixed(v: f64, places: usize) -> String {
    if !(v.is_finite() && v.abs() < FIXED_LIMIT) {
        return short(v);
    }
    let text = format!("{v:.places$}");
    match text.strip_prefix('-') {
        Some(unsigned) if unsigned.chars().all(|c| c == '0' || c == '.') => unsigned.to_string(),
        _ => text,
    }
}

/// `a` and `b` with at least `places` decimals and as many more (up to 12) as it takes to
/// tell them apart: a message that says one is beyond the other never prints them equal.
pub fn distinct(a: f64, b: f64, places: usize) -> (String, String) {
    let mut p = places;
    loop {
        let (x, y) = (fixed(a, p), fixed(b, p));
        if x != y || a == b || p >= MOST_DECIMALS {
            return (x, y);
        }
        p += 1;
    }
}

/// A number written out longer than this many characters in someone else's message (a
/// parser's "invalid type: floating point `1000…0.0`") is rewritten short.
const LONG_NUMBER: usize = 20;

/// `text` with every number written out in more than 20 characters printed `short`:
/// for messages from parsers navdeck does not format itself (TOML's, serde's).
pub fn shorten_long_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        let (before, from) = rest.split_at(start);
        let len = from
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(from.len());
        let (token, after) = from.split_at(len);
        out.push_str(before);
        match token.parse::<f64>() {
            Ok(v) if token.len() > LONG_NUMBER => out.push_str(&short(v)),
            _ => out.push_str(token),
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_numbers_read_as_a_person_writes_them() {
        assert_eq!(short(1e308), "1e308");
        assert_eq!(short(-1e308), "-1e308");
        assert_eq!(short(1e-300), "1e-300");
        assert_eq!(short(0.25), "0.25");
        assert_eq!(short(-3.0), "-3");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(-0.0), "0");
        assert_eq!(short(7200.0), "7200");
        assert_eq!(short(0.1 + 0.2), "0.3");
        assert_eq!(short(std::f64::consts::TAU), "6.28319");
        assert_eq!(short(1.5e20), "1.5e20");
        assert_eq!(short(1234567.5), "1.23457e6");
        assert_eq!(short(0.000123), "0.000123");
        assert_eq!(short(1e-12), "1e-12");
        assert_eq!(short(f64::NAN), "NaN");
        assert_eq!(short(f64::NEG_INFINITY), "-inf");
        assert_eq!(short(4294967295.0), "4294967295");
        assert_eq!(significant(0.40412, 3), "0.404");
    }

    #[test]
    fn fixed_decimals_stay_short_and_never_show_minus_zero() {
        assert_eq!(fixed(0.4041, 3), "0.404");
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-0.0, 1), "0.0");
        assert_eq!(fixed(1e308, 3), "1e308");
        assert_eq!(fixed(f64::INFINITY, 3), "inf");
    }

    #[test]
    fn long_numbers_in_other_messages_are_shortened() {
        let long = format!("floating point `1{}.0`, expected u32", "0".repeat(308));
        assert_eq!(
            shorten_long_numbers(&long),
            "floating point `1e308`, expected u32"
        );
        let line = "line 2, column 25: `-0.5` at 12345";
        assert_eq!(shorten_long_numbers(line), line);
    }

    #[test]
    fn distinct_adds_decimals_until_the_two_differ() {
        assert_eq!(
            distinct(0.4040002, 0.404, 3),
            ("0.4040002".into(), "0.4040000".into())
        );
        assert_eq!(distinct(0.5, 0.404, 3), ("0.500".into(), "0.404".into()));
        assert_eq!(distinct(0.3, 0.3, 3), ("0.300".into(), "0.300".into()));
    }
}
