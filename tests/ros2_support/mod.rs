//! A fake TurtleBot3 on ROS 2 for the link tests: it subscribes to cmd_vel (Twist or
//! TwistStamped), integrates a unicycle, and publishes odometry, wheel joints and a scan
//! of a 4 m square room, on its own DDS participant in this process (loopback only).
//! It also listens to what navdeck shows RViz.

use navdeck::msgs::ros as msgs;
use ros2_client::{
    Context, MessageTypeName, Name, NodeName, NodeOptions, QosProfile, Subscription,
    qos::{Durability, History, WhenFull},
};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The fake robot's wheel radius and track (TurtleBot3 Burger), metres.
pub const WHEEL_RADIUS: f64 = 0.033;
pub const TRACK: f64 = 0.160;

#[derive(Clone, Debug)]
pub struct FakeOptions {
    pub domain: u16,
    /// Listen for TwistStamped (Jazzy) instead of Twist (Humble).
    pub stamped: bool,
    pub joints: bool,
    /// Every n-th odometry message carries NaN.
    pub bad_odom_every: Option<u64>,
    /// Joins the domain on 127.0.0.1 only, as a navdeck process with
    /// `[ros2] interfaces = ["127.0.0.1"]` does.
    pub loopback: bool,
    /// While set, no odometry goes out: a test keeps a clone to silence the robot and
    /// bring it back.
    pub odom_paused: Arc<AtomicBool>,
}

impl FakeOptions {
    pub fn new(domain: u16) -> Self {
        Self {
            domain,
            stamped: false,
            joints: true,
            bad_odom_every: None,
            loopback: false,
            odom_paused: Arc::new(AtomicBool::new(false)),
        }
    }
}

/// What the fake robot received and where it is.
#[derive(Clone, Debug, Default)]
pub struct Seen {
    /// (when, linear x, angular z) of every cmd_vel received.
    pub cmd_vel: Vec<(Instant, f64, f64)>,
    pub pose: (f64, f64, f64),
    pub gripper: Vec<f64>,
    pub maps: Vec<(u32, u32, f32)>,
    pub paths: Vec<usize>,
    pub poses: Vec<(f64, f64)>,
    pub transforms: Vec<(String, String)>,
    pub landmark_arrays: Vec<Vec<(String, i32, usize)>>,
    pub odom_sent: u64,
}

