"""A seeded fuzzer of the ParaView plugin's properties, run by pvpython: builds the plugin's
pipeline (environment frame, remesher, point-set surface, projection, lighting, painter sort,
compositor, ray tracer, rig), then sets random properties of random proxies to extreme or wrong
values (NaN, infinities, huge, negative and out-of-domain numbers, empty and missing file names),
updates every sink and sometimes shows it in a render view.

    pvpython --force-offscreen-rendering FuzzParaView.py PLUGIN [--iterations N] [--seed K]
        [--verbose]

Every case must end in an error message or a result; a crash fails the test, and so does an
image whose size disagrees with its data.
"""

import argparse
import random
import sys
import tempfile

from paraview import servermanager, simple
from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow, vtkStringOutputWindow

NUMBERS = [float("nan"), float("inf"), -float("inf"), 0, -1, 1e-300, 1e300, 2 ** 31 - 1,
           -2 ** 31, 0.5, 3, 1e6, 40000, -1e-9]
STRINGS = ["", "/nonexistent/file.yaml", "/dev/null", "/", "x" * 5000]
CALIBRATION = """image_width: 160
image_height: 120
camera_matrix: [ 120.0, 0.0, 79.5, 0.0, 120.0, 59.5, 0.0, 0.0, 1.0 ]
mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
"""


def build(calib):
    sphere = simple.Sphere(Center=[0.06, -0.32, 0.92], Radius=0.03)
    frame = simple.CatadioptricEnvironment(CalibrationFileName=calib, Samples=1)
    remesher = simple.CatadioptricRemesher(Input=sphere)
    points = simple.CatadioptricPointSetSurface(Input=sphere)
    projection = simple.CatadioptricProjection(Input=remesher, CalibrationFileName=calib)
    lighting = simple.CatadioptricLighting(Input=projection)
    sort = simple.CatadioptricPainterSort(Input=lighting)
    compositor = simple.CatadioptricCompositor(Frame=frame, Input=[sort])
    tracer = simple.CatadioptricRayTracer(Frame=frame, Input=[points], CalibrationFileName=calib)
    rig = simple.CatadioptricRig(CalibrationFileName=calib, MirrorResolution=8)
    proxies = {"frame": frame, "remesher": remesher, "points": points,
               "projection": projection, "lighting": lighting, "sort": sort,
               "compositor": compositor, "tracer": tracer, "rig": rig}
    return proxies, [compositor, tracer, rig]


# A scene for the scene reader, beside the calibration (camera.yaml): two frames.
SCENE = """camera: camera.yaml
sequence: { frames: 2, fps: 10 }
background: { type: color, color: [ 0.1, 0.1, 0.1 ] }
objects:
  - { type: sphere, radius: 0.03, resolution: 8, translate: [ 0.06, -0.32, 0.92 ] }
"""


def add_scene_reader(folder, proxies, sinks):
    """The scene reader, a source and a sink (its image is checked as the others')."""
    scene = folder + "/scene.yaml"
    with open(scene, "w") as f:
        f.write(SCENE)
    reader = simple.CatadioptricARSceneReader(FileName=scene)
    proxies["scene"] = reader
    sinks.append(reader)


def settable(proxy):
    """Names and kinds of the properties a user can type into."""
    out = []
    for name in proxy.ListProperties():
        sm = proxy.GetProperty(name).SMProperty
        kind = sm.GetClassName()
        if kind in ("vtkSMDoubleVectorProperty", "vtkSMIntVectorProperty",
                    "vtkSMIdTypeVectorProperty", "vtkSMStringVectorProperty"):
            if not sm.GetInformationOnly():
                out.append((name, kind, sm))
    return out


def random_setting(rng, sm, kind):
    n = max(1, sm.GetNumberOfElements()) if not sm.GetRepeatable() else rng.choice([0, 1, 3, 7])
    if kind == "vtkSMStringVectorProperty":
        return [rng.choice(STRINGS) for _ in range(n)] if n != 1 else rng.choice(STRINGS)
    values = [rng.choice(NUMBERS) if rng.random() < 0.7 else rng.uniform(-5, 5) for _ in range(n)]
    if kind != "vtkSMDoubleVectorProperty":
        values = [int(max(-2 ** 31, min(2 ** 31 - 1, v))) if v == v and abs(v) != float("inf")
                  else rng.choice([-1, 0, 2 ** 31 - 1]) for v in values]
    return values if n != 1 else values[0]


def update(rng, sinks, view, cases):
    for sink in sinks:
        sink.UpdatePipeline()
        image = servermanager.Fetch(sink)
        if not image.IsA("vtkImageData"):
            continue  # the rig's polydata: a result or an error, checked by not crashing
        dims = image.GetDimensions()
        scalars = image.GetPointData().GetScalars()
        if scalars is not None and scalars.GetNumberOfTuples() > 0:
            assert scalars.GetNumberOfTuples() == dims[0] * dims[1] * dims[2], (
                cases, dims, scalars.GetNumberOfTuples())
    if rng.random() < 0.2:
        shown = rng.choice(sinks)
        simple.Show(shown, view)
        simple.Render(view)
        simple.Hide(shown, view)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("plugin")
    parser.add_argument("--iterations", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--verbose", action="store_true")
    args = parser.parse_args()
    simple.LoadPlugin(args.plugin, remote=False)
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)  # counted, not shown
    rng = random.Random(args.seed)
    view = simple.CreateView("RenderView")
    errors = 0
    with tempfile.TemporaryDirectory() as folder:
        calib = folder + "/camera.yaml"
        with open(calib, "w") as f:
            f.write(CALIBRATION)
        for it in range(args.iterations):
            proxies, sinks = build(calib)
            add_scene_reader(folder, proxies, sinks)
            cases = []
            for _ in range(rng.choice([1, 1, 2, 3])):
                name = rng.choice(sorted(proxies))
                options = settable(proxies[name])
                prop, kind, sm = rng.choice(options)
                value = random_setting(rng, sm, kind)
                cases.append("%s.%s = %r" % (name, prop, value))
                if args.verbose:
                    print("case %d: %s" % (it, cases[-1]), flush=True)
                try:
                    proxies[name].SetPropertyWithName(prop, value)
                except (TypeError, ValueError, OverflowError, AttributeError):
                    pass  # refused by the Python layer
            # pvpython prints through the output window too: capture only the updates.
            previous = vtkOutputWindow.GetInstance()
            messages = vtkStringOutputWindow()
            vtkOutputWindow.SetInstance(messages)
            try:
                update(rng, sinks, view, cases)
            finally:
                vtkOutputWindow.SetInstance(previous)
            errors += 1 if messages.GetOutput() else 0
            for proxy in reversed(list(proxies.values())):
                simple.Delete(proxy)
    print("FuzzParaView: %d cases (seed %d): %d ended in an error message, %d in a result, "
          "none crashed" % (args.iterations, args.seed, errors, args.iterations - errors))


if __name__ == "__main__":
    main()
