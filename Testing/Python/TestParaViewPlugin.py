"""Loads the CatadioptricAR ParaView plugin in pvpython and renders through its proxies:
environment frame + sphere -> projection -> painter sort -> compositor."""

import os
import sys
import tempfile

from paraview import servermanager
from paraview import simple

plugin = sys.argv[1]
SOURCE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")

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
             "sources": ["CatadioptricEnvironmentSource", "CatadioptricRigSource"]}
    for group, proxies in names.items():
        for name in proxies:
            prototype = pxm.SMProxyManager.GetPrototypeProxy(group, name)
            assert prototype is not None, (group, name)
            hints = prototype.GetHints()
            menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
            assert menu is not None and menu.GetAttribute("category") == "CatadioptricAR", name
    print("menu: the %d proxies under CatadioptricAR" % sum(len(p) for p in names.values()))


def check_selection_goes_to_the_meshes():
    """ParaView's Filters menu gives the selected object to the first input property in the
    proxy's XML order (pqFiltersMenuReaction::createFilter: the first of
    pqPipelineFilter::getInputPorts, which walks vtkSMOrderedPropertyIterator). For every plugin
    filter that first input is a required one that takes meshes, so that selecting the painter
    sort (or the projection) and applying the compositor or the ray tracer connects it as Input,
    not as the optional Frame."""
    pxm = servermanager.ProxyManager().SMProxyManager
    mesh = simple.Sphere()  # a vtkPolyData, as the projection and the sort give
    mesh.UpdatePipeline()
    checked = 0
    for name in ["CatadioptricRemesher", "CatadioptricPointSetSurface", "CatadioptricProjection",
                 "CatadioptricLighting", "CatadioptricPainterSort", "CatadioptricCompositor",
                 "CatadioptricRayTracer"]:
        prototype = pxm.GetPrototypeProxy("filters", name)
        it = servermanager.vtkSMOrderedPropertyIterator()
        it.SetProxy(prototype)
        it.Begin()
        inputs = []
        while not it.IsAtEnd():
            prop = it.GetProperty()
            if prop.IsA("vtkSMInputProperty"):
                hints = prop.GetHints()
                if not (hints and hints.FindNestedElementByName("NoGUI")):
                    inputs.append((it.GetKey(), prop))
            it.Next()
        assert inputs, name
        first, prop = inputs[0]
        hints = prop.GetHints()
        assert not (hints and hints.FindNestedElementByName("Optional")), (name, first)
        domain = prop.GetDomain("input_type")
        assert domain is not None and domain.IsInDomain(mesh.SMProxy, 0), (name, first)
        checked += 1
    simple.Delete(mesh)
    print("menu selection: the first input of %d filters takes the selected meshes" % checked)


