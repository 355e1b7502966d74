"""A stand-in robot with a tag camera, as seed 003's warehouse robot runs on ROS 2, for
navdeck's interop test of route mode: it listens on rt/cmd_vel, integrates a unicycle,
publishes rt/odom, and draws what its downward camera sees of the floor's AprilTags
(nearest-neighbour, from the cells and camera the test gives it) as sensor_msgs/Image
mono8 on rt/rgb with its sensor_msgs/CameraInfo on rt/camera_info.

Usage: tag_robot_peer.py DOMAIN SCENE.json OUT.json
SCENE.json: width, height, fx, fy, cx, cy (the camera), mount_r (3x3, camera to robot
frame, row-major), mount_t (the lens in the robot frame, metres), cell (metres), tags
([{id, centre, up, cells}], cells 64 characters row by row from the marker's top-left,
1 for white), start ([x, y, theta]), rate (frames a second).
Prints "ready" once its readers and writers exist, runs until stdin closes (or 120 s),
then writes {"pose": [x, y, theta], "frames": n, "cmd_vel": count} to OUT.json.
"""

import json
import math
import select
import sys
import time
from dataclasses import dataclass, field

import numpy as np
from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import Header, Image, Odometry, Twist, odometry, ros, stamp_now

FLOOR, BLACK, WHITE = 120, 25, 230


@dataclass
class RegionOfInterest(IdlStruct, typename=ros("sensor_msgs", "RegionOfInterest")):
    x_offset: t.uint32 = 0
    y_offset: t.uint32 = 0
    height: t.uint32 = 0
    width: t.uint32 = 0
    do_rectify: bool = False


@dataclass
class CameraInfo(IdlStruct, typename=ros("sensor_msgs", "CameraInfo")):
    header: Header = field(default_factory=Header)
    height: t.uint32 = 0
    width: t.uint32 = 0
    distortion_model: str = ""
    d: t.sequence[t.float64] = field(default_factory=list)
    k: t.array[t.float64, 9] = field(default_factory=lambda: [0.0] * 9)
    r: t.array[t.float64, 9] = field(default_factory=lambda: [0.0] * 9)
    p: t.array[t.float64, 12] = field(default_factory=lambda: [0.0] * 12)
    binning_x: t.uint32 = 0
    binning_y: t.uint32 = 0
    roi: RegionOfInterest = field(default_factory=RegionOfInterest)


class Camera:
    """The floor point under every pixel, in the robot frame, and the tags drawn there."""

    def __init__(self, scene):
        w, h = scene["width"], scene["height"]
        u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
        # The pixel's ray in the camera frame (pinhole), turned into the robot frame.
        ray = np.stack([(u - scene["cx"]) / scene["fx"], (v - scene["cy"]) / scene["fy"], np.ones_like(u)])
        r = np.array(scene["mount_r"], dtype=np.float64)
        lens = np.array(scene["mount_t"], dtype=np.float64)
        d = np.tensordot(r, ray, axes=1)
        # Where it meets the floor (z = 0): lens + s d with s = -lens_z / d_z.
        s = np.where(d[2] < -1e-9, -lens[2] / np.minimum(d[2], -1e-9), np.nan)
        self.fx_, self.fy_ = lens[0] + s * d[0], lens[1] + s * d[1]
        self.shape = (h, w)
        self.cell = scene["cell"]
        self.tags = [
            (np.array(tag["centre"]), np.array(tag["up"]), np.array([c == "1" for c in tag["cells"]]).reshape(8, 8))
            for tag in scene["tags"]
        ]

    def frame(self, x, y, th):
        c, s = math.cos(th), math.sin(th)
        wx = x + c * self.fx_ - s * self.fy_
        wy = y + s * self.fx_ + c * self.fy_
        img = np.full(self.shape, FLOOR, dtype=np.uint8)
        img[np.isnan(wx)] = 0
        for centre, (ux, uy), cells in self.tags:
            if math.hypot(centre[0] - x, centre[1] - y) > 1.0:
                continue
            dx, dy = wx - centre[0], wy - centre[1]
            # Across the marker (its right) and up it, in cells from the printed tag's corner.
            col = np.floor((dx * uy - dy * ux) / self.cell + 5.0)
            row = np.floor(5.0 - (dx * ux + dy * uy) / self.cell)
            inside = (col >= 0) & (col < 10) & (row >= 0) & (row < 10)
            if not inside.any():
                continue
            ci, ri = col[inside].astype(int), row[inside].astype(int)
            border = (ci == 0) | (ri == 0) | (ci == 9) | (ri == 9)
            white = border | cells[np.clip(ri - 1, 0, 7), np.clip(ci - 1, 0, 7)]
            img[inside] = np.where(white, WHITE, BLACK)
        return img


def main():
    domain, scene_path, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    with open(scene_path) as f:
        scene = json.load(f)
    camera = Camera(scene)
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    sensor = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(2))
    dp = DomainParticipant(domain)
    cmd_reader = DataReader(dp, Topic(dp, "rt/cmd_vel", Twist), qos=reliable)
    odom_writer = DataWriter(dp, Topic(dp, "rt/odom", Odometry), qos=reliable)
    image_writer = DataWriter(dp, Topic(dp, "rt/rgb", Image), qos=sensor)
    info_writer = DataWriter(dp, Topic(dp, "rt/camera_info", CameraInfo), qos=sensor)
    fx, fy, cx, cy = scene["fx"], scene["fy"], scene["cx"], scene["cy"]
    info = CameraInfo(
        header=Header(frame_id="camera_optical_frame"),
        height=scene["height"],
        width=scene["width"],
        distortion_model="plumb_bob",
        d=[0.0] * 5,
        k=[fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0],
        r=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        p=[fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
    )
    print("ready", flush=True)

    x, y, th = scene["start"]
    v = w = 0.0
    commands = frames = 0
    period = 1.0 / scene["rate"]
    next_frame = last = time.monotonic()
    give_up = last + 120.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.005)
        if ready and not sys.stdin.readline():
            break
        now = time.monotonic()
        dt, last = now - last, now
        x += v * math.cos(th) * dt
        y += v * math.sin(th) * dt
        th += w * dt
        for sample in cmd_reader.take(N=100):
            if isinstance(sample, Twist):
                v, w = sample.linear.x, sample.angular.z
                commands += 1
        odom_writer.write(odometry(x, y, th))
        if now >= next_frame:
            next_frame = now + period
            img = camera.frame(x, y, th)
            stamp = stamp_now()
            info.header.stamp = stamp
            info_writer.write(info)
            image_writer.write(
                Image(
                    header=Header(stamp=stamp, frame_id="camera_optical_frame"),
                    height=img.shape[0],
                    width=img.shape[1],
                    encoding="mono8",
                    step=img.shape[1],
                    data=img.tobytes(),
                )
            )
            frames += 1
    with open(out, "w") as f:
        json.dump({"pose": [x, y, th], "frames": frames, "cmd_vel": commands}, f)


if __name__ == "__main__":
    main()
