//! A stand-in ROS 2 node on Eclipse Cyclone DDS (tests/interop/*.py), run with the
//! interop Python: started on a domain, read line by line, told things on its stdin,
//! and gone when its stdin closes.

use std::io::{BufRead, BufReader};
use std::process::{ChildStdin, Command, Stdio};

/// Cyclone on loopback only: no multicast, unicast discovery to 127.0.0.1.
pub const CYCLONE_CONFIG: &str = "<CycloneDDS><Domain Id=\"any\"><General><Interfaces>\
<NetworkInterface name=\"lo\"/></Interfaces><AllowMulticast>false</AllowMulticast>\
</General><Discovery><ParticipantIndex>auto</ParticipantIndex>\
<MaxAutoParticipantIndex>20</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/>\
</Peers></Discovery></Domain></CycloneDDS>";

/// Upper bound on any wait for DDS (discovery on loopback takes well under a second).
pub const PATIENCE: f64 = 20.0;

/// The Python with the PyPI `cyclonedds` package, or None when the test is skipped.
pub fn python() -> Option<String> {
    crate::python_support::python("the Cyclone DDS peer", "cyclonedds")
}

/// A peer script on `domain` whose stdout lines arrive on a channel and which reads lines
/// on its stdin; closing its stdin (on drop) makes it leave.
pub struct LinePeer {
    child: std::process::Child,
    pub stdin: Option<ChildStdin>,
    pub lines: std::sync::mpsc::Receiver<String>,
}

impl LinePeer {
    pub fn start(script: &str, domain: u16) -> Option<LinePeer> {
        Self::start_with(script, domain, &[])
    }

    /// `start` with arguments after the domain.
    pub fn start_with(script: &str, domain: u16, args: &[&str]) -> Option<LinePeer> {
        let python = python()?;
        let path = format!("{}/tests/interop/{script}", env!("CARGO_MANIFEST_DIR"));
        let mut child = Command::new(&python)
            .arg(path)
            .arg(domain.to_string())
            .args(args)
            .env("CYCLONEDDS_URI", CYCLONE_CONFIG)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("start the Cyclone DDS peer");
        let stdin = child.stdin.take();
        let out = BufReader::new(child.stdout.take().unwrap());
        let (tx, lines) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in out.lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let mut peer = LinePeer {
            child,
            stdin,
            lines,
        };
        assert_eq!(peer.next_line("ready"), "ready", "the peer did not start");
        Some(peer)
    }

    /// Closes the peer's stdin, which tells it to write down what it got and leave, and
    /// waits for it: whether it ended well. (Not every test binary sharing this module
    /// asks for it.)
    #[allow(dead_code)]
    pub fn finish(mut self) -> bool {
        drop(self.stdin.take());
        self.child.wait().is_ok_and(|s| s.success())
    }

    /// The peer's next line, waiting at most PATIENCE for `what`.
    pub fn next_line(&mut self, what: &str) -> String {
        self.lines
            .recv_timeout(std::time::Duration::from_secs_f64(PATIENCE))
            .unwrap_or_else(|e| panic!("no {what} from the peer: {e}"))
    }
}

impl Drop for LinePeer {
    fn drop(&mut self) {
        drop(self.stdin.take());
        let _ = self.child.wait();
    }
}
