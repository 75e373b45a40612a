"""A seeded fuzzer of the Python API: builds the whole pipeline (environment frame, remesher,
projection, lighting with occluders, painter sort, compositor, ray tracer) and the rig source,
then misuses it at random before each update: every Set* method of every wrapped object called
with extreme or wrong values (NaN, infinities, huge and negative numbers, empty and missing files,
None), and inputs swapped for broken data sets (no cells, lines, quads and strips, NaN and huge
points, ids past the end, arrays of the wrong type, length or component count, garbage camera field
data, float or 3D frames and textures).

    FuzzApi.py [--iterations N] [--seed K] [--verbose]

Every case must end in an error message or a result; a crash (signal) fails the test, and so does
an output that claims success but is malformed (an image of another size than its camera's, a
projected point marked valid at a non-finite pixel). Each case is printed before it runs when
--verbose is given, so that a crash names it; without it, the seed and iteration reproduce it.
"""

import argparse
import math
import random
import sys
import tempfile

import catadioptricar as car
from vtkmodules.vtkCommonCore import (vtkDoubleArray, vtkFloatArray, vtkIntArray, vtkLogger,
                                      vtkOutputWindow, vtkPoints, vtkStringOutputWindow,
                                      vtkUnsignedCharArray)
from vtkmodules.vtkCommonDataModel import (vtkCellArray, vtkImageData, vtkPolyData,
                                           vtkUnstructuredGrid)
from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkLight, vtkLightCollection, vtkProperty

NUMBERS = [float("nan"), float("inf"), -float("inf"), 0, -1, 1e-300, 1e300, 2 ** 31 - 1,
           -2 ** 31, 2 ** 63 - 1, 0.5, 3, 1e6, 40000, -1e-9]
STRINGS = ["", "/nonexistent/file.yaml", "/dev/null", "/", "\u00e9\u00e8", "x" * 5000, None]

# Methods that are not parameters of the algorithm (VTK's own plumbing) or need a special type.
SKIP = {"SetDebug", "SetGlobalWarningDisplay", "SetReferenceCount", "SetObjectName",
        "SetProgressText", "SetAbortExecute", "SetAbortOutput", "SetProgressObserver",
        "SetProgressShiftScale", "SetReleaseDataFlag", "SetInformation", "SetExecutive",
        "SetContainerAlgorithm", "SetNoPriority", "SetProgress", "SetDefaultExecutivePrototype",
        "SetInputArrayToProcess", "SetInputConnection", "SetInputData", "SetInputDataObject",
        "SetNumberOfInputConnections", "SetMemkindDirectory", "SetOutput",
        "SetAbortExecuteAndUpdateTime", "SetFrameConnection"}


def random_value(rng):
    kind = rng.random()
    if kind < 0.6:
        return rng.choice(NUMBERS)
    if kind < 0.8:
        return rng.choice(STRINGS)
    return rng.uniform(-2, 2)


def calibration(folder):
    path = folder + "/camera.yaml"
    with open(path, "w") as f:
        f.write("""image_width: 160
image_height: 120
camera_matrix: [ 120.0, 0.0, 79.5, 0.0, 120.0, 59.5, 0.0, 0.0, 1.0 ]
mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
""")
    return path


def polydata(points, polys=(), lines=(), verts=(), strips=()):
    pd = vtkPolyData()
    pts = vtkPoints()
    for p in points:
        pts.InsertNextPoint(*p)
    pd.SetPoints(pts)
    for cells, setter in ((polys, pd.SetPolys), (lines, pd.SetLines), (verts, pd.SetVerts),
                          (strips, pd.SetStrips)):
        if cells:
            ca = vtkCellArray()
            for c in cells:
                ca.InsertNextCell(len(c), c)
            setter(ca)
    return pd


