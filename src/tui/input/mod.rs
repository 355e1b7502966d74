//! Key input from a real terminal: the device reader and the byte decoder.

pub mod decode;
pub mod tty;

pub use decode::{Input, InputDecoder};
pub use tty::TtyEvents;
