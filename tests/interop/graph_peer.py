"""The ROS 2 graph around navdeck, on Eclipse Cyclone DDS with ROS 2's wire types, for
navdeck's interop test: a robot node's /rosout, RViz's "2D Goal Pose", and the tools
that read /rosout, navdeck's state topic and the graph's node list.

Usage: graph_peer.py DOMAIN DISTRO
DISTRO (humble or jazzy) picks the participant GID layout ros_discovery_info is read
with (Humble 24 bytes, Iron and later 16), as `ros2 node list` on that distribution does.
Prints "ready" once its readers and writers exist. Stdin lines:
  "log LEVEL NODE TEXT..."   publish an rcl_interfaces/Log on rt/rosout as node NODE
  "goal FRAME X Y YAW"       publish a geometry_msgs/PoseStamped on rt/goal_pose (FRAME
                             "-" for an empty frame_id), once navdeck's reader matched
Prints one JSON line per thing received: {"rosout": {"name", "level", "msg"}},
{"state": "<navdeck's JSON>"}, {"node": "/ns/name"}; "sent" after each goal. Runs
until stdin closes (or 120 s).
"""

import json
import math
import os
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

from turtlebot_peer import Header, Pose, Time, ros, stamp_now


@dataclass
class Log(IdlStruct, typename=ros("rcl_interfaces", "Log")):
    stamp: Time = field(default_factory=Time)
    level: t.uint8 = 0
    name: str = ""
    msg: str = ""
    file: str = ""
    function: str = ""
    line: t.uint32 = 0


@dataclass
class String(IdlStruct, typename=ros("std_msgs", "String")):
    data: str = ""


@dataclass
class PoseStamped(IdlStruct, typename=ros("geometry_msgs", "PoseStamped")):
    header: Header = field(default_factory=Header)
    pose: Pose = field(default_factory=Pose)


def discovery_types(gid_size):
    """rmw_dds_common's ParticipantEntitiesInfo with a GID of `gid_size` bytes."""

    @dataclass
    class Gid(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
        data: t.array[t.uint8, gid_size] = field(default_factory=lambda: bytearray(gid_size))

    @dataclass
    class NodeEntitiesInfo(IdlStruct, typename="rmw_dds_common::msg::dds_::NodeEntitiesInfo_"):
        node_namespace: str = ""
        node_name: str = ""
        reader_gid_seq: t.sequence[Gid] = field(default_factory=list)
        writer_gid_seq: t.sequence[Gid] = field(default_factory=list)

    @dataclass
    class ParticipantEntitiesInfo(
        IdlStruct, typename="rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"
    ):
        gid: Gid = field(default_factory=Gid)
        node_entities_info_seq: t.sequence[NodeEntitiesInfo] = field(default_factory=list)

    return ParticipantEntitiesInfo


def goal(frame, x, y, yaw):
    msg = PoseStamped(header=Header(stamp=stamp_now(), frame_id=frame))
    msg.pose.position.x = x
    msg.pose.position.y = y
    msg.pose.orientation.z = math.sin(yaw / 2)
    msg.pose.orientation.w = math.cos(yaw / 2)
    return msg


def main():
    domain, distro = int(sys.argv[1]), sys.argv[2]
    info_type = discovery_types(24 if distro == "humble" else 16)
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    # /rosout as rcl sets it up: reliable, transient local, the last 1000 lines.
    rosout_qos = Qos(
        Policy.Reliability.Reliable(duration(milliseconds=100)),
        Policy.Durability.TransientLocal,
        Policy.History.KeepLast(1000),
    )
    latched = Qos(
        Policy.Reliability.Reliable(duration(milliseconds=100)),
        Policy.Durability.TransientLocal,
        Policy.History.KeepLast(1),
    )
    dp = DomainParticipant(domain)
    rosout_topic = Topic(dp, "rt/rosout", Log)
    rosout_writer = DataWriter(dp, rosout_topic, qos=rosout_qos)
    rosout_reader = DataReader(dp, rosout_topic, qos=rosout_qos)
    goal_writer = DataWriter(dp, Topic(dp, "rt/goal_pose", PoseStamped), qos=reliable)
    state_reader = DataReader(dp, Topic(dp, "rt/navdeck/state", String), qos=latched)
    info_reader = DataReader(dp, Topic(dp, "ros_discovery_info", info_type), qos=latched)
    print("ready", flush=True)

    goals = []
    logs = []
    nodes = set()
    give_up = time.monotonic() + 120.0
    pending = b""
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready:
            # Raw reads: several lines may come at once, and a buffered reader would keep
            # the later ones out of select's sight.
            chunk = os.read(sys.stdin.fileno(), 65536)
            if not chunk:
                break
            pending += chunk
        while b"\n" in pending:
            line, pending = pending.split(b"\n", 1)
            words = line.decode().split()
            if words and words[0] == "goal":
                frame = "" if words[1] == "-" else words[1]
                goals.append(goal(frame, *map(float, words[2:5])))
            elif words and words[0] == "log":
                level, node, text = int(words[1]), words[2], " ".join(words[3:])
                logs.append(Log(stamp=stamp_now(), level=level, name=node, msg=text))
        # Volatile goals sent before navdeck's reader matched would be lost.
        while goals and goal_writer.get_publication_matched_status().current_count > 0:
            goal_writer.write(goals.pop(0))
            print("sent", flush=True)
        # Lines wait for navdeck's reader, matched beside this peer's own.
        while logs and rosout_writer.get_publication_matched_status().current_count > 1:
            rosout_writer.write(logs.pop(0))
        for m in rosout_reader.take(N=100):
            if isinstance(m, Log):
                record = {"name": m.name, "level": m.level, "msg": m.msg}
                print(json.dumps({"rosout": record}), flush=True)
        for m in state_reader.take(N=10):
            if isinstance(m, String):
                print(json.dumps({"state": m.data}), flush=True)
        for m in info_reader.take(N=10):
            if isinstance(m, info_type):
                for node in m.node_entities_info_seq:
                    name = node.node_namespace.rstrip("/") + "/" + node.node_name
                    if name not in nodes:
                        nodes.add(name)
                        print(json.dumps({"node": name}), flush=True)


if __name__ == "__main__":
    main()
