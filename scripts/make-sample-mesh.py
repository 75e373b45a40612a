#!/usr/bin/python3
"""Writes Data/meshes/trefoil-knot.ply, the project's small sample mesh: a tube of radius 0.012 m
around a (2, 3) torus knot of overall size about 0.2 m, 96 x 12 quads split into 2304 triangles,
outward normals, binary little-endian PLY. Usage: scripts/make-sample-mesh.py [OUT.ply]"""
import struct
import sys

import numpy as np

ALONG, AROUND, TUBE, SCALE = 96, 12, 0.012, 0.035


def knot(t):
    r = 2.0 + np.cos(3.0 * t)
    return SCALE * np.stack([r * np.cos(2.0 * t), r * np.sin(2.0 * t), -np.sin(3.0 * t)], -1)


def main(out):
    t = np.linspace(0.0, 2.0 * np.pi, ALONG, endpoint=False)
    centre = knot(t)
    tangent = knot(t + 1e-4) - knot(t - 1e-4)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    # A frame along the curve: any vector not along the tangent, made orthogonal to it.
    normal = np.cross(tangent, [0.0, 0.0, 1.0])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    binormal = np.cross(tangent, normal)
    a = np.linspace(0.0, 2.0 * np.pi, AROUND, endpoint=False)
    ring = np.cos(a)[None, :, None] * normal[:, None] + np.sin(a)[None, :, None] * binormal[:, None]
    points = (centre[:, None] + TUBE * ring).reshape(-1, 3)
    faces = []
    for i in range(ALONG):
        for j in range(AROUND):
            p = [i * AROUND + j, i * AROUND + (j + 1) % AROUND,
                 ((i + 1) % ALONG) * AROUND + (j + 1) % AROUND, ((i + 1) % ALONG) * AROUND + j]
            faces += [(p[0], p[2], p[1]), (p[0], p[3], p[2])]
    # Outward: the ring's (n, b) turn with the tangent; flip all if the first face points inward.
    f = faces[0]
    face_normal = np.cross(points[f[1]] - points[f[0]], points[f[2]] - points[f[0]])
    if np.dot(face_normal, points[f[0]] - centre[0]) < 0:
        faces = [(f[0], f[2], f[1]) for f in faces]
    with open(out, "wb") as stream:
        stream.write((
            "ply\nformat binary_little_endian 1.0\n"
            "comment CatadioptricAR sample mesh: a (2, 3) torus knot (scripts/make-sample-mesh.py)\n"
            f"element vertex {len(points)}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
        ).encode())
        stream.write(points.astype("<f4").tobytes())
        for f in faces:
            stream.write(struct.pack("<Biii", 3, *f))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "Data/meshes/trefoil-knot.ply")
