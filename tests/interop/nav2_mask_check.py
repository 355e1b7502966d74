"""A Nav2 costmap filter read as Nav2 reads it, independent of navdeck's reader.

Usage: nav2_mask_check.py FILTER_INFO.yaml X,Y [X,Y ...]

Reads the costmap_filter_info_server parameter file (type, base, multiplier and the
filter_mask_server's yaml_filename), the map_server YAML it names and its PGM image, turns
pixels into OccupancyGrid values by map_server's rules (trinary or scale, negate,
occupied_thresh, free_thresh), and prints each point's filter value: for a keepout filter
(type 0) the mask value (100 lethal), for a speed filter (1, 2) base + multiplier * value,
or 0 (Nav2's "no limit") where the mask is 0 or unknown. Standard library only: the YAML
these files use is a small subset (nested maps, scalars, one flow list).
"""

import os
import sys


def parse_yaml(text):
    """Nested block mappings of scalars and [a, b, c] flow lists."""
    root = {}
    stack = [(-1, root)]
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].rstrip()
        if not line.strip():
            continue
        indent = len(line) - len(line.lstrip())
        key, _, value = line.strip().partition(":")
        while stack[-1][0] >= indent:
            stack.pop()
        parent = stack[-1][1]
        value = value.strip()
        if value == "":
            child = {}
            parent[key] = child
            stack.append((indent, child))
        else:
            parent[key] = scalar(value)
    return root


def scalar(value):
    if value.startswith("[") and value.endswith("]"):
        return [scalar(v.strip()) for v in value[1:-1].split(",")]
    if value[0] in "\"'":
        return value[1:-1]
    for kind in (int, float):
        try:
            return kind(value)
        except ValueError:
            pass
    return value


def read_pgm(path):
    data = open(path, "rb").read()
    tokens, at = [], 0
    while len(tokens) < 4:
        while data[at:at + 1].isspace():
            at += 1
        if data[at:at + 1] == b"#":
            while data[at:at + 1] != b"\n":
                at += 1
            continue
        start = at
        while not data[at:at + 1].isspace():
            at += 1
        tokens.append(data[start:at].decode())
    assert tokens[0] == "P5", "binary PGM expected"
    width, height, maxval = int(tokens[1]), int(tokens[2]), int(tokens[3])
    assert maxval < 256
    pixels = data[at + 1:at + 1 + width * height]
    assert len(pixels) == width * height, "truncated image"
    return width, height, maxval, pixels


def mask_value(pixel, maxval, meta):
    # nav2_map_server map_io: shade 0..1, occ = 1 - shade unless negate.
    shade = pixel / maxval
    occ = shade if meta.get("negate", 0) else 1.0 - shade
    occ_t, free_t = float(meta["occupied_thresh"]), float(meta["free_thresh"])
    mode = meta.get("mode", "trinary")
    if occ > occ_t:
        return 100
    if occ < free_t:
        return 0
    if mode == "scale":
        return round((occ - free_t) / (occ_t - free_t) * 100.0)
    return -1


def main():
    info_path = sys.argv[1]
    params = parse_yaml(open(info_path).read())
    info = next(n["ros__parameters"] for n in params.values()
                if "type" in n.get("ros__parameters", {}))
    mask_name = next(n["ros__parameters"]["yaml_filename"] for n in params.values()
                     if "yaml_filename" in n.get("ros__parameters", {}))
    folder = os.path.dirname(info_path)
    meta = parse_yaml(open(os.path.join(folder, mask_name)).read())
    width, height, maxval, pixels = read_pgm(os.path.join(folder, meta["image"]))
    res = float(meta["resolution"])
    ox, oy = float(meta["origin"][0]), float(meta["origin"][1])
    kind = int(info["type"])
    base, mult = float(info.get("base", 0.0)), float(info.get("multiplier", 1.0))
    out = []
    for arg in sys.argv[2:]:
        x, y = (float(v) for v in arg.split(","))
        col, row = int((x - ox) // res), int((y - oy) // res)
        assert 0 <= col < width and 0 <= row < height, f"{arg} is off the mask"
        # Image rows run top down; grid rows bottom up.
        value = mask_value(pixels[(height - 1 - row) * width + col], maxval, meta)
        if kind == 0:
            out.append(float(value))
        elif value <= 0:
            out.append(0.0)
        else:
            out.append(base + mult * value)
    print(" ".join(f"{v:.6f}" for v in out))


if __name__ == "__main__":
    main()
