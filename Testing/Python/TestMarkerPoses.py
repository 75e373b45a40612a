"""catadioptricar.marker_poses: the camera pose of each frame from its markers, with verdict and
uncertainty, as numpy arrays. Frames of six markers on the floor are rendered along a known
camera path (a TUM trajectory) and saved as PNGs; a scene with those frames as its background
and the board as its markers must give every frame's pose reliable, within 1 cm and 0.5 degrees
of the path, with a one-sigma uncertainty under the guards' bound; the same poses as
catadioptric-render --poses-out FILE.csv writes; a board none of whose markers is in the frames
gives 'missing' with a note and NaN poses; bad arguments are refused. (The pose's accuracy
itself is measured on frames of an independent renderer: TestPoseGuardsPovRay.)"""

import csv
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
MARKERS = [(k, -0.45 + 0.45 * (k % 3), -0.5 - 0.45 * (k // 3)) for k in range(6)]
FRAMES = 4

work = tempfile.mkdtemp(prefix="catar-marker-poses-")
with open(os.path.join(work, "board.yaml"), "w") as f:
    f.write("dictionary: DICT_4X4_50\nmarkers:\n")
    for k, x, y in MARKERS:
        f.write("  - { id: %d, size: 0.2, translate: [ %g, %g, 0.0 ] }\n" % (k, x, y))
with open(os.path.join(work, "absent.yaml"), "w") as f:
    f.write("dictionary: DICT_4X4_50\nmarkers:\n  - { id: 49, size: 0.2 }\n")

# The path: the demo camera sliding 3 cm a frame sideways (TUM: camera centre, camera-to-world
# quaternion x y z w; the demo camera looks along world +y with image up = world +z).
truth = []
with open(os.path.join(work, "path.tum"), "w") as f:
    for k in range(FRAMES):
        centre = np.array([-0.05 + 0.03 * k, -0.14, 1.0])
        # camera-to-world rotation: columns are the camera's x, y, z axes in the world.
        rotation = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
        w = math.sqrt(1.0 + np.trace(rotation)) / 2.0
        q = [(rotation[2, 1] - rotation[1, 2]) / (4 * w), (rotation[0, 2] - rotation[2, 0]) / (4 * w),
             (rotation[1, 0] - rotation[0, 1]) / (4 * w), w]
        f.write("%.6f %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n"
                % ((k / 30.0,) + tuple(centre) + tuple(q)))
        pose = np.eye(4)
        pose[:3, :3] = rotation.T
        pose[:3, 3] = -rotation.T @ centre
        truth.append(pose)
with open(os.path.join(work, "render.yaml"), "w") as f:
    f.write(CAMERA + "background: { type: color, color: [ 0.45, 0.4, 0.35 ] }\n"
            "trajectory: path.tum\nobjects:\n")
    for k, x, y in MARKERS:
        f.write("  - { type: marker, id: %d, size: 0.2, translate: [ %g, %g, 0.0 ] }\n" % (k, x, y))
renderer = car.vtkCatadioptricSceneRenderer()
renderer.SetSceneFileName(os.path.join(work, "render.yaml"))
check(renderer.LoadScene(), "render scene: " + renderer.GetLastError())
writer = vtkPNGWriter()
for k in range(FRAMES):
    check(renderer.RenderFrame(k), "frame %d: %s" % (k, renderer.GetLastError()))
    writer.SetInputData(renderer.GetOutput())
    writer.SetFileName(os.path.join(work, "frame_%03d.png" % k))
    writer.Write()
with open(os.path.join(work, "estimate.yaml"), "w") as f:
    f.write(CAMERA + "background: { type: video, file: frame_%03d.png, fps: 30 }\n"
            "markers: board.yaml\nobjects:\n"
            "  - { type: sphere, radius: 0.05, translate: [ 0.0, -0.5, 0.05 ] }\n")
scene = os.path.join(work, "estimate.yaml")

poses = car.marker_poses(scene)
check(list(poses["frame"]) == list(range(FRAMES)), "frames %s" % poses["frame"])
check(np.allclose(poses["time"], np.arange(FRAMES) / 30.0), "times %s" % poses["time"])
check(poses["world_to_camera"].shape == (FRAMES, 4, 4), "pose shape")
for k in range(FRAMES):
    check(poses["verdict"][k] == "reliable", "frame %d: %s (%s)" % (k, poses["verdict"][k],
                                                                    poses["note"][k]))
    found = poses["world_to_camera"][k]
    centre = -found[:3, :3].T @ found[:3, 3]
    true_centre = -truth[k][:3, :3].T @ truth[k][:3, 3]
    turn = found[:3, :3] @ truth[k][:3, :3].T
    degrees = math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(turn) - 1) / 2))))
    check(np.linalg.norm(centre - true_centre) < 0.01,
          "frame %d: centre %s, true %s" % (k, centre, true_centre))
    check(degrees < 0.5, "frame %d: %g degrees off" % (k, degrees))
    check(0.0 < poses["sigma_position"][k] < 0.008, "sigma %s" % poses["sigma_position"][k])
    check(0.0 < poses["sigma_angle"][k] < 0.4, "sigma angle %s" % poses["sigma_angle"][k])
    check(poses["markers"][k] >= 4 and poses["inliers"][k] == poses["corners"][k] ==
          4 * poses["markers"][k], "markers %s inliers %s corners %s"
          % (poses["markers"][k], poses["inliers"][k], poses["corners"][k]))
    check(poses["note"][k] == "", "note %r" % poses["note"][k])
