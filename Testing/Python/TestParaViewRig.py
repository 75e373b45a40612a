"""The plugin's Catadioptric Rig source in pvpython: the demo camera's rig (its calibration file),
its parts and where they lie in the world; the frustum at a set length; the tilted hyperboloid
chosen in the panel; a render view colouring the parts, without an error message.

    pvpython --force-offscreen-rendering TestParaViewRig.py PLUGIN SOURCE_DIR
"""

import math
import os
import sys

from paraview import servermanager
from paraview import simple

plugin, source_dir = sys.argv[1], sys.argv[2]
CALIBRATION = os.path.join(source_dir, "Data", "calibration", "demo-camera.yaml")
# Data/scenes/hyperbolic-tilted.yaml's mirror: a, b, mirror_to_camera, z_range.
TILT = [1, 0, 0, 0, 0, 0.9975640502598242, -0.0697564737441253, 0,
        0, 0.0697564737441253, 0.9975640502598242, 0.05, 0, 0, 0, 1]
HYPERBOLOID = [0.03, 0.04] + TILT + [0.03, 0.07]


def parts(data):
    """The points of each RigPart (0 centre, 1 frustum, 2 mirror, 3 outline) and its cell count."""
    array = data.GetCellData().GetArray("RigPart")
    assert array is not None, "no RigPart array"
    assert array.GetNumberOfTuples() == data.GetNumberOfCells()
    points, cells = {}, {}
    for c in range(data.GetNumberOfCells()):
        part = int(array.GetValue(c))
        cells[part] = cells.get(part, 0) + 1
        ids = data.GetCell(c).GetPointIds()
        points.setdefault(part, set()).update(ids.GetId(k) for k in range(ids.GetNumberOfIds()))
    return {p: [data.GetPoint(i) for i in sorted(ids)] for p, ids in points.items()}, cells


def bounds(points):
    return [f(p[k] for p in points) for k in range(3) for f in (min, max)]


def main():
    simple.LoadPlugin(plugin, remote=False)
    rig = simple.CatadioptricRig(CalibrationFileName=CALIBRATION)
    rig.UpdatePipeline()
    data = servermanager.Fetch(rig)
    points, cells = parts(data)
    # The demo camera: centre at world (0, -0.14, 1) looking along +y; a 5 cm sphere whose centre
    # is 14 cm ahead, at world (0, 0, 1), all of it inside the image.
    assert cells[0] == 1 and points[0] == [(0.0, -0.14, 1.0)], points[0]
    assert cells[1] == 5, cells  # four lines to the corners, the border loop
    assert cells[2] > 1000, cells  # triangles
    assert cells[3] == 1, cells  # the rim, one loop
    worst = max(abs(math.dist(p, (0.0, 0.0, 1.0)) - 0.05) for p in points[2])
    assert worst < 1e-12, worst
    # The side of the sphere that faces the camera, less than a hemisphere: y in [-0.05, -r^2/d].
    b = bounds(points[2])
    assert -0.0501 < b[2] and b[3] < -0.05 * 0.05 / 0.14 + 1e-9, b
    assert abs(b[0] + b[1]) < 1e-3 and abs(b[4] + b[5] - 2.0) < 1e-3, b  # centred on the axis
    # The automatic frustum: 1.25 times the farthest mirror point's depth, y = -0.14 + depth.
    depth = max(p[1] for p in points[2]) + 0.14
    far = [p for p in points[1] if p != (0.0, -0.14, 1.0)]
    assert all(abs(p[1] - (-0.14 + 1.25 * depth)) < 1e-12 for p in far), far
    # A frustum of depth 0.5: x to +-0.5 * 664 / 1000, z to 1 +- 0.5 * 524 / 1000.
    rig.FrustumLength = 0.5
    rig.UpdatePipeline()
    points, cells = parts(servermanager.Fetch(rig))
    b = bounds(points[1])
    expected = [-0.332, 0.332, -0.14, 0.36, 1.0 - 0.262, 1.0 + 0.262]
    assert max(abs(x - y) for x, y in zip(b, expected)) < 1e-12, b
    whole = servermanager.Fetch(rig).GetBounds()
    assert max(abs(x - y) for x, y in zip(whole, expected)) < 1e-12, whole
    # The tilted hyperboloid from the panel: every mirror point on
    # (x^2 + y^2) / b^2 - z^2 / a^2 + 1 = 0 in the mirror frame, 0.03 <= z <= 0.07.
    rig.MirrorType = "hyperboloid"
    rig.MirrorParameters = HYPERBOLOID
    rig.UpdatePipeline()
    points, cells = parts(servermanager.Fetch(rig))
    assert cells[2] > 1000 and cells[3] >= 1, cells
    worst = 0.0
    for x, y, z in points[2]:
        # world -> camera (x, z - 1, y + 0.14) -> mirror frame (the rotation's transpose)
        c = (x, 1.0 - z, y + 0.14)
        c = (c[0], c[1], c[2] - 0.05)
        m = (c[0], TILT[5] * c[1] + TILT[9] * c[2], TILT[6] * c[1] + TILT[10] * c[2])
        value = (m[0] ** 2 + m[1] ** 2) / 0.04 ** 2 - m[2] ** 2 / 0.03 ** 2 + 1.0
        assert 0.03 - 1e-9 <= m[2] <= 0.07 + 1e-9, m  # Intersect's own tolerance: 1e-10
        worst = max(worst, abs(value))
    assert worst < 1e-9, worst
    hyperboloidTriangles = cells[2]

    # Shown in a render view, coloured by part: no error message.
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
    messages = vtkStringOutputWindow()
    previous = vtkOutputWindow.GetInstance()
    vtkOutputWindow.SetInstance(messages)
    try:
        view = simple.CreateView("RenderView")
        display = simple.Show(rig, view)
        simple.ColorBy(display, ("CELLS", "RigPart"))
        simple.ResetCamera(view)
        simple.Render(view)
    finally:
        vtkOutputWindow.SetInstance(previous)
    assert messages.GetOutput() == "", messages.GetOutput()
    # A missing calibration file: an error, an empty output, no crash.
    messages = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(messages)
    try:
        rig.CalibrationFileName = "/nonexistent/camera.yaml"
        rig.UpdatePipeline()
    finally:
        vtkOutputWindow.SetInstance(previous)
    assert "nonexistent" in messages.GetOutput(), messages.GetOutput()
    assert servermanager.Fetch(rig).GetNumberOfPoints() == 0
    print("ParaView rig: the demo sphere's points within %.1e of it; the tilted hyperboloid's "
          "%d triangles within %.1e of its equation; 1 passed, 0 failed"
          % (1e-12, hyperboloidTriangles, worst))


if __name__ == "__main__":
    main()
