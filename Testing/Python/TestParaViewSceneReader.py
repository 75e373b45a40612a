"""Opens scene files in pvpython through the plugin's scene reader (OpenDataFile, as File ->
Open does) and checks its two outputs against independent oracles:

- the image equals, pixel for pixel, the PNG that catadioptric-render writes for the same scene;
- the objects are one block per object of the scene, named after them, and a procedural
  object's bounds are its size and position as the scene file (read with PyYAML) gives them;
- a scene with a trajectory announces the trajectory file's times as time steps, and two times
  give different frames (the keyframed torus moves, the still box does not); a scene with the
  `sequence` key announces frames / fps;
- a scene with an unknown key is an error that names the key, and nothing crashes.

    pvpython --force-offscreen-rendering TestParaViewSceneReader.py PLUGIN CATADIOPTRIC_RENDER
        SOURCE_DIR
"""

import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import yaml

from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, render, source = sys.argv[1:4]
SCENES = os.path.join(source, "Data", "scenes")


def load_yaml(path):
    """A scene file as PyYAML reads it (OpenCV's "%YAML:1.0" first line is not YAML 1.1's)."""
    with open(path) as f:
        lines = f.read().splitlines()
    if lines and lines[0].startswith("%YAML"):
        lines = lines[1:]
    return yaml.safe_load("\n".join(lines))


def pixels(image):
    """The image's RGBA scalars as an (n, 4) uint8 array, VTK's row order."""
    scalars = image.GetPointData().GetScalars()
    array = vtk_to_numpy(scalars)
    if scalars.GetNumberOfComponents() == 3:  # an opaque PNG may be written without alpha
        array = np.concatenate([array, np.full((array.shape[0], 1), 255, np.uint8)], axis=1)
    return array


def rotation(degrees):
    """Rotation about x, then y, then z (the scene's `rotate`)."""
    ax, ay, az = (math.radians(a) for a in degrees)
    rx = np.array([[1, 0, 0], [0, math.cos(ax), -math.sin(ax)], [0, math.sin(ax), math.cos(ax)]])
    ry = np.array([[math.cos(ay), 0, math.sin(ay)], [0, 1, 0], [-math.sin(ay), 0, math.cos(ay)]])
    rz = np.array([[math.cos(az), -math.sin(az), 0], [math.sin(az), math.cos(az), 0], [0, 0, 1]])
    return rz @ ry @ rx


def expected_bounds(obj):
    """The bounds of a procedural sphere or cylinder placed as the scene says, and how far each
    may fall short: its local box turned by a quarter-turn rotation (so that the turned box is
    the mesh's box), then moved. A cylinder's ring of `resolution` points reaches its radius
    exactly at these resolutions (a multiple of 4); a sphere's poles do, but its rings of
    latitude, `resolution` of them from pole to pole, may miss the equator by half their spacing:
    r (1 - cos(pi / (2 (resolution - 1)))) short of r across the axis."""
    r = obj["radius"]
    if obj["type"] == "sphere":
        half = np.array([r, r, r])
        short = r * (1.0 - math.cos(math.pi / (2.0 * (obj["resolution"] - 1))))
        slack = np.array([short, short, 0.0])
    else:  # cylinder, along y
        assert obj["resolution"] % 4 == 0, obj["resolution"]
        half = np.array([r, obj["height"] / 2.0, r])
        slack = np.zeros(3)
    rotate = obj.get("rotate", [0.0, 0.0, 0.0])
    assert all(a % 90.0 == 0.0 for a in rotate), rotate
    turn = np.abs(rotation(rotate))
    half, slack = turn @ half, turn @ slack
    centre = np.array(obj["translate"], dtype=float)
    bounds = [v for lo, hi in zip(centre - half, centre + half) for v in (lo, hi)]
    return bounds, [v for v in slack for _ in (0, 1)]


def capture():
    messages = vtkStringOutputWindow()
    previous = vtkOutputWindow.GetInstance()
    vtkOutputWindow.SetInstance(messages)
    return messages, previous