pub struct FakeRobot {
    pub seen: Arc<Mutex<Seen>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Drop for FakeRobot {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn qos(durable: bool, best_effort: bool) -> QosProfile {
    let q = QosProfile::publisher_default()
        .history(History::KeepLast { depth: 10 })
        .durability(if durable {
            Durability::TransientLocal
        } else {
            Durability::Volatile
        });
    if best_effort {
        q.reliability_best_effort()
    } else {
        q.reliability_reliable(WhenFull::DEFAULT)
    }
}

/// A context on `domain`: on 127.0.0.1 alone when `loopback`, else on the interface
/// NAVDECK_TEST_IFACES names, else on all.
pub fn context(domain: u16, loopback: bool) -> Context {
    let mut b = ros2_client::dds::rustdds::DomainParticipantBuilder::new(domain);
    let only = if loopback {
        Some("127.0.0.1".to_string())
    } else {
        std::env::var("NAVDECK_TEST_IFACES").ok()
    };
    if let Some(ip) = only {
        b = b.with_only_networks([ip.parse::<std::net::IpAddr>().unwrap()]);
    }
    let participant = b.build().expect("DDS participant");
    Context::from_domain_participant(participant).expect("context")
}

/// Distance from (x, y) along `angle` to the walls of the square |x|, |y| <= 2.
fn ray_to_walls(x: f64, y: f64, angle: f64) -> f64 {
    let (dx, dy) = (angle.cos(), angle.sin());
    let mut best = f64::INFINITY;
    for (d, p) in [(dx, x), (dy, y)] {
        if d.abs() > 1e-9 {
            let wall = if d > 0.0 { 2.0 } else { -2.0 };
            best = best.min((wall - p) / d);
        }
    }
    best
}

impl FakeRobot {
    pub fn start(options: FakeOptions) -> FakeRobot {
        let seen = Arc::new(Mutex::new(Seen::default()));
        let stop = Arc::new(AtomicBool::new(false));
        let (s, st) = (seen.clone(), stop.clone());
        let thread = std::thread::spawn(move || run(options, s, st));
        FakeRobot {
            seen,
            stop,
            thread: Some(thread),
        }
    }

    pub fn seen(&self) -> Seen {
        self.seen.lock().unwrap().clone()
    }
}

fn drain<M: serde::de::DeserializeOwned + 'static>(sub: &Subscription<M>, mut each: impl FnMut(M)) {
    while let Ok(Some((m, _))) = sub.take() {
        each(m);
    }
}

fn run(options: FakeOptions, seen: Arc<Mutex<Seen>>, stop: Arc<AtomicBool>) {
    let context = context(options.domain, options.loopback);
    let mut node = context
        .new_node(
            NodeName::new("/", "fake_turtlebot").unwrap(),
            NodeOptions::new().enable_rosout(false),
        )
        .unwrap();
    let reliable = qos(false, false);
    // `path` is a topic's full name, e.g. "/gripper/position".
    let topic =
        |node: &mut ros2_client::Node, path: &str, pkg: &str, kind: &str, q: &QosProfile| {
            node.create_topic(
                &Name::parse(path).unwrap(),
                MessageTypeName::new(pkg, kind),
                q,
            )
            .unwrap()
        };
    let t = topic(&mut node, "/odom", "nav_msgs", "Odometry", &reliable);
    let odom_pub = node.create_publisher::<msgs::Odometry>(&t, None).unwrap();
    let t = topic(
        &mut node,
        "/joint_states",
        "sensor_msgs",
        "JointState",
        &reliable,
    );
    let joints_pub = node.create_publisher::<msgs::JointState>(&t, None).unwrap();
    let sensor = qos(false, true);
    let t = topic(&mut node, "/scan", "sensor_msgs", "LaserScan", &sensor);
    let scan_pub = node
        .create_publisher::<msgs::LaserScan>(&t, Some(sensor.clone()))
        .unwrap();
    let twist_sub = (!options.stamped).then(|| {
        let t = topic(&mut node, "/cmd_vel", "geometry_msgs", "Twist", &reliable);
        node.create_subscription::<msgs::Twist>(&t, None).unwrap()
    });
    let stamped_sub = options.stamped.then(|| {
        let t = topic(
            &mut node,
            "/cmd_vel",
            "geometry_msgs",
            "TwistStamped",
            &reliable,
        );
        node.create_subscription::<msgs::TwistStamped>(&t, None)
            .unwrap()
    });
    let gt = topic(
        &mut node,
        "/gripper/position",
        "std_msgs",
        "Float64",
        &reliable,
    );
    let gripper_sub = node
        .create_subscription::<msgs::Float64>(&gt, None)
        .unwrap();
    let durable = qos(true, false);
    let t = topic(&mut node, "/map", "nav_msgs", "OccupancyGrid", &durable);
    let map_sub = node
        .create_subscription::<msgs::OccupancyGrid>(&t, Some(durable.clone()))
        .unwrap();
    let t = topic(&mut node, "/plan", "nav_msgs", "Path", &reliable);
    let plan_sub = node.create_subscription::<msgs::Path>(&t, None).unwrap();
    let pt = topic(
        &mut node,
        "/navdeck/pose",
        "geometry_msgs",
        "PoseWithCovarianceStamped",
        &reliable,
    );
    let pose_sub = node
        .create_subscription::<msgs::PoseWithCovarianceStamped>(&pt, None)
        .unwrap();
    let t = topic(&mut node, "/tf", "tf2_msgs", "TFMessage", &reliable);
    let tf_sub = node
        .create_subscription::<msgs::TfMessage>(&t, None)
        .unwrap();
    let t = topic(
        &mut node,
        "/landmarks",
        "visualization_msgs",
        "MarkerArray",
        &reliable,
    );
    let marks_sub = node
        .create_subscription::<msgs::MarkerArray<msgs::MarkerJazzy>>(&t, None)
        .unwrap();

    let (mut x, mut y, mut th) = (0.0f64, 0.0f64, 0.0f64);
    let (mut v, mut w) = (0.0f64, 0.0f64);
    let (mut wl, mut wr) = (0.0f64, 0.0f64);
    let start = Instant::now();
    let mut last = start;
    let mut next_odom = start;
    let mut next_scan = start;
    let mut count = 0u64;
    while !stop.load(Ordering::SeqCst) {
        let now = Instant::now();
        let dt = (now - last).as_secs_f64();
        last = now;
        // Unicycle: the wheels turn by (v ∓ wb/2) dt / r.
        x += v * th.cos() * dt;
        y += v * th.sin() * dt;
        th += w * dt;
        wl += (v - w * TRACK / 2.0) * dt / WHEEL_RADIUS;
        wr += (v + w * TRACK / 2.0) * dt / WHEEL_RADIUS;
        {
            let mut s = seen.lock().unwrap();
            if let Some(sub) = &twist_sub {
                drain(sub, |m: msgs::Twist| {
                    v = m.linear.x;
                    w = m.angular.z;
                    s.cmd_vel.push((Instant::now(), v, w));
                });
            }
            if let Some(sub) = &stamped_sub {
                drain(sub, |m: msgs::TwistStamped| {
                    v = m.twist.linear.x;
                    w = m.twist.angular.z;
                    s.cmd_vel.push((Instant::now(), v, w));
                });
            }
            drain(&gripper_sub, |m: msgs::Float64| s.gripper.push(m.data));
            drain(&map_sub, |m: msgs::OccupancyGrid| {
                s.maps
                    .push((m.info.width, m.info.height, m.info.resolution))
            });
            drain(&plan_sub, |m: msgs::Path| s.paths.push(m.poses.len()));
            drain(&pose_sub, |m: msgs::PoseWithCovarianceStamped| {
                s.poses
                    .push((m.pose.pose.position.x, m.pose.pose.position.y))
            });
            drain(&tf_sub, |m: msgs::TfMessage| {
                for t in m.transforms {
                    s.transforms.push((t.header.frame_id, t.child_frame_id));
                }
            });
            drain(&marks_sub, |m: msgs::MarkerArray<msgs::MarkerJazzy>| {
                s.landmark_arrays.push(
                    m.markers
                        .iter()
                        .map(|k| (k.ns.clone(), k.kind, k.points.len()))
                        .collect(),
                )
            });
            s.pose = (x, y, th);
        }
        if now >= next_odom && !options.odom_paused.load(Ordering::SeqCst) {
            next_odom = now + Duration::from_millis(20);
            count += 1;
            let stamp = msgs::Time::from_seconds(1000.0 + (now - start).as_secs_f64());
            let mut odom = msgs::Odometry {
                header: msgs::Header::new(stamp, "odom"),
                child_frame_id: "base_footprint".into(),
                ..Default::default()
            };
            odom.pose.pose.position.x = x;
            odom.pose.pose.position.y = y;
            odom.pose.pose.orientation = msgs::Quaternion::from_yaw(th);
            if options
                .bad_odom_every
                .is_some_and(|n| count.is_multiple_of(n))
            {
                odom.pose.pose.position.x = f64::NAN;
            }
            let _ = odom_pub.publish(odom);
            if options.joints {
                let _ = joints_pub.publish(msgs::JointState {
                    header: msgs::Header::new(stamp, ""),
                    name: vec!["wheel_left_joint".into(), "wheel_right_joint".into()],
                    position: vec![wl, wr],
                    velocity: vec![],
                    effort: vec![],
                });
            }
            seen.lock().unwrap().odom_sent = count;
        }
        if now >= next_scan {
            next_scan = now + Duration::from_millis(200);
            let n = 360;
            let inc = std::f64::consts::TAU / n as f64;
            let ranges = (0..n)
                .map(|i| ray_to_walls(x, y, th + i as f64 * inc) as f32)
                .map(|r| if r > 3.5 { f32::INFINITY } else { r })
                .collect();
            let _ = scan_pub.publish(msgs::LaserScan {
                header: msgs::Header::new(msgs::Time::default(), "base_scan"),
                angle_min: 0.0,
                angle_max: (std::f64::consts::TAU - inc) as f32,
                angle_increment: inc as f32,
                range_min: 0.12,
                range_max: 3.5,
                ranges,
                ..Default::default()
            });
        }
        // The fake robot's own control period, like a real base's firmware loop.
        std::thread::sleep(Duration::from_millis(2));
    }
}
