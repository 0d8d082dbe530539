#!/usr/bin/env python3
"""Writes the small model files the mesh tests load (tests/data/models/), the same solids in each
of the three formats the scene YAML reads: glTF 2.0 (.gltf, its buffer inline), Wavefront OBJ and
AC3D. Made by the project, under its licence. Run from anywhere:
    scripts/make_test_models.py [OUT_DIR]
Coordinates are written in the files' own convention, +y up (glTF's, and Blender's and
FlightGear's for OBJ and AC3D); the project reads them back +z up.

  ramp      a wedge 0.8 m long (x), 0.3 m wide (y), its top a 20 deg slope falling toward +x,
            its bottom on z = 0 (project axes), its node origin at the bottom's centre
  button    a 24 x 24 x 12 mm block with a 2 mm chamfer on its top edges (a push button's cap),
            its origin at its centre
  placard   a textured plate 0.2 m wide (y) and 0.1 m high (z) in the x = 0 plane, its face
            toward -x; its image placard.png (64 x 32 px) is red top left, green top right,
            blue bottom left and yellow bottom right as seen from -x (+y on the left). The glTF
            names the image as a file; placard_embedded.gltf carries it inline.
"""
import base64
import json
import math
import struct
import sys
import zlib
from pathlib import Path


def oriented(vertices, faces):
    """Each face (a list of vertex indices, convex, planar) as triangles facing away from the
    solid's centre: counter-clockwise seen from outside."""
    c = [sum(v[i] for v in vertices) / len(vertices) for i in range(3)]
    out = []
    for f in faces:
        a, b, d = (vertices[f[0]], vertices[f[1]], vertices[f[2]])
        u = [b[i] - a[i] for i in range(3)]
        w = [d[i] - a[i] for i in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        fc = [sum(vertices[k][i] for k in f) / len(f) for i in range(3)]
        if sum(n[i] * (fc[i] - c[i]) for i in range(3)) < 0:
            f = list(reversed(f))
        for k in range(1, len(f) - 1):
            out.append((f[0], f[k], f[k + 1]))
    return out


def ramp():
    t = math.tan(math.radians(20.0))
    h = 0.8 * t
    v = [(-0.4, -0.15, 0.0), (0.4, -0.15, 0.0), (-0.4, -0.15, h),
         (-0.4, 0.15, 0.0), (0.4, 0.15, 0.0), (-0.4, 0.15, h)]
    faces = [[0, 1, 4, 3], [0, 3, 5, 2], [1, 4, 5, 2], [0, 1, 2], [3, 4, 5]]
    return v, faces, (0.55, 0.55, 0.6, 1.0)


def button():
    s, c, hz = 0.012, 0.002, 0.006  # half size, chamfer, half height
    v = []
    for z, r in ((-hz, s), (hz - c, s), (hz, s - c)):
        v += [(-r, -r, z), (r, -r, z), (r, r, z), (-r, r, z)]
    faces = [[0, 1, 2, 3], [8, 9, 10, 11]]
    for ring in (0, 4):
        for k in range(4):
            a, b = ring + k, ring + (k + 1) % 4
            faces.append([a, b, b + 4, a + 4])
    return v, faces, (0.15, 0.15, 0.17, 1.0)


def placard():
    """The plate's corners (project axes) and their texture coordinates (u right, v up from the
    image's bottom row: OBJ's and AC3D's convention)."""
    v = [(0.0, 0.1, -0.05), (0.0, -0.1, -0.05), (0.0, -0.1, 0.05), (0.0, 0.1, 0.05)]
    uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    tris = [(0, 1, 2), (0, 2, 3)]  # counter-clockwise seen from -x
    return v, uv, tris


PLACARD_QUADRANTS = ((255, 0, 0), (0, 200, 0), (0, 0, 255), (255, 255, 0))  # TL, TR, BL, BR


def placard_png(width=64, height=32):
    rows = b""
    for y in range(height):
        rows += b"\0"  # filter: none
        for x in range(width):
            q = (0 if y < height // 2 else 2) + (0 if x < width // 2 else 1)
            rows += bytes(PLACARD_QUADRANTS[q]) + b"\xff"

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def write_placard(out):
    v, uv, tris = placard()
    png = placard_png()
    (out / "placard.png").write_bytes(png)
    (out / "placard.mtl").write_text("newmtl placard\nKd 1 1 1\nmap_Kd placard.png\n")
    lines = ["# placard: made by scripts/make_test_models.py", "mtllib placard.mtl", "o placard",
             "usemtl placard"]
    lines += ["v %.6f %.6f %.6f" % file_axes(p) for p in v]
    lines += ["vt %.6f %.6f" % t for t in uv]
    lines += ["f %d/%d %d/%d %d/%d" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1) for a, b, c in tris]
    (out / "placard.obj").write_text("\n".join(lines) + "\n")
    ac = ["AC3Db", 'MATERIAL "placard" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  shi 10  '
          "trans 0", "OBJECT world", "kids 1", "OBJECT poly", 'name "placard"', 'texture "placard.png"',
          f"numvert {len(v)}"]
    ac += ["%.6f %.6f %.6f" % file_axes(p) for p in v]
    ac.append(f"numsurf {len(tris)}")
    for t in tris:
        ac += ["SURF 0x10", "mat 0", "refs 3"] + ["%d %.6f %.6f" % (i, uv[i][0], uv[i][1]) for i in t]
    ac.append("kids 0")
    (out / "placard.ac").write_text("\n".join(ac) + "\n")
    # glTF's texture coordinates run down from the image's top row
    extra = b"".join(struct.pack("<2f", u, 1.0 - w) for u, w in uv)
    for name, uri in (("placard.gltf", "placard.png"),
                      ("placard_embedded.gltf", "data:image/png;base64," + base64.b64encode(png).decode())):
        write_gltf(out / name, "placard", v, tris, (1.0, 1.0, 1.0, 1.0), texcoords=extra, image_uri=uri)


def file_axes(p):
    """Project (x, y, z), +z up, to the files' +y up: (x, z, -y)."""
    return (p[0], p[2], -p[1])


def write_obj(path, name, v, tris, rgba):
    mtl = path.with_suffix(".mtl")
    mtl.write_text(f"newmtl {name}\nKd {rgba[0]} {rgba[1]} {rgba[2]}\nd {rgba[3]}\n")
    lines = [f"# {name}: made by scripts/make_test_models.py", f"mtllib {mtl.name}", f"o {name}",
             f"usemtl {name}"]
    lines += ["v %.6f %.6f %.6f" % file_axes(p) for p in v]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in tris]
    path.write_text("\n".join(lines) + "\n")


