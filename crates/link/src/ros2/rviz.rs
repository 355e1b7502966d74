//! What navdeck believes, published for RViz: the estimated pose, the map -> odom
//! transform, the plan, the map (latched), the landmarks and route mode's tag graph
//! (latched) in the distribution's Marker layout and MCL's particle cloud.

use super::config::{Distro, Qos, Reliability, Ros2Config};
use super::participant::{Factory, qos_profile};
use super::{msgs, now_stamp, picture};
use crate::{LinkError, Picture};
use navdeck_core::geometry::Pose2;
use navdeck_msgs::tag_graph_markers::tag_graph_markers;
use ros2_client::{Publisher, QosProfile};

/// A MarkerArray publisher in the distribution's Marker layout.
enum MarkerPublisher {
    Humble(Publisher<msgs::MarkerArray<msgs::MarkerHumble>>),
    Jazzy(Publisher<msgs::MarkerArray<msgs::MarkerJazzy>>),
}

impl MarkerPublisher {
    fn open(
        f: &mut Factory<'_>,
        field: &str,
        topic: &str,
        qos: QosProfile,
    ) -> Result<Self, LinkError> {
        let (package, kind) = ("visualization_msgs", "MarkerArray");
        Ok(match f.config.distro {
            Distro::Humble => Self::Humble(f.publisher(field, topic, package, kind, qos)?),
            Distro::Jazzy => Self::Jazzy(f.publisher(field, topic, package, kind, qos)?),
        })
    }

    /// Publishes `markers`, laid out for Jazzy when the robot runs it; a failure is
    /// dropped, as every RViz topic's is.
    fn publish(&self, markers: Vec<msgs::MarkerHumble>) {
        match self {
            Self::Humble(p) => {
                let _ = p.publish(msgs::MarkerArray { markers });
            }
            Self::Jazzy(p) => {
                let markers = markers.into_iter().map(Into::into).collect();
                let _ = p.publish(msgs::MarkerArray { markers });
            }
        }
    }
}

/// The publishers RViz reads.
pub(super) struct RvizPublishers {
    map: Publisher<msgs::OccupancyGrid>,
    plan: Publisher<msgs::Path>,
    landmarks: MarkerPublisher,
    tag_graph: MarkerPublisher,
    pose: Publisher<msgs::PoseWithCovarianceStamped>,
    tf: Publisher<msgs::TfMessage>,
    particles: Publisher<msgs::PoseArray>,
}

impl RvizPublishers {
    /// Sets up every RViz topic: `qos` for the streams, `latched` for the map.
    pub(super) fn open(
        f: &mut Factory<'_>,
        qos: QosProfile,
        latched: QosProfile,
    ) -> Result<Self, LinkError> {
        let c = f.config;
        let map = f.publisher(
            "map_topic",
            &c.map_topic,
            "nav_msgs",
            "OccupancyGrid",
            latched.clone(),
        )?;
        let plan = f.publisher("plan_topic", &c.plan_topic, "nav_msgs", "Path", qos.clone())?;
        let landmarks =
            MarkerPublisher::open(f, "landmarks_topic", &c.landmarks_topic, qos.clone())?;
        // Reliable and transient local, keep-last 1, as Nav2's map_server latches the map:
        // the graph changes seldom, and a display that joins late gets the last one.
        let graph_qos = Qos {
            reliability: Reliability::Reliable,
            depth: 1,
        };
        let tag_graph = MarkerPublisher::open(
            f,
            "tags.graph_topic",
            &c.tags.graph_topic,
            qos_profile(graph_qos, true),
        )?;
        let pose = f.publisher(
            "pose_topic",
            &c.pose_topic,
            "geometry_msgs",
            "PoseWithCovarianceStamped",
            qos.clone(),
        )?;
        let tf = f.publisher(
            "tf",
            "/tf",
            "tf2_msgs",
            "TFMessage",
            qos_profile(
                Qos {
                    depth: 100,
                    ..c.qos
                },
                false,
            ),
        )?;
        // Best effort, as AMCL publishes its cloud (RViz's display must ask for best effort).
        let particles = f.publisher(
            "particle_cloud_topic",
            &c.particle_cloud_topic,
            "geometry_msgs",
            "PoseArray",
            qos_profile(Qos::SENSOR_DATA, false),
        )?;
        Ok(Self {
            map,
            plan,
            landmarks,
            tag_graph,
            pose,
            tf,
            particles,
        })
    }

    /// The pose (and, with odometry, the map -> odom transform) every call; the plan, the
    /// map, the landmarks, the particles and the tag graph when the picture carries them.
    pub(super) fn show(&self, picture: &Picture, odom: Option<Pose2>, config: &Ros2Config) {
        let stamp = now_stamp();
        let frame = config.map_frame.clone();
        let _ = self.pose.publish(picture::pose_with_covariance(
            picture.pose,
            &picture.pose_covariance,
            stamp,
            &frame,
        ));
        if let Some(in_odom) = odom {
            let t = picture::map_to_odom(picture.pose, in_odom);
            let _ = self
                .tf
                .publish(picture::transform(&frame, &config.odom_frame, t, stamp));
        }
        if let Some(particles) = &picture.particles {
            let _ = self
                .particles
                .publish(picture::particle_cloud(particles, stamp, &frame));
        }
        if let Some(path) = &picture.path {
            let _ = self.plan.publish(picture::path(path, stamp, &frame));
        }
        if let Some(grid) = &picture.map {
            let _ = self.map.publish(picture::grid(grid, stamp, &frame));
        }
        if let Some(list) = &picture.landmarks {
            self.landmarks
                .publish(picture::landmarks(list, stamp, &frame));
        }
        if let Some(graph) = &picture.tag_graph {
            self.tag_graph
                .publish(tag_graph_markers(graph, stamp, &frame));
        }
    }
}
