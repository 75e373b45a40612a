"""Builds the whole pipeline from Python: camera, a sphere, projection, painter sort and
compositing onto a synthesised frame, and checks the picture against the camera's own
projection."""

import math
import os
import sys
import tempfile
import unittest

import catadioptricar as car
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.util.numpy_support import vtk_to_numpy


def demo_camera():
    cam = car.vtkCatadioptricCamera()
    cam.SetImageWidth(320)
    cam.SetImageHeight(240)
    cam.SetFocalLength(240, 240)
    cam.SetPrincipalPoint(159.5, 119.5)
    cam.SetMirrorParameter("center", (0, 0, 0.14))
    cam.SetMirrorParameter("radius", 0.05)
    # camera at world (0, -0.14, 1) looking along world +y, image up = world +z
    cam.SetWorldToCameraElements([1, 0, 0, 0, 0, 0, -1, 1.0, 0, 1, 0, 0.14, 0, 0, 0, 1])
    return cam


def sorted_sphere(cam, resolution=(32, 16)):
    """A small sphere at (0.06, -0.32, 0.92), projected through cam and painter-sorted: the
    source and the sort (whose output the compositor draws)."""
    sphere = vtkSphereSource()
    sphere.SetCenter(0.06, -0.32, 0.92)
    sphere.SetRadius(0.03)
    sphere.SetThetaResolution(resolution[0])
    sphere.SetPhiResolution(resolution[1])
    projection = car.vtkCatadioptricProjection()
    projection.SetCamera(cam)
    projection.SetInputConnection(sphere.GetOutputPort())
    sort = car.vtkCatadioptricPainterSort()
    sort.SetInputConnection(projection.GetOutputPort())
    return sphere, sort


def pixel(image, x, y):
    """RGBA of pixel (x right, y down) of a VTK image (row 0 at the bottom)."""
    w, h, _ = image.GetDimensions()
    rgba = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, 4)
    return tuple(int(v) for v in rgba[h - 1 - int(round(y)), int(round(x))])


