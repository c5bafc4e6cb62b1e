#!/usr/bin/env python3
"""Writes a glTF 2.0 grid of spheres over glTF's material model: metallic grows left to right
(0 to 1), roughness bottom to top (0 to 1), one material each, on a grey floor, with a camera and
a sun and a point light (KHR_lights_punctual). Every backend renders it the same; the grid shows
the model continuous in both factors, as every glTF viewer's sample of it does.

Usage: tools/make_material_grid.py [out.gltf] [count]   (default: material-grid.gltf, 5 a side)
Render: photon-render material-grid.gltf --width 640 --height 480 -o grid.png
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path

from uv_sphere import sphere


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("material-grid.gltf")
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    if not 1 <= count <= 16:
        sys.exit("make_material_grid.py: count must be 1 to 16")
    positions, _, _, triangles = sphere(1.0, 24, 48)
    floor = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
    blob = bytearray()
    views = []

    def view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    flat = [c for p in positions for c in p]
    sphere_positions = view(struct.pack("<%df" % len(flat), *flat), 34962)
    sphere_indices = view(struct.pack("<%dI" % (3 * len(triangles)), *[i for t in triangles for i in t]), 34963)
    floor_flat = [c for p in floor for c in p]
    floor_positions = view(struct.pack("<12f", *floor_flat), 34962)
    floor_normals = view(struct.pack("<12f", *([0, 1, 0] * 4)), 34962)
    floor_indices = view(struct.pack("<6I", 0, 2, 1, 0, 3, 2), 34963)
    accessors = [
        {"bufferView": sphere_positions, "componentType": 5126, "type": "VEC3", "count": len(positions),
         "min": [-1, -1, -1], "max": [1, 1, 1]},
        {"bufferView": sphere_indices, "componentType": 5125, "type": "SCALAR", "count": 3 * len(triangles)},
        {"bufferView": floor_positions, "componentType": 5126, "type": "VEC3", "count": 4,
         "min": [-1, 0, -1], "max": [1, 0, 1]},
        {"bufferView": floor_normals, "componentType": 5126, "type": "VEC3", "count": 4},
        {"bufferView": floor_indices, "componentType": 5125, "type": "SCALAR", "count": 6},
    ]
    materials = [{"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                            "metallicFactor": 0, "roughnessFactor": 1}}]
    meshes = [{"name": "floor", "primitives": [{"attributes": {"POSITION": 2, "NORMAL": 3}, "indices": 4, "material": 0}]}]
    nodes = [{"name": "floor", "mesh": 0, "scale": [count + 2, 1, count + 2], "translation": [0, -0.5, 0]}]
    spacing = 1.25
    for row in range(count):
        for column in range(count):
            metallic = column / max(count - 1, 1)
            roughness = row / max(count - 1, 1)
            materials.append({"name": f"metallic {metallic:.2f} roughness {roughness:.2f}",
                              "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1],
                                                       "metallicFactor": metallic, "roughnessFactor": roughness}})
            meshes.append({"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 0}, "indices": 1,
                                           "material": len(materials) - 1}]})
            x = (column - (count - 1) / 2) * spacing
            y = row * spacing
            nodes.append({"name": materials[-1]["name"], "mesh": len(meshes) - 1, "translation": [x, y, 0],
                          "scale": [0.5, 0.5, 0.5]})
    # The camera looks down -z at the middle of the grid; the sun from behind its right shoulder.
    height = (count - 1) * spacing / 2
    distance = count * spacing * 1.6 + 2
    nodes.append({"name": "camera", "camera": 0, "translation": [0, height, distance]})
    nodes.append({"name": "sun", "rotation": [-0.3535534, 0.3535534, 0.1464466, 0.8535534],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes.append({"name": "lamp", "translation": [-count, count * 1.5, count],
                  "extensions": {"KHR_lights_punctual": {"light": 1}}})
    gltf = {
        "asset": {"version": "2.0", "generator": "photon tools/make_material_grid.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "color": [1, 0.96, 0.9], "intensity": 1500},
            {"name": "lamp", "type": "point", "color": [0.9, 0.95, 1], "intensity": 20000}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": math.radians(40), "znear": 0.1}}],
    }
    out.write_text(json.dumps(gltf, indent=1))
    print(f"{out}: {count}x{count} spheres")


if __name__ == "__main__":
    main()
