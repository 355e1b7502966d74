"""RViz's MarkerArray display on route mode's tag graph, on Eclipse Cyclone DDS with
ROS 2's wire types, for navdeck's interop test: it subscribes to rt/navdeck/tag_graph
(visualization_msgs/MarkerArray in Humble's or Jazzy's Marker layout) and reports what
each array held.

Usage: tag_graph_peer.py DOMAIN humble|jazzy
Prints "ready" once its reader exists, then one JSON line per MarkerArray received:
{"graph": {"count": n, "first_action": a, "frame": ..., "kinds": {"NS/ID": type},
"route": [[x, y], ...] (the LINE_STRIP's points, or null), "route_rgb": [r, g, b],
"blocked": [[x, y], ...] (the red LINE_LIST's, or null), "blocked_rgb": [r, g, b],
"next": [x, y] (the CUBE's position, or null), "labels": ["101", ...]}}.
Runs until stdin closes (or 60 s).
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
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import Header, Point, Pose, Vector3, ros

# visualization_msgs/msg/Marker.msg's type constants.
CUBE, LINE_STRIP, LINE_LIST, TEXT_VIEW_FACING = 1, 4, 5, 9


@dataclass
class ColorRGBA(IdlStruct, typename=ros("std_msgs", "ColorRGBA")):
    r: t.float32 = 0.0
    g: t.float32 = 0.0
    b: t.float32 = 0.0
    a: t.float32 = 0.0


@dataclass
class Duration(IdlStruct, typename=ros("builtin_interfaces", "Duration")):
    sec: t.int32 = 0
    nanosec: t.uint32 = 0


def humble_types():
    """Marker and MarkerArray as Humble defines them."""

    @dataclass
    class Marker(IdlStruct, typename=ros("visualization_msgs", "Marker")):
        header: Header = field(default_factory=Header)
        ns: str = ""
        id: t.int32 = 0
        type: t.int32 = 0
        action: t.int32 = 0
        pose: Pose = field(default_factory=Pose)
        scale: Vector3 = field(default_factory=Vector3)
        color: ColorRGBA = field(default_factory=ColorRGBA)
        lifetime: Duration = field(default_factory=Duration)
        frame_locked: bool = False
        points: t.sequence[Point] = field(default_factory=list)
        colors: t.sequence[ColorRGBA] = field(default_factory=list)
        text: str = ""
        mesh_resource: str = ""
        mesh_use_embedded_materials: bool = False

    @dataclass
    class MarkerArray(IdlStruct, typename=ros("visualization_msgs", "MarkerArray")):
        markers: t.sequence[Marker] = field(default_factory=list)

    return MarkerArray


def jazzy_types():
    """Marker and MarkerArray as Iron and Jazzy define them (texture and mesh fields)."""

    @dataclass
    class CompressedImage(IdlStruct, typename=ros("sensor_msgs", "CompressedImage")):
        header: Header = field(default_factory=Header)
        format: str = ""
        data: t.sequence[t.uint8] = field(default_factory=list)

    @dataclass
    class UVCoordinate(IdlStruct, typename=ros("visualization_msgs", "UVCoordinate")):
        u: t.float32 = 0.0
        v: t.float32 = 0.0

    @dataclass
    class MeshFile(IdlStruct, typename=ros("visualization_msgs", "MeshFile")):
        filename: str = ""
        data: t.sequence[t.uint8] = field(default_factory=list)

    @dataclass
    class Marker(IdlStruct, typename=ros("visualization_msgs", "Marker")):
        header: Header = field(default_factory=Header)
        ns: str = ""
        id: t.int32 = 0
        type: t.int32 = 0
        action: t.int32 = 0
        pose: Pose = field(default_factory=Pose)
        scale: Vector3 = field(default_factory=Vector3)
        color: ColorRGBA = field(default_factory=ColorRGBA)
        lifetime: Duration = field(default_factory=Duration)
        frame_locked: bool = False
        points: t.sequence[Point] = field(default_factory=list)
        colors: t.sequence[ColorRGBA] = field(default_factory=list)
        texture_resource: str = ""
        texture: CompressedImage = field(default_factory=CompressedImage)
        uv_coordinates: t.sequence[UVCoordinate] = field(default_factory=list)
        text: str = ""
        mesh_resource: str = ""
        mesh_file: MeshFile = field(default_factory=MeshFile)
        mesh_use_embedded_materials: bool = False

    @dataclass
    class MarkerArray(IdlStruct, typename=ros("visualization_msgs", "MarkerArray")):
        markers: t.sequence[Marker] = field(default_factory=list)

    return MarkerArray


def rgb(c):
    return [round(c.r, 3), round(c.g, 3), round(c.b, 3)]


def report(array):
    """What an array held, as the docstring's JSON."""
    markers = array.markers
    shapes = [m for m in markers if m.ns == "tag_graph"]
    strip = next((m for m in shapes if m.type == LINE_STRIP), None)
    # The blocked edges: the LINE_LIST drawn in red (the plain edges are grey).
    red = next((m for m in shapes if m.type == LINE_LIST and m.color.r > 0.9 and m.color.g < 0.5), None)
    cube = next((m for m in shapes if m.type == CUBE), None)
    return {
        "count": len(markers),
        "first_action": markers[0].action if markers else None,
        "frame": markers[-1].header.frame_id if markers else None,
        "kinds": {f"{m.ns}/{m.id}": m.type for m in markers[1:]},
        "route": [[p.x, p.y] for p in strip.points] if strip else None,
        "route_rgb": rgb(strip.color) if strip else None,
        "blocked": [[p.x, p.y] for p in red.points] if red else None,
        "blocked_rgb": rgb(red.color) if red else None,
        "next": [cube.pose.position.x, cube.pose.position.y] if cube else None,
        "labels": [m.text for m in markers if m.type == TEXT_VIEW_FACING],
    }


def main():
    domain, distro = int(sys.argv[1]), sys.argv[2]
    MarkerArray = jazzy_types() if distro == "jazzy" else humble_types()
    # As navdeck publishes the graph: reliable, transient local, the last one kept.
    qos = Qos(
        Policy.Reliability.Reliable(duration(milliseconds=100)),
        Policy.Durability.TransientLocal,
        Policy.History.KeepLast(1),
    )
    dp = DomainParticipant(domain)
    reader = DataReader(dp, Topic(dp, "rt/navdeck/tag_graph", MarkerArray), qos=qos)
    print("ready", flush=True)
    give_up = time.monotonic() + 60.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready and not sys.stdin.readline():
            break
        for array in reader.take(N=10):
            if isinstance(array, MarkerArray):
                print(json.dumps({"graph": report(array)}), flush=True)


if __name__ == "__main__":
    main()
