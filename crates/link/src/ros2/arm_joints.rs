//! The arm's joints on the wire: a target as the one-point JointTrajectory a
//! JointTrajectoryController follows, and the arm's positions found by name in a
//! sensor_msgs/JointState. What makes no sense is refused here with the field and value.

use navdeck_core::data::{ArmState, ArmTarget};
use navdeck_msgs::ros as msgs;

/// Why a joint_states message told nothing of the arm: the kind (counted apart) and the
/// field and value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refused {
    pub kind: &'static str,
    pub detail: String,
}

fn refused(kind: &'static str, detail: String) -> Refused {
    Refused { kind, detail }
}

/// The arm's four joints in `js`, by name, in the order of `names`.
///
/// `Ok(None)` when the message names none of them (another publisher's joints, e.g. the
/// wheels alone); `Err` names the field and value that made it unusable.
pub fn arm_state(js: &msgs::JointState, names: &[String]) -> Result<Option<ArmState>, Refused> {
    let found: Vec<Option<usize>> = names
        .iter()
        .map(|name| js.name.iter().position(|n| n == name))
        .collect();
    if found.iter().all(Option::is_none) {
        return Ok(None);
    }
    if js.name.len() != js.position.len() {
        return Err(refused(
            "arm joints mismatched",
            format!(
                "name has {} entries but position has {}",
                js.name.len(),
                js.position.len()
            ),
        ));
    }
    let mut joints = [0.0; 4];
    for ((slot, at), name) in joints.iter_mut().zip(&found).zip(names) {
        let Some(i) = *at else {
            return Err(refused("arm joint missing", format!("name lacks {name:?}")));
        };
        let value = js.position[i];
        if !value.is_finite() {
            return Err(refused(
                "non-finite arm joint",
                format!("position[{i}] ({name}) = {}", printable(value)),
            ));
        }
        *slot = value;
    }
    Ok(Some(ArmState { joints }))
}

/// `target` as a JointTrajectory with one point: the four positions, reached `within`
/// seconds after the controller receives it (a zero stamp means "start on receipt", so
/// clocks that differ between navdeck and the robot cannot make it start in the past).
pub fn trajectory(target: &ArmTarget, names: &[String]) -> Result<msgs::JointTrajectory, String> {
    for (k, v) in target.joints.iter().enumerate() {
        if !v.is_finite() {
            return Err(format!("joints[{k}] = {}", printable(*v)));
        }
    }
    if !(target.within.is_finite() && target.within >= 0.0) {
        return Err(format!("within = {}", printable(target.within)));
    }
    Ok(msgs::JointTrajectory {
        header: msgs::Header::default(),
        joint_names: names.to_vec(),
        points: vec![msgs::JointTrajectoryPoint {
            positions: target.joints.to_vec(),
            time_from_start: msgs::Duration::from_seconds(target.within),
            ..Default::default()
        }],
    })
}

/// A number as the warning shows it: NaN and infinities by name.
fn printable(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Vec<String> {
        ["joint1", "joint2", "joint3", "joint4"]
            .map(String::from)
            .to_vec()
    }

    fn state(pairs: &[(&str, f64)]) -> msgs::JointState {
        msgs::JointState {
            name: pairs.iter().map(|(n, _)| n.to_string()).collect(),
            position: pairs.iter().map(|(_, p)| *p).collect(),
            ..Default::default()
        }
    }

    #[test]
    fn arm_joints_are_found_by_name_in_any_order_beside_others() {
        let js = state(&[
            ("joint3", 0.3),
            ("wheel_left_joint", 9.0),
            ("joint1", -0.1),
            ("joint4", 0.4),
            ("joint2", 0.2),
        ]);
        assert_eq!(
            arm_state(&js, &names()),
            Ok(Some(ArmState {
                joints: [-0.1, 0.2, 0.3, 0.4]
            }))
        );
        let wheels = state(&[("wheel_left_joint", 1.0), ("wheel_right_joint", 2.0)]);
        assert_eq!(arm_state(&wheels, &names()), Ok(None));
    }

    #[test]
    fn unusable_joint_states_name_the_field_and_value() {
        let nan = state(&[
            ("joint1", 0.0),
            ("joint2", f64::NAN),
            ("joint3", 0.0),
            ("joint4", 0.0),
        ]);
        let detail = |js| arm_state(js, &names()).unwrap_err().detail;
        assert_eq!(detail(&nan), "position[1] (joint2) = NaN");
        let missing = state(&[("joint1", 0.0), ("joint2", 0.0), ("joint4", 0.0)]);
        assert_eq!(detail(&missing), "name lacks \"joint3\"");
        let mut short = state(&[
            ("joint1", 0.0),
            ("joint2", 0.0),
            ("joint3", 0.0),
            ("joint4", 0.0),
        ]);
        short.position.pop();
        assert_eq!(detail(&short), "name has 4 entries but position has 3");
    }

    #[test]
    fn a_target_is_one_point_reached_within_its_seconds() {
        let target = ArmTarget {
            joints: [0.5, -1.0, 0.7, 0.3],
            within: 2.25,
        };
        let t = trajectory(&target, &names()).unwrap();
        assert_eq!(t.joint_names, names());
        assert_eq!(t.header.stamp, msgs::Time::default());
        assert_eq!(t.points.len(), 1);
        assert_eq!(t.points[0].positions, vec![0.5, -1.0, 0.7, 0.3]);
        assert_eq!(
            t.points[0].time_from_start,
            msgs::Duration {
                sec: 2,
                nanosec: 250_000_000
            }
        );
        let bad = ArmTarget {
            within: f64::NAN,
            ..target
        };
        assert_eq!(trajectory(&bad, &names()), Err("within = NaN".into()));
        let bad = ArmTarget {
            joints: [0.0, f64::INFINITY, 0.0, 0.0],
            ..target
        };
        assert_eq!(trajectory(&bad, &names()), Err("joints[1] = inf".into()));
    }
}
