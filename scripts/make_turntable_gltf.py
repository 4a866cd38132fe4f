#!/usr/bin/env python3
"""Writes scenes/meshes/turntable.gltf: a node hierarchy that moves, for the tests and docs.

A grey pillar stands still at the origin. A turntable node (no mesh of its own) turns about y,
once in two seconds, carrying two children: a red box and a blue box that also rises, shrinks
and comes back (its own channels, composed with its parent's turn). Animation "Spin" does all
of that; animation "Hop" only lifts the red box by 1 over a second.

    scripts/make_turntable_gltf.py > scenes/meshes/turntable.gltf
"""
import base64
import json
import math
import struct

# A unit cube, four corners a face (so that each face has its own normal), wound outwards.
FACES = [((1, 0, 0), (0, 1, 0), (0, 0, 1)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
         ((0, 1, 0), (0, 0, 1), (1, 0, 0)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
         ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (0, 1, 0), (1, 0, 0))]
positions, normals, indices = [], [], []
for n, u, v in FACES:
    base = len(positions)
    for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        positions.append([0.5 * (n[i] + su * u[i] + sv * v[i]) for i in range(3)])
        normals.append(list(n))
    indices += [base, base + 1, base + 2, base, base + 2, base + 3]


def y_turn(degrees):
    half = math.radians(degrees) / 2
    return [0.0, math.sin(half), 0.0, math.cos(half)]  # glTF: x, y, z, w


blob = bytearray()
views, accessors = [], []


def add(values, kind, component, fmt, target=None, bounds=False):
    flat = [x for v in values for x in (v if isinstance(v, list) else [v])]
    data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
    while len(blob) % 4:
        blob.append(0)
    view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
    if target:
        view["target"] = target
    blob.extend(data)
    views.append(view)
    accessor = {"bufferView": len(views) - 1, "componentType": component, "count": len(values),
                "type": kind}
    if bounds:
        width = len(values[0]) if isinstance(values[0], list) else 1
        column = [[v[i] if isinstance(v, list) else v for v in values] for i in range(width)]
        accessor["min"] = [min(c) for c in column]
        accessor["max"] = [max(c) for c in column]
    accessors.append(accessor)
    return len(accessors) - 1


FLOAT, UINT16 = 5126, 5123
position = add(positions, "VEC3", FLOAT, "f", 34962, bounds=True)
normal = add(normals, "VEC3", FLOAT, "f", 34962)
index = add(indices, "SCALAR", UINT16, "H", 34963)
quarter_turns = [0.0, 0.5, 1.0, 1.5, 2.0]
spin_times = add(quarter_turns, "SCALAR", FLOAT, "f", bounds=True)
spin_turns = add([y_turn(90 * k) for k in range(5)], "VEC4", FLOAT, "f")
bob_times = add([0.0, 1.0, 2.0], "SCALAR", FLOAT, "f", bounds=True)
bob_moves = add([[-1.5, 1.0, 0.0], [-1.5, 2.0, 0.0], [-1.5, 1.0, 0.0]], "VEC3", FLOAT, "f")
bob_scales = add([[0.6] * 3, [0.3] * 3, [0.6] * 3], "VEC3", FLOAT, "f")
hop_times = add([0.0, 1.0], "SCALAR", FLOAT, "f", bounds=True)
hop_moves = add([[1.5, 0.5, 0.0], [1.5, 1.5, 0.0]], "VEC3", FLOAT, "f")

materials = [("Red", [0.8, 0.1, 0.1, 1]), ("Blue", [0.1, 0.2, 0.8, 1]),
             ("Stone", [0.6, 0.6, 0.6, 1])]
gltf = {
    "asset": {"version": "2.0", "generator": "scripts/make_animated_gltf.py"},
    "scene": 0,
    "scenes": [{"name": "Turntable scene", "nodes": [0, 1]}],
    "nodes": [
        {"name": "Pillar", "mesh": 2, "translation": [0, 1, 0], "scale": [0.4, 2, 0.4]},
        {"name": "Turntable", "children": [2, 3]},
        {"name": "Box", "mesh": 0, "translation": [1.5, 0.5, 0]},
        {"name": "Bob", "mesh": 1, "translation": [-1.5, 1, 0], "scale": [0.6, 0.6, 0.6]},
    ],
    "meshes": [{"name": name + "Cube", "primitives": [
        {"attributes": {"POSITION": position, "NORMAL": normal}, "indices": index,
         "material": m}]} for m, (name, _) in enumerate(materials)],
    "materials": [{"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour}}
                  for name, colour in materials],
    "animations": [
        {"name": "Spin",
         "samplers": [{"input": spin_times, "output": spin_turns},
                      {"input": bob_times, "output": bob_moves},
                      {"input": bob_times, "output": bob_scales}],
         "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                      {"sampler": 1, "target": {"node": 3, "path": "translation"}},
                      {"sampler": 2, "target": {"node": 3, "path": "scale"}}]},
        {"name": "Hop",
         "samplers": [{"input": hop_times, "output": hop_moves}],
         "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}}]},
    ],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," +
                        base64.b64encode(bytes(blob)).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
print(json.dumps(gltf, indent=1))
