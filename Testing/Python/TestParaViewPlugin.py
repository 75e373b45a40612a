"""Loads the CatadioptricAR ParaView plugin in pvpython and renders through its proxies:
environment frame + sphere -> projection -> painter sort -> compositor."""

import os
import sys
import tempfile

from paraview import servermanager
from paraview import simple

plugin = sys.argv[1]

CALIBRATION = """%YAML:1.0
---
image_width: 320
image_height: 240
camera_matrix: [ 240.0, 0.0, 159.5, 0.0, 240.0, 119.5, 0.0, 0.0, 1.0 ]
mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
"""

# The same rig with a hyperbolic mirror tilted 4 degrees (Data/scenes/hyperbolic-tilted.yaml's).
HYPERBOLOID = CALIBRATION.replace(
    "mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }",
    "mirror: { type: hyperboloid, a: 0.03, b: 0.04, z_range: [ 0.03, 0.07 ],\n"
    "          mirror_to_camera: [ 1, 0, 0, 0,  0, 0.9975640502598242, -0.0697564737441253, 0,\n"
    "                              0, 0.0697564737441253, 0.9975640502598242, 0.05,  0, 0, 0, 1 ] }")


def check_menu():
    """Every proxy of the plugin is in the CatadioptricAR menu category (Filters or Sources)."""
    pxm = servermanager.ProxyManager()
    names = {"filters": ["CatadioptricRemesher", "CatadioptricPointSetSurface",
                         "CatadioptricProjection", "CatadioptricLighting", "CatadioptricPainterSort",
                         "CatadioptricCompositor", "CatadioptricRayTracer"],
             "sources": ["CatadioptricEnvironmentSource"]}
    for group, proxies in names.items():
        for name in proxies:
            prototype = pxm.SMProxyManager.GetPrototypeProxy(group, name)
            assert prototype is not None, (group, name)
            hints = prototype.GetHints()
            menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
            assert menu is not None and menu.GetAttribute("category") == "CatadioptricAR", name
    print("menu: the 8 proxies under CatadioptricAR")


