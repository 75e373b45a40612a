"""catadioptricar's numpy helpers: images to numpy and back (top row first, BGR on request),
vectorised projection and back projection equal to the point-by-point calls and inverse to each
other, render() equal to the scene renderer's output, bad shapes refused. Prints the time per
point of the vectorised calls against a Python loop of the point-by-point ones."""

import sys
import time

import numpy as np

import catadioptricar as car

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


rng = np.random.default_rng(7)

# Images: round trips of every channel count, the row order, BGR.
for shape in [(5, 7), (5, 7, 1), (6, 4, 3), (3, 8, 4)]:
    a = rng.integers(0, 256, size=shape, dtype=np.uint8)
    image = car.numpy_to_image(a)
    width, height, _ = image.GetDimensions()
    check((width, height) == (shape[1], shape[0]), "dimensions of %s" % (shape,))
    back = car.image_to_numpy(image)
    check(back.shape == (shape[0], shape[1], 1 if len(shape) == 2 else shape[2]),
          "shape back %s" % (back.shape,))
    check((back.reshape(a.shape) == a).all(), "round trip of %s" % (shape,))
    # The array's top-left pixel is VTK's (0, H - 1).
    top_left = image.GetScalarComponentAsDouble(0, height - 1, 0, 0)
    check(top_left == a.reshape(shape[0], shape[1], -1)[0, 0, 0], "row order of %s" % (shape,))
a = rng.integers(0, 256, size=(4, 5, 4), dtype=np.uint8)
check((car.image_to_numpy(car.numpy_to_image(a), bgr=True) == a[:, :, [2, 1, 0, 3]]).all(),
      "image_to_numpy bgr")
check((car.image_to_numpy(car.numpy_to_image(a, bgr=True)) == a[:, :, [2, 1, 0, 3]]).all(),
      "numpy_to_image bgr")
# A big-endian array gives its values, not its bytes in another order.
big = np.arange(12, dtype=">u2").reshape(3, 4) * 1000
check((car.image_to_numpy(car.numpy_to_image(big))[..., 0] == big).all(), "big-endian values")
for bad in [np.zeros((2, 3, 5), np.uint8), np.zeros((0, 3), np.uint8), np.zeros(4, np.uint8)]:
    try:
        car.numpy_to_image(bad)
        check(False, "numpy_to_image accepted %s" % (bad.shape,))
    except ValueError:
        pass

# Projection: the demo scene's camera, world points around the mirror.
scene = car.vtkCatadioptricSceneRenderer()
check(scene.LoadScene(), "demo scene")
camera = scene.GetCamera()
n = 3000
points = np.column_stack([rng.uniform(-1, 1, n), rng.uniform(-1.5, 0.5, n), rng.uniform(0, 2, n)])
for solver, code in (("quartic", 0), ("iterative", 1)):
    t0 = time.perf_counter()
    pixels, statuses, mirror = car.project_points(camera, points, solver=solver)
    vectorised = time.perf_counter() - t0
    t0 = time.perf_counter()
    worst, mismatched = 0.0, 0
    for i in range(n):
        pixel, m = [0.0, 0.0], [0.0, 0.0, 0.0]
        status = camera.ProjectWorldPoint(points[i], pixel, m, code)
        mismatched += status != statuses[i]
        worst = max(worst, abs(pixel[0] - pixels[i, 0]), abs(pixel[1] - pixels[i, 1]),
                    *np.abs(np.array(m) - mirror[i]))
    loop = time.perf_counter() - t0
    valid = int((statuses == car.vtkCatadioptricCamera.VALID).sum())
    print("project_points (%s): %d points, %d valid; %.2f us a point against %.2f us in a Python "
          "loop; largest difference %.1e, statuses differing %d"
          % (solver, n, valid, 1e6 * vectorised / n, 1e6 * loop / n, worst, mismatched))
    check(valid > 300, "valid projections (%d)" % valid)
    has = statuses <= car.vtkCatadioptricCamera.OUTSIDE_IMAGE
    check((~has).sum() > 0 and np.isnan(pixels[~has]).all() and np.isnan(mirror[~has]).all(),
          "NaN pixels and mirror points where there is no projection (%d)" % (~has).sum())
    check(not np.isnan(pixels[has]).any(), "numbers where there is a projection")
    check(mismatched == 0 and worst == 0.0, "project_points equals ProjectWorldPoint (%s)" % solver)

