#!/usr/bin/env python3
"""Writes the default cockpit's model, config/models/cockpit/*.glb (glTF 2.0, binary): the look of
config/cockpit.yaml's static shell, a file per object that wears it, each one node named as the
part (`look: {mesh: models/cockpit/instrument_panel.glb, node: InstrumentPanel}`). The build
runs it (CMakeLists.txt); the files are not kept in git. Made by the project, under its
licence. Run from anywhere:
    scripts/make_cockpit_model.py [OUT_DIR]

The physics collides with the scene's boxes; the model is only what the pilot sees, so each node
keeps to its box's faces where a hand or a loose object touches them (the panel's face, the
console and pedestal tops) and adds what no hand leans on (rounded edges, the panel's rim and
screws, the glareshield's padded hood, the seat and rudder pedals, the windshield's frame).

Each node is written in its object's frame (the box centre, the box's axes), +z up in the
project's axes, then turned to glTF's +y up: (x, y, z) -> (x, z, -y).
"""
import json
import math
import os
import struct
import sys
from array import array
from pathlib import Path

# ---- solids: each returns (positions, normals, triangles) in the frame it is built in ---------


def rounded_box(half, r, band=8, spacing=0.08):
    """A box of half extents `half` whose edges and corners are rounded with radius r: flat
    faces exactly at +-half (within r of an edge the surface turns), smooth normals. Each face is
    a grid, `band` rows across each rounded strip and rows `spacing` apart across the flat
    middle."""
    hx, hy, hz = half
    r = min(r, hx, hy, hz)

    def ticks(h):
        """Rising from -h to h: the rounded strip, the flat middle, the other strip."""
        inner = h - r
        if inner < 1e-6:  # rounded right across: the two strips meet in the middle
            return ([-h * math.sin(math.pi / 2 * (band - k) / band) for k in range(band)] +
                    [h * math.sin(math.pi / 2 * k / band) for k in range(band + 1)])
        flat = max(1, math.ceil(2.0 * inner / spacing))
        out = [-inner - r * math.sin(math.pi / 2 * (band - k) / band) for k in range(band)]
        out += [-inner + 2.0 * inner * k / flat for k in range(flat + 1)]
        out += [inner + r * math.sin(math.pi / 2 * k / band) for k in range(1, band + 1)]
        return out

    grids = {0: ticks(hx), 1: ticks(hy), 2: ticks(hz)}
    P, N, T = [], [], []
    for axis in range(3):
        a, b = [i for i in range(3) if i != axis]
        for sign in (-1.0, 1.0):
            base = len(P)
            ua, ub = grids[a], grids[b]
            for u in ua:
                for v in ub:
                    q = [0.0, 0.0, 0.0]
                    q[axis] = sign * half[axis]
                    q[a], q[b] = u, v
                    inner = [max(-(half[i] - r), min(half[i] - r, q[i])) for i in range(3)]
                    d = [q[i] - inner[i] for i in range(3)]
                    n = math.sqrt(sum(c * c for c in d)) or 1.0
                    d = [c / n for c in d]
                    P.append([inner[i] + r * d[i] for i in range(3)])
                    N.append(d)
            nb = len(ub)
            for i in range(len(ua) - 1):
                for j in range(nb - 1):
                    k0, k1 = base + i * nb + j, base + (i + 1) * nb + j
                    quad = (k0, k1, k1 + 1, k0 + 1)
                    # counter-clockwise seen from outside: (a, b, axis) right-handed or not
                    right_handed = (a, b, axis) in ((0, 1, 2), (1, 2, 0), (2, 0, 1))
                    if (sign > 0) == right_handed:
                        T += [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
                    else:
                        T += [(quad[0], quad[2], quad[1]), (quad[0], quad[3], quad[2])]
    return P, N, T


def cylinder(radius, length, segments=16):
    """Along z, centred, with flat caps (flat-shaded caps, smooth side)."""
    P, N, T = [], [], []
    h = length / 2
    for k in range(segments):
        a = 2 * math.pi * k / segments
        c, s = math.cos(a), math.sin(a)
        P += [[radius * c, radius * s, -h], [radius * c, radius * s, h]]
        N += [[c, s, 0.0], [c, s, 0.0]]
    for k in range(segments):
        i, j = 2 * k, 2 * ((k + 1) % segments)
        T += [(i, j, j + 1), (i, j + 1, i + 1)]
    for z, nz in ((-h, -1.0), (h, 1.0)):
        centre = len(P)
        P.append([0.0, 0.0, z])
        N.append([0.0, 0.0, nz])
        ring = len(P)
        for k in range(segments):
            a = 2 * math.pi * k / segments
            P.append([radius * math.cos(a), radius * math.sin(a), z])
            N.append([0.0, 0.0, nz])
        for k in range(segments):
            i, j = ring + k, ring + (k + 1) % segments
            T.append((centre, i, j) if nz > 0 else (centre, j, i))
    return P, N, T


def rot_rpy(rpy_deg):
    """Extrinsic roll-pitch-yaw about fixed x, y, z (the scene YAML's): R = Rz Ry Rx."""
    r, p, y = (math.radians(a) for a in rpy_deg)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def apply(R, v):
    return [sum(R[i][k] * v[k] for k in range(3)) for i in range(3)]


class Part:
    """A node's triangles, one primitive per colour."""

    def __init__(self, name):
        self.name = name
        self.by_colour = {}

    def add(self, solid, colour, at=(0.0, 0.0, 0.0), rpy_deg=(0.0, 0.0, 0.0)):
        P, N, T = solid
        R = rot_rpy(rpy_deg)
        prim = self.by_colour.setdefault(tuple(colour), ([], [], []))
        base = len(prim[0])
        prim[0].extend([a + b for a, b in zip(apply(R, p), at)] for p in P)
        prim[1].extend(apply(R, n) for n in N)
        prim[2].extend((t[0] + base, t[1] + base, t[2] + base) for t in T)

    def triangles(self):
        return sum(len(p[2]) for p in self.by_colour.values())


# ---- the cockpit (metres; each part in its object's frame, as config/cockpit.yaml places it) ---

PANEL = (0.16, 0.17, 0.18)
RIM = (0.10, 0.10, 0.11)
SCREW = (0.55, 0.55, 0.57)
BLACK = (0.035, 0.035, 0.038)
GREY = (0.42, 0.43, 0.45)
PEDESTAL = (0.30, 0.31, 0.33)
DARK_PLATE = (0.12, 0.12, 0.13)
WALL = (0.30, 0.31, 0.33)
FABRIC = (0.13, 0.15, 0.20)
FRAME = (0.24, 0.25, 0.27)
METAL = (0.45, 0.46, 0.48)
CARPET = (0.22, 0.22, 0.24)


def screw(part, at, axis_rpy):
    part.add(cylinder(0.0035, 0.002, 16), SCREW, at, axis_rpy)


def instrument_panel():
    """The panel's frame: x out of its back (the face, toward the pilot, at x = -0.015), y along
    its span, z up its face. The face stays flat; a raised rim 12 mm wide frames it."""
    p = Part("InstrumentPanel")
    p.add(rounded_box((0.015, 0.55, 0.175), 0.004, band=6), PANEL)
    rim_x = -0.015 - 0.0015
    for z in (-0.169, 0.169):  # top and bottom rails
        p.add(rounded_box((0.0015, 0.55, 0.006), 0.0012, band=4), RIM, (rim_x, 0.0, z))
    for y in (-0.544, 0.544):  # the ends
        p.add(rounded_box((0.0015, 0.006, 0.163), 0.0012, band=4), RIM, (rim_x, y, 0.0))
    for k in range(21):  # screws along the rails, every 5.4 cm
        y = -0.54 + 1.08 * k / 20
        for z in (-0.169, 0.169):
            screw(p, (rim_x - 0.0015, y, z), (0, 90, 0))
    for k in range(7):
        z = -0.15 + 0.30 * k / 6
        for y in (-0.544, 0.544):
            screw(p, (rim_x - 0.0015, y, z), (0, 90, 0))
    return p


def glareshield():
    """A padded hood over the panel's top: the box's top (z 0.015) and a rounded lip toward the
    pilot that hangs 12 mm below it, with a coaming strip along its edge."""
    p = Part("Glareshield")
    p.add(rounded_box((0.11, 0.58, 0.015), 0.014, band=10), BLACK)
    p.add(rounded_box((0.018, 0.575, 0.021), 0.016, band=10), BLACK, (-0.092, 0.0, -0.006))
    return p


def console(name, half, colour, plate):
    """A console: a box with edges rounded 12 mm (its top flat inside that, where things rest),
    a darker plate set into the top (0.2 mm proud, so what rests on the box's top is drawn on
    it) with four flush screw heads, and a kick strip at the floor."""
    p = Part(name)
    p.add(rounded_box(half, 0.012, band=8), colour)
    hx, hy, hz = half
    p.add(rounded_box((hx - 0.02, hy - 0.02, 0.001), 0.0008, band=3), plate,
          (0.0, 0.0, hz - 0.0008))
    for sx in (-1, 1):
        for sy in (-1, 1):
            p.add(cylinder(0.0035, 0.001, 16), SCREW, (sx * (hx - 0.03), sy * (hy - 0.03), hz - 0.0002))
    p.add(rounded_box((hx + 0.003, hy + 0.003, 0.03), 0.004, band=4), BLACK,
          (0.0, 0.0, -hz + 0.03))
    return p


def side_wall(name, inner_sign):
    """A side wall (its inner face toward the cockpit's middle at y = -inner_sign * 0.025 in its
    frame) with an armrest ledge along its top."""
    p = Part(name)
    p.add(rounded_box((0.55, 0.025, 0.50), 0.01, band=6), WALL)
    y = -inner_sign * 0.045
    p.add(rounded_box((0.30, 0.03, 0.025), 0.015, band=8), FABRIC, (-0.35, y, 0.17))
    for k in range(6):
        x = -0.5 + 1.0 * k / 5
        screw(p, (x, -inner_sign * 0.026, 0.46), (90, 0, 0))
    return p


def floor_with_seat():
    """The floor (the box's top at z = 0.05 in its frame, 0 in the cockpit's) with the pilot's
    seat behind the hands and the rudder pedals under the panel. The floor's frame sits at
    (0.5, 0, -0.05) in the cockpit."""
    p = Part("Floor")
    off = (-0.5, 0.0, 0.05)  # the cockpit's origin in the floor's frame

    def at(x, y, z):
        return (x + off[0], y + off[1], z + off[2])

    p.add(rounded_box((1.5, 1.0, 0.05), 0.01, band=4), CARPET)
    # the seat: pan, back, headrest, on a frame of rails and legs
    p.add(rounded_box((0.21, 0.22, 0.05), 0.04, band=14), FABRIC, at(0.03, 0.0, 0.44))
    p.add(rounded_box((0.05, 0.22, 0.27), 0.04, band=14), FABRIC, at(-0.15, 0.0, 0.76), (0, -12, 0))
    p.add(rounded_box((0.04, 0.13, 0.07), 0.03, band=12), FABRIC, at(-0.24, 0.0, 1.13), (0, -12, 0))
    for y in (-0.18, 0.18):
        p.add(rounded_box((0.24, 0.015, 0.015), 0.006, band=4), METAL, at(0.0, y, 0.375))
        for x in (-0.17, 0.17):
            p.add(rounded_box((0.015, 0.015, 0.18), 0.006, band=4), METAL, at(x, y, 0.19))
    for y in (-0.25, 0.25):  # seat rails on the floor
        p.add(rounded_box((0.3, 0.012, 0.008), 0.004, band=4), METAL, at(0.0, y, 0.008))
    # rudder pedals: each a pad on an arm hung from under the panel
    for y in (-0.16, 0.16):
        p.add(rounded_box((0.012, 0.055, 0.075), 0.008, band=8), BLACK, at(0.62, y, 0.24), (0, -25, 0))
        p.add(rounded_box((0.012, 0.012, 0.16), 0.006, band=4), METAL, at(0.68, y, 0.42), (0, -10, 0))
        for z in (0.19, 0.22, 0.25, 0.28):  # the pad's grip ribs
            p.add(rounded_box((0.003, 0.05, 0.003), 0.002, band=3), METAL,
                  at(0.607 + (z - 0.24) * math.tan(math.radians(25)), y, z), (0, -25, 0))
    return p


def canopy_with_frame():
    """The roof (the box of 1.2 x 1.3 x 0.05 m at (0.35, 0, 1.625)) and the windshield's frame:
    the posts at its sides and middle, the bow along its top, and the bows between the side
    windows and the roof."""
    p = Part("Canopy")
    c = (0.35, 0.0, 1.625)

    def at(x, y, z):
        return (x - c[0], y - c[1], z - c[2])

    p.add(rounded_box((0.60, 0.65, 0.025), 0.01, band=6), WALL)
    for y in (-0.62, 0.0, 0.62):  # posts: the windscreen's sides and its middle
        half_w = 0.03 if y else 0.018
        p.add(rounded_box((0.022, half_w, 0.27), 0.012, band=6), FRAME, at(0.89, y, 1.34))
    p.add(rounded_box((0.03, 0.65, 0.025), 0.012, band=6), FRAME, at(0.88, 0.0, 1.585))
    p.add(rounded_box((0.03, 0.65, 0.02), 0.01, band=6), FRAME, at(0.88, 0.0, 1.09))
    for y in (-0.62, 0.62):  # the side windows' frames
        p.add(rounded_box((0.55, 0.025, 0.02), 0.01, band=6), FRAME, at(0.35, y, 1.585))
        p.add(rounded_box((0.02, 0.025, 0.30), 0.01, band=6), FRAME, at(-0.19, y, 1.30))
    return p


def cockpit_parts():
    return [
        instrument_panel(),
        glareshield(),
        console("CentreConsole", (0.20, 0.15, 0.35), GREY, DARK_PLATE),
        console("LeftPedestal", (0.10, 0.095, 0.35), PEDESTAL, DARK_PLATE),
        side_wall("LeftWall", +1),
        side_wall("RightWall", -1),
        floor_with_seat(),
        canopy_with_frame(),
    ]


# ---- glTF 2.0 binary ----------------------------------------------------------------------------


def to_gltf_axes(v):
    return (v[0], v[2], -v[1])


def write_glb(parts, path):
    blob = bytearray()
    views, accessors, meshes, nodes, materials = [], [], [], [], []
    material_of = {}

    def view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    for part in parts:
        primitives = []
        for colour, (P, N, T) in part.by_colour.items():
            if colour not in material_of:
                material_of[colour] = len(materials)
                materials.append({"pbrMetallicRoughness": {"baseColorFactor": [*colour, 1.0],
                                                           "metallicFactor": 0.0,
                                                           "roughnessFactor": 0.8}})
            pos = array("f", [c for p in P for c in to_gltf_axes(p)])
            nor = array("f", [c for n in N for c in to_gltf_axes(n)])
            idx = array("I", [i for t in T for i in t])
            lo = [min(pos[k::3]) for k in range(3)]
            hi = [max(pos[k::3]) for k in range(3)]
            accessors.append({"bufferView": view(pos.tobytes(), 34962), "componentType": 5126,
                              "count": len(P), "type": "VEC3", "min": lo, "max": hi})
            accessors.append({"bufferView": view(nor.tobytes(), 34962), "componentType": 5126,
                              "count": len(N), "type": "VEC3"})
            accessors.append({"bufferView": view(idx.tobytes(), 34963), "componentType": 5125,
                              "count": len(idx), "type": "SCALAR"})
            n = len(accessors)
            primitives.append({"attributes": {"POSITION": n - 3, "NORMAL": n - 2},
                               "indices": n - 1, "material": material_of[colour]})
        meshes.append({"name": part.name, "primitives": primitives})
        nodes.append({"name": part.name, "mesh": len(meshes) - 1})
    doc = {
        "asset": {"version": "2.0", "generator": "vcockpit scripts/make_cockpit_model.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob.extend(b"\0" * (-len(blob) % 4))
    total = 12 + 8 + len(text) + 8 + len(blob)
    out = struct.pack("<4sII", b"glTF", 2, total)
    out += struct.pack("<I4s", len(text), b"JSON") + text
    out += struct.pack("<I4s", len(blob), b"BIN\0") + bytes(blob)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(f".glb.{os.getpid()}.part")  # written whole, then renamed
    temporary.write_bytes(out)
    temporary.replace(path)


def file_name(part):
    """InstrumentPanel -> instrument_panel.glb"""
    return "".join("_" + c.lower() if c.isupper() else c for c in part.name).lstrip("_") + ".glb"


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else \
        Path(__file__).resolve().parent.parent / "config" / "models" / "cockpit"
    parts = cockpit_parts()
    # one file a part: a reader reads (and post-processes) a whole file for any node of it, and
    # each process that loads the scene reads each part once
    for part in parts:
        write_glb([part], out / file_name(part))
    total = sum(p.triangles() for p in parts)
    print(f"{out}: {len(parts)} parts, {total} triangles")


if __name__ == "__main__":
    main()
