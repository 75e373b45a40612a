"""vtkCatadioptricRigCalibrator: the rig's calibration from Python, as catadioptric-calibrate.
Eight views of a 4 x 4 marker board in the demo's mirror sphere are rendered (the board fixed on
the floor, the camera moved along a TUM trajectory round it); calibrating from a start 3 mm and
5 % off must bring the mirror nearer (within 1.5 mm and 1.5 % on these frames of the project's
own rasteriser), each estimated number with its standard deviation, the same numbers as the program on the same images, and a file the camera loads; bad
calls are refused with a sentence. (The calibration's accuracy itself is measured on frames of an
independent renderer: TestRigCalibrationPovRay.)"""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.vtkIOImage import vtkPNGWriter

import catadioptricar as car

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


CAMERA = """camera:
  image_width: 1328
  image_height: 1048
  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
"""
MARKERS = [(k, (k % 4 - 1.5) * 0.065, (1.5 - k // 4) * 0.065) for k in range(16)]
VIEWS = 8


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def unit_orthogonal(v):
    # As Eigen's unitOrthogonal: perpendicular to v.
    if abs(v[0]) > abs(v[2]) or abs(v[1]) > abs(v[2]):
        u = np.array([-v[1], v[0], 0.0])
    else:
        u = np.array([0.0, -v[2], v[1]])
    return u / np.linalg.norm(u)


def board_poses(viewpoint, count, distance):
    """Board-to-camera poses round the mirror (as CalibrationTestViews.h's BoardPosesAround)."""
    poses = []
    for i in range(count):
        phi = 2 * math.pi * (i + 0.3) / count
        alpha = math.radians(100.0 + 25.0 * ((i * 7) % 3))
        u = np.array([math.cos(phi) * math.sin(alpha), math.sin(phi) * math.sin(alpha),
                      math.cos(alpha)])
        d = distance * (0.75 + 0.5 * ((i * 5) % 4) / 3.0)
        centre = viewpoint + d * u
        tilt = math.radians(25.0 * (((i * 3) % 5) - 2) / 2.0)
        normal = rotation(unit_orthogonal(u), tilt) @ (-u)
        x = rotation(normal, 0.7 * i) @ unit_orthogonal(normal)
        pose = np.eye(4)
        pose[:3, 0] = x
        pose[:3, 1] = np.cross(normal, x)
        pose[:3, 2] = normal
        pose[:3, 3] = centre
        poses.append(pose)
    return poses


work = tempfile.mkdtemp(prefix="catar-rig-calibrator-")
board = os.path.join(work, "board.yaml")
with open(board, "w") as f:
    f.write("dictionary: DICT_4X4_50\nmarkers:\n")
    for k, x, y in MARKERS:
        f.write("  - { id: %d, size: 0.05, translate: [ %.6f, %.6f, 0.0 ] }\n" % (k, x, y))
# The camera round the board: world = the board's frame; camera-to-world = the inverse of each
# board-to-camera pose (TUM: the camera centre, then camera-to-world's quaternion x y z w).
with open(os.path.join(work, "path.tum"), "w") as f:
    for k, pose in enumerate(board_poses(np.array([0.0, 0.0, 0.14]), VIEWS, 0.2)):
        r = pose[:3, :3].T
        centre = -r @ pose[:3, 3]
        w = math.sqrt(max(0.0, 1.0 + np.trace(r))) / 2.0
        q = [(r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w),
             (r[1, 0] - r[0, 1]) / (4 * w), w]
        f.write("%.6f %.12f %.12f %.12f %.15f %.15f %.15f %.15f\n"
                % ((k / 30.0,) + tuple(centre) + tuple(q)))
with open(os.path.join(work, "render.yaml"), "w") as f:
    f.write(CAMERA + "background: { type: color, color: [ 0.75, 0.75, 0.75 ] }\n"
            "trajectory: path.tum\nobjects:\n")
    for k, x, y in MARKERS:
        f.write("  - { type: marker, id: %d, size: 0.05, translate: [ %.6f, %.6f, 0.0 ] }\n"
                % (k, x, y))
renderer = car.vtkCatadioptricSceneRenderer()
renderer.SetSceneFileName(os.path.join(work, "render.yaml"))
check(renderer.LoadScene(), "render scene: " + renderer.GetLastError())
writer = vtkPNGWriter()
files = []
for k in range(VIEWS):
    check(renderer.RenderFrame(k), "frame %d: %s" % (k, renderer.GetLastError()))
    writer.SetInputData(renderer.GetOutput())
    files.append(os.path.join(work, "view_%02d.png" % k))
    writer.SetFileName(files[-1])
    writer.Write()

# The start: the mirror 3 mm off and 5 % too large.
start = car.vtkCatadioptricCamera()
start.SetImageWidth(1328)
start.SetImageHeight(1048)
start.SetFocalLength(1000.0, 1000.0)
start.SetPrincipalPoint(663.5, 523.5)
check(start.SetMirrorType("sphere"), "sphere")
check(start.SetMirrorParameters([0.0017, -0.0017, 0.1417, 0.0525]), "start's mirror")
calibrator = car.vtkCatadioptricRigCalibrator()
calibrator.SetCamera(start)
calibrator.SetBoardFileName(board)
for name in files:
    check(calibrator.AddImageFile(name), name + ": " + calibrator.GetLastError())
check(calibrator.GetNumberOfImages() == VIEWS, "images %d" % calibrator.GetNumberOfImages())
check(calibrator.Calibrate(), "calibrate: " + calibrator.GetLastError())
rig = calibrator.GetCalibratedCamera()
check(rig is not None, "a calibrated camera")
if rig is not None:
    centre_x, centre_y, centre_z, radius = rig.GetMirrorParameters()
    off = math.sqrt(centre_x ** 2 + centre_y ** 2 + (centre_z - 0.14) ** 2)
    check(off < 0.0015, "centre off by %.3f mm" % (1000 * off))
    check(abs(radius / 0.05 - 1) < 0.015, "radius %.5f" % radius)
    print("vtkCatadioptricRigCalibrator: %d views, rms %.3f px, centre off by %.3f mm, radius %.3f %%"
          % (calibrator.GetNumberOfImagesUsed(), calibrator.GetRMSError(), 1000 * off,
             100 * (radius / 0.05 - 1)))
names = list(calibrator.GetEstimatedNames())
check(names == ["center_x", "center_y", "center_z", "radius"], "names %s" % names)
sigmas = list(calibrator.GetEstimatedSigmas())
check(len(sigmas) == 4 and all(0 < s < 0.002 for s in sigmas), "sigmas %s" % sigmas)
check(list(calibrator.GetEstimatedUnits()) == ["m"] * 4, "units")
check(0 < calibrator.GetRMSError() < 1.0, "rms %g" % calibrator.GetRMSError())
saved = os.path.join(work, "rig.yaml")
check(calibrator.Save(saved), "save: " + calibrator.GetLastError())
loaded = car.vtkCatadioptricCamera()
check(loaded.Load(saved), "load: " + loaded.GetLastError())
check(np.allclose(loaded.GetMirrorParameters(), rig.GetMirrorParameters(), atol=1e-12)
      if rig is not None else False, "loaded mirror")
with open(saved) as f:
    check("calibration:" in f.read(), "the calibration map")

# The program on the same images: the same numbers.
init = os.path.join(work, "init.yaml")
check(start.Save(init), "init: " + start.GetLastError())
program = os.path.join(os.environ["CATAR_BUILD_DIR"], "bin", "catadioptric-calibrate")
run = subprocess.run([program, init, board] + files + ["-o", os.path.join(work, "cli.yaml"),
                     "--json"], capture_output=True, text=True)
check(run.returncode == 0, "program: %s" % run.stderr)
if run.returncode == 0:
    result = json.loads(run.stdout)
    check(abs(result["rms_px"] - calibrator.GetRMSError()) < 1e-6, "rms %s" % result["rms_px"])
    check(np.allclose(result["mirror"]["center"] + [result["mirror"]["radius"]],
                      rig.GetMirrorParameters(), atol=1e-12), "program's mirror %s" % result)

# Refusals, each with a sentence.
empty = car.vtkCatadioptricRigCalibrator()
empty.GlobalWarningDisplayOff()
check(not empty.Calibrate() and "SetCamera" in empty.GetLastError(), empty.GetLastError())
empty.SetCamera(start)
check(not empty.Calibrate() and "SetBoardFileName" in empty.GetLastError(), empty.GetLastError())
empty.SetBoardFileName(board)
check(not empty.Calibrate() and "too few views" in empty.GetLastError(), empty.GetLastError())
check(not empty.AddImageFile(os.path.join(work, "missing.png")) and
      "missing.png" in empty.GetLastError(), empty.GetLastError())
check(not empty.Save(os.path.join(work, "none.yaml")) and "Calibrate" in empty.GetLastError(),
      empty.GetLastError())

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
subprocess.run(["rm", "-rf", work])
print("ok")
