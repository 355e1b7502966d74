//! Keymaps as data (stub).
