//! rcl_interfaces: a line of a node's log.

use super::Time;
use serde::{Deserialize, Serialize};

/// rcl_interfaces/Log: a line on /rosout (severities in `rosout.rs`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Log {
    pub stamp: Time,
    pub level: u8,
    pub name: String,
    pub msg: String,
    pub file: String,
    pub function: String,
    pub line: u32,
}
