"""RViz and a robot beside navdeck's localisation, on Eclipse Cyclone DDS with ROS 2's
wire types, for navdeck's interop test: it publishes rt/odom (so that navdeck's link is
up), publishes RViz's "2D Pose Estimate" on rt/initialpose when told, and reports every
geometry_msgs/PoseArray navdeck publishes on rt/particlecloud.

Usage: amcl_peer.py DOMAIN
Prints "ready" once its readers and writers exist. Each stdin line
"pose FRAME X Y YAW" (FRAME "-" for an empty frame_id, X "nan" for NaN) is published
once navdeck's reader is matched, then "sent" is printed. Each cloud received is printed
as one JSON line {"cloud": {"frame": ..., "poses": [[x, y, yaw], ...]}}. Runs until
stdin closes (or 60 s).
"""

import json
import math
import select
import sys
import time
from dataclasses import dataclass, field

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import Header, Odometry, Pose, PoseWithCovariance, ros, stamp_now


@dataclass
class PoseWithCovarianceStamped(IdlStruct, typename=ros("geometry_msgs", "PoseWithCovarianceStamped")):
    header: Header = field(default_factory=Header)
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)


@dataclass
class PoseArray(IdlStruct, typename=ros("geometry_msgs", "PoseArray")):
    header: Header = field(default_factory=Header)
    poses: t.sequence[Pose] = field(default_factory=list)


def estimate(frame, x, y, yaw):
    """What RViz's pose tool sends: yaw as a quaternion about z, its default covariance."""
    msg = PoseWithCovarianceStamped(header=Header(stamp=stamp_now(), frame_id=frame))
    msg.pose.pose.position.x = x
    msg.pose.pose.position.y = y
    msg.pose.pose.orientation.z = math.sin(yaw / 2)
    msg.pose.pose.orientation.w = math.cos(yaw / 2)
    cov = [0.0] * 36
    cov[0], cov[7], cov[35] = 0.25, 0.25, (math.pi / 12) ** 2
    msg.pose.covariance = cov
    return msg


def yaw_of(q):
    """tf2::getYaw: atan2(2(xy + wz), w² + x² - y² - z²)."""
    return math.atan2(2 * (q.x * q.y + q.w * q.z), q.w * q.w + q.x * q.x - q.y * q.y - q.z * q.z)


def main():
    domain = int(sys.argv[1])
    # RViz's pose tool and AMCL's subscription: reliable, volatile.
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    # AMCL's particle cloud: sensor-data QoS, best effort.
    best_effort = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(5))
    dp = DomainParticipant(domain)
    odom_writer = DataWriter(dp, Topic(dp, "rt/odom", Odometry), qos=reliable)
    pose_writer = DataWriter(dp, Topic(dp, "rt/initialpose", PoseWithCovarianceStamped), qos=reliable)
    cloud_reader = DataReader(dp, Topic(dp, "rt/particlecloud", PoseArray), qos=best_effort)
    print("ready", flush=True)

    queued = []
    give_up = time.monotonic() + 60.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready:
            line = sys.stdin.readline()
            if not line:
                break
            words = line.split()
            if words and words[0] == "pose":
                frame = "" if words[1] == "-" else words[1]
                queued.append(estimate(frame, *map(float, words[2:5])))
        # A volatile message sent before navdeck's reader matches would be lost.
        while queued and pose_writer.get_publication_matched_status().current_count > 0:
            pose_writer.write(queued.pop(0))
            print("sent", flush=True)
        for cloud in cloud_reader.take(N=10):
            if isinstance(cloud, PoseArray):
                poses = [[p.position.x, p.position.y, yaw_of(p.orientation)] for p in cloud.poses]
                print(json.dumps({"cloud": {"frame": cloud.header.frame_id, "poses": poses}}), flush=True)
        odom_writer.write(Odometry(header=Header(stamp=stamp_now(), frame_id="odom"), child_frame_id="base_footprint"))


if __name__ == "__main__":
    main()
