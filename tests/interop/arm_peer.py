"""A TurtleBot3 with an OpenManipulator-X arm beside navdeck, on Eclipse Cyclone DDS with
ROS 2's wire types, for navdeck's interop test: it publishes rt/odom (so that navdeck's
link is up), reports every trajectory_msgs/JointTrajectory navdeck publishes on
rt/arm_controller/joint_trajectory, publishes sensor_msgs/JointState on rt/joint_states
when told, and plays the gripper_controller's control_msgs/action/GripperCommand server
far enough to read its goals (and, with the Cyclone mapping, to answer them).

Usage: arm_peer.py DOMAIN [--cyclone-mapping] [--reject]
--cyclone-mapping reads goal requests as rmw_cyclonedds frames them (a request id in
front of the data) and answers each one, accepted unless --reject; without it, requests
are read as Fast DDS frames them (the id beside the data) and not answered.

Prints "ready" once its readers and writers exist. Each stdin line
"joints NAME=VALUE ..." (VALUE "nan" for NaN) is published once navdeck's reader is
matched, then "sent" is printed. Each trajectory received is printed as one JSON line
{"trajectory": {"stamp": [sec, nanosec], "names": [...], "points": [{"positions": [...],
"time_from_start": [sec, nanosec]}]}}, each goal as {"goal": {"position": ...,
"max_effort": ...}}. Runs until stdin closes (or 60 s).
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
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import Header, JointState, Odometry, Time, ros, stamp_now


def action(pkg, name):
    return f"{pkg}::action::dds_::{name}_"


@dataclass
class Duration(IdlStruct, typename=ros("builtin_interfaces", "Duration")):
    sec: t.int32 = 0
    nanosec: t.uint32 = 0


@dataclass
class JointTrajectoryPoint(IdlStruct, typename=ros("trajectory_msgs", "JointTrajectoryPoint")):
    positions: t.sequence[t.float64] = field(default_factory=list)
    velocities: t.sequence[t.float64] = field(default_factory=list)
    accelerations: t.sequence[t.float64] = field(default_factory=list)
    effort: t.sequence[t.float64] = field(default_factory=list)
    time_from_start: Duration = field(default_factory=Duration)


@dataclass
class JointTrajectory(IdlStruct, typename=ros("trajectory_msgs", "JointTrajectory")):
    header: Header = field(default_factory=Header)
    joint_names: t.sequence[str] = field(default_factory=list)
    points: t.sequence[JointTrajectoryPoint] = field(default_factory=list)


@dataclass
class UUID(IdlStruct, typename=ros("unique_identifier_msgs", "UUID")):
    uuid: t.array[t.uint8, 16] = field(default_factory=lambda: [0] * 16)


@dataclass
class GripperCommand(IdlStruct, typename=ros("control_msgs", "GripperCommand")):
    position: t.float64 = 0.0
    max_effort: t.float64 = 0.0


@dataclass
class GripperCommandGoal(IdlStruct, typename=action("control_msgs", "GripperCommand_Goal")):
    command: GripperCommand = field(default_factory=GripperCommand)


@dataclass
class SendGoalRequest(IdlStruct, typename=action("control_msgs", "GripperCommand_SendGoal_Request")):
    goal_id: UUID = field(default_factory=UUID)
    goal: GripperCommandGoal = field(default_factory=GripperCommandGoal)


@dataclass
class CycloneSendGoalRequest(IdlStruct, typename=action("control_msgs", "GripperCommand_SendGoal_Request")):
    """rmw_cyclonedds' framing: the client's GUID's last 8 bytes and a sequence number first."""

    guid: t.array[t.uint8, 8] = field(default_factory=lambda: [0] * 8)
    seq_high: t.int32 = 0
    seq_low: t.uint32 = 0
    goal_id: UUID = field(default_factory=UUID)
    goal: GripperCommandGoal = field(default_factory=GripperCommandGoal)


@dataclass
class CycloneSendGoalResponse(IdlStruct, typename=action("control_msgs", "GripperCommand_SendGoal_Response")):
    guid: t.array[t.uint8, 8] = field(default_factory=lambda: [0] * 8)
    seq_high: t.int32 = 0
    seq_low: t.uint32 = 0
    accepted: bool = False
    stamp: Time = field(default_factory=Time)


def joint_state(words):
    """JointState from NAME=VALUE words, in their order."""
    pairs = [w.split("=", 1) for w in words]
    return JointState(
        header=Header(stamp=stamp_now()),
        name=[n for n, _ in pairs],
        position=[float(v) for _, v in pairs],
    )


def main():
    domain = int(sys.argv[1])
    cyclone = "--cyclone-mapping" in sys.argv[2:]
    reject = "--reject" in sys.argv[2:]
    # ROS 2's default profile (topics and services): reliable, volatile, keep-last 10.
    reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    dp = DomainParticipant(domain)
    odom_writer = DataWriter(dp, Topic(dp, "rt/odom", Odometry), qos=reliable)
    joint_writer = DataWriter(dp, Topic(dp, "rt/joint_states", JointState), qos=reliable)
    trajectory_reader = DataReader(dp, Topic(dp, "rt/arm_controller/joint_trajectory", JointTrajectory), qos=reliable)
    service = "gripper_controller/gripper_cmd/_action/send_goal"
    request_type = CycloneSendGoalRequest if cyclone else SendGoalRequest
    goal_reader = DataReader(dp, Topic(dp, f"rq/{service}Request", request_type), qos=reliable)
    reply_writer = None
    if cyclone:
        reply_writer = DataWriter(dp, Topic(dp, f"rr/{service}Reply", CycloneSendGoalResponse), qos=reliable)
    print("ready", flush=True)

    queued = []
    give_up = time.monotonic() + 60.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready:
            line = sys.stdin.readline()
            if not line:
                break
            words = line.split()
            if words and words[0] == "joints":
                queued.append(joint_state(words[1:]))
        # A volatile message sent before navdeck's reader matches would be lost.
        while queued and joint_writer.get_publication_matched_status().current_count > 0:
            joint_writer.write(queued.pop(0))
            print("sent", flush=True)
        for msg in trajectory_reader.take(N=10):
            if isinstance(msg, JointTrajectory):
                points = [
                    {"positions": list(p.positions), "time_from_start": [p.time_from_start.sec, p.time_from_start.nanosec]}
                    for p in msg.points
                ]
                stamp = [msg.header.stamp.sec, msg.header.stamp.nanosec]
                record = {"stamp": stamp, "names": list(msg.joint_names), "points": points}
                print(json.dumps({"trajectory": record}), flush=True)
        for request in goal_reader.take(N=10):
            if not isinstance(request, request_type):
                continue
            command = request.goal.command
            print(json.dumps({"goal": {"position": command.position, "max_effort": command.max_effort}}), flush=True)
            if reply_writer is not None:
                reply_writer.write(
                    CycloneSendGoalResponse(
                        guid=request.guid,
                        seq_high=request.seq_high,
                        seq_low=request.seq_low,
                        accepted=not reject,
                        stamp=stamp_now(),
                    )
                )
        odom_writer.write(Odometry(header=Header(stamp=stamp_now(), frame_id="odom"), child_frame_id="base_footprint"))


if __name__ == "__main__":
    main()
