#!/usr/bin/env python3
"""The CatadioptricAR pipeline from Python: a calibration file, a cone and a sphere from VTK's
sources, projection through the mirror, painter sort, compositing onto a synthesised frame.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/pipeline.py \
        --calibration Data/calibration/demo-camera.yaml -o pipeline.png
"""

import argparse
import sys

import catadioptricar as car
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkConeSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calibration", required=True, help="calibration file (YAML/JSON)")
    parser.add_argument("-o", "--output", default="pipeline.png", help="PNG to write")
    args = parser.parse_args()

    car.enable_threads()
    camera = car.vtkCatadioptricCamera()
    if not camera.Load(args.calibration):
        print("cannot load the calibration:", camera.GetLastError(), file=sys.stderr)
        return 1

    frame = car.vtkCatadioptricEnvironmentSource()
    frame.SetCamera(camera)
    frame.SetSamples(1)
    compositor = car.vtkCatadioptricCompositor()
    compositor.SetFrameConnection(frame.GetOutputPort())

    cone = vtkConeSource()
    cone.SetCenter(-0.12, -0.3, 0.9)
    cone.SetDirection(0, 0, 1)
    cone.SetHeight(0.12)
    cone.SetRadius(0.04)
    cone.SetResolution(48)
    sphere = vtkSphereSource()
    sphere.SetCenter(0.12, -0.35, 1.05)
    sphere.SetRadius(0.04)
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(24)
    for source in (cone, sphere):
        triangles = vtkTriangleFilter()
        triangles.SetInputConnection(source.GetOutputPort())
        projection = car.vtkCatadioptricProjection()
        projection.SetCamera(camera)
        projection.SetInputConnection(triangles.GetOutputPort())
        sort = car.vtkCatadioptricPainterSort()
        sort.SetInputConnection(projection.GetOutputPort())
        sort.DropInvisibleCellsOn()
        compositor.AddMeshConnection(sort.GetOutputPort())
    compositor.SetColor(0.3, 0.8, 0.4)

    writer = vtkPNGWriter()
    writer.SetInputConnection(compositor.GetOutputPort())
    writer.SetFileName(args.output)
    writer.Write()
    drawn = compositor.GetNumberOfDrawnTriangles()
    print("drew %d triangles into %s" % (drawn, args.output))
    return 0 if drawn > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
