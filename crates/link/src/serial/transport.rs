//! One request, one reply line, over a byte stream with timeouts: what the firmware's
//! protocol needs from a serial port, with garbage, stray replies and silence counted.

use super::protocol::{Reply, Request, parse_reply};
use std::io::{self, Read, Write};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// A byte stream whose reads give up after a timeout: a serial port, or a test double.
pub trait Port: Read + Write + Send {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()>;
}

impl Port for Box<dyn serialport::SerialPort> {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        self.set_timeout(timeout).map_err(io::Error::from)
    }
}

/// Running totals of what went wrong on the wire, shared with the link's owner.
#[derive(Debug, Default)]
pub struct Counters {
    pub requests: AtomicU64,
    pub retries: AtomicU64,
    pub timeouts: AtomicU64,
    /// Lines that are no reply the firmware sends: noise, partial or merged lines.
    pub garbage: AtomicU64,
    /// Well-formed replies of the wrong kind: late answers to earlier requests.
    pub out_of_turn: AtomicU64,
    /// `Invalid Command` replies.
    pub refused: AtomicU64,
    /// Encoder readings further than the robot could have moved.
    pub jumps: AtomicU64,
    /// Encoder readings used.
    pub readings: AtomicU64,
    pub reconnects: AtomicU64,
}

impl Counters {
    pub fn bump(counter: &AtomicU64) {
        counter.fetch_add(1, Ordering::Relaxed);
    }

    pub fn snapshot(&self) -> SerialStats {
        let get = |c: &AtomicU64| c.load(Ordering::Relaxed);
        SerialStats {
            requests: get(&self.requests),
            retries: get(&self.retries),
            timeouts: get(&self.timeouts),
            garbage: get(&self.garbage),
            out_of_turn: get(&self.out_of_turn),
            refused: get(&self.refused),
            jumps: get(&self.jumps),
            readings: get(&self.readings),
            reconnects: get(&self.reconnects),
        }
    }
}

/// A copy of the counters at one moment.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SerialStats {
    pub requests: u64,
    pub retries: u64,
    pub timeouts: u64,
    pub garbage: u64,
    pub out_of_turn: u64,
    pub refused: u64,
    pub jumps: u64,
    pub readings: u64,
    pub reconnects: u64,
}

