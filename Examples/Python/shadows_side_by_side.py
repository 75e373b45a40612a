#!/usr/bin/env python3
"""The same lit scene with the illumination occlusion (shadows) off and on, side by side in one
PNG: the paper's figure 7.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Examples/Python/shadows_side_by_side.py [--mesh ../shared/data/happy-buddha-67k.ply] \\
        [-o shadows.png]

Without --mesh the scene is a box standing on a plate, lit from above at a slant.
"""

import argparse
import os
import sys
import tempfile

import catadioptricar as car
from vtkmodules.vtkFiltersCore import vtkImageAppend
from vtkmodules.vtkIOImage import vtkPNGWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from three_spotlights import CAMERA  # noqa: E402  (the same camera)


def scene_text(mesh, shadows):
    if mesh:
        objects = ('  - { type: mesh, file: "%s", rotate: [ 90, 0, 0 ], scale: 1.2, '
                   'translate: [ 0.0, -0.25, 0.75 ], color: [ 0.85, 0.7, 0.3 ], '
                   'material: { ambient: 0.3, diffuse: 0.8, specular: 0.5, specular_power: 40 } }\n'
                   % mesh)
    else:
        objects = ("  - { type: box, size: [ 0.08, 0.08, 0.12 ], resolution: 8, "
                   "translate: [ 0.0, -0.25, 0.86 ], color: [ 0.9, 0.5, 0.2 ] }\n")
    objects += ("  - { type: plane, size: [ 0.4, 0.4 ], resolution: 80, translate: [ 0.0, -0.25, 0.8 ], "
                "color: [ 0.8, 0.8, 0.8 ] }\n")
    return ("---\n%soutput: { width: 664, height: 524 }\n"
            "background: { type: environment, samples: 1 }\n"
            "lighting:\n  shading: gouraud\n  shadows: %d\n  global_ambient: [ 0.3, 0.3, 0.3 ]\n"
            "  lights:\n    - { type: spot, position: [ 0.25, 0.0, 1.25 ], focal_point: [ 0.0, -0.25, 0.8 ], "
            "cone_angle: 45, color: [ 1, 1, 1 ] }\nobjects:\n%s" % (CAMERA, 1 if shadows else 0, objects))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh", default="")
    parser.add_argument("-o", "--output", default="shadows-side-by-side.png")
    args = parser.parse_args()
    mesh = os.path.abspath(args.mesh) if args.mesh and os.path.exists(args.mesh) else ""
    car.enable_threads()
    append = vtkImageAppend()
    append.SetAppendAxis(0)
    renderers = []
    with tempfile.TemporaryDirectory() as tmp:
        for shadows in (False, True):
            path = os.path.join(tmp, "scene-%d.yaml" % shadows)
            with open(path, "w") as f:
                f.write(scene_text(mesh, shadows))
            renderer = car.vtkCatadioptricSceneRenderer()
            renderer.SetSceneFileName(path)
            if not renderer.Render():
                print(renderer.GetLastError(), file=sys.stderr)
                return 1
            renderers.append(renderer)
            append.AddInputData(renderer.GetOutput())
            print("shadows %-3s: lighting %.1f ms" % ("on" if shadows else "off",
                                                     1e3 * renderer.GetStageTime(4)))
    writer = vtkPNGWriter()
    writer.SetInputConnection(append.GetOutputPort())
    writer.SetFileName(args.output)
    writer.Write()
    print("wrote", args.output, "(left: shadows off, right: shadows on)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
