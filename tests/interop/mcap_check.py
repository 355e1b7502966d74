#!/usr/bin/env python3
"""Reads a navdeck recording with the PyPI MCAP reader and its ROS 2 decoder, as a tool
outside navdeck would, and prints one JSON object that tests/record_python.rs checks.

Usage: mcap_check.py FILE.mcap

Every message is decoded on its own: one that fails is listed under "decode_errors" and
the rest still count. A file without its summary (a crashed recording) is read again as
a stream up to where it breaks, with "recovered": true and the reason.
"""

import json
import math
import sys

from mcap.reader import NonSeekingReader, make_reader
from mcap_ros2.decoder import DecoderFactory


def finite(value):
    """A float JSON can carry: None for NaN and the infinities."""
    value = float(value)
    return value if math.isfinite(value) else None


def yaw_of(q):
    """Rotation about z of a geometry_msgs/Quaternion, radians."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def planar(pose):
    """x, y and yaw of a geometry_msgs/Pose."""
    return {
        "x": finite(pose.position.x),
        "y": finite(pose.position.y),
        "yaw": finite(yaw_of(pose.orientation)),
    }


class Summary:
    """What the test wants to know, gathered one decoded message at a time."""

    def __init__(self):
        self.counts = {}
        self.channels = {}
        self.errors = []
        self.odom = None
        self.cmd_vel = {"count": 0, "max_abs_linear_x": 0.0, "max_abs_angular_z": 0.0}
        self.scan = None
        self.map = None
        self.tf = None
        self.rosout = {"count": 0, "first": []}
        self.estimate = None

    def channel(self, schema, channel):
        if channel.topic in self.channels:
            return
        self.counts.setdefault(channel.topic, 0)
        self.channels[channel.topic] = {
            "schema": schema.name if schema else None,
            "schema_encoding": schema.encoding if schema else None,
            "message_encoding": channel.message_encoding,
        }

    def take(self, topic, msg):
        if topic == "/odom":
            self.odom = dict(
                planar(msg.pose.pose),
                frame_id=msg.header.frame_id,
                child_frame_id=msg.child_frame_id,
            )
        elif topic == "/cmd_vel":
            c = self.cmd_vel
            c["count"] += 1
            c["max_abs_linear_x"] = max(c["max_abs_linear_x"], abs(msg.linear.x))
            c["max_abs_angular_z"] = max(c["max_abs_angular_z"], abs(msg.angular.z))
        elif topic == "/scan" and self.scan is None:
            self.scan = {
                "frame_id": msg.header.frame_id,
                "angle_min": finite(msg.angle_min),
                "angle_increment": finite(msg.angle_increment),
                "range_min": finite(msg.range_min),
                "range_max": finite(msg.range_max),
                "ranges": len(msg.ranges),
                "finite_ranges": sum(1 for r in msg.ranges if math.isfinite(r)),
            }
        elif topic == "/map":
            info = msg.info
            data = list(msg.data)
            self.map = {
                "frame_id": msg.header.frame_id,
                "width": info.width,
                "height": info.height,
                "resolution": finite(info.resolution),
                "origin_x": finite(info.origin.position.x),
                "origin_y": finite(info.origin.position.y),
                "data": len(data),
                "unknown": sum(1 for v in data if v == -1),
                "free": sum(1 for v in data if 0 <= v < 50),
                "occupied": sum(1 for v in data if v >= 50),
            }
        elif topic == "/tf":
            self.tf = [
                {
                    "parent": t.header.frame_id,
                    "child": t.child_frame_id,
                    "x": finite(t.transform.translation.x),
                    "y": finite(t.transform.translation.y),
                    "yaw": finite(yaw_of(t.transform.rotation)),
                }
                for t in msg.transforms
            ]
        elif topic == "/rosout":
            self.rosout["count"] += 1
            if len(self.rosout["first"]) < 5:
                self.rosout["first"].append([msg.level, msg.msg])
        elif topic == "/navdeck/estimate":
            self.estimate = dict(planar(msg.pose.pose), frame_id=msg.header.frame_id)


def collect(path, out):
    """(schema, channel, message) of every message readable, in log-time order."""
    with open(path, "rb") as f:
        reader = make_reader(f)
        header = reader.get_header()
        out["profile"] = header.profile
        out["library"] = header.library
        try:
            summary = reader.get_summary()
        except Exception as e:  # a missing or broken footer: stream it instead
            out["recovered"] = True
            out["summary_error"] = f"{type(e).__name__}: {e}"
            summary = None
        found = []
        try:
            if out["recovered"]:
                f.seek(0)
                stream = NonSeekingReader(f).iter_messages(log_time_order=False)
            else:
                if summary is not None:
                    out["statistics_messages"] = (
                        summary.statistics.message_count if summary.statistics else None
                    )
                stream = reader.iter_messages(log_time_order=True)
            for item in stream:
                found.append(item)
        except Exception as e:  # the stream breaks where the file was cut
            out["stream_error"] = f"{type(e).__name__}: {e}"
    found.sort(key=lambda item: item[2].log_time)
    return found


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: mcap_check.py FILE.mcap")
    out = {
        "profile": None,
        "library": None,
        "recovered": False,
        "summary_error": None,
        "stream_error": None,
    }
    found = collect(sys.argv[1], out)
    seen = Summary()
    factory = DecoderFactory()
    decoders = {}
    for schema, channel, message in found:
        seen.channel(schema, channel)
        topic = channel.topic
        seen.counts[topic] += 1
        try:
            if channel.id not in decoders:
                decoders[channel.id] = factory.decoder_for(channel.message_encoding, schema)
            decode = decoders[channel.id]
            if decode is None:
                raise ValueError(
                    f"no ROS 2 decoder for {channel.message_encoding} / "
                    f"{schema.encoding if schema else 'no schema'}"
                )
            seen.take(topic, decode(message.data))
        except Exception as e:
            seen.errors.append({"topic": topic, "error": f"{type(e).__name__}: {e}"})
    out.update(
        {
            "messages": len(found),
            "counts": seen.counts,
            "channels": seen.channels,
            "decode_errors": seen.errors,
            "odom": seen.odom,
            "cmd_vel": seen.cmd_vel,
            "scan": seen.scan,
            "map": seen.map,
            "tf": seen.tf,
            "rosout": seen.rosout,
            "estimate": seen.estimate,
        }
    )
    json.dump(out, sys.stdout, allow_nan=False)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
