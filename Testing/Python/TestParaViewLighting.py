"""Catadioptric Lighting through the ParaView plugin, run by pvpython: spot, point and directional
lights in the panel, each kind kept when another is changed; the reference ray tracer given the
Lighting's output is lit as the compositor's picture is; the colour arrays are chosen from the
inputs' arrays.

    pvpython --force-offscreen-rendering TestParaViewLighting.py PLUGIN
"""

import sys

from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

import numpy as np

plugin = sys.argv[1]

# Two point lights (position, colour, attenuation constant, linear, quadratic) and a directional
# light (towards the light, colour) around the ball at (0.06, -0.32, 0.92), on its side that faces
# the mirror at (0, 0, 1).
POINT_LIGHTS = [0.15, -0.22, 1.02, 1.0, 0.85, 0.7, 1.0, 0.0, 0.0,
                -0.04, -0.26, 0.98, 0.3, 0.5, 1.0, 1.0, 2.0, 10.0]
DIRECTIONAL_LIGHTS = [-0.3, 1.0, 0.6, 0.35, 0.35, 0.25]


def rgba(proxy):
    """The proxy's image as an (n, 4) array of floats."""
    proxy.UpdatePipeline()
    return vtk_to_numpy(servermanager.Fetch(proxy).GetPointData().GetScalars()).astype(float)


def kinds(lighting):
    """How many spot, point and directional lights the filter has (as the lighting reads them)."""
    lights = lighting.GetClientSideObject().GetLights()
    count = [0, 0, 0]
    for i in range(lights.GetNumberOfItems()):
        light = lights.GetItemAsObject(i)
        if not light.GetPositional():
            count[2] += 1
        elif light.GetConeAngle() < 90:
            count[0] += 1
        else:
            count[1] += 1
    return count


def domain_strings(proxy, name):
    """The strings of the property's ArrayListDomain."""
    domain = proxy.GetProperty(name).SMProperty.FindDomain("vtkSMArrayListDomain")
    assert domain is not None, name
    return [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]


def main():
    simple.LoadPlugin(plugin, remote=False)
    # The Python wrapping of the same classes, to read the filter's lights.
    import catadioptricar  # noqa: F401
    # The demo camera (no calibration file): 1328 x 1048.
    ball = simple.Sphere(Center=[0.06, -0.32, 0.92], Radius=0.03, ThetaResolution=64,
                         PhiResolution=32)
    projection = simple.CatadioptricProjection(Input=ball)
    lighting = simple.CatadioptricLighting(Input=projection)
    sort = simple.CatadioptricPainterSort(Input=lighting)
    compositor = simple.CatadioptricCompositor(Input=[sort], Frame=None)
    tracer = simple.CatadioptricRayTracer(Input=[lighting], Frame=None)
    assert tracer.UseInputLighting == 1

    # Colour arrays chosen from the inputs' arrays, "(none: ...)" for the solid colour.
    lighting.UpdatePipeline()
    names = domain_strings(lighting, "InputColorArrayName")
    assert "(none: DiffuseColor)" in names and "MirrorPoint" in names, names
    assert "WorldToCamera" not in names, names  # field data is no colour
    assert lighting.InputColorArrayName == "Colors", lighting.InputColorArrayName
    names = domain_strings(tracer, "ColorArrayName")
    assert "Colors" in names and "(none: Color)" in names, names
    assert "LightingSettings" not in names, names

    # Each kind of light changes the picture when added, and stays when another kind changes.
    lighting.SpotLights = []
    images = {"none": rgba(compositor)}
    assert kinds(lighting) == [0, 0, 0], kinds(lighting)
    lighting.SpotLights = [0.2, -0.2, 1.3, 0.06, -0.32, 0.92, 30, 1, 1, 1]
    images["spot"] = rgba(compositor)
    lighting.PointLights = POINT_LIGHTS
    images["spot+point"] = rgba(compositor)
    lighting.DirectionalLights = DIRECTIONAL_LIGHTS
    images["spot+point+directional"] = rgba(compositor)
    assert kinds(lighting) == [1, 2, 1], kinds(lighting)
    lighting.SpotLights = []
    assert kinds(lighting) == [0, 2, 1], kinds(lighting)
    images["point+directional"] = rgba(compositor)
    order = ["none", "spot", "spot+point", "spot+point+directional"]
    for before, after in zip(order, order[1:]):
        changed = int(np.count_nonzero(np.any(images[before] != images[after], axis=1)))
        assert changed > 100, (before, after, changed)
    lighting.PointLights = []
    assert kinds(lighting) == [0, 0, 1], kinds(lighting)
    lighting.PointLights = POINT_LIGHTS
    assert kinds(lighting) == [0, 2, 1], kinds(lighting)

    # The ray tracer given the Lighting's output is lit as the compositor's picture (two point
    # lights and a directional light), exactly at each hit.
    fast = rgba(compositor)
    exact = rgba(tracer)
    assert fast.shape == exact.shape, (fast.shape, exact.shape)
    ink = lambda a: np.any(a[:, :3] > 0, axis=1)
    both = ink(fast) & ink(exact)
    objectPixels = int(both.sum())
    assert objectPixels > 500, objectPixels
    lit = float(np.abs(fast[both, :3] - exact[both, :3]).mean())
    # The same ball unlit in the ray tracer (the raw sphere in its solid Color), and the Lighting's
    # output with Use Input Lighting off (its per-vertex Colors drawn as they are).
    unlitTracer = simple.CatadioptricRayTracer(Input=[ball], Frame=None)
    unlit = rgba(unlitTracer)
    unlitDifference = float(np.abs(fast[both, :3] - unlit[both, :3]).mean())
    tracer.UseInputLighting = 0
    vertexColours = float(np.abs(fast[both, :3] - rgba(tracer)[both, :3]).mean())
    tracer.UseInputLighting = 1
    print("lighting: compositor and ray tracer over %d object pixels: mean absolute difference "
          "%.2f levels (the unlit ray tracer: %.2f; Use Input Lighting off: %.2f)"
          % (objectPixels, lit, unlitDifference, vertexColours))
    assert lit < 3.0, lit
    assert unlitDifference > 10 * max(lit, 1.0), (unlitDifference, lit)
    # Lit, not drawn with the Lighting's colours: the same image as SetMeshLighting with the
    # Lighting filter gives the raw sphere, and Color Array Name (for unlit meshes) changes nothing.
    given = simple.CatadioptricRayTracer(Input=[ball], Frame=None)
    given.GetClientSideObject().SetMeshLighting(0, lighting.GetClientSideObject())
    given.GetClientSideObject().Modified()
    assert np.array_equal(rgba(given), exact)
    tracer.ColorArrayName = "(none: Color)"
    tracer.Color = [0.0, 1.0, 0.0]
    assert np.array_equal(rgba(tracer), exact)
    tracer.UseInputLighting = 0
    green = int(np.count_nonzero(np.all(rgba(tracer) == [0, 255, 0, 255], axis=1)))
    assert green > 0.9 * objectPixels, (green, objectPixels)
    tracer.UseInputLighting = 1
    # Changing a light in the panel reaches the ray tracer too.
    lighting.DirectionalLights = [-0.3, 1.0, 0.6, 1.0, 0.0, 0.0]
    moved = rgba(tracer)
    assert int(np.count_nonzero(np.any(moved != exact, axis=1))) > 100

    for proxy in (given, unlitTracer, tracer, compositor, sort, lighting, projection, ball):
        simple.Delete(proxy)
    print("ParaView lighting: 1 passed, 0 failed")


if __name__ == "__main__":
    main()