def main():
    simple.LoadPlugin(plugin, remote=False)
    check_menu()
    # The plugin's proxies are now in paraview.simple, named after their labels.
    Sphere = simple.Sphere
    CatadioptricProjection = simple.CatadioptricProjection
    CatadioptricPainterSort = simple.CatadioptricPainterSort
    CatadioptricEnvironment = simple.CatadioptricEnvironment
    CatadioptricCompositor = simple.CatadioptricCompositor
    CatadioptricRayTracer = simple.CatadioptricRayTracer
    with tempfile.TemporaryDirectory() as d:
        calib = os.path.join(d, "calibration.yaml")
        with open(calib, "w") as f:
            f.write(CALIBRATION)
        sphere = Sphere(Center=[0.06, -0.32, 0.92], Radius=0.03, ThetaResolution=32, PhiResolution=16)
        projection = CatadioptricProjection(Input=sphere, CalibrationFileName=calib)
        projection.Solver = 1
        sort = CatadioptricPainterSort(Input=projection, DropInvisibleCells=1)
        frame = CatadioptricEnvironment(CalibrationFileName=calib, Samples=1)
        compositor = CatadioptricCompositor(Frame=frame, Input=[sort])
        compositor.ColorArrayName = ""
        compositor.Color = [1.0, 0.0, 1.0]
        compositor.UpdatePipeline()

        image = servermanager.Fetch(compositor)
        dims = image.GetDimensions()
        assert dims == (320, 240, 1), dims
        scalars = image.GetPointData().GetScalars()
        assert scalars.GetNumberOfComponents() == 4
        magenta = 0
        for i in range(scalars.GetNumberOfTuples()):
            if scalars.GetTuple4(i) == (255.0, 0.0, 255.0, 255.0):
                magenta += 1
        # The sphere covers a small disc: some pixels, far from the whole image.
        assert 20 < magenta < dims[0] * dims[1] // 20, magenta
        # ... around the pixel where the camera projects its centre (the Python wrapping of the
        # same modules gives the projection).
        import catadioptricar as car
        camera = car.vtkCatadioptricCamera()
        assert camera.Load(calib), camera.GetLastError()
        px, mp = [0.0, 0.0], [0.0, 0.0, 0.0]
        assert camera.ProjectWorldPoint([0.06, -0.32, 0.92], px, mp) == 0
        x, y = int(round(px[0])), int(round(px[1]))
        centre = scalars.GetTuple4((dims[1] - 1 - y) * dims[0] + x)
        assert centre == (255.0, 0.0, 255.0, 255.0), (px, centre)
        # Back-face culling on the closed sphere: fewer triangles drawn, the same silhouette.
        drawn = compositor.GetClientSideObject().GetNumberOfDrawnTriangles()
        projection.BackFaceCulling = 1
        compositor.UpdatePipeline()
        culled = servermanager.Fetch(compositor).GetPointData().GetScalars()
        assert compositor.GetClientSideObject().GetNumberOfDrawnTriangles() < drawn
        assert sum(1 for i in range(culled.GetNumberOfTuples())
                   if culled.GetTuple4(i) == (255.0, 0.0, 255.0, 255.0)) == magenta
        projection.BackFaceCulling = 0
        compositor.UpdatePipeline()
        # The exact reference of the same sphere: magenta at the same pixel, a similar count.
        tracer = CatadioptricRayTracer(Frame=frame, Input=[sphere], CalibrationFileName=calib)
        tracer.ColorArrayName = ""
        tracer.Color = [1.0, 0.0, 1.0]
        tracer.UpdatePipeline()
        exact = servermanager.Fetch(tracer)
        assert exact.GetDimensions() == dims, exact.GetDimensions()
        traced = exact.GetPointData().GetScalars()
        assert traced.GetTuple4((dims[1] - 1 - y) * dims[0] + x) == (255.0, 0.0, 255.0, 255.0)
        exactMagenta = sum(
            1 for i in range(traced.GetNumberOfTuples())
            if traced.GetTuple4(i) == (255.0, 0.0, 255.0, 255.0))
        assert abs(exactMagenta - magenta) < 0.25 * magenta, (exactMagenta, magenta)
        projected = servermanager.Fetch(projection)
        assert projected.GetPointData().GetArray("ImageCoordinates") is not None
        assert projected.GetCellData().GetArray("CentroidDepth") is not None

        # Through the tilted hyperbolic mirror: the same pipeline and the reference agree, and the
        # sphere covers the pixel its centre projects to.
        hyperboloid = os.path.join(d, "hyperboloid.yaml")
        with open(hyperboloid, "w") as f:
            f.write(HYPERBOLOID)
        for proxy in (projection, frame, tracer):
            proxy.CalibrationFileName = hyperboloid
        compositor.UpdatePipeline()
        tracer.UpdatePipeline()
        fast = servermanager.Fetch(compositor).GetPointData().GetScalars()
        exact = servermanager.Fetch(tracer).GetPointData().GetScalars()
        count = lambda a: sum(1 for i in range(a.GetNumberOfTuples())
                              if a.GetTuple4(i) == (255.0, 0.0, 255.0, 255.0))
        hyperMagenta, hyperExact = count(fast), count(exact)
        assert hyperMagenta > 20 and abs(hyperExact - hyperMagenta) < 0.25 * hyperMagenta, (
            hyperMagenta, hyperExact)
        assert camera.Load(hyperboloid), camera.GetLastError()
        assert camera.ProjectWorldPoint([0.06, -0.32, 0.92], px, mp) == 0
        x, y = int(round(px[0])), int(round(px[1]))
        assert fast.GetTuple4((dims[1] - 1 - y) * dims[0] + x) == (255.0, 0.0, 255.0, 255.0), px
        # The same mirror chosen in the panel (Mirror Type, Mirror Parameters) over the sphere's
        # calibration file: the same pictures.
        tilt = (1, 0, 0, 0, 0, 0.9975640502598242, -0.0697564737441253, 0,
                0, 0.0697564737441253, 0.9975640502598242, 0.05, 0, 0, 0, 1)
        for proxy in (projection, frame, tracer):
            proxy.CalibrationFileName = calib
            proxy.MirrorType = "hyperboloid"
            proxy.MirrorParameters = [0.03, 0.04] + list(tilt) + [0.03, 0.07]
        compositor.UpdatePipeline()
        tracer.UpdatePipeline()
        panelFast = count(servermanager.Fetch(compositor).GetPointData().GetScalars())
        panelExact = count(servermanager.Fetch(tracer).GetPointData().GetScalars())
        assert (panelFast, panelExact) == (hyperMagenta, hyperExact), (panelFast, panelExact)
        for proxy in (projection, frame, tracer):
            proxy.MirrorType = ""
            proxy.MirrorParameters = []
        compositor.UpdatePipeline()
        assert count(servermanager.Fetch(compositor).GetPointData().GetScalars()) == magenta

        # A trajectory (a timestamp and world-to-camera, row-major): its times become the
        # pipeline's time steps; at each time the sphere is where the camera at that pose sees it,
        # and Save Animation writes one image a time step.
        trajectory = os.path.join(d, "poses.txt")
        shifts = [0.0, 0.02, 0.04]
        with open(trajectory, "w") as f:
            for k, dx in enumerate(shifts):
                f.write("%g 1 0 0 %g  0 0 -1 1.0  0 1 0 0.14  0 0 0 1\n" % (0.5 * k, -dx))
        for proxy in (projection, frame):
            proxy.TrajectoryFileName = trajectory
        compositor.UpdatePipelineInformation()
        assert list(projection.TimestepValues) == [0.0, 0.5, 1.0], projection.TimestepValues
        assert list(compositor.TimestepValues) == [0.0, 0.5, 1.0], compositor.TimestepValues
        moving = car.vtkCatadioptricCamera()
        assert moving.Load(calib), moving.GetLastError()
        seen = []
        for k, dx in enumerate(shifts):
            compositor.UpdatePipeline(0.5 * k)
            pixels = servermanager.Fetch(compositor).GetPointData().GetScalars()
            elements = [1, 0, 0, -dx, 0, 0, -1, 1.0, 0, 1, 0, 0.14, 0, 0, 0, 1]
            moving.SetWorldToCameraElements(elements)
            assert moving.ProjectWorldPoint([0.06, -0.32, 0.92], px, mp) == 0
            x, y = int(round(px[0])), int(round(px[1]))
            assert pixels.GetTuple4((dims[1] - 1 - y) * dims[0] + x) == (255.0, 0.0, 255.0, 255.0), (k, px)
            seen.append((x, y))
        assert len(set(seen)) == 3, seen
        scene = simple.GetAnimationScene()
        scene.UpdateAnimationUsingDataTimeSteps()
        view = simple.CreateView("RenderView")
        display = simple.Show(compositor, view)
        # Its true colours (RGBA, no colour map).
        simple.ColorBy(display, ("POINTS", pixels.GetName()))
        display.MapScalars = 0
        view.CameraParallelProjection = 1
        simple.ResetCamera(view)
        frames = os.path.join(d, "frame.png")
        simple.SaveAnimation(frames, view, ImageResolution=[160, 120], FrameWindow=[0, 2])
        written = sorted(n for n in os.listdir(d) if n.startswith("frame") and n.endswith(".png"))
        assert len(written) == 3, written
        contents = set(open(os.path.join(d, n), "rb").read() for n in written)
        assert len(contents) == 3, "the frames differ"
        for proxy in (projection, frame):
            proxy.TrajectoryFileName = ""
        simple.Delete(view)
        compositor.UpdatePipeline(0.0)

        # Shown in a render view without a frame: no error at all (the image views used to print
        # "Incorrect dimensionality": the extent announced before the data was 1x1).
        from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
        messages = vtkStringOutputWindow()
        previous = vtkOutputWindow.GetInstance()
        vtkOutputWindow.SetInstance(messages)
        try:
            bare = CatadioptricCompositor(Input=[sort], Frame=None)
            view = simple.CreateView("RenderView")
            simple.Show(bare, view)
            simple.Render(view)
            shown = servermanager.Fetch(bare)
        finally:
            vtkOutputWindow.SetInstance(previous)
        assert shown.GetDimensions() == dims, shown.GetDimensions()
        assert messages.GetOutput() == "", messages.GetOutput()
    print("ParaView plugin: %d magenta pixels (ray tracer %d); through the tilted hyperboloid %d "
          "(ray tracer %d); 1 passed, 0 failed" % (magenta, exactMagenta, hyperMagenta, hyperExact))


if __name__ == "__main__":
    main()
