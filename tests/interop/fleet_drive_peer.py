"""N stand-in TurtleBot3s on one ROS 2 domain, robot k under the namespace /tb3_k, on
Eclipse Cyclone DDS with ROS 2's wire types, for the test of navdeck's fleet console:
each listens on rt/tb3_k/cmd_vel, integrates a unicycle, and publishes rt/tb3_k/odom
and rt/tb3_k/joint_states.

With --lose K@S robot K goes silent (no more odometry, joint states or motion) S seconds
after its first command that moves it: a robot whose link is lost. It still records
what arrives on its cmd_vel.

Usage: fleet_drive_peer.py DOMAIN N OUT.json [--lose K@S]
Prints "ready" once its readers and writers exist, runs until stdin closes (or 90 s),
then writes per robot the commands it got (UNIX time, v, w), its final pose, and every
robot's pose when robot K went silent.
"""

import json
import math
import select
import sys
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import TRACK, WHEEL_RADIUS, Header, JointState, Odometry, Twist, odometry, stamp_now


class Robot:
    def __init__(self, dp, k, qos):
        ns = f"rt/tb3_{k}"
        self.cmd = DataReader(dp, Topic(dp, f"{ns}/cmd_vel", Twist), qos=qos)
        self.odom = DataWriter(dp, Topic(dp, f"{ns}/odom", Odometry), qos=qos)
        self.joints = DataWriter(dp, Topic(dp, f"{ns}/joint_states", JointState), qos=qos)
        self.x = self.y = self.th = self.v = self.w = self.wl = self.wr = 0.0
        self.received = []
        self.first_move = None
        self.silent = False

    def step(self, dt, now_unix):
        if self.silent:
            self.v = self.w = 0.0
        self.x += self.v * math.cos(self.th) * dt
        self.y += self.v * math.sin(self.th) * dt
        self.th += self.w * dt
        self.wl += (self.v - self.w * TRACK / 2) * dt / WHEEL_RADIUS
        self.wr += (self.v + self.w * TRACK / 2) * dt / WHEEL_RADIUS
        for sample in self.cmd.take(N=100):
            if not isinstance(sample, Twist):
                continue  # a writer went away
            self.v, self.w = sample.linear.x, sample.angular.z
            self.received.append([now_unix, self.v, self.w])
            if self.first_move is None and (self.v != 0.0 or self.w != 0.0):
                self.first_move = time.monotonic()
        if self.silent:
            return
        self.odom.write(odometry(self.x, self.y, self.th))
        names = ["wheel_left_joint", "wheel_right_joint"]
        self.joints.write(JointState(header=Header(stamp=stamp_now()), name=names, position=[self.wl, self.wr]))


def main():
    domain, count, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    lose, after = None, None
    if "--lose" in sys.argv:
        k, s = sys.argv[sys.argv.index("--lose") + 1].split("@")
        lose, after = int(k), float(s)
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    dp = DomainParticipant(domain)
    robots = [Robot(dp, k, reliable) for k in range(count)]
    print("ready", flush=True)
    lost_at = None
    poses_at_loss = None
    last = time.monotonic()
    give_up = last + 90.0
    next_odom = last
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.005)
        if ready and not sys.stdin.readline():
            break
        now = time.monotonic()
        if now < next_odom:
            continue
        # Odometry at 20 Hz, as a TurtleBot3's.
        next_odom = now + 0.05
        dt, last = now - last, now
        unix = time.time()
        for r in robots:
            r.step(dt, unix)
        if lose is not None and lost_at is None:
            first = robots[lose].first_move
            if first is not None and now - first >= after:
                robots[lose].silent = True
                lost_at = unix
                poses_at_loss = [[r.x, r.y, r.th] for r in robots]
    record = {
        "robots": [{"cmd_vel": r.received, "pose": [r.x, r.y, r.th]} for r in robots],
        "lost_at": lost_at,
        "poses_at_loss": poses_at_loss,
    }
    with open(out, "w") as f:
        json.dump(record, f)


if __name__ == "__main__":
    main()