class PipelineTest(unittest.TestCase):
    def test_camera_projection_and_back_projection(self):
        cam = demo_camera()
        self.assertTrue(cam.IsValid(), cam.GetLastError())
        px, mp = [0.0, 0.0], [0.0, 0.0, 0.0]
        status = cam.ProjectWorldPoint([0.1, -0.3, 0.95], px, mp)
        self.assertEqual(status, car.vtkCatadioptricCamera.VALID)
        origin, direction = [0.0] * 3, [0.0] * 3
        self.assertEqual(cam.BackProjectPixel(px, origin, direction), car.vtkCatadioptricCamera.VALID)
        # The reflected ray passes through the point.
        p = [0.1, -0.3, 0.95]
        v = [p[i] - origin[i] for i in range(3)]
        cross = [v[1] * direction[2] - v[2] * direction[1],
                 v[2] * direction[0] - v[0] * direction[2],
                 v[0] * direction[1] - v[1] * direction[0]]
        self.assertLess(math.sqrt(sum(c * c for c in cross)), 1e-9)
        # Inside the mirror: a status, no NaN.
        self.assertEqual(cam.ProjectWorldPoint([0, 0, 1.0], px, mp), car.vtkCatadioptricCamera.INSIDE_MIRROR)
        self.assertEqual(car.vtkCatadioptricCamera.GetStatusName(2), "inside-mirror")

    def test_calibration_round_trip(self):
        cam = demo_camera()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "calibration.yaml")
            self.assertTrue(cam.Save(path))
            other = car.vtkCatadioptricCamera()
            self.assertTrue(other.Load(path), other.GetLastError())
            self.assertEqual(other.GetImageWidth(), 320)
            self.assertEqual(other.GetMirrorType(), "sphere")
            self.assertAlmostEqual(other.GetMirrorParameter("radius")[0], 0.05)

    def test_pipeline_draws_the_sphere_where_it_projects(self):
        cam = demo_camera()
        centre = [0.06, -0.32, 0.92]
        sphere, sort = sorted_sphere(cam)
        sort.DropInvisibleCellsOn()
        frame = car.vtkCatadioptricEnvironmentSource()
        frame.SetCamera(cam)
        frame.SetSamples(1)
        compositor = car.vtkCatadioptricCompositor()
        compositor.SetFrameConnection(frame.GetOutputPort())
        compositor.AddMeshConnection(sort.GetOutputPort())
        compositor.SetColor(1.0, 0.0, 1.0)
        compositor.Update()

        image = compositor.GetOutput()
        self.assertEqual(image.GetDimensions(), (320, 240, 1))
        self.assertGreater(compositor.GetNumberOfDrawnTriangles(), 0)
        px, mp = [0.0, 0.0], [0.0] * 3
        self.assertEqual(cam.ProjectWorldPoint(centre, px, mp), car.vtkCatadioptricCamera.VALID)
        self.assertEqual(pixel(image, *px), (255, 0, 255, 255))
        # Far from the sphere's image, the frame shows through (not magenta).
        self.assertNotEqual(pixel(image, 5, 5)[:3], (255, 0, 255))
        # Moving the camera re-executes the per-frame stages.
        cam.SetMirrorParameter("radius", 0.045)
        compositor.Update()
        self.assertEqual(cam.ProjectWorldPoint(centre, px, mp), car.vtkCatadioptricCamera.VALID)
        self.assertEqual(pixel(compositor.GetOutput(), *px), (255, 0, 255, 255))

    def test_tilted_hyperboloid_agrees_with_the_reference(self):
        # The scene file's tilted hyperbolic mirror from Python: the sphere drawn by the fast path
        # and by the reference ray tracer covers the same pixels, within a few per cent.
        cam = demo_camera()
        here = os.path.dirname(os.path.abspath(__file__))
        scene = os.path.join(here, "..", "..", "Data", "scenes", "hyperbolic-tilted.yaml")
        tilted = car.vtkCatadioptricCamera()
        with tempfile.TemporaryDirectory() as d:
            # The scene's camera section is a calibration: keep it (mirror included).
            with open(scene) as f:
                lines = f.read().split("\n")
            start = lines.index("camera:") + 1
            body = []
            for line in lines[start:]:
                if line and not line.startswith(" "):
                    break
                body.append(line[2:])
            path = os.path.join(d, "calibration.yaml")
            with open(path, "w") as f:
                f.write("\n".join(body))
            self.assertTrue(tilted.Load(path), tilted.GetLastError())
        self.assertEqual(tilted.GetMirrorType(), "hyperboloid")
        # The small image of demo_camera(), the scene's mirror and pose.
        tilted.SetImageWidth(cam.GetImageWidth())
        tilted.SetImageHeight(cam.GetImageHeight())
        tilted.SetFocalLength(cam.GetFocalLength())
        tilted.SetPrincipalPoint(cam.GetPrincipalPoint())
        sphere, sort = sorted_sphere(tilted, (64, 32))
        compositor = car.vtkCatadioptricCompositor()
        compositor.AddMeshConnection(sort.GetOutputPort())
        compositor.SetColor(1.0, 0.0, 1.0)
        compositor.SetImageSize(cam.GetImageWidth(), cam.GetImageHeight())
        compositor.Update()
        tracer = car.vtkCatadioptricRayTracer()
        tracer.SetCamera(tilted)
        tracer.AddMeshConnection(sphere.GetOutputPort())
        tracer.SetColor(1.0, 0.0, 1.0)
        tracer.Update()

        def magenta(image):
            a = vtk_to_numpy(image.GetPointData().GetScalars())
            return set(map(int, ((a[:, 0] == 255) & (a[:, 1] == 0) & (a[:, 2] == 255)).nonzero()[0]))

        fast, exact = magenta(compositor.GetOutput()), magenta(tracer.GetOutput())
        self.assertGreater(len(exact), 50)
        iou = len(fast & exact) / len(fast | exact)
        self.assertGreater(iou, 0.9, (len(fast), len(exact)))

    def test_scene_renderer_demo(self):
        renderer = car.vtkCatadioptricSceneRenderer()
        text = car.vtkCatadioptricSceneRenderer.GetDemoSceneText()
        text = text.replace("output: { width: 1328, height: 1048 }", "output: { width: 332, height: 262 }")
        text = text.replace("samples: 2", "samples: 1")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "scene.yaml")
            with open(path, "w") as f:
                f.write(text)
            renderer.SetSceneFileName(path)
            self.assertTrue(renderer.Render(), renderer.GetLastError())
            self.assertEqual(renderer.GetOutput().GetDimensions(), (332, 262, 1))
            self.assertGreater(renderer.GetNumberOfTriangles(), 1000)
            names = [renderer.GetStageName(i) for i in range(renderer.GetNumberOfStages())]
            self.assertEqual(names, ["scene", "meshes", "background", "projection", "lighting", "sort", "composite"])
            png = os.path.join(d, "out.png")
            self.assertTrue(renderer.WritePNG(png))
            self.assertGreater(os.path.getsize(png), 1000)

    def test_scene_sequence_frames(self):
        """A scene with a trajectory (Data/scenes/moving-camera.yaml): its frames, their times,
        and the camera at pose k after RenderFrame(k)."""
        source = os.environ.get("CATAR_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
        scene = os.path.join(source, "Data", "scenes", "moving-camera.yaml")
        text = open(scene).read().replace("samples: 2", "samples: 1")
        text = text.replace("output: { width: 664, height: 524 }", "output: { width: 166, height: 131 }")
        text = text.replace("trajectory: moving-camera.tum",
                            "trajectory: " + os.path.join(source, "Data", "scenes", "moving-camera.tum"))
        renderer = car.vtkCatadioptricSceneRenderer()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "scene.yaml")
            with open(path, "w") as f:
                f.write(text)
            renderer.SetSceneFileName(path)
            self.assertTrue(renderer.LoadScene(), renderer.GetLastError())
            self.assertEqual(renderer.GetNumberOfFrames(), 60)
            self.assertAlmostEqual(renderer.GetFrameRate(), 30.0, places=3)
            centres = []
            for k in (0, 59):
                self.assertTrue(renderer.RenderFrame(k), renderer.GetLastError())
                self.assertAlmostEqual(renderer.GetFrameTime(k), k / 30.0, places=5)
                centre = [0.0, 0.0, 0.0]
                renderer.GetCamera().GetCameraPosition(centre)
                centres.append(centre)
            # The trajectory slides the camera 16 cm along x and 5 cm up.
            self.assertAlmostEqual(centres[0][0], -0.08, places=5)
            self.assertAlmostEqual(centres[1][0], 0.08, places=5)
            self.assertAlmostEqual(centres[1][2] - centres[0][2], 0.05, places=5)
            self.assertFalse(renderer.RenderFrame(60))

    def test_bad_scene_reports_an_error(self):
        renderer = car.vtkCatadioptricSceneRenderer()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bad.yaml")
            with open(path, "w") as f:
                f.write("%YAML:1.0\n---\nobjects: []\n")
            renderer.SetSceneFileName(path)
            renderer.GlobalWarningDisplayOff()
            try:
                self.assertFalse(renderer.Render())
            finally:
                renderer.GlobalWarningDisplayOn()
            self.assertIn("camera", renderer.GetLastError())


    def test_render_uses_the_data_search_path(self):
        # car.render() finds a scene by its data-path name as catadioptric-render does, and a
        # name found nowhere is an error that says where it looked.
        data = os.path.join(os.environ["CATAR_SOURCE_DIR"], "Data")
        saved = os.environ.get("CATAR_DATA_PATH")
        here = os.getcwd()
        with tempfile.TemporaryDirectory() as d:
            os.chdir(d)
            try:
                os.environ["CATAR_DATA_PATH"] = data
                frame = car.render("scenes/two-objects.yaml")
                self.assertEqual(frame.shape, (524, 664, 4))
                with self.assertRaises(RuntimeError) as raised:
                    car.render("scenes/no-such-scene.yaml")
                message = str(raised.exception)
                self.assertIn("'scenes/no-such-scene.yaml' not found; looked in", message)
                self.assertIn("'%s' (CATAR_DATA_PATH)" % data, message)
                with self.assertRaises(RuntimeError) as raised:
                    car.render("https://example.org/scene.yaml")
                self.assertIn("is a URL", str(raised.exception))
            finally:
                os.chdir(here)
                if saved is None:
                    os.environ.pop("CATAR_DATA_PATH", None)
                else:
                    os.environ["CATAR_DATA_PATH"] = saved

    def test_quadric_mirror_by_type_and_keys(self):
        # A hyperbolic mirror with the camera at its outer focus: set by type and keys, it
        # projects a point, and the ray of that pixel passes through the point.
        cam = car.vtkCatadioptricCamera()
        self.assertIn("hyperboloid", cam.GetMirrorTypes())
        self.assertTrue(cam.SetMirrorType("hyperboloid"))
        self.assertEqual(cam.GetMirrorParameterKeys("hyperboloid"),
                         ("a", "b", "mirror_to_camera", "z_range"))
        self.assertTrue(cam.SetMirrorParameter("a", 0.03))
        self.assertTrue(cam.SetMirrorParameter("b", 0.04))
        self.assertTrue(cam.SetMirrorParameter(
            "mirror_to_camera", (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.05, 0, 0, 0, 1)))
        self.assertTrue(cam.SetMirrorParameter("z_range", (0.03, 0.07)))
        self.assertTrue(cam.IsValid(), cam.GetLastError())
        origin, direction = [0.0] * 3, [0.0] * 3
        px = [663.5 + 150, 523.5 - 80]
        self.assertEqual(cam.BackProjectPixel(px, origin, direction),
                         car.vtkCatadioptricCamera.VALID)
        point = [origin[k] + 0.4 * direction[k] for k in range(3)]
        pixel, mirror = [0.0, 0.0], [0.0] * 3
        self.assertEqual(cam.ProjectWorldPoint(point, pixel, mirror),
                         car.vtkCatadioptricCamera.VALID)
        self.assertAlmostEqual(pixel[0], px[0], places=6)
        self.assertAlmostEqual(pixel[1], px[1], places=6)

    def test_vector_setters_refuse_scalars(self):
        # SetDistortion(1) read past its argument (an unsized vtkSetVectorMacro) and crashed.
        cam = demo_camera()
        for name, size in (("SetDistortion", 5), ("SetFocalLength", 2),
                           ("SetPrincipalPoint", 2)):
            for bad in ((1,), ("",), (None,), ([1.0] * (size - 1),)):
                with self.assertRaises(TypeError, msg="%s%r" % (name, bad)):
                    getattr(cam, name)(*bad)
        # Mirror parameters of the wrong count or key are refused and change nothing.
        cam.GlobalWarningDisplayOff()
        self.assertFalse(cam.SetMirrorParameter("center", [1.0, 2.0]))
        self.assertFalse(cam.SetMirrorParameter("no such key", 1.0))
        self.assertFalse(cam.SetMirrorType("no such type"))
        self.assertEqual(cam.GetMirrorParameter("center"), (0.0, 0.0, 0.14))
        cam.GlobalWarningDisplayOn()
        cam.SetDistortion([0.1, 0.2, 0.0, 0.0, 0.3])
        self.assertEqual(cam.GetDistortion(), (0.1, 0.2, 0.0, 0.0, 0.3))
        cam.SetDistortion(0.0, 0.0, 0.0, 0.0, 0.0)
        self.assertEqual(cam.GetDistortion(), (0.0,) * 5)


    def test_pose_from_pixels_of_known_points(self):
        """vtkCatadioptricPoseEstimator: pixels of known world points (the camera's own
        projection, some replaced by wrong pixels) give back the camera's pose and reject the
        wrong ones."""
        from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
        import random
        cam = demo_camera()
        rng = random.Random(3)
        world, pixels = vtkPoints(), vtkDoubleArray()
        pixels.SetNumberOfComponents(2)
        truth = []
        while world.GetNumberOfPoints() < 30:
            p = [rng.uniform(-0.5, 0.5), rng.uniform(-1.0, -0.3), rng.uniform(0.6, 1.4)]
            px, mp = [0.0, 0.0], [0.0, 0.0, 0.0]
            if cam.ProjectWorldPoint(p, px, mp) != 0:
                continue
            outlier = world.GetNumberOfPoints() % 5 == 0
            if outlier:
                px = [px[0] + rng.choice([-1, 1]) * rng.uniform(20, 60), px[1]]
            truth.append(not outlier)
            world.InsertNextPoint(p)
            pixels.InsertNextTuple2(*px)
        estimator = car.vtkCatadioptricPoseEstimator()
        other = demo_camera()
        other.SetWorldToCameraElements([1, 0, 0, 0.2, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
        estimator.SetCamera(other)  # its pose is not used
        estimator.SetObservations(world, pixels)
        self.assertTrue(estimator.Estimate(), estimator.GetLastError())
        expected = [0.0] * 16
        cam.GetWorldToCameraElements(expected)
        m = estimator.GetWorldToCamera()
        for i in range(16):
            self.assertAlmostEqual(m.GetElement(i // 4, i % 4), expected[i], places=6)
        inliers = [bool(estimator.GetInliers().GetValue(i)) for i in range(len(truth))]
        self.assertEqual(inliers, truth)
        self.assertEqual(estimator.GetNumberOfInliers(), sum(truth))
        self.assertLess(estimator.GetRMSError(), 1e-4)
        # Too few points: a sentence, no crash.
        few = vtkPoints()
        few.SetNumberOfPoints(3)
        three = vtkDoubleArray()
        three.SetNumberOfComponents(2)
        three.SetNumberOfTuples(3)
        estimator.SetObservations(few, three)
        estimator.GlobalWarningDisplayOff()
        self.assertFalse(estimator.Estimate())
        self.assertIn("4", estimator.GetLastError())
        estimator.SetObservations(world, three)
        self.assertFalse(estimator.Estimate())
        self.assertIn("pixels", estimator.GetLastError())
        estimator.GlobalWarningDisplayOn()

    def test_enable_threads(self):
        from vtkmodules.vtkCommonCore import vtkSMPTools
        car.enable_threads(2)
        self.assertEqual(vtkSMPTools.GetBackend(), "STDThread")
        self.assertEqual(vtkSMPTools.GetEstimatedNumberOfThreads(), 2)
        with self.assertRaises(ValueError):
            car.enable_threads(0)
        self.assertIn("enable_threads", car.__all__)


if __name__ == "__main__":
    result = unittest.main(exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() and result.testsRun > 0 else 1)