print("marker_poses: %d frames, camera centre sigma %.2f-%.2f mm"
      % (FRAMES, 1e3 * poses["sigma_position"].min(), 1e3 * poses["sigma_position"].max()))

# The program's CSV: the same poses, row by row.
program = os.path.join(os.environ["CATAR_BUILD_DIR"], "bin", "catadioptric-render")
table = os.path.join(work, "poses.csv")
run = subprocess.run([program, scene, "-o", os.path.join(work, "out_%03d.png"), "--poses-out",
                      table, "--quiet"], capture_output=True, text=True)
check(run.returncode == 0, "catadioptric-render: %s" % run.stderr)
with open(table) as f:
    rows = list(csv.DictReader(f))
check(len(rows) == FRAMES, "csv rows %d" % len(rows))
for k, row in enumerate(rows):
    found = poses["world_to_camera"][k]
    centre = -found[:3, :3].T @ found[:3, 3]
    check(row["verdict"] == poses["verdict"][k], "csv verdict %s" % row["verdict"])
    check(np.allclose([float(row["tx"]), float(row["ty"]), float(row["tz"])], centre, atol=1e-9),
          "csv centre of frame %d" % k)
    check(abs(float(row["sigma_position_m"]) - poses["sigma_position"][k]) < 1e-12,
          "csv sigma of frame %d" % k)

# A board whose markers are not in the frames: missing, with a note, NaN poses.
absent = car.marker_poses(scene, markers=os.path.join(work, "absent.yaml"), frames=[1, 2])
check(list(absent["frame"]) == [1, 2], "frames %s" % absent["frame"])
check(list(absent["verdict"]) == ["missing", "missing"], "verdicts %s" % absent["verdict"])
check("on the board" in absent["note"][0], "note %r" % absent["note"][0])
check(np.isnan(absent["world_to_camera"]).all(), "NaN poses")
check(np.isnan(absent["sigma_position"]).all(), "NaN sigmas")

# Refused: a frame outside the scene, a scene without markers.
for call, error in ((lambda: car.marker_poses(scene, frames=[FRAMES]), IndexError),
                    (lambda: car.marker_poses(os.path.join(work, "render.yaml")), ValueError),
                    (lambda: car.marker_poses(os.path.join(work, "nothing.yaml")), RuntimeError)):
    try:
        call()
        check(False, "no %s" % error.__name__)
    except error as e:
        print("refused:", e)

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
subprocess.run(["rm", "-rf", work])
print("passed")