def broken_meshes(rng, projected):
    """Broken polydata; `projected` is a good projected mesh whose arrays are damaged."""
    tri = [(0.06, -0.32, 0.92), (0.09, -0.32, 0.92), (0.06, -0.32, 0.95)]
    cases = {
        "empty": lambda: vtkPolyData(),
        "points only": lambda: polydata(tri),
        "lines and verts": lambda: polydata(tri, lines=[(0, 1), (1, 2)], verts=[(0,), (2,)]),
        "quad, pentagon and strip": lambda: polydata(
            tri + [(0.09, -0.32, 0.95), (0.1, -0.3, 0.9)], polys=[(0, 1, 3, 2), (0, 1, 3, 2, 4)],
            strips=[(0, 1, 2, 3)]),
        "NaN point": lambda: polydata([(float("nan"), 0, 1)] + tri[1:], polys=[(0, 1, 2)]),
        "huge points": lambda: polydata([(1e30, 0, 0), (0, 1e30, 0), (0, 0, 1e30)],
                                        polys=[(0, 1, 2)]),
        "id past the end": lambda: polydata(tri, polys=[(0, 1, 7)]),
        "negative id": lambda: polydata(tri, polys=[(0, -1, 2)]),
        "degenerate": lambda: polydata(tri, polys=[(0, 0, 0), (1, 1, 2)]),
    }
    if projected is not None:
        def damaged(kind):
            pd = vtkPolyData()
            pd.DeepCopy(projected)
            pdata, cdata, fdata = pd.GetPointData(), pd.GetCellData(), pd.GetFieldData()
            n = pd.GetNumberOfPoints()
            if kind == "pixels as ints":
                a = vtkIntArray()
                a.SetNumberOfComponents(3)
                a.SetNumberOfTuples(n)
                a.Fill(2 ** 30)
                a.SetName("ImageCoordinates")
                pdata.AddArray(a)
            elif kind == "short pixels":
                a = vtkDoubleArray()
                a.SetNumberOfComponents(2)
                a.SetNumberOfTuples(max(0, n // 2))
                a.SetName("ImageCoordinates")
                pdata.AddArray(a)
            elif kind == "NaN pixels":
                a = vtkDoubleArray()
                a.SetNumberOfComponents(2)
                a.SetNumberOfTuples(n)
                a.Fill(float("nan"))
                a.SetName("ImageCoordinates")
                pdata.AddArray(a)
            elif kind == "float depths":
                a = vtkFloatArray()
                a.SetNumberOfTuples(max(0, pd.GetNumberOfCells() - 1))
                a.Fill(float("inf"))
                a.SetName("CentroidDepth")
                cdata.AddArray(a)
            elif kind == "visible as floats":
                a = vtkFloatArray()
                a.SetNumberOfTuples(pd.GetNumberOfCells())
                a.Fill(7.5)
                a.SetName("Visible")
                cdata.AddArray(a)
            elif kind == "short colours":
                a = vtkUnsignedCharArray()
                a.SetNumberOfComponents(rng.choice([1, 2, 3, 4, 5]))
                a.SetNumberOfTuples(3)
                a.SetName("Colors")
                pdata.AddArray(a)
                cdata.AddArray(a)
            elif kind == "garbage camera":
                for name, count in (("CameraIntrinsics", 7), ("CameraDistortion", 5),
                                    ("MirrorParameters", 4), ("WorldToCamera", 16)):
                    a = vtkDoubleArray()
                    a.SetNumberOfTuples(rng.choice([0, 1, count, count + 3]))
                    a.Fill(rng.choice(NUMBERS))
                    a.SetName(name)
                    fdata.AddArray(a)
            elif kind == "no field data":
                fdata.Initialize()
            return pd
        for kind in ("pixels as ints", "short pixels", "NaN pixels", "float depths",
                     "visible as floats", "short colours", "garbage camera", "no field data"):
            cases["projected, " + kind] = (lambda k=kind: damaged(k))
    name = rng.choice(sorted(cases))
    return name, cases[name]()


def broken_image(rng):
    image = vtkImageData()
    kind = rng.choice(["float", "3D", "no scalars", "1x1", "5 components", "empty"])
    if kind == "empty":
        return kind, image
    dims = {"3D": (16, 12, 3), "1x1": (1, 1, 1)}.get(kind, (160, 120, 1))
    image.SetDimensions(*dims)
    if kind == "no scalars":
        return kind, image
    a = vtkFloatArray() if kind == "float" else vtkUnsignedCharArray()
    a.SetNumberOfComponents(5 if kind == "5 components" else 3)
    a.SetNumberOfTuples(dims[0] * dims[1] * dims[2])
    a.Fill(200)
    image.GetPointData().SetScalars(a)
    return kind, image


class Pipeline:
    def __init__(self, calib):
        self.sphere = vtkSphereSource()
        self.sphere.SetCenter(0.06, -0.32, 0.92)
        self.sphere.SetRadius(0.03)
        self.camera = car.vtkCatadioptricCamera()
        assert self.camera.Load(calib), self.camera.GetLastError()
        self.frame = car.vtkCatadioptricEnvironmentSource()
        self.frame.SetCamera(self.camera)
        self.frame.SetSamples(1)
        self.remesher = car.vtkCatadioptricRemesher()
        self.remesher.SetInputConnection(self.sphere.GetOutputPort())
        self.remesher.SetModeToRepairOnly()
        self.projection = car.vtkCatadioptricProjection()
        self.projection.SetInputConnection(self.remesher.GetOutputPort())
        self.projection.SetCamera(self.camera)
        self.lighting = car.vtkCatadioptricLighting()
        self.lighting.SetInputConnection(self.projection.GetOutputPort())
        self.occluders = car.vtkCatadioptricOccluders()
        self.lighting.SetOccluders(self.occluders)
        lights = vtkLightCollection()
        light = vtkLight()
        light.SetPosition(0.2, 0.0, 1.3)
        light.SetFocalPoint(0.06, -0.32, 0.92)
        lights.AddItem(light)
        self.light, self.lights = light, lights
        self.lighting.SetLights(lights)
        self.lighting.SetShadows(True)
        self.sort = car.vtkCatadioptricPainterSort()
        self.sort.SetInputConnection(self.lighting.GetOutputPort())
        self.compositor = car.vtkCatadioptricCompositor()
        self.compositor.SetFrameConnection(self.frame.GetOutputPort())
        self.compositor.AddInputConnection(1, self.sort.GetOutputPort())
        self.tracer = car.vtkCatadioptricRayTracer()
        self.tracer.SetCamera(self.camera)
        self.tracer.SetInputConnection(1, self.sphere.GetOutputPort())
        self.rig = car.vtkCatadioptricRigSource()
        self.rig.SetCamera(self.camera)
        self.rig.SetMirrorResolution(8)
        self.objects = {"camera": self.camera, "frame": self.frame, "remesher": self.remesher,
                        "projection": self.projection, "lighting": self.lighting,
                        "sort": self.sort, "compositor": self.compositor, "tracer": self.tracer,
                        "rig": self.rig, "light": light, "property": None}

    def sinks(self):
        return [self.compositor, self.tracer, self.rig]


def setters(obj):
    return sorted(m for m in dir(obj) if m.startswith("Set") and m not in SKIP)


def misuse(rng, p, calib):
    """One random misuse of the pipeline; returns its description."""
    roll = rng.random()
    if roll < 0.55:
        name = rng.choice([k for k in p.objects if p.objects[k] is not None and k != "light"])
        obj = p.objects[name]
        method = rng.choice(setters(obj))
        if method in ("SetCamera", "SetOccluders", "SetLights", "SetProperty", "SetFrameData",
                      "SetWorldToCamera"):
            args = [None]
            if method == "SetWorldToCamera" and rng.random() < 0.7:
                m = vtkMatrix4x4()
                for i in range(16):
                    m.SetElement(i // 4, i % 4, rng.choice(NUMBERS))
                args = [m]
            elif method == "SetFrameData":
                kind, image = broken_image(rng)
                args = [image]
                method += " (%s)" % kind
        else:
            args = [random_value(rng) for _ in range(rng.choice([1, 1, 2, 3, 4, 6, 16]))]
        call = getattr(obj, method.split(" ")[0])
        try:
            call(*args)
        except (TypeError, ValueError, OverflowError):
            pass  # refused by the wrapping's own type checks
        return "%s.%s%r" % (name, method, tuple(args))
    if roll < 0.65:
        attr = rng.choice(["SetPosition", "SetFocalPoint", "SetColor", "SetIntensity",
                           "SetConeAngle", "SetExponent", "SetAttenuationValues"])
        n = 1 if attr in ("SetIntensity", "SetConeAngle", "SetExponent") else 3
        args = [rng.choice(NUMBERS) for _ in range(n)]
        getattr(p.light, attr)(*args)
        return "light.%s%r" % (attr, tuple(args))
    if roll < 0.72:
        prop = vtkProperty()
        attr = rng.choice(["SetAmbient", "SetDiffuse", "SetSpecular", "SetSpecularPower",
                           "SetOpacity", "SetDiffuseColor"])
        args = [rng.choice(NUMBERS) for _ in range(3 if attr.endswith("Color") else 1)]
        getattr(prop, attr)(*args)
        p.lighting.SetProperty(prop)
        return "lighting.SetProperty(%s%r)" % (attr, tuple(args))
    projected = None
    if rng.random() < 0.5:
        good = Pipeline(calib)
        good.projection.Update()
        projected = good.projection.GetOutput()
    kind, mesh = broken_meshes(rng, projected)
    where = rng.choice(["remesher", "projection", "lighting", "lighting occluders", "sort",
                        "compositor", "compositor texture", "tracer", "tracer frame"])
    if where == "lighting occluders":
        p.lighting.SetInputData(1, mesh)
    elif where == "compositor":
        p.compositor.AddInputData(1, mesh)
    elif where == "compositor texture":
        kind, image = broken_image(rng)
        p.compositor.AddInputData(2, image)
    elif where == "tracer frame":
        kind, image = broken_image(rng)
        p.tracer.SetInputData(0, image)
    elif where == "tracer":
        p.tracer.AddInputData(1, mesh)
    else:
        p.objects[where].SetInputData(0, mesh)
    if rng.random() < 0.1:
        p.projection.SetInputData(vtkUnstructuredGrid())  # the wrong type altogether
        kind += ", then an unstructured grid"
    return "%s input: %s" % (where, kind)


def check(p, messages):
    """An update that reported no error must have produced a well-formed result."""
    for sink in p.sinks():
        image = sink.GetOutput()
        if not image.IsA("vtkImageData"):
            continue  # the rig's polydata
        dims = image.GetDimensions()
        scalars = image.GetPointData().GetScalars()
        if scalars is not None and scalars.GetNumberOfTuples() > 0:
            assert scalars.GetNumberOfTuples() == dims[0] * dims[1] * dims[2], (
                sink.GetClassName(), dims, scalars.GetNumberOfTuples())
    projected = p.projection.GetOutput()
    pixels = projected.GetPointData().GetArray("ImageCoordinates")
    status = projected.GetPointData().GetArray("ProjectionStatus")
    if pixels is not None and status is not None:
        assert pixels.GetNumberOfTuples() == status.GetNumberOfTuples()
        for i in range(pixels.GetNumberOfTuples()):
            if status.GetValue(i) == 0:
                x, y = pixels.GetTuple2(i)
                assert math.isfinite(x) and math.isfinite(y), (i, x, y)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--iterations", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--verbose", action="store_true")
    parser.add_argument("--only", type=int, help="run only this case (to reproduce it)")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)  # the messages are counted, not shown
    errors = 0
    with tempfile.TemporaryDirectory() as folder:
        calib = calibration(folder)
        for it in range(args.iterations):
            p = Pipeline(calib)
            cases = [misuse(rng, p, calib) for _ in range(rng.choice([1, 1, 2, 3]))]
            if args.only is not None and it != args.only:
                continue
            if args.verbose:
                print("case %d: %s" % (it, "; ".join(cases)), flush=True)
            messages = vtkStringOutputWindow()
            vtkOutputWindow.SetInstance(messages)
            for sink in p.sinks():
                sink.Update()
            if "ERR|" in messages.GetOutput() or "ERROR" in messages.GetOutput():
                errors += 1
            check(p, messages)
    print("FuzzApi: %d cases (seed %d): %d ended in an error message, %d in a result, "
          "none crashed" % (args.iterations, args.seed, errors, args.iterations - errors))


if __name__ == "__main__":
    main()