def check_still_scene(d):
    """two-objects.yaml: the CLI's image and the scene's objects."""
    path = os.path.join(SCENES, "two-objects.yaml")
    reader = simple.OpenDataFile(path)
    assert reader is not None, "no reader for " + path
    assert reader.GetXMLName() == "CatadioptricSceneReader", reader.GetXMLName()
    assert reader.GetXMLLabel() == "CatadioptricAR Scene Reader"
    assert len(reader.TimestepValues) == 0, reader.TimestepValues  # a still scene
    reader.UpdatePipeline()
    image = servermanager.Fetch(reader, idx=0)
    scene = load_yaml(path)
    dims = image.GetDimensions()
    assert dims == (scene["output"]["width"], scene["output"]["height"], 1), dims

    # The CLI's PNG of the same scene (same renderer: the same pixels, exactly).
    png = os.path.join(d, "two-objects.png")
    subprocess.run([render, path, "-o", png, "--quiet"], check=True)
    read = vtkPNGReader()
    read.SetFileName(png)
    read.Update()
    assert read.GetOutput().GetDimensions() == dims, read.GetOutput().GetDimensions()
    ours, cli = pixels(image), pixels(read.GetOutput())
    different = int(np.count_nonzero(np.any(ours != cli, axis=1)))
    assert different == 0, "%d pixels differ from catadioptric-render's" % different
    background = np.round(255 * np.array(scene["background"]["color"])).astype(np.uint8)
    drawn = int(np.count_nonzero(np.any(ours[:, :3] != background, axis=1)))
    assert drawn > 100, drawn  # the objects are in the image

    # The objects: one named block each, in world coordinates.
    objects = reader.GetClientSideObject().GetOutputDataObject(1)
    assert objects.IsA("vtkMultiBlockDataSet"), objects.GetClassName()
    assert objects.GetNumberOfBlocks() == len(scene["objects"]), objects.GetNumberOfBlocks()
    for i, obj in enumerate(scene["objects"]):
        block = objects.GetBlock(i)
        name = objects.GetMetaData(i).Get(objects.NAME())
        assert name == obj["name"], (i, name)
        assert block.GetNumberOfPolys() > 0, name
        colors = block.GetCellData().GetArray("Colors")
        assert colors is not None and colors.GetNumberOfComponents() == 4, name
        bounds = block.GetBounds()
        expected, slack = expected_bounds(obj)
        # 1e-6: the meshes' points are floats.
        assert all(abs(a - b) <= s + 1e-6 for a, b, s in zip(bounds, expected, slack)), (
            name, bounds, expected, slack)
    # Through ParaView's data information too (what the Information panel shows).
    info = reader.GetDataInformation(1)
    assert info.GetNumberOfPoints() == sum(
        objects.GetBlock(i).GetNumberOfPoints() for i in range(objects.GetNumberOfBlocks()))

    # Shown in a render view, both outputs: no message at all.
    messages, previous = capture()
    try:
        view = simple.CreateView("RenderView")
        shown = simple.Show(simple.OutputPort(reader, 0), view)
        objectsShown = simple.Show(simple.OutputPort(reader, 1), view)
        simple.Render(view)
    finally:
        vtkOutputWindow.SetInstance(previous)
    assert messages.GetOutput() == "", messages.GetOutput()
    # The image in its own colours (the plugin's image representation, Map Scalars off); the
    # objects in ParaView's usual one.
    assert shown.GetXMLName() == "CatadioptricImageRepresentation", shown.GetXMLName()
    assert shown.MapScalars == 0
    assert objectsShown.GetXMLName() != "CatadioptricImageRepresentation"
    print("still scene: %dx%d, %d pixels drawn, the same as catadioptric-render's; %d objects "
          "(%s); image shown as %s, MapScalars %d" % (
              dims[0], dims[1], drawn, objects.GetNumberOfBlocks(),
              ", ".join(o["name"] for o in scene["objects"]), shown.Representation,
              shown.MapScalars))
    simple.Delete(view)
    simple.Delete(reader)


