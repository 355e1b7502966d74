//! `[ros2.tags]`: route mode's topics over ROS 2 (seed 003 §1.2.2): the tag camera's
//! image and calibration in, the tag graph and the route out for RViz.

use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TagTopics {
    /// The tag camera's sensor_msgs/Image (mono8, rgb8 or bgr8), or a topic ending in
    /// `/compressed` for sensor_msgs/CompressedImage (seed 003: `/rgb`, 1280x720).
    pub image_topic: String,
    /// Its sensor_msgs/CameraInfo: tags are read once one has come (seed 003: K's fx,
    /// fy, cx and cy; navdeck also takes D when the model is plumb_bob).
    pub camera_info_topic: String,
    /// The tag graph and the route as visualization_msgs/MarkerArray, for RViz.
    pub graph_topic: String,
}

impl Default for TagTopics {
    fn default() -> Self {
        Self {
            image_topic: "rgb".into(),
            camera_info_topic: "camera_info".into(),
            graph_topic: "navdeck/tag_graph".into(),
        }
    }
}
