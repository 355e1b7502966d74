//! ROSArduinoBridge's line protocol: a command letter and up to two integer arguments ended by
//! CR; one reply line ended by CR LF.

use std::fmt;

/// A request the console makes of the firmware.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Request {
    /// `e`: both encoder counts.
    Encoders,
    /// `m L R`: closed-loop wheel targets in encoder ticks per PID frame; `m 0 0` stops.
    Motors(i32, i32),
    /// `o L R`: raw PWM, -255..=255, open loop (forks that have it).
    RawPwm(i32, i32),
    /// `r`: zero the encoders.
    ResetEncoders,
    /// `u Kp:Kd:Ki:Ko`: PID gains.
    Gains([i32; 4]),
    /// `s IDX DEG`: move a servo.
    Servo(u8, u16),
    /// `t IDX`: a servo's angle.
    ServoAngle(u8),
    /// `b`: the firmware's baud rate.
    Baud,
}

/// The shape of reply a request is answered with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expect {
    Counts,
    Ok,
    Number,
}

impl Request {
    /// The bytes on the wire, CR included.
    pub fn line(&self) -> String {
        format!("{self}\r")
    }

    pub fn expects(&self) -> Expect {
        match self {
            Request::Encoders => Expect::Counts,
            Request::ServoAngle(_) | Request::Baud => Expect::Number,
            _ => Expect::Ok,
        }
    }
}

impl fmt::Display for Request {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Request::Encoders => write!(f, "e"),
            Request::Motors(l, r) => write!(f, "m {l} {r}"),
            Request::RawPwm(l, r) => write!(f, "o {l} {r}"),
            Request::ResetEncoders => write!(f, "r"),
            Request::Gains([p, d, i, o]) => write!(f, "u {p}:{d}:{i}:{o}"),
            Request::Servo(i, deg) => write!(f, "s {i} {deg}"),
            Request::ServoAngle(i) => write!(f, "t {i}"),
            Request::Baud => write!(f, "b"),
        }
    }
}

/// A well-formed reply line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reply {
    Ok,
    /// Left and right encoder counts: the firmware's `long`s.
    Counts(i32, i32),
    Number(i64),
    /// `Invalid Command`: the firmware did not know the request.
    Invalid,
}

impl Reply {
    /// Whether this reply is the kind `expect` asks for.
    pub fn answers(&self, expect: Expect) -> bool {
        matches!(
            (self, expect),
            (Reply::Ok, Expect::Ok)
                | (Reply::Counts(..), Expect::Counts)
                | (Reply::Number(_), Expect::Number)
        )
    }
}

/// Reads one reply line (without its line end); `None` for anything the firmware never sends.
pub fn parse_reply(line: &[u8]) -> Option<Reply> {
    let text = std::str::from_utf8(line).ok()?.trim_end_matches('\r');
    if !text.bytes().all(|b| b.is_ascii_graphic() || b == b' ') {
        return None;
    }
    match text {
        "OK" => return Some(Reply::Ok),
        "Invalid Command" => return Some(Reply::Invalid),
        _ => {}
    }
    let fields: Vec<&str> = text.split(' ').collect();
    match fields.as_slice() {
        [n] => integer(n).map(Reply::Number),
        [l, r] => {
            let l = i32::try_from(integer(l)?).ok()?;
            let r = i32::try_from(integer(r)?).ok()?;
            Some(Reply::Counts(l, r))
        }
        _ => None,
    }
}

/// A decimal integer as Arduino's `Serial.print` writes one: optional minus, digits only.
fn integer(s: &str) -> Option<i64> {
    let digits = s.strip_prefix('-').unwrap_or(s);
    if digits.is_empty() || digits.len() > 18 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_letters_and_integers_ended_by_cr() {
        assert_eq!(Request::Encoders.line(), "e\r");
        assert_eq!(Request::Motors(12, -3).line(), "m 12 -3\r");
        assert_eq!(Request::Gains([20, 12, 0, 50]).line(), "u 20:12:0:50\r");
        assert_eq!(Request::Servo(1, 90).line(), "s 1 90\r");
        assert_eq!(Request::ServoAngle(1).line(), "t 1\r");
        assert_eq!(Request::Motors(0, 0).expects(), Expect::Ok);
        assert_eq!(Request::Baud.expects(), Expect::Number);
    }

    #[test]
    fn replies_parse_and_garbage_does_not() {
        assert_eq!(parse_reply(b"OK"), Some(Reply::Ok));
        assert_eq!(parse_reply(b"-12 40013\r"), Some(Reply::Counts(-12, 40013)));
        assert_eq!(parse_reply(b"57600"), Some(Reply::Number(57600)));
        assert_eq!(parse_reply(b"Invalid Command"), Some(Reply::Invalid));
        for bad in [
            &b""[..],
            b"O",
            b"12 x",
            b"1 2 3",
            b"\xff\x00OK",
            b"12 -",
            b"3000000000 1",
            b"+5",
            b" 5",
        ] {
            assert_eq!(parse_reply(bad), None, "{:?}", String::from_utf8_lossy(bad));
        }
        assert!(Reply::Counts(1, 2).answers(Expect::Counts));
        assert!(!Reply::Ok.answers(Expect::Counts));
    }
}
