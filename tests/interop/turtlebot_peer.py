"""A stand-in TurtleBot3 on Eclipse Cyclone DDS, speaking ROS 2's wire types, for
navdeck's interop test: it listens on rt/cmd_vel, integrates a unicycle, and publishes
rt/odom and rt/joint_states; it also reads what navdeck shows RViz (rt/map).

Usage: turtlebot_peer.py DOMAIN OUT.json [--stamped]
Prints "ready" once its readers and writers exist, runs until stdin closes (or 60 s),
then writes what it received to OUT.json.
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

WHEEL_RADIUS = 0.033
TRACK = 0.160


def ros(pkg, name):
    return f"{pkg}::msg::dds_::{name}_"


@dataclass
class Time(IdlStruct, typename=ros("builtin_interfaces", "Time")):
    sec: t.int32 = 0
    nanosec: t.uint32 = 0


@dataclass
class Header(IdlStruct, typename=ros("std_msgs", "Header")):
    stamp: Time = field(default_factory=Time)
    frame_id: str = ""


@dataclass
class Vector3(IdlStruct, typename=ros("geometry_msgs", "Vector3")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0


@dataclass
class Point(IdlStruct, typename=ros("geometry_msgs", "Point")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0


@dataclass
class Quaternion(IdlStruct, typename=ros("geometry_msgs", "Quaternion")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0
    w: t.float64 = 1.0


@dataclass
class Pose(IdlStruct, typename=ros("geometry_msgs", "Pose")):
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)


@dataclass
class PoseWithCovariance(IdlStruct, typename=ros("geometry_msgs", "PoseWithCovariance")):
    pose: Pose = field(default_factory=Pose)
    covariance: t.array[t.float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
class Twist(IdlStruct, typename=ros("geometry_msgs", "Twist")):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


@dataclass
class TwistStamped(IdlStruct, typename=ros("geometry_msgs", "TwistStamped")):
    header: Header = field(default_factory=Header)
    twist: Twist = field(default_factory=Twist)


@dataclass
class TwistWithCovariance(IdlStruct, typename=ros("geometry_msgs", "TwistWithCovariance")):
    twist: Twist = field(default_factory=Twist)
    covariance: t.array[t.float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
class Odometry(IdlStruct, typename=ros("nav_msgs", "Odometry")):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = field(default_factory=TwistWithCovariance)


@dataclass
class JointState(IdlStruct, typename=ros("sensor_msgs", "JointState")):
    header: Header = field(default_factory=Header)
    name: t.sequence[str] = field(default_factory=list)
    position: t.sequence[t.float64] = field(default_factory=list)
    velocity: t.sequence[t.float64] = field(default_factory=list)
    effort: t.sequence[t.float64] = field(default_factory=list)


@dataclass
class MapMetaData(IdlStruct, typename=ros("nav_msgs", "MapMetaData")):
    map_load_time: Time = field(default_factory=Time)
    resolution: t.float32 = 0.0
    width: t.uint32 = 0
    height: t.uint32 = 0
    origin: Pose = field(default_factory=Pose)


@dataclass
class OccupancyGrid(IdlStruct, typename=ros("nav_msgs", "OccupancyGrid")):
    header: Header = field(default_factory=Header)
    info: MapMetaData = field(default_factory=MapMetaData)
    data: t.sequence[t.int8] = field(default_factory=list)


def stamp_now():
    now = time.time()
    return Time(sec=int(now), nanosec=int((now % 1.0) * 1e9))


def main():
    domain, out = int(sys.argv[1]), sys.argv[2]
    stamped = "--stamped" in sys.argv[3:]
    # ROS 2's default profile: reliable, volatile, keep-last 10.
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    latched = Qos(
        Policy.Reliability.Reliable(duration(milliseconds=100)),
        Policy.History.KeepLast(1),
        Policy.Durability.TransientLocal,
    )
    dp = DomainParticipant(domain)
    cmd_type = TwistStamped if stamped else Twist
    cmd_reader = DataReader(dp, Topic(dp, "rt/cmd_vel", cmd_type), qos=reliable)
    map_reader = DataReader(dp, Topic(dp, "rt/map", OccupancyGrid), qos=latched)
    odom_writer = DataWriter(dp, Topic(dp, "rt/odom", Odometry), qos=reliable)
    joint_writer = DataWriter(dp, Topic(dp, "rt/joint_states", JointState), qos=reliable)
    print("ready", flush=True)

    x = y = th = 0.0
    v = w = 0.0
    wl = wr = 0.0
    received = []
    maps = []
    last = time.monotonic()
    give_up = last + 60.0
    while time.monotonic() < give_up:
        # Stop when the test closes our stdin.
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready and not sys.stdin.readline():
            break
        now = time.monotonic()
        dt, last = now - last, now
        x += v * math.cos(th) * dt
        y += v * math.sin(th) * dt
        th += w * dt
        wl += (v - w * TRACK / 2) * dt / WHEEL_RADIUS
        wr += (v + w * TRACK / 2) * dt / WHEEL_RADIUS
        for sample in cmd_reader.take(N=100):
            if not isinstance(sample, cmd_type):
                continue  # a writer went away
            body = sample.twist if stamped else sample
            v, w = body.linear.x, body.angular.z
            received.append([v, w])
        for grid in map_reader.take(N=10):
            if isinstance(grid, OccupancyGrid):
                maps.append([grid.info.width, grid.info.height, grid.info.resolution, len(grid.data)])
        header = Header(stamp=stamp_now(), frame_id="odom")
        odom = Odometry(header=header, child_frame_id="base_footprint")
        odom.pose.pose.position.x = x
        odom.pose.pose.position.y = y
        odom.pose.pose.orientation.z = math.sin(th / 2)
        odom.pose.pose.orientation.w = math.cos(th / 2)
        odom_writer.write(odom)
        joint_writer.write(
            JointState(
                header=Header(stamp=stamp_now()),
                name=["wheel_left_joint", "wheel_right_joint"],
                position=[wl, wr],
            )
        )
    with open(out, "w") as f:
        json.dump({"cmd_vel": received, "pose": [x, y, th], "maps": maps}, f)


if __name__ == "__main__":
    main()
