"""Big messages both ways between navdeck and Eclipse Cyclone DDS, for navdeck's interop
test: a 384 x 384 OccupancyGrid (a TurtleBot3 map, 147 KB) and 640 x 480 images cross
DDS as fragmented samples, and every byte is checked against the pattern both sides
compute.

Usage: big_peer.py DOMAIN RELIABILITY   (reliable or best_effort)
Prints "ready" once its readers and writers exist. Every 0.2 s it publishes a map on
rt/big/map_in, a mono8 image on rt/camera/image_raw and an rgb8 image on
rt/big/image_in. It reads navdeck's map on rt/map and an rgb8 image on rt/big/image_out
and prints one JSON line per sample: {"map_out": {"width", "height", "intact"}} or
{"image_out": {...}}, "intact" being true when every byte is the pattern's. Runs until
stdin closes (or 120 s).
"""

import json
import select
import sys
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from turtlebot_peer import Header, Image, ros, stamp_now
from turtlebot_peer import OccupancyGrid as Grid


MAP_SIDE = 384
WIDTH, HEIGHT = 640, 480


def map_cells(seed):
    """Occupancy values -1..100 that differ from cell to cell and row to row."""
    return [((i * 31 + (i // MAP_SIDE) * 7 + seed) % 102) - 1 for i in range(MAP_SIDE * MAP_SIDE)]


def pixels(count, seed):
    return [(i * 13 + (i // 640) * 5 + seed) & 0xFF for i in range(count)]


# Both sides use the same seeds: 1 for the map in, 2 for navdeck's map out, 3 the mono
# image in, 4 the rgb image in, 5 the rgb image out.
MAP_IN, MAP_OUT = map_cells(1), map_cells(2)
MONO_IN = pixels(WIDTH * HEIGHT, 3)
RGB_IN, RGB_OUT = pixels(WIDTH * HEIGHT * 3, 4), pixels(WIDTH * HEIGHT * 3, 5)


def main():
    domain, reliability = int(sys.argv[1]), sys.argv[2]
    kind = (
        Policy.Reliability.Reliable(duration(milliseconds=500))
        if reliability == "reliable"
        else Policy.Reliability.BestEffort
    )
    qos = Qos(kind, Policy.History.KeepLast(2))
    dp = DomainParticipant(domain)
    map_writer = DataWriter(dp, Topic(dp, "rt/big/map_in", Grid), qos=qos)
    mono_writer = DataWriter(dp, Topic(dp, "rt/camera/image_raw", Image), qos=qos)
    rgb_writer = DataWriter(dp, Topic(dp, "rt/big/image_in", Image), qos=qos)
    map_reader = DataReader(dp, Topic(dp, "rt/map", Grid), qos=qos)
    image_reader = DataReader(dp, Topic(dp, "rt/big/image_out", Image), qos=qos)
    print("ready", flush=True)

    grid = Grid(header=Header(frame_id="map"), data=MAP_IN)
    grid.info.resolution = 0.05
    grid.info.width = grid.info.height = MAP_SIDE
    mono = Image(height=HEIGHT, width=WIDTH, encoding="mono8", step=WIDTH, data=MONO_IN)
    rgb = Image(height=HEIGHT, width=WIDTH, encoding="rgb8", step=WIDTH * 3, data=RGB_IN)
    next_send = 0.0
    give_up = time.monotonic() + 120.0
    while time.monotonic() < give_up:
        ready, _, _ = select.select([sys.stdin], [], [], 0.02)
        if ready and not sys.stdin.readline():
            break
        if time.monotonic() >= next_send:
            next_send = time.monotonic() + 0.2
            for writer, msg in ((map_writer, grid), (mono_writer, mono), (rgb_writer, rgb)):
                msg.header.stamp = stamp_now()
                writer.write(msg)
        for m in map_reader.take(N=10):
            if isinstance(m, Grid):
                intact = m.info.width == MAP_SIDE and m.info.height == MAP_SIDE and list(m.data) == MAP_OUT
                record = {"width": m.info.width, "height": m.info.height, "intact": intact}
                print(json.dumps({"map_out": record}), flush=True)
        for m in image_reader.take(N=10):
            if isinstance(m, Image):
                intact = m.encoding == "rgb8" and m.step == WIDTH * 3 and list(m.data) == RGB_OUT
                record = {"width": m.width, "height": m.height, "intact": intact}
                print(json.dumps({"image_out": record}), flush=True)


if __name__ == "__main__":
    main()
