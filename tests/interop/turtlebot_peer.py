"""A stand-in TurtleBot3 on Eclipse Cyclone DDS, speaking ROS 2's wire types, for
navdeck's interop test: it listens on rt/cmd_vel, integrates a unicycle, and publishes
rt/odom and rt/joint_states; it also reads what navdeck shows RViz (rt/map).

With --room it stands in a rectangular room (ROOM, metres in its odometry frame) and
publishes rt/scan as a 360-beam LDS-01 would there; it then also reads rt/tf and checks
the last map navdeck published against the room's walls, seen through map -> odom.

Usage: turtlebot_peer.py DOMAIN OUT.json [--stamped] [--room]
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
# The room's walls: x from ROOM[0] to ROOM[1], y from ROOM[2] to ROOM[3] (not centred
# on the start, so that it has no symmetry a match could slip along).
ROOM = (-1.0, 1.8, -1.2, 0.9)
# The LDS-01's range (TurtleBot3 e-Manual: 120 to 3500 mm), 360 beams, 5 Hz.
RANGE_MIN, RANGE_MAX, BEAMS, SCAN_PERIOD = 0.12, 3.5, 360, 0.2
# A map cell counts as a wall's when it lies this close to one, metres (5 cells of 1 cm).
NEAR_WALL = 0.05


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
class Image(IdlStruct, typename=ros("sensor_msgs", "Image")):
    header: Header = field(default_factory=Header)
    height: t.uint32 = 0
    width: t.uint32 = 0
    encoding: str = ""
    is_bigendian: t.uint8 = 0
    step: t.uint32 = 0
    data: t.sequence[t.uint8] = field(default_factory=list)


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
class Transform(IdlStruct, typename=ros("geometry_msgs", "Transform")):
    translation: Vector3 = field(default_factory=Vector3)
    rotation: Quaternion = field(default_factory=Quaternion)


@dataclass
class TransformStamped(IdlStruct, typename=ros("geometry_msgs", "TransformStamped")):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    transform: Transform = field(default_factory=Transform)


@dataclass
class TFMessage(IdlStruct, typename=ros("tf2_msgs", "TFMessage")):
    transforms: t.sequence[TransformStamped] = field(default_factory=list)


def room_range(x, y, heading):
    """The distance from (x, y) along `heading` to the room's walls (from inside)."""
    x0, x1, y0, y1 = ROOM
    dx, dy = math.cos(heading), math.sin(heading)
    hits = []
    if dx > 1e-9:
        hits.append((x1 - x) / dx)
    elif dx < -1e-9:
        hits.append((x0 - x) / dx)
    if dy > 1e-9:
        hits.append((y1 - y) / dy)
    elif dy < -1e-9:
        hits.append((y0 - y) / dy)
    return min(hits)


def room_scan(x, y, th):
    step = 2 * math.pi / BEAMS
    ranges = []
    for k in range(BEAMS):
        r = room_range(x, y, th + k * step)
        ranges.append(r if RANGE_MIN <= r <= RANGE_MAX else math.inf)
    return LaserScan(
        header=Header(stamp=stamp_now(), frame_id="base_scan"),
        angle_min=0.0,
        angle_max=step * (BEAMS - 1),
        angle_increment=step,
        scan_time=SCAN_PERIOD,
        range_min=RANGE_MIN,
        range_max=RANGE_MAX,
        ranges=ranges,
    )


def wall_distance(x, y):
    """The distance from (x, y) to the nearest of the room's four walls (as segments)."""
    x0, x1, y0, y1 = ROOM
    cx, cy = min(max(x, x0), x1), min(max(y, y0), y1)
    return min(
        math.hypot(x - x0, y - cy),
        math.hypot(x - x1, y - cy),
        math.hypot(x - cx, y - y0),
        math.hypot(x - cx, y - y1),
    )


