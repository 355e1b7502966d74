"""Two TurtleBot3s on one ROS 2 domain, each under its own namespace, on Eclipse Cyclone
DDS with ROS 2's wire types, for the test of `navdeck ros2 robots`:

  /tb3_0  Odometry on odom at 20 Hz, a Twist reader on cmd_vel (Humble), scan
  /tb3_1  Odometry on odom at 20 Hz, a TwistStamped reader on cmd_vel (Jazzy), rgb
  /chatter a String publisher: no robot

Usage: fleet_peer.py DOMAIN
Prints "ready" once its readers and writers exist, runs until stdin closes (or 60 s).
"""

import select
import sys
import time
from dataclasses import dataclass

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from topics_peer import LaserScan
from turtlebot_peer import Image, Odometry, Twist, TwistStamped, odometry, ros


@dataclass
class String(IdlStruct, typename=ros("std_msgs", "String")):
    data: str = ""


def main():
    domain = int(sys.argv[1])
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    sensor = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(5))
    dp = DomainParticipant(domain)
    odom = [DataWriter(dp, Topic(dp, f"rt/tb3_{k}/odom", Odometry), qos=reliable) for k in (0, 1)]
    keep = [
        DataReader(dp, Topic(dp, "rt/tb3_0/cmd_vel", Twist), qos=reliable),
        DataReader(dp, Topic(dp, "rt/tb3_1/cmd_vel", TwistStamped), qos=reliable),
        DataWriter(dp, Topic(dp, "rt/tb3_0/scan", LaserScan), qos=sensor),
        DataWriter(dp, Topic(dp, "rt/tb3_1/rgb", Image), qos=sensor),
        DataWriter(dp, Topic(dp, "rt/chatter", String), qos=reliable),
    ]
    print("ready", flush=True)
    give_up = time.monotonic() + 60.0
    while time.monotonic() < give_up and keep:
        ready, _, _ = select.select([sys.stdin], [], [], 0.05)
        if ready and not sys.stdin.readline():
            break
        for w in odom:
            w.write(odometry())


if __name__ == "__main__":
    main()
