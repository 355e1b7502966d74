//! Entering and leaving the terminal's raw, alternate-screen mode; restoring it always.

use crossterm::event::{
    KeyboardEnhancementFlags, PopKeyboardEnhancementFlags, PushKeyboardEnhancementFlags,
};
use crossterm::style::Print;
use crossterm::terminal::{self, EnterAlternateScreen, LeaveAlternateScreen};
use crossterm::{cursor, execute};
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use std::io::{self, Stdout, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set while the terminal is in raw mode; the panic hook restores only then.
static ACTIVE: AtomicBool = AtomicBool::new(false);
/// Whether the kitty keyboard flags were pushed and must be popped.
static ENHANCED: AtomicBool = AtomicBool::new(false);

/// Owns the raw terminal; dropping it restores the terminal as it was.
pub struct TerminalGuard {
    pub terminal: Terminal<CrosstermBackend<TerminalOut>>,
}

/// Set once a write to the terminal failed: it has gone, and nothing more is written.
static GONE: AtomicBool = AtomicBool::new(false);

/// Standard output until a write fails (the terminal hung up), then a sink: the failure
/// reaches the loop once, and later writes (ratatui showing the cursor as it is dropped,
/// the restore) neither fail again nor wait on a terminal that is not there.
pub struct TerminalOut(Stdout);

impl TerminalOut {
    fn check<T>(result: io::Result<T>) -> io::Result<T> {
        if result.is_err() {
            mark_gone();
        }
        result
    }
}

impl Write for TerminalOut {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if GONE.load(Ordering::SeqCst) {
            return Ok(buf.len());
        }
        Self::check(self.0.write(buf))
    }

    fn flush(&mut self) -> io::Result<()> {
        if GONE.load(Ordering::SeqCst) {
            return Ok(());
        }
        Self::check(self.0.flush())
    }
}

/// Asks whether the terminal speaks the kitty keyboard protocol (`CSI ? u`), then for the
/// primary device attributes (`CSI c`), which every terminal answers. The replies arrive
/// with the keys; nothing waits for them, so a silent terminal delays nothing.
const KEYBOARD_PROBE: &str = "\x1b[?u\x1b[c";

impl TerminalGuard {
    /// Raw mode, alternate screen, hidden cursor, and the keyboard probe.
    pub fn enter() -> io::Result<Self> {
        install_panic_hook();
        terminal::enable_raw_mode()?;
        ACTIVE.store(true, Ordering::SeqCst);
        let mut stdout = io::stdout();
        if let Err(e) = execute!(
            stdout,
            EnterAlternateScreen,
            cursor::Hide,
            Print(KEYBOARD_PROBE)
        ) {
            restore();
            return Err(e);
        }
        let terminal = Terminal::new(CrosstermBackend::new(TerminalOut(stdout)))?;
        Ok(Self { terminal })
    }
}

/// Asks a terminal that answered the probe for key events with press, repeat and release,
/// every key as an escape code (so releases of Enter, Tab and Backspace cannot be taken for
/// presses) and the shifted key beside the base key. Popped again on restore.
pub fn request_key_releases() -> io::Result<()> {
    if !ACTIVE.load(Ordering::SeqCst) || ENHANCED.swap(true, Ordering::SeqCst) {
        return Ok(());
    }
    execute!(
        io::stdout(),
        PushKeyboardEnhancementFlags(
            KeyboardEnhancementFlags::DISAMBIGUATE_ESCAPE_CODES
                | KeyboardEnhancementFlags::REPORT_EVENT_TYPES
                | KeyboardEnhancementFlags::REPORT_ALTERNATE_KEYS
                | KeyboardEnhancementFlags::REPORT_ALL_KEYS_AS_ESCAPE_CODES
        )
    )
}

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        // Shown here, so that a failure marks the terminal gone instead of ratatui
        // reporting it on a standard error that may have gone with the terminal.
        let _ = self.terminal.show_cursor();
        restore();
    }
}

/// The terminal hung up (its input ended or failed): nothing more is written to it.
pub fn mark_gone() {
    GONE.store(true, Ordering::SeqCst);
}

/// Puts the terminal back: keyboard flags, main screen, cursor, cooked mode. Idempotent.
pub fn restore() {
    if !ACTIVE.swap(false, Ordering::SeqCst) {
        return;
    }
    if GONE.load(Ordering::SeqCst) {
        // Nothing to restore on a terminal that hung up; its settings went with it.
        return;
    }
    let mut stdout = io::stdout();
    if ENHANCED.swap(false, Ordering::SeqCst) {
        let _ = execute!(stdout, PopKeyboardEnhancementFlags);
    }
    let _ = execute!(stdout, LeaveAlternateScreen, cursor::Show);
    let _ = terminal::disable_raw_mode();
}

/// On panic, restore the terminal before the message prints, so it stays readable.
/// (The app's `Drop` stops the robot as the panic unwinds.)
fn install_panic_hook() {
    static INSTALLED: AtomicBool = AtomicBool::new(false);
    if INSTALLED.swap(true, Ordering::SeqCst) {
        return;
    }
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        restore();
        previous(info);
    }));
}