def check_map(grid, map_to_odom):
    """The map's occupied cells against the room: how many, the share of them near a wall
    and the share of the walls (sampled every 5 cm) with an occupied cell near them."""
    res, w = grid.info.resolution, grid.info.width
    ox, oy = grid.info.origin.position.x, grid.info.origin.position.y
    tx, ty, tth = map_to_odom
    c, s = math.cos(tth), math.sin(tth)
    occupied = []
    for i, v in enumerate(grid.data):
        if v >= 50:
            mx = ox + (i % w + 0.5) * res
            my = oy + (i // w + 0.5) * res
            # A point of the map frame in the odometry frame: T_map_odom^-1 (REP 105).
            dx, dy = mx - tx, my - ty
            occupied.append((c * dx + s * dy, -s * dx + c * dy))
    near = sum(1 for p in occupied if wall_distance(*p) <= NEAR_WALL)
    x0, x1, y0, y1 = ROOM
    samples = []
    for k in range(int((x1 - x0) / 0.05) + 1):
        samples += [(x0 + k * 0.05, y0), (x0 + k * 0.05, y1)]
    for k in range(int((y1 - y0) / 0.05) + 1):
        samples += [(x0, y0 + k * 0.05), (x1, y0 + k * 0.05)]
    # Cells by their position rounded to a grid of NEAR_WALL, for a quick neighbourhood.
    buckets = {}
    for p in occupied:
        buckets.setdefault((round(p[0] / NEAR_WALL), round(p[1] / NEAR_WALL)), []).append(p)

    def seen(q):
        bx, by = round(q[0] / NEAR_WALL), round(q[1] / NEAR_WALL)
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for p in buckets.get((bx + i, by + j), []):
                    if math.hypot(p[0] - q[0], p[1] - q[1]) <= NEAR_WALL:
                        return True
        return False

    covered = sum(1 for q in samples if seen(q))
    return {
        "occupied": len(occupied),
        "near_walls": near / max(len(occupied), 1),
        "walls_seen": covered / len(samples),
    }


def stamp_now():
    now = time.time()
    return Time(sec=int(now), nanosec=int((now % 1.0) * 1e9))


def odometry(x=0.0, y=0.0, th=0.0):
    """nav_msgs/Odometry of base_footprint in odom, stamped now, at (x, y) heading th."""
    odom = Odometry(header=Header(stamp=stamp_now(), frame_id="odom"), child_frame_id="base_footprint")
    odom.pose.pose.position.x = x
    odom.pose.pose.position.y = y
    odom.pose.pose.orientation.z = math.sin(th / 2)
    odom.pose.pose.orientation.w = math.cos(th / 2)
    return odom


def main():
    domain, out = int(sys.argv[1]), sys.argv[2]
    stamped = "--stamped" in sys.argv[3:]
    room = "--room" in sys.argv[3:]
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
    # Sensor data: best effort, keep-last 5 (rclcpp's SensorDataQoS), as the LDS driver.
    sensor = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(5))
    scan_writer = DataWriter(dp, Topic(dp, "rt/scan", LaserScan), qos=sensor) if room else None
    tf_qos = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(100))
    tf_reader = DataReader(dp, Topic(dp, "rt/tf", TFMessage), qos=tf_qos) if room else None
    print("ready", flush=True)

    x = y = th = 0.0
    v = w = 0.0
    wl = wr = 0.0
    received = []
    maps = []
    last_grid = None
    map_to_odom = []
    next_scan = time.monotonic()
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
                last_grid = grid
        for message in tf_reader.take(N=100) if tf_reader else []:
            for tf in getattr(message, "transforms", []):
                if tf.header.frame_id == "map" and tf.child_frame_id == "odom":
                    q = tf.transform.rotation
                    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
                    map_to_odom.append([tf.transform.translation.x, tf.transform.translation.y, yaw])
        if scan_writer and now >= next_scan:
            next_scan = now + SCAN_PERIOD
            scan_writer.write(room_scan(x, y, th))
        odom_writer.write(odometry(x, y, th))
        joint_writer.write(
            JointState(
                header=Header(stamp=stamp_now()),
                name=["wheel_left_joint", "wheel_right_joint"],
                position=[wl, wr],
            )
        )
    record = {"cmd_vel": received, "pose": [x, y, th], "maps": maps}
    if room:
        record["map_to_odom"] = map_to_odom
        if last_grid is not None:
            latest = map_to_odom[-1] if map_to_odom else [0.0, 0.0, 0.0]
            record["map_check"] = check_map(last_grid, latest)
    with open(out, "w") as f:
        json.dump(record, f)


if __name__ == "__main__":
    main()
