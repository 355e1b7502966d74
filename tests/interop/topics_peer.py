"""A small ROS 2 graph on Eclipse Cyclone DDS, with ROS 2's wire types, for the test of
`navdeck ros2 topics`: one healthy topic and three mismatches that silently break a link.

  /odom      nav_msgs/Odometry, reliable publisher at 20 Hz, no subscriber
  /cmd_vel   a Twist publisher and a TwistStamped subscriber (Humble against Jazzy)
  /scan      sensor_msgs/LaserScan, best-effort publisher, reliable subscriber
  /map       nav_msgs/OccupancyGrid, volatile publisher, transient-local subscriber
  /goal_pose geometry_msgs/PoseStamped, a subscriber alone (no mismatch)

Usage: topics_peer.py DOMAIN
Prints "ready" once its readers and writers exist, runs until stdin closes (or 60 s).
"""

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

ODOM_PERIOD = 0.05


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
class PoseStamped(IdlStruct, typename=ros("geometry_msgs", "PoseStamped")):
    header: Header = field(default_factory=Header)
    pose: Pose = field(default_factory=Pose)


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
class LaserScan(IdlStruct, typename=ros("sensor_msgs", "LaserScan")):
    header: Header = field(default_factory=Header)
    angle_min: t.float32 = 0.0
    angle_max: t.float32 = 0.0
    angle_increment: t.float32 = 0.0
    time_increment: t.float32 = 0.0
    scan_time: t.float32 = 0.0
    range_min: t.float32 = 0.0
    range_max: t.float32 = 0.0
    ranges: t.sequence[t.float32] = field(default_factory=list)
    intensities: t.sequence[t.float32] = field(default_factory=list)


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


def qos(reliable, latched=False):
    policies = [
        Policy.Reliability.Reliable(duration(milliseconds=100))
        if reliable
        else Policy.Reliability.BestEffort,
        Policy.History.KeepLast(10),
        Policy.Durability.TransientLocal if latched else Policy.Durability.Volatile,
    ]
    return Qos(*policies)


def main():
    domain = int(sys.argv[1])
    # Publishers and subscribers in two participants, as two nodes of two processes
    # would be (one participant refuses one topic name with two types).
    talker = DomainParticipant(domain)
    listener = DomainParticipant(domain)
    odom = DataWriter(talker, Topic(talker, "rt/odom", Odometry), qos=qos(True))
    twist = DataWriter(talker, Topic(talker, "rt/cmd_vel", Twist), qos=qos(True))
    stamped = DataReader(listener, Topic(listener, "rt/cmd_vel", TwistStamped), qos=qos(True))
    scan = DataWriter(talker, Topic(talker, "rt/scan", LaserScan), qos=qos(False))
    scan_reader = DataReader(listener, Topic(listener, "rt/scan", LaserScan), qos=qos(True))
    grid = DataWriter(talker, Topic(talker, "rt/map", OccupancyGrid), qos=qos(True))
    grid_reader = DataReader(
        listener, Topic(listener, "rt/map", OccupancyGrid), qos=qos(True, latched=True)
    )
    goal = DataReader(listener, Topic(listener, "rt/goal_pose", PoseStamped), qos=qos(True))
    endpoints = [twist, stamped, scan, scan_reader, grid, grid_reader, goal]
    print("ready", flush=True)

    start = time.monotonic()
    give_up = start + 60.0
    next_odom = start
    while time.monotonic() < give_up:
        # Stop when the test closes our stdin; otherwise wake for the next odometry.
        wait = max(0.0, next_odom - time.monotonic())
        ready, _, _ = select.select([sys.stdin], [], [], wait)
        if ready and not sys.stdin.readline():
            break
        now = time.monotonic()
        if now < next_odom:
            continue
        # On schedule, not after the last send: the rate stays 20 Hz when a tick is late.
        next_odom += ODOM_PERIOD
        if next_odom < now - 1.0:
            next_odom = now + ODOM_PERIOD
        sec = time.time()
        header = Header(stamp=Time(sec=int(sec), nanosec=int((sec % 1.0) * 1e9)), frame_id="odom")
        odom.write(Odometry(header=header, child_frame_id="base_footprint"))
    del endpoints


if __name__ == "__main__":
    main()
