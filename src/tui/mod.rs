//! The terminal face of navdeck: event sources, the main loop, and the widgets.
//! Everything here reads the `App`; only the loop feeds it events.

pub mod deck;
pub mod draw;
pub mod events;
pub mod input;
pub mod run;
pub mod signals;
pub mod terminal;
pub mod theme;
pub mod widgets;