# Back projection: a grid of pixels; equal to BackProjectPixel; inverse of the projection.
u, v = np.meshgrid(np.linspace(300, 1000, 40), np.linspace(200, 850, 30))
grid = np.column_stack([u.ravel(), v.ravel()])
t0 = time.perf_counter()
origins, directions, statuses = car.back_project(camera, grid)
vectorised = time.perf_counter() - t0
worst = 0.0
t0 = time.perf_counter()
for i in range(len(grid)):
    o, d = [0.0] * 3, [0.0] * 3
    status = camera.BackProjectPixel(grid[i], o, d)
    check(status == statuses[i], "back projection status of pixel %d" % i)
    worst = max(worst, *np.abs(np.array(o) - origins[i]), *np.abs(np.array(d) - directions[i]))
loop = time.perf_counter() - t0
valid = statuses == car.vtkCatadioptricCamera.VALID
print("back_project: %d pixels, %d valid; %.2f us a pixel against %.2f us in a Python loop; "
      "largest difference %.1e" % (len(grid), valid.sum(), 1e6 * vectorised / len(grid),
                                    1e6 * loop / len(grid), worst))
check(worst < 1e-12, "back_project equals BackProjectPixel (%.1e)" % worst)
check(valid.sum() > 500, "pixels that see the mirror (%d)" % valid.sum())
check(np.allclose((directions[valid] ** 2).sum(axis=1), 1.0, atol=1e-12), "unit directions")
# A point 0.6 m along each ray projects back to its pixel.
along = origins[valid] + 0.6 * directions[valid]
pixels, statuses_back, _ = car.project_points(camera, along)
error = np.abs(pixels - grid[valid]).max()
print("back projection then projection: largest pixel error %.1e" % error)
check((statuses_back <= car.vtkCatadioptricCamera.OUTSIDE_IMAGE).all() and error < 1e-6,
      "projection inverts back projection (%.1e px)" % error)
# Any shape but N x 3 (N x 2 for pixels) is refused, and the message names the shape given:
# a 3 x N array is not reinterpreted as N x 3 rows of mixed-up coordinates.
for function, bad in ((car.project_points, np.zeros((4, 2))), (car.project_points, np.zeros((3, 2))),
                      (car.project_points, points[:5].T), (car.back_project, np.zeros((4, 3))),
                      (car.back_project, grid[:7].T), (car.project_points, np.zeros((2, 3, 1)))):
    try:
        function(camera, bad)
        check(False, "%s accepted shape %s" % (function.__name__, bad.shape))
    except ValueError as e:
        check(str(bad.shape) in str(e), "the message names the shape: %s" % e)
check(car.project_points(camera, points[0])[0].shape == (1, 2), "one point of 3")

# Out of memory: results that do not fit in what the address-space limit leaves raise MemoryError
# with their size, and the points are not copied first (VTK's own copy aborted the interpreter).
# 2 million points (48 MB) with 40 MB left: their results need 88 MB.
if sys.platform.startswith("linux"):
    import resource

    many = np.tile(points[:1], (2_000_000, 1))
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    size = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
    for function, rows in ((car.project_points, many), (car.back_project, many[:, :2])):
        resource.setrlimit(resource.RLIMIT_AS, (size + 40_000_000, hard))
        try:
            function(camera, rows)
            check(False, "%s of 2000000 rows fitted in 40 MB" % function.__name__)
        except MemoryError as e:
            print("%s under a limit: %s" % (function.__name__, e))
            check("2000000 points" in str(e) and "left under the address-space limit" in str(e),
                  "%s's MemoryError gives the sizes: %s" % (function.__name__, e))
        finally:
            resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
    check(car.project_points(camera, many[:10])[1].shape == (10,), "projection after the limit")

# Poses and 4x4 mirror keys as 4x4 numpy arrays: the same as their 16 numbers row by row.
pose = np.array([[0.0, -1.0, 0.0, 0.02], [0.0, 0.0, -1.0, 1.0], [1.0, 0.0, 0.0, 0.14],
                 [0.0, 0.0, 0.0, 1.0]])
flat, square = car.vtkCatadioptricCamera(), car.vtkCatadioptricCamera()
flat.SetWorldToCameraElements(list(pose.ravel()))
square.SetWorldToCamera(pose)
got = [0.0] * 16
square.GetWorldToCameraElements(got)
check(got == list(pose.ravel()), "SetWorldToCamera(4x4 numpy): %s" % got)
check(square.GetWorldToCamera().GetElement(0, 3) == 0.02, "the 4x4 pose as vtkMatrix4x4")
tilt = np.eye(4)
tilt[1:3, 1:3] = [[0.9975640502598242, -0.0697564737441253], [0.0697564737441253, 0.9975640502598242]]
tilt[2, 3] = 0.05
for c in (flat, square):
    check(c.SetMirrorType("hyperboloid"), "hyperboloid")
