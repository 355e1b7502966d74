"""A TurtleBot3's camera as image_transport's compressed topic carries it, for navdeck's
interop test of lane mode on a real robot's frames: a JPEG the test wrote (a frame of
the twin's track) published as sensor_msgs/CompressedImage on
rt/camera/image_raw/compressed, in the format string image_transport writes.

Usage: lane_camera_peer.py DOMAIN JPEG_FILE
Prints "ready" once its writer exists, then publishes the picture every 0.1 s (a 10 Hz
camera) and prints {"published": n} every 10 frames. Runs until stdin closes (or 60 s).
"""

import json
import select
import sys
import time
from dataclasses import dataclass, field

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.pub import DataWriter
from cyclonedds.topic import Topic

from turtlebot_peer import Header, ros, stamp_now


@dataclass
class CompressedImage(IdlStruct, typename=ros("sensor_msgs", "CompressedImage")):
    header: Header = field(default_factory=Header)
    format: str = ""
    data: t.sequence[t.uint8] = field(default_factory=list)


def main():
    domain, path = int(sys.argv[1]), sys.argv[2]
    with open(path, "rb") as f:
        jpeg = list(f.read())
    # A camera's sensor-data QoS: best effort, the newest frames only.
    qos = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(2))
    dp = DomainParticipant(domain)
    writer = DataWriter(dp, Topic(dp, "rt/camera/image_raw/compressed", CompressedImage), qos=qos)
    print("ready", flush=True)
    msg = CompressedImage(header=Header(frame_id="camera_rgb_optical_frame"),
                          format="rgb8; jpeg compressed bgr8", data=jpeg)
    sent = 0
    give_up = time.monotonic() + 60.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.1)
        if ready and not sys.stdin.readline():
            break
        msg.header.stamp = stamp_now()
        writer.write(msg)
        sent += 1
        if sent % 10 == 0:
            print(json.dumps({"published": sent}), flush=True)


if __name__ == "__main__":
    main()