def check_first_apply():
    """With every property at its default (no calibration file), the pipeline draws through the
    demo camera; the images show in their own colours; the camera's properties are grouped; a bad
    panel value is an error that names the panel property."""
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
    ball = simple.Sphere(Center=[0.06, -0.32, 0.92], Radius=0.03, ThetaResolution=32,
                         PhiResolution=16)
    projection = simple.CatadioptricProjection(Input=ball)
    sort = simple.CatadioptricPainterSort(Input=projection)
    compositor = simple.CatadioptricCompositor(Input=[sort], Frame=None)
    compositor.Color = [1.0, 0.0, 1.0]
    compositor.ColorArrayName = ""
    compositor.BackgroundColor = [0.2, 0.6, 0.1, 1.0]
    compositor.UpdatePipeline()
    image = servermanager.Fetch(compositor)
    assert image.GetDimensions() == (1328, 1048, 1), image.GetDimensions()
    rgba = image.GetPointData().GetScalars()
    # The ball is where the demo camera (the file that describes it, read by the Python bindings)
    # projects its centre.
    import catadioptricar as car
    camera = car.vtkCatadioptricCamera()
    assert camera.Load(os.path.join(SOURCE_DIR, "Data", "calibration", "demo-camera.yaml"))
    px, mp = [0.0, 0.0], [0.0, 0.0, 0.0]
    assert camera.ProjectWorldPoint([0.06, -0.32, 0.92], px, mp) == 0
    x, y = int(round(px[0])), int(round(px[1]))
    assert rgba.GetTuple4((1048 - 1 - y) * 1328 + x) == (255.0, 0.0, 255.0, 255.0), px
    ballPixels = sum(1 for i in range(rgba.GetNumberOfTuples())
                     if rgba.GetTuple4(i) == (255.0, 0.0, 255.0, 255.0))
    assert 20 < ballPixels < 1328 * 1048 // 20, ballPixels

    # True colours: Map Scalars off, and the render view shows the background's own green.
    view = simple.CreateView("RenderView")
    view.ViewSize = [400, 300]
    view.OrientationAxesVisibility = 0
    view.Background = [0.0, 0.0, 0.0]
    view.UseColorPaletteForBackground = 0
    display = simple.Show(compositor, view)
    assert display.GetXMLName() == "CatadioptricImageRepresentation", display.GetXMLName()
    assert display.MapScalars == 0 and display.ColorArrayName[1] == rgba.GetName(), (
        display.MapScalars, display.ColorArrayName)
    view.CameraParallelProjection = 1
    simple.ResetCamera(view)

    def green_in_view():
        """Pixels of the view that show the background's own green (51, 153, 25)."""
        with tempfile.TemporaryDirectory() as d:
            shot = os.path.join(d, "view.png")
            simple.SaveScreenshot(shot, view, ImageResolution=[400, 300])
            from vtkmodules.vtkIOImage import vtkPNGReader
            reader = vtkPNGReader()
            reader.SetFileName(shot)
            reader.Update()
            pixels = reader.GetOutput().GetPointData().GetScalars()
            return sum(1 for i in range(pixels.GetNumberOfTuples())
                       if all(abs(a - b) <= 2 for a, b in zip(pixels.GetTuple3(i), (51, 153, 25))))

    green = green_in_view()
    # The image covers about a third of the view (ResetCamera leaves a margin).
    assert green > 0.25 * 400 * 300, green
    # Through a colour map (Map Scalars on) the green is gone: the check sees the difference.
    display.MapScalars = 1
    mapped = green_in_view()
    assert mapped < 0.01 * green, (mapped, green)
    simple.Delete(display)
    simple.Delete(view)

    # The camera's properties in groups.
    labels = [projection.SMProxy.GetPropertyGroup(i).GetXMLLabel()
              for i in range(projection.SMProxy.GetNumberOfPropertyGroups())]
    for label in ("Calibration file", "Intrinsics (without a calibration file)", "Mirror",
                  "Pose (without a calibration file)", "Trajectory"):
        assert label in labels, (label, labels)

    # A bad panel value: an error that names the property, never a C++ method.
    messages = vtkStringOutputWindow()
    previous = vtkOutputWindow.GetInstance()
    vtkOutputWindow.SetInstance(messages)
    try:
        projection.FocalLength = [-5.0, 1000.0]
        projection.UpdatePipeline()
    finally:
        vtkOutputWindow.SetInstance(previous)
    text = messages.GetOutput()
    assert "Focal Length must be two positive numbers" in text and "Set" not in text.split(
        "Focal Length")[1], text
    projection.FocalLength = [1000.0, 1000.0]
    for proxy in (compositor, sort, projection, ball):
        simple.Delete(proxy)
    print("first Apply: the ball through the demo camera, %d pixels; %d view pixels in the image's "
          "own green (%d through a colour map)" % (ballPixels, green, mapped))


def check_colour_arrays():
    """The compositor's colour array is chosen from its meshes' arrays: after Catadioptric
    Lighting the list has its Colors (the default stays Colors); "(none: Color)" draws the solid
    Color."""
    ball = simple.Sphere(Center=[0.06, -0.32, 0.92], Radius=0.03)
    projection = simple.CatadioptricProjection(Input=ball)
    lighting = simple.CatadioptricLighting(Input=projection)
    lighting.UpdatePipeline()
    compositor = simple.CatadioptricCompositor(Input=[lighting], Frame=None)
    domain = compositor.GetProperty("ColorArrayName").SMProperty.FindDomain("vtkSMArrayListDomain")
    names = [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]
    assert "Colors" in names and "(none: Color)" in names, names
    assert "WorldToCamera" not in names, names  # field data is no colour
    assert compositor.ColorArrayName == "Colors", compositor.ColorArrayName
    compositor.ColorArrayName = "(none: Color)"
    compositor.Color = [0.0, 1.0, 0.0]
    compositor.UpdatePipeline()
    rgba = servermanager.Fetch(compositor).GetPointData().GetScalars()
    green = sum(1 for i in range(rgba.GetNumberOfTuples())
                if rgba.GetTuple4(i) == (0.0, 255.0, 0.0, 255.0))
    assert green > 20, green
    for proxy in (compositor, lighting, projection, ball):
        simple.Delete(proxy)
    print("colour arrays: %d to choose from; the solid colour drawn on %d pixels"
          % (len(names), green))


def main():
    simple.LoadPlugin(plugin, remote=False)
    check_menu()
    check_selection_goes_to_the_meshes()
    check_first_apply()
    check_colour_arrays()
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
            # The panel's default names itself (a blank entry looked unset).
            default = proxy.SMProxy.GetProperty("MirrorType").GetDefaultValue(0)
            assert default == "from calibration", default
            proxy.MirrorType = default
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
        # In its true colours (RGBA, no colour map) by default.
        assert display.MapScalars == 0
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