def write_ac(path, name, v, tris, rgba):
    lines = ["AC3Db",
             f'MATERIAL "{name}" rgb {rgba[0]} {rgba[1]} {rgba[2]}  amb 0.2 0.2 0.2  emis 0 0 0  '
             f'spec 0 0 0  shi 10  trans {1.0 - rgba[3]}',
             "OBJECT world", "kids 1", "OBJECT poly", f'name "{name}"', f"numvert {len(v)}"]
    lines += ["%.6f %.6f %.6f" % file_axes(p) for p in v]
    lines.append(f"numsurf {len(tris)}")
    for t in tris:
        lines += ["SURF 0x10", "mat 0", "refs 3"] + [f"{i} 0 0" for i in t]
    lines.append("kids 0")
    path.write_text("\n".join(lines) + "\n")


def write_gltf(path, name, v, tris, rgba, texcoords=b"", image_uri=None):
    positions = [file_axes(p) for p in v]
    pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
    idx_bytes = b"".join(struct.pack("<3H", *t) for t in tris)
    idx_bytes += b"\0" * (-len(idx_bytes) % 4)
    data = pos_bytes + idx_bytes + texcoords
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    gltf = {
        "asset": {"version": "2.0", "generator": "vcockpit scripts/make_test_models.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": name, "mesh": 0}],
        "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                                   "material": 0}]}],
        "materials": [{"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgba),
                                                              "metallicFactor": 0.0}}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
                        {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": 6 * len(tris),
                         "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5123, "count": 3 * len(tris), "type": "SCALAR"}],
    }
    if image_uri:
        gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(pos_bytes) + len(idx_bytes),
                                    "byteLength": len(texcoords), "target": 34962})
        gltf["accessors"].append({"bufferView": 2, "componentType": 5126, "count": len(v), "type": "VEC2"})
        gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2
        gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        gltf["textures"] = [{"source": 0}]
        gltf["images"] = [{"uri": image_uri}]
    path.write_text(json.dumps(gltf, indent=1) + "\n")


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "tests/data/models"
    out.mkdir(parents=True, exist_ok=True)
    for name, make in (("ramp", ramp), ("button", button)):
        v, faces, rgba = make()
        tris = oriented(v, faces)
        write_gltf(out / f"{name}.gltf", name, v, tris, rgba)
        write_obj(out / f"{name}.obj", name, v, tris, rgba)
        write_ac(out / f"{name}.ac", name, v, tris, rgba)
    write_placard(out)
    print(f"wrote the ramp, the button and the placard as .gltf, .obj and .ac in {out}")


if __name__ == "__main__":
    main()
