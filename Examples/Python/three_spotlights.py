#!/usr/bin/env python3
"""Three coloured spotlights (red, green, blue) moving around an object seen in the spherical
mirror: the paper's figure 10. Writes FRAMES PNG frames.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Examples/Python/three_spotlights.py [--mesh ../shared/data/stanford-bunny.obj] \\
        [--frames 12] [--prefix three]

Without --mesh (or when the file is missing) the object is a torus.
"""

import argparse
import math
import os
import sys
import tempfile

import catadioptricar as car

CAMERA = """camera:
  image_width: 1328
  image_height: 1048
  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
"""

COLORS = ((1.0, 0.15, 0.15), (0.15, 1.0, 0.15), (0.2, 0.3, 1.0))


def scene_text(mesh, width, height, shadows):
    if mesh:
        obj = ('  - { type: mesh, file: "%s", rotate: [ 90, 0, 0 ], scale: 1.2, '
               'translate: [ 0.0, -0.25, 0.75 ], color: [ 0.9, 0.9, 0.9 ], '
               'material: { ambient: 0.2, diffuse: 0.9, specular: 0.4, specular_power: 30 } }\n' % mesh)
    else:
        obj = ('  - { type: torus, radius: 0.08, tube_radius: 0.03, resolution: 96, '
               'translate: [ 0.0, -0.25, 0.9 ], rotate: [ 60, 0, 0 ], color: [ 0.9, 0.9, 0.9 ], '
               'material: { ambient: 0.2, diffuse: 0.9, specular: 0.4, specular_power: 30 } }\n')
    lights = "".join(
        "    - { type: spot, position: [ 0.0, 0.0, 1.3 ], focal_point: [ 0.0, -0.25, 0.9 ], "
        "cone_angle: 30, exponent: 2, color: [ %g, %g, %g ] }\n" % c for c in COLORS)
    return ("---\n%soutput: { width: %d, height: %d }\n"
            "background: { type: environment, samples: 1 }\n"
            "lighting:\n  shading: gouraud\n  shadows: %d\n  global_ambient: [ 0.15, 0.15, 0.15 ]\n"
            "  lights:\n%sobjects:\n%s" % (CAMERA, width, height, 1 if shadows else 0, lights, obj))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="", help="a Stanford mesh (y up, metres)")
    parser.add_argument("--frames", type=int, default=12)
    parser.add_argument("--size", type=int, nargs=2, default=(664, 524))
    parser.add_argument("--prefix", default="three-spotlights")
    args = parser.parse_args()
    mesh = os.path.abspath(args.mesh) if args.mesh and os.path.exists(args.mesh) else ""
    car.enable_threads()

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.yaml")
        with open(path, "w") as f:
            f.write(scene_text(mesh, args.size[0], args.size[1], True))
        renderer = car.vtkCatadioptricSceneRenderer()
        renderer.SetSceneFileName(path)
        if not renderer.LoadScene():
            print(renderer.GetLastError(), file=sys.stderr)
            return 1
        lights = [renderer.GetLights().GetItemAsObject(i) for i in range(3)]
        total = 0.0
        for frame in range(args.frames):
            t = 2 * math.pi * frame / args.frames
            # Three different movements: a circle, a figure of eight, a vertical swing.
            lights[0].SetPosition(0.3 * math.cos(t), -0.25 + 0.3 * math.sin(t), 1.2)
            lights[1].SetPosition(0.3 * math.sin(2 * t), -0.25 + 0.25 * math.cos(t), 1.15)
            lights[2].SetPosition(-0.25, 0.05 + 0.1 * math.cos(t), 1.0 + 0.3 * (1 + math.sin(t)))
            if not renderer.Render():
                print(renderer.GetLastError(), file=sys.stderr)
                return 1
            total += renderer.GetFrameTime()
            renderer.WritePNG("%s_%03d.png" % (args.prefix, frame))
    print("%d frames of %s, %d triangles, 3 spotlights with shadows: %.1f ms per frame "
          "(background + projection + lighting + sort + composite)"
          % (args.frames, os.path.basename(mesh) or "a torus", renderer.GetNumberOfTriangles(),
             1e3 * total / args.frames))
    return 0


if __name__ == "__main__":
    sys.exit(main())
