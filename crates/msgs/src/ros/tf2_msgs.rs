//! tf2_msgs: the transforms on /tf.

use super::TransformStamped;
use serde::{Deserialize, Serialize};

/// tf2_msgs/TFMessage.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TfMessage {
    pub transforms: Vec<TransformStamped>,
}