def check_sequences(d):
    """moving-camera.yaml (a trajectory, a keyframed torus) and a scene with `sequence`."""
    path = os.path.join(SCENES, "moving-camera.yaml")
    scene = load_yaml(path)
    with open(os.path.join(SCENES, scene["trajectory"])) as f:
        stamps = [float(line.split()[0]) for line in f if line.strip() and not line.startswith("#")]
    reader = simple.OpenDataFile(path)
    times = list(reader.TimestepValues)
    assert len(times) == len(stamps), (len(times), len(stamps))
    assert max(abs(a - b) for a, b in zip(times, stamps)) < 1e-9, (times[:3], stamps[:3])
    frames, torus = [], []
    names = [o["name"] for o in scene["objects"]]
    for t in (times[0], times[30]):
        reader.UpdatePipeline(t)
        algorithm = reader.GetClientSideObject()
        image = algorithm.GetOutputDataObject(0)
        assert image.GetInformation().Get(image.DATA_TIME_STEP()) == t
        frames.append(pixels(image).copy())
        objects = algorithm.GetOutputDataObject(1)
        torus.append(vtk_to_numpy(objects.GetBlock(names.index("torus")).GetPoints().GetData())
                     .copy())
        box = objects.GetBlock(names.index("parallelepiped")).GetBounds()
    moved = int(np.count_nonzero(np.any(frames[0] != frames[1], axis=1)))
    assert moved > 1000, moved
    assert np.abs(torus[0] - torus[1]).max() > 1e-3  # the keyframed torus turned
    # It turns in place: the centre of its box stays where the scene puts it, to within 1 mm
    # (the tessellated torus is not quite symmetric about its centre; it is 20 cm across).
    for points in torus:
        centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
        assert np.abs(centre - np.array(scene["objects"][1]["translate"])).max() < 1e-3, centre
    simple.Delete(reader)

    # The `sequence` key: frames / fps; a time between steps takes the frame before it.
    sequence = os.path.join(d, "sequence.yaml")
    with open(sequence, "w") as f:
        f.write("camera: %s\n" % os.path.join(source, "Data", "calibration", "demo-camera.yaml"))
        f.write("output: { width: 332, height: 262 }\n"
                "sequence: { frames: 4, fps: 8 }\n"
                "background: { type: color, color: [ 0, 0, 0 ] }\n"
                "objects:\n"
                "  - { name: ball, type: sphere, radius: 0.05, translate: [ 0.15, -0.35, 0.95 ],\n"
                "      keyframes: [ { time: 0, translate: [ 0.15, -0.35, 0.95 ] },\n"
                "                   { time: 0.375, translate: [ -0.15, -0.35, 0.95 ] } ] }\n")
    reader = simple.CatadioptricARSceneReader(FileName=sequence)
    assert list(reader.TimestepValues) == [0.0, 0.125, 0.25, 0.375], reader.TimestepValues
    reader.UpdatePipeline(0.2)
    algorithm = reader.GetClientSideObject()
    drawn = algorithm.GetOutputDataObject(0)
    assert drawn.GetInformation().Get(drawn.DATA_TIME_STEP()) == 0.125  # frame 1's time
    ball = algorithm.GetOutputDataObject(1).GetBlock(0).GetBounds()
    # Linear between the keyframes: at 0.125, a third of the way from x 0.15 to -0.15.
    assert abs(0.5 * (ball[0] + ball[1]) - 0.05) < 1e-6, ball
    simple.Delete(reader)
    print("sequences: %d time steps from the trajectory (%d pixels change from t = %g to %g); "
          "the sequence key: 4 time steps, t = 0.2 draws frame 1" % (
              len(times), moved, times[0], times[30]))


def check_bad_scenes(d):
    """Mistakes give an error message that says what is wrong, and empty outputs."""
    bad = os.path.join(d, "bad.yaml")
    with open(bad, "w") as f:
        f.write("camera: %s\nobjetcs: []\n"
                % os.path.join(source, "Data", "calibration", "demo-camera.yaml"))
    cases = [(bad, "objetcs"), (os.path.join(d, "missing.yaml"), "missing.yaml"),
             ("", "FileName")]
    first = None
    for path, word in cases:
        messages, previous = capture()
        try:
            reader = simple.CatadioptricARSceneReader(FileName=path)
            reader.UpdatePipeline()
            image = reader.GetClientSideObject().GetOutputDataObject(0)
            objects = reader.GetClientSideObject().GetOutputDataObject(1)
        finally:
            vtkOutputWindow.SetInstance(previous)
        text = messages.GetOutput()
        ours = [line for line in text.splitlines()
                if line.strip().startswith("vtkCatadioptricSceneReader (")]
        # Said once, by the reader, with the parser's words.
        assert len(ours) == 1 and word in ours[0], (path, text)
        first = first or ours[0].strip()
        assert image.GetNumberOfPoints() == 0 and objects.GetNumberOfBlocks() == 0
        simple.Delete(reader)
    # The bad scene is still opened by the scene reader (so that File -> Open says what is wrong).
    messages, previous = capture()
    try:
        opened = simple.OpenDataFile(bad)
    finally:
        vtkOutputWindow.SetInstance(previous)
    assert opened is not None and opened.GetXMLName() == "CatadioptricSceneReader"
    simple.Delete(opened)
    print("bad scenes: %d errors, each naming what is wrong; the first: %s" % (
        len(cases), first))


def main():
    simple.LoadPlugin(plugin, remote=False)
    with tempfile.TemporaryDirectory() as d:
        check_still_scene(d)
        check_sequences(d)
        check_bad_scenes(d)
    print("ParaView scene reader: 1 passed, 0 failed")


if __name__ == "__main__":
    main()