check(square.SetMirrorParameter("mirror_to_camera", tilt), "mirror_to_camera as 4x4 numpy")
check(flat.SetMirrorParameter("mirror_to_camera", list(tilt.ravel())), "mirror_to_camera as 16")
check(square.GetMirrorParameter("mirror_to_camera") == flat.GetMirrorParameter("mirror_to_camera")
      and flat.GetMirrorParameter("mirror_to_camera")[11] == 0.05, "the same mirror_to_camera")
try:
    square.SetWorldToCamera(np.eye(3))
    check(False, "SetWorldToCamera accepted a 3x3")
except TypeError:
    pass
projection = car.vtkCatadioptricProjection()
projection.SetWorldToCamera(pose)
got = [0.0] * 16
projection.GetWorldToCamera(got)
check(got == list(pose.ravel()), "vtkCatadioptricProjection.SetWorldToCamera(4x4 numpy)")

# render_mesh(): numpy vertices and triangles in, numpy image out. An icosahedron around a point:
# the pixel where project_points puts its centre is the mesh's colour, the frame shows through
# elsewhere unchanged, and the mesh covers about the disc its radius gives (the mirror's
# magnification measured with project_points, an independent route through the same camera).
phi = (1 + 5 ** 0.5) / 2
ico = np.array([[-1, phi, 0], [1, phi, 0], [-1, -phi, 0], [1, -phi, 0], [0, -1, phi], [0, 1, phi],
                [0, -1, -phi], [0, 1, -phi], [phi, 0, -1], [phi, 0, 1], [-phi, 0, -1],
                [-phi, 0, 1]], dtype=float)
ico /= np.linalg.norm(ico[0])
faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
         [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
centre, radius = np.array([0.06, -0.32, 0.92]), 0.03
import os
camera = car.vtkCatadioptricCamera()  # the demo camera (render_mesh's default) from its file
check(camera.Load(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data",
                               "calibration", "demo-camera.yaml")), "demo camera file")
frame_in = rng.integers(0, 256, size=(1048, 1328, 3), dtype=np.uint8)
drawn = car.render_mesh(centre + radius * ico, faces, frame=frame_in, color=(0.0, 1.0, 0.0))
check(drawn.shape == (1048, 1328, 4), "render_mesh shape %s" % (drawn.shape,))
(cx, cy), = car.project_points(camera, [centre])[0]
check((drawn[int(round(cy)), int(round(cx))] == [0, 255, 0, 255]).all(), "the centre is green")
green = (drawn[:, :, :3] == [0, 255, 0]).all(axis=2)
check((drawn[~green][:, :3] == frame_in[~green]).all(), "the frame shows through unchanged")
# Pixels per metre at the centre, across the line of sight: project points 1 mm off it.
ring = car.project_points(camera, [centre + [0.001, 0, 0], centre + [0, 0, 0.001]])[0]
scale = np.sqrt(abs(np.linalg.det(np.array(ring) - [cx, cy]))) / 0.001
expected = np.pi * (radius * scale) ** 2
check(0.75 * expected < green.sum() < 1.1 * expected,
      "render_mesh covers %d pixels, the sphere's disc about %.0f" % (green.sum(), expected))
bgr = car.render_mesh(centre + radius * ico, faces, frame=frame_in[:, :, ::-1], bgr=True,
                      color=(0.0, 1.0, 0.0))
check((bgr == drawn[:, :, [2, 1, 0, 3]]).all(), "render_mesh bgr")
for bad, error in (((ico, [[0, 1, 12]]), ValueError), ((ico[:, :2], faces), ValueError),
                   ((ico, faces, "/nonexistent/calibration.yaml"), RuntimeError),
                   ((ico, faces, None, None, (float("nan"), 0, 0)), ValueError),
                   ((ico, faces, None, None, (1, 1, 1), (0, 0, float("inf"), 1)), ValueError)):
    try:
        car.render_mesh(*bad)
        check(False, "render_mesh accepted %s" % (error.__name__,))
    except error as e:
        check(str(e).startswith("render_mesh: "), "render_mesh's error: %s" % e)
print("render_mesh: %d pixels for a sphere whose disc is %.0f" % (green.sum(), expected))

# render(): the scene renderer's frame, top row first.
frame = car.render()
check(frame.shape == (1048, 1328, 4) and frame.dtype == np.uint8, "render() shape %s" % (frame.shape,))
check(scene.Render(), "demo render")
check((frame == car.image_to_numpy(scene.GetOutput())).all(), "render() equals the renderer")
check((car.render(bgr=True)[:, :, :3] == frame[:, :, 2::-1]).all(), "render(bgr=True)")
try:
    car.render("/nonexistent/scene.yaml")
    check(False, "render of a missing file")
except RuntimeError as e:
    check("/nonexistent/scene.yaml" in str(e), "the error names the file: %s" % e)

print("numpy helpers: %d failed" % len(failures))
sys.exit(1 if failures else 0)
