//! Key input straight from the terminal device: poll(2) on the terminal, the signal socket
//! and the links' wake socket (terminal input, link events and the tick timer, the poll's
//! timeout, are waited on in this one place), one read, bytes to keys. A terminal that has gone (end of file, EIO, hang-up)
//! ends the input at once instead of being polled in a loop, and a signal wakes the wait.

use super::decode::{Input, InputDecoder};
use crate::link::tasks::wake;
use crate::tui::events::{Event, EventSource};
use crate::tui::signals::Signals;
use crate::tui::terminal;
use rustix::event::{PollFd, PollFlags, Timespec, poll};
use rustix::io::Errno;
use std::collections::VecDeque;
use std::io;
use std::os::fd::{AsFd, BorrowedFd, OwnedFd};
use std::time::Duration;

/// The terminal's input: standard input when it is one, else the controlling terminal.
enum Device {
    Stdin,
    Opened(OwnedFd),
}

impl Device {
    fn open() -> io::Result<Self> {
        if rustix::termios::isatty(std::io::stdin()) {
            return Ok(Device::Stdin);
        }
        use rustix::fs::{Mode, OFlags, open};
        let fd = open(
            "/dev/tty",
            OFlags::RDWR | OFlags::NOCTTY | OFlags::CLOEXEC,
            Mode::empty(),
        )?;
        Ok(Device::Opened(fd))
    }

    fn fd(&self) -> BorrowedFd<'_> {
        match self {
            Device::Stdin => rustix::stdio::stdin(),
            Device::Opened(fd) => fd.as_fd(),
        }
    }
}

/// The console's event source on a real terminal.
pub struct TtyEvents<'s> {
    device: Device,
    signals: &'s Signals,
    decoder: InputDecoder,
    queue: VecDeque<Input>,
    size: Option<(u16, u16)>,
    closed: bool,
}

impl<'s> TtyEvents<'s> {
    pub fn open(signals: &'s Signals) -> io::Result<Self> {
        let device = Device::open()?;
        let size = window_size(device.fd());
        Ok(Self {
            device,
            signals,
            decoder: InputDecoder::default(),
            queue: VecDeque::new(),
            size,
            closed: false,
        })
    }

    /// The first queued key; probe replies are acted on and passed over.
    fn next_queued(&mut self) -> Option<Event> {
        while let Some(input) = self.queue.pop_front() {
            match input {
                Input::Key(key, kind) => return Some(Event::Key(key, kind)),
                Input::KeyboardProtocol => {
                    // Best effort: a terminal that cannot take the flags sends no releases,
                    // and the deadman governs as before.
                    let _ = terminal::request_key_releases();
                }
                Input::DeviceAttributes => {}
            }
        }
        None
    }

    fn resize_event(&mut self) -> Option<Event> {
        let now = window_size(self.device.fd())?;
        if self.size == Some(now) {
            return None;
        }
        self.size = Some(now);
        Some(Event::Resize(now.0, now.1))
    }

    fn close(&mut self) -> io::Result<Option<Event>> {
        self.closed = true;
        terminal::mark_gone();
        Ok(Some(Event::Closed))
    }
}

impl EventSource for TtyEvents<'_> {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        if self.closed {
            return Ok(Some(Event::Closed));
        }
        if let Some(event) = self.next_queued() {
            return Ok(Some(event));
        }
        // A signal that arrived since the loop last looked has left a byte on the wake
        // socket, so the poll below returns at once.
        let timeout = Timespec::try_from(timeout).unwrap_or(Timespec {
            tv_sec: 1,
            tv_nsec: 0,
        });
        let tty = self.device.fd();
        let links = wake::global();
        let mut fds = [
            PollFd::from_borrowed_fd(tty, PollFlags::IN),
            PollFd::from_borrowed_fd(self.signals.wake_fd(), PollFlags::IN),
            PollFd::from_borrowed_fd(links.map_or(tty, |w| w.fd()), PollFlags::IN),
        ];
        match poll(&mut fds[..2 + usize::from(links.is_some())], Some(&timeout)) {
            Ok(_) => {}
            Err(Errno::INTR) => return Ok(None),
            Err(e) => return Err(e.into()),
        }
        let (tty_ready, woken) = (fds[0].revents(), fds[1].revents());
        // A link event: the loop's update takes it from the link at once.
        if let Some(links) = links
            && !fds[2].revents().is_empty()
        {
            links.drain();
        }
        if !woken.is_empty() {
            self.signals.drain();
            if self.signals.take_resized()
                && let Some(event) = self.resize_event()
            {
                return Ok(Some(event));
            }
        }
        if tty_ready.contains(PollFlags::IN) {
            let mut buf = [0u8; 1024];
            match rustix::io::read(self.device.fd(), &mut buf) {
                // End of file: the terminal hung up.
                Ok(0) => return self.close(),
                Ok(n) => self.decoder.feed(&buf[..n], &mut self.queue),
                Err(Errno::INTR | Errno::AGAIN) => {}
                Err(e) => {
                    self.closed = true;
                    terminal::mark_gone();
                    return Err(e.into());
                }
            }
        } else if tty_ready.intersects(PollFlags::HUP | PollFlags::ERR | PollFlags::NVAL) {
            return self.close();
        }
        Ok(self.next_queued())
    }
}

fn window_size(fd: BorrowedFd<'_>) -> Option<(u16, u16)> {
    let size = rustix::termios::tcgetwinsize(fd).ok()?;
    (size.ws_col > 0 && size.ws_row > 0).then_some((size.ws_col, size.ws_row))
}
