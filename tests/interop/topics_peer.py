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

from graph_peer import PoseStamped
from turtlebot_peer import Header, OccupancyGrid, Odometry, Twist, TwistStamped, ros, stamp_now

ODOM_PERIOD = 0.05


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
        header = Header(stamp=stamp_now(), frame_id="odom")
        odom.write(Odometry(header=header, child_frame_id="base_footprint"))
    del endpoints


if __name__ == "__main__":
    main()