impl SerialStats {
    /// The faults only, e.g. `2 retries, 1 timeout, 3 garbage lines`; empty when none.
    pub fn faults(&self) -> String {
        let parts = [
            (self.retries, "retry", "retries"),
            (self.timeouts, "timeout", "timeouts"),
            (self.garbage, "garbage line", "garbage lines"),
            (self.out_of_turn, "reply out of turn", "replies out of turn"),
            (self.refused, "Invalid Command", "Invalid Commands"),
            (
                self.jumps,
                "encoder jump rejected",
                "encoder jumps rejected",
            ),
            (self.reconnects, "reconnect", "reconnects"),
        ];
        parts
            .iter()
            .filter(|(n, _, _)| *n > 0)
            .map(|(n, one, many)| format!("{n} {}", if *n == 1 { one } else { many }))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Why a request got no usable reply.
#[derive(Debug, thiserror::Error)]
pub enum TransactError {
    #[error("no reply to `{0}` after {1} tries")]
    Silent(Request, u32),
    #[error("the firmware answered `Invalid Command` to `{0}`")]
    Refused(Request),
    #[error("port failed: {0}")]
    Io(#[from] io::Error),
}

/// Longest line kept while waiting for its end; the firmware's replies are far shorter.
const MAX_LINE: usize = 64;

/// Requests and replies over one open port.
pub struct Transport<P: Port> {
    port: P,
    pending: Vec<u8>,
    /// Bytes of the line being read were dropped for length: the line is garbage.
    overlong: bool,
}

impl<P: Port> Transport<P> {
    pub fn new(port: P) -> Self {
        Self {
            port,
            pending: Vec::new(),
            overlong: false,
        }
    }

    /// Writes `request` and waits up to `timeout` for its reply, asking again up to
    /// `retries` more times after silence or `Invalid Command`.
    pub fn transact(
        &mut self,
        request: Request,
        timeout: Duration,
        retries: u32,
        counters: &Counters,
    ) -> Result<Reply, TransactError> {
        let mut refused = false;
        for attempt in 0..=retries {
            if attempt > 0 {
                Counters::bump(&counters.retries);
            }
            Counters::bump(&counters.requests);
            self.port.write_all(request.line().as_bytes())?;
            self.port.flush()?;
            match self.await_reply(request, timeout, counters)? {
                Some(Reply::Invalid) => {
                    refused = true;
                    Counters::bump(&counters.refused);
                }
                Some(reply) => return Ok(reply),
                None => {
                    refused = false;
                    Counters::bump(&counters.timeouts);
                }
            }
        }
        if refused {
            Err(TransactError::Refused(request))
        } else {
            Err(TransactError::Silent(request, retries + 1))
        }
    }

    /// Writes `request` without waiting for its reply (a last stop on the way out).
    pub fn send_only(&mut self, request: Request) -> io::Result<()> {
        self.port.write_all(request.line().as_bytes())?;
        self.port.flush()
    }

    /// The reply to `request`, `Some(Invalid)` if refused, or `None` after `timeout`.
    fn await_reply(
        &mut self,
        request: Request,
        timeout: Duration,
        counters: &Counters,
    ) -> io::Result<Option<Reply>> {
        let deadline = Instant::now() + timeout;
        loop {
            while let Some(line) = self.take_line() {
                match parse_reply(&line) {
                    Some(r) if r == Reply::Invalid || r.answers(request.expects()) => {
                        return Ok(Some(r));
                    }
                    Some(_) => Counters::bump(&counters.out_of_turn),
                    None => Counters::bump(&counters.garbage),
                }
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            self.port.set_read_timeout(left)?;
            let mut buf = [0u8; 256];
            match self.port.read(&mut buf) {
                Ok(0) => {
                    return Err(io::Error::new(
                        io::ErrorKind::UnexpectedEof,
                        "the device closed",
                    ));
                }
                Ok(n) => self.pending.extend_from_slice(&buf[..n]),
                Err(e) if e.kind() == io::ErrorKind::TimedOut => {}
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
    }

    /// The next complete line in the buffer, without its CR LF; an overlong one comes out
    /// as garbage.
    fn take_line(&mut self) -> Option<Vec<u8>> {
        match self.pending.iter().position(|&b| b == b'\n') {
            Some(end) => {
                let mut line: Vec<u8> = self.pending.drain(..=end).collect();
                line.pop();
                if line.last() == Some(&b'\r') {
                    line.pop();
                }
                if std::mem::take(&mut self.overlong) {
                    line.insert(0, 0xff);
                }
                Some(line)
            }
            None => {
                if self.pending.len() > MAX_LINE {
                    self.pending.clear();
                    self.overlong = true;
                }
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::VecDeque;

    /// Replies scripted per write: each write releases the next chunk (or nothing).
    struct Script {
        replies: VecDeque<Option<&'static [u8]>>,
        ready: Vec<u8>,
        written: Vec<u8>,
    }

    impl Read for Script {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            if self.ready.is_empty() {
                return Err(io::Error::new(io::ErrorKind::TimedOut, "quiet"));
            }
            let n = buf.len().min(self.ready.len());
            buf[..n].copy_from_slice(&self.ready[..n]);
            self.ready.drain(..n);
            Ok(n)
        }
    }

    impl Write for Script {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            self.written.extend_from_slice(buf);
            if let Some(Some(reply)) = self.replies.pop_front() {
                self.ready.extend_from_slice(reply);
            }
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    impl Port for Script {
        fn set_read_timeout(&mut self, _: Duration) -> io::Result<()> {
            Ok(())
        }
    }

    fn transport(replies: Vec<Option<&'static [u8]>>) -> Transport<Script> {
        Transport::new(Script {
            replies: replies.into(),
            ready: Vec::new(),
            written: Vec::new(),
        })
    }

    const T: Duration = Duration::from_millis(1);

    #[test]
    fn garbage_and_stray_replies_are_counted_and_skipped() {
        let mut t = transport(vec![Some(b"\xfe\x01zz\r\nOK\r\n12 -4\r\n")]);
        let c = Counters::default();
        let reply = t.transact(Request::Encoders, T, 0, &c).unwrap();
        assert_eq!(reply, Reply::Counts(12, -4));
        let s = c.snapshot();
        assert_eq!((s.garbage, s.out_of_turn, s.retries), (1, 1, 0));
        assert_eq!(t.port.written, b"e\r");
    }

    #[test]
    fn silence_is_retried_a_bounded_number_of_times() {
        let mut t = transport(vec![None, Some(b"OK\r\n")]);
        let c = Counters::default();
        assert_eq!(
            t.transact(Request::Motors(3, 3), T, 2, &c).unwrap(),
            Reply::Ok
        );
        assert_eq!((c.snapshot().timeouts, c.snapshot().retries), (1, 1));
        let mut t = transport(vec![None, None, None]);
        let err = t.transact(Request::Encoders, T, 2, &c).unwrap_err();
        assert!(err.to_string().contains("after 3 tries"), "{err}");
    }

    #[test]
    fn invalid_command_is_retried_then_reported() {
        let c = Counters::default();
        let mut t = transport(vec![Some(b"Invalid Command\r\n"), Some(b"OK\r\n")]);
        assert_eq!(
            t.transact(Request::Servo(0, 90), T, 1, &c).unwrap(),
            Reply::Ok
        );
        let mut t = transport(vec![Some(b"Invalid Command\r\n"); 2]);
        let err = t.transact(Request::Servo(0, 90), T, 1, &c).unwrap_err();
        assert!(matches!(err, TransactError::Refused(_)), "{err}");
        assert_eq!(c.snapshot().refused, 3);
    }

    #[test]
    fn a_partial_line_spoils_only_itself() {
        let c = Counters::default();
        let mut t = transport(vec![Some(b"12 3"), Some(b"OK\r\n"), Some(b"OK\r\n")]);
        // "12 3" and the first retry's "OK" merge into one bad line; the next reply is clean.
        assert_eq!(
            t.transact(Request::Motors(1, 1), T, 2, &c).unwrap(),
            Reply::Ok
        );
        let s = c.snapshot();
        assert_eq!((s.garbage, s.timeouts), (1, 2), "{s:?}");
        let mut long = transport(vec![Some(&[b'7'; 200]), Some(b"\r\nOK\r\n")]);
        assert_eq!(
            long.transact(Request::Motors(1, 1), T, 2, &c).unwrap(),
            Reply::Ok
        );
    }
}
