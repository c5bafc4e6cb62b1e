#!/usr/bin/env python3
"""Writes scenes/textured.glb: a glTF 2.0 scene that exercises what the glTF loader maps.

A checkerboard floor and a brick-striped back wall (base-colour textures, embedded PNGs, sRGB,
repeat and mirrored-repeat samplers; the wall's mortar carved by a normal texture), a textured box
on a node hierarchy (translation, rotation, scale) whose metallic-roughness texture makes its
squares alternately rough paint and polished metal, a glass sphere (KHR_materials_transmission,
_ior and _volume: a solid, tinted body) that throws a caustic, a mirror-metal sphere, an emissive panel (an area light of emissive triangles), a perspective camera,
and KHR_lights_punctual: the sun (directional) and a spot. Python's standard library only: the
PNGs are written with zlib, the binary chunk with struct.

Usage: tools/make_textured_scene.py [out.glb]   (default: scenes/textured.glb next to this script)
"""
import json
import math
import struct
import sys
import zlib
from pathlib import Path

from uv_sphere import sphere


def png(width, height, pixel):
    """An 8-bit RGB PNG of pixel(x, y) -> (r, g, b)."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def brick_normals(x, y):
    """Tangent-space normals of the bricks: the mortar lines are grooves (their edges lean out)."""
    row = y // 8
    u = (x + (4 if row % 2 else 0)) % 16
    v = y % 8
    nx = -0.6 if u == 1 else (0.6 if u == 15 else 0.0)
    ny = 0.6 if v == 1 else (-0.6 if v == 7 else 0.0)
    length = math.sqrt(nx * nx + ny * ny + 1)
    return tuple(int(round((c / length * 0.5 + 0.5) * 255)) for c in (nx, ny, 1.0))


def metal_squares(x, y):
    """Metallic-roughness texels: green roughness, blue metallic; polished metal on every other square."""
    metal = (x // 8 + y // 8) % 2 == 1
    return (0, 40, 255) if metal else (0, 230, 0)


def checker(x, y):
    return (225, 220, 205) if (x // 8 + y // 8) % 2 == 0 else (60, 70, 95)


def bricks(x, y):
    row = y // 8
    mortar = y % 8 == 0 or (x + (4 if row % 2 else 0)) % 16 == 0
    return (200, 195, 185) if mortar else (150 + 8 * (row % 3), 62, 42)


class Builder:
    def __init__(self):
        self.binary = bytearray()
        self.gltf = {"asset": {"version": "2.0", "generator": "photon tools/make_textured_scene.py"},
                     "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "nodes": [],
                     "materials": [], "textures": [], "images": [], "samplers": []}

    def view(self, data, target=None):
        while len(self.binary) % 4:
            self.binary += b"\0"
        view = {"buffer": 0, "byteOffset": len(self.binary), "byteLength": len(data)}
        if target:
            view["target"] = target
        self.binary += data
        self.gltf["bufferViews"].append(view)
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, values, kind, components):
        flat = [c for v in values for c in (v if components > 1 else (v,))]
        if kind == "indices":
            data = struct.pack("<%dI" % len(flat), *flat)
            accessor = {"componentType": 5125, "type": "SCALAR", "count": len(flat),
                        "bufferView": self.view(data, 34963)}
        else:
            data = struct.pack("<%df" % len(flat), *flat)
            accessor = {"componentType": 5126, "type": {2: "VEC2", 3: "VEC3"}[components], "count": len(values),
                        "bufferView": self.view(data, 34962)}
            if kind == "positions":
                accessor["min"] = [min(v[i] for v in values) for i in range(3)]
                accessor["max"] = [max(v[i] for v in values) for i in range(3)]
        self.gltf["accessors"].append(accessor)
        return len(self.gltf["accessors"]) - 1

    def mesh(self, positions, normals, texcoords, triangles, material):
        attributes = {"POSITION": self.accessor(positions, "positions", 3), "NORMAL": self.accessor(normals, "normals", 3)}
        if texcoords:
            attributes["TEXCOORD_0"] = self.accessor(texcoords, "texcoords", 2)
        indices = self.accessor([i for t in triangles for i in t], "indices", 1)
        self.gltf["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices, "material": material}]})
        return len(self.gltf["meshes"]) - 1

    def material(self, description):
        self.gltf["materials"].append(description)
        return len(self.gltf["materials"]) - 1

    def texture(self, image_bytes, wrap_s, wrap_t):
        self.gltf["images"].append({"mimeType": "image/png", "bufferView": self.view(image_bytes)})
        self.gltf["samplers"].append({"wrapS": wrap_s, "wrapT": wrap_t, "magFilter": 9729, "minFilter": 9729})
        self.gltf["textures"].append({"source": len(self.gltf["images"]) - 1, "sampler": len(self.gltf["samplers"]) - 1})
        return len(self.gltf["textures"]) - 1

    def node(self, **node):
        self.gltf["nodes"].append(node)
        return len(self.gltf["nodes"]) - 1

    def glb(self):
        self.gltf["buffers"].append({"byteLength": len(self.binary)})
        text = json.dumps(self.gltf, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        binary = bytes(self.binary) + b"\0" * (-len(self.binary) % 4)
        total = 12 + 8 + len(text) + 8 + len(binary)
        return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
                struct.pack("<II", len(binary), 0x004E4942) + binary)


def quad(width, height, repeats):
    """A unit-normal +z quad centred at the origin, texture coordinates repeating `repeats` times."""
    w, h = width / 2, height / 2
    positions = [(-w, -h, 0), (w, -h, 0), (w, h, 0), (-w, h, 0)]
    texcoords = [(0, repeats[1]), (repeats[0], repeats[1]), (repeats[0], 0), (0, 0)]
    return positions, [(0, 0, 1)] * 4, texcoords, [(0, 1, 2), (0, 2, 3)]


def box():
    """A unit cube about the origin, each face its own four vertices and texture square."""
    positions, normals, texcoords, triangles = [], [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v = [0, 0, 0]
            v[(axis + 2) % 3] = 1
            if sign < 0:
                u, v = v, u
            base = len(positions)
            for (a, b), st in zip(((-1, -1), (1, -1), (1, 1), (-1, 1)), ((0, 1), (1, 1), (1, 0), (0, 0))):
                positions.append(tuple(0.5 * (n[i] + a * u[i] + b * v[i]) for i in range(3)))
                normals.append(tuple(n))
                texcoords.append(st)
            triangles += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return positions, normals, texcoords, triangles


def quaternion(degrees, axis):
    s = math.sin(math.radians(degrees) / 2)
    length = math.sqrt(sum(c * c for c in axis))
    return [s * c / length for c in axis] + [math.cos(math.radians(degrees) / 2)]


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenes" / "textured.glb"
    g = Builder()
    repeat, mirrored = 10497, 33648
    floor_tex = g.texture(png(64, 64, checker), repeat, repeat)
    wall_tex = g.texture(png(64, 64, bricks), mirrored, repeat)
    floor = g.material({"name": "checker floor", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": floor_tex}, "metallicFactor": 0, "roughnessFactor": 1}})
    wall_normals = g.texture(png(64, 64, brick_normals), mirrored, repeat)
    crate_mr = g.texture(png(64, 64, metal_squares), repeat, repeat)
    wall = g.material({"name": "brick wall", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": wall_tex}, "metallicFactor": 0, "roughnessFactor": 1},
        "normalTexture": {"index": wall_normals, "scale": 1.0}})
    crate = g.material({"name": "crate", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": floor_tex}, "baseColorFactor": [0.9, 0.75, 0.5, 1], "metallicFactor": 1,
        "roughnessFactor": 1, "metallicRoughnessTexture": {"index": crate_mr}}})
    glass = g.material({"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0,
                                                                  "baseColorFactor": [1, 1, 1, 1]},
                        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                       "KHR_materials_ior": {"ior": 1.5},
                                       "KHR_materials_volume": {"thicknessFactor": 0.9, "attenuationDistance": 2.0,
                                                                "attenuationColor": [0.85, 0.95, 1.0]}}})
    chrome = g.material({"name": "chrome", "pbrMetallicRoughness": {
        "baseColorFactor": [0.95, 0.93, 0.88, 1], "metallicFactor": 1, "roughnessFactor": 0}})
    panel = g.material({"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                        "emissiveFactor": [1, 0.85, 0.6],
                        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12}}})

    floor_mesh = g.mesh(*quad(9, 7, (4, 3)), floor)
    wall_mesh = g.mesh(*quad(9, 3.5, (3, 1)), wall)
    box_mesh = g.mesh(*box(), crate)
    glass_mesh = g.mesh(*sphere(0.45, 24, 48), glass)
    chrome_mesh = g.mesh(*sphere(0.35, 16, 32), chrome)
    panel_mesh = g.mesh(*quad(0.8, 0.4, (1, 1)), panel)

    nodes = [
        g.node(name="floor", mesh=floor_mesh, rotation=quaternion(-90, (1, 0, 0))),
        g.node(name="wall", mesh=wall_mesh, translation=[0, 1.75, -2]),
        g.node(name="panel", mesh=panel_mesh, translation=[0.9, 2.5, -1.98]),
        g.node(name="glass sphere", mesh=glass_mesh, translation=[0.2, 0.45, 0.4]),
    ]
    # A table of a box carrying a smaller box: the child's transform composes with its parent's.
    small = g.node(name="small box", mesh=box_mesh, translation=[0, 0.8, 0], rotation=quaternion(30, (0, 1, 0)),
                   scale=[0.6, 0.6, 0.6])
    chrome_node = g.node(name="chrome sphere", mesh=chrome_mesh, translation=[0, 1.45, 0], scale=[1 / 0.6] * 3)
    g.gltf["nodes"][small]["children"] = [chrome_node]
    nodes.append(g.node(name="box", mesh=box_mesh, translation=[-1.2, 0.5, -0.6], rotation=quaternion(-20, (0, 1, 0)),
                        children=[small]))

    g.gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": math.radians(45), "aspectRatio": 4 / 3,
                                                                 "znear": 0.05}}]
    eye, target = (0.6, 1.6, 4.6), (-0.2, 0.7, 0.0)
    forward = [t - e for t, e in zip(target, eye)]
    yaw = math.degrees(math.atan2(-forward[0], -forward[2]))
    pitch = math.degrees(math.atan2(forward[1], math.hypot(forward[0], forward[2])))
    # Camera orientation: yaw about y, then pitch about the camera's x.
    qy, qx = quaternion(yaw, (0, 1, 0)), quaternion(pitch, (1, 0, 0))
    q = [qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
         qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
         qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
         qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2]]
    nodes.append(g.node(name="camera", camera=0, translation=list(eye), rotation=q))

    g.gltf["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                "KHR_materials_emissive_strength", "KHR_materials_volume"]
    g.gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1, 0.95, 0.85], "intensity": 2000},
        {"name": "spot", "type": "spot", "color": [0.8, 0.9, 1], "intensity": 4000,
         "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}}]}}
    # The sun from the upper right, behind the camera's shoulder; the spot from above the glass.
    nodes.append(g.node(name="sun", rotation=quaternion(-55, (1, -0.6, 0)), extensions={"KHR_lights_punctual": {"light": 0}}))
    nodes.append(g.node(name="spot", translation=[0.8, 3.2, 1.2], rotation=quaternion(-80, (1, 0.3, 0)),
                        extensions={"KHR_lights_punctual": {"light": 1}}))
    g.gltf["scenes"] = [{"name": "textured", "nodes": nodes}]
    g.gltf["scene"] = 0
    data = g.glb()
    out.write_bytes(data)
    print(f"{out}: {len(data)} bytes")


if __name__ == "__main__":
    main()
