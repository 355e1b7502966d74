//! The console's state and behaviour, free of terminal and clock: actions in, commands out.

pub mod action;
pub mod mode;
