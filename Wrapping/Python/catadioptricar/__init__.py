"""CatadioptricAR: augmented reality for non-central catadioptric cameras, as VTK classes.

    import catadioptricar as car
    camera = car.vtkCatadioptricCamera()
    camera.Load("calibration.yaml")
    projection = car.vtkCatadioptricProjection()
    projection.SetCamera(camera)

The classes come from the wrapped VTK modules CatadioptricARCommon (the camera),
CatadioptricARFilters, CatadioptricARRendering and CatadioptricARScene (scene files);
VTK itself (ParaView's vtkmodules) is imported as needed.
"""

try:
    import vtkmodules.vtkCommonCore  # noqa: F401  (ParaView's VTK, which the modules are built on)
except ImportError as _error:
    import sys as _sys

    raise ImportError(
        "catadioptricar needs ParaView's VTK (Debian's paraview-dev), which this Python (%s, "
        "Python %d.%d) cannot import: %s. Use Debian's /usr/bin/python3 or pvpython; a pip, "
        "conda or pyenv Python has another VTK or none."
        % (_sys.executable, _sys.version_info[0], _sys.version_info[1], _error)
    ) from _error

from .CatadioptricARCommon import *  # noqa: F401,F403,E402
from .CatadioptricARFilters import *  # noqa: F401,F403,E402
from .CatadioptricARRendering import *  # noqa: F401,F403,E402
from .CatadioptricARScene import *  # noqa: F401,F403,E402

__all__ = [name for name in dir() if name.startswith("vtk")]


def enable_threads(n=None):
    """Run the parallel loops of every filter on several threads (the one opt-in for threads).

    Selects VTK's STDThread backend and, when ``n`` is given, that many threads, as
    ``vtkCatadioptricParallel::EnableThreads`` does in C++. Without it, Debian's VTK runs the
    loops on one thread. Setting ``VTK_SMP_BACKEND_IN_USE=STDThread`` in the environment before
    Python starts does the same.

    Parameters
    ----------
    n : int, optional
        Number of threads (the caller's included); the default is VTK's estimate, the number of
        cores.

    Examples
    --------
    >>> import catadioptricar as car
    >>> car.enable_threads()
    >>> car.enable_threads(2)
    """
    from vtkmodules.vtkCommonCore import vtkSMPTools

    vtkSMPTools.SetBackend("STDThread")
    if n is not None:
        if int(n) < 1:
            raise ValueError("enable_threads: n must be at least 1, not %r" % (n,))
        vtkSMPTools.Initialize(int(n))


__all__.append("enable_threads")


def _numpy():
    import numpy

    return numpy


def image_to_numpy(image, bgr=False):
    """A vtkImageData (2D, unsigned char scalars) as a numpy array, top row first.

    VTK stores the bottom row first; OpenCV, matplotlib and PIL expect the top row first, which
    is what this returns (a copy, not a view of VTK's memory).

    Parameters
    ----------
    image : vtkImageData
        A 2D image, for example the output of vtkCatadioptricCompositor or of
        vtkCatadioptricSceneRenderer.GetOutput(); its point-data scalars are read.
    bgr : bool, optional
        Swap the first and third channels (OpenCV's order) of a 3- or 4-channel image.

    Returns
    -------
    numpy.ndarray
        ``H x W x C`` (``C`` the scalars' components: 4 for RGBA) of the scalars' type
        (``uint8`` for the renderers' images).

    Examples
    --------
    >>> import catadioptricar as car
    >>> frame = car.render("Data/scenes/two-objects.yaml")   # the same as:
    >>> scene = car.vtkCatadioptricSceneRenderer()
    >>> scene.SetSceneFileName("Data/scenes/two-objects.yaml")
    >>> scene.Render()
    True
    >>> car.image_to_numpy(scene.GetOutput()).shape
    (524, 664, 4)
    """
    from vtkmodules.util.numpy_support import vtk_to_numpy

    np = _numpy()
    if image is None or image.GetPointData().GetScalars() is None:
        raise ValueError("image_to_numpy: the image has no scalars")
    width, height, depth = image.GetDimensions()
    if depth != 1:
        raise ValueError("image_to_numpy: a 2D image is needed, not %d slices" % depth)
    scalars = vtk_to_numpy(image.GetPointData().GetScalars())
    array = scalars.reshape(height, width, -1)[::-1]
    if bgr and array.shape[2] >= 3:
        array = array[:, :, [2, 1, 0] + list(range(3, array.shape[2]))]
    return np.ascontiguousarray(array)


def numpy_to_image(array, bgr=False):
    """A numpy image (top row first) as a vtkImageData, for frames and textures.

    Parameters
    ----------
    array : array_like
        ``H x W`` (grey) or ``H x W x C`` with ``C`` of 1 to 4, top row first, as OpenCV,
        matplotlib and PIL give it; ``uint8`` as the compositor, the ray tracer and the
        textures expect (other types are kept as they are).
    bgr : bool, optional
        The array is in OpenCV's channel order (``cv2.imread``): swap the first and third
        channels.

    Returns
    -------
    vtkImageData
        ``W x H`` pixels, origin 0, spacing 1, bottom row first (VTK's order), the values copied.

    Examples
    --------
    >>> import numpy, catadioptricar as car
    >>> frame = numpy.zeros((1048, 1328, 3), numpy.uint8)        # a black camera frame
    >>> image = car.numpy_to_image(frame)
    >>> image.GetDimensions()
    (1328, 1048, 1)
    >>> compositor = car.vtkCatadioptricCompositor()
    >>> compositor.SetInputData(0, image)                       # the frame to draw on
    """
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData

    np = _numpy()
    a = np.asarray(array)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3 or not 1 <= a.shape[2] <= 4 or a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError("numpy_to_image: an H x W or H x W x C array (C of 1 to 4) is needed, "
                         "not %s" % (a.shape,))
    if bgr and a.shape[2] >= 3:
        a = a[:, :, [2, 1, 0] + list(range(3, a.shape[2]))]
    if a.dtype.byteorder not in ("=", "|"):
        # VTK's arrays are in the machine's byte order: a big-endian array's values, not its bytes.
        a = a.astype(a.dtype.newbyteorder("="))
    height, width, channels = a.shape
    flat = np.ascontiguousarray(a[::-1]).reshape(-1, channels)
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    scalars = numpy_to_vtk(flat, deep=True)
    scalars.SetName("Scalars")
    image.GetPointData().SetScalars(scalars)
    return image


def _vtk_out(kind):
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray

    return vtkDoubleArray() if kind == "double" else vtkIntArray()


def _lend(rows):
    """A VTK array over a contiguous float64 ``N x width`` array, without a copy (VTK's
    numpy_to_vtk sizes an array of its own first, even when it then lends): the VTK array keeps
    ``rows`` alive."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray

    array = vtkDoubleArray()
    array.SetNumberOfComponents(rows.shape[1])
    array.SetVoidArray(rows.ravel(), rows.size, 1)
    array._numpy_reference = rows
    return array


def _rows(function, values, width):
    """``values`` as a contiguous float64 ``N x width`` array; one row of ``width`` is ``1 x
    width``. Any other shape (``width x N`` among them) is refused: reshaping it would pair up
    the wrong numbers."""
    np = _numpy()
    a = np.asarray(values, dtype=np.float64)
    if a.ndim == 1 and a.shape[0] == width:
        a = a.reshape(1, width)
    if a.ndim != 2 or a.shape[1] != width:
        raise ValueError("%s: expected an N x %d array (or one row of %d), not shape %s%s"
                         % (function, width, width, a.shape,
                            " (transpose it: .T)" if a.ndim == 2 and a.shape[0] == width else ""))
    return np.ascontiguousarray(a)


def _raise_batch_error(message):
    """A batch call's error: MemoryError when the results did not fit (the message gives their
    size and the memory left), ValueError otherwise."""
    raise (MemoryError if "out of memory" in message else ValueError)(message)


def project_points(camera, points, solver="auto"):
    """Project many world points through the mirror at once (C++, on the thread pool).

    The same results as ``camera.ProjectWorldPoint`` point by point.

    Parameters
    ----------
    camera : vtkCatadioptricCamera
    points : array_like
        ``N x 3`` world points (or one point of 3).
    solver : {"quartic", "iterative"}, optional
        ``"auto"`` (default): the faster where it gives the same answer (the Newton iteration
        for the sphere and most quadrics; the quartic for a quadric with the camera on its
        axis); or the closed-form quartic, or the safeguarded Newton iteration.

    Returns
    -------
    pixels : numpy.ndarray
        ``N x 2`` pixel coordinates (OpenCV's convention: (0, 0) the centre of the top-left
        pixel); NaN where the status says there is no projection (neither ``VALID`` nor
        ``OUTSIDE_IMAGE``).
    statuses : numpy.ndarray
        ``N`` status codes (``vtkCatadioptricCamera.VALID`` = 0, ``OUTSIDE_IMAGE``, ...).
    mirror_points : numpy.ndarray
        ``N x 3`` reflection points on the mirror, in the camera frame; NaN where there is no
        projection.

    Raises
    ------
    ValueError
        ``points`` not ``N x 3`` (a ``3 x N`` array is refused, not reinterpreted), or an
        unknown solver.
    MemoryError
        The results do not fit in the memory left (the message gives their size).

    Examples
    --------
    >>> import numpy, catadioptricar as car
    >>> camera = car.vtkCatadioptricCamera()
    >>> camera.Load("Data/calibration/demo-camera.yaml")  # the demo camera
    True
    >>> pixels, statuses, mirror = car.project_points(camera, [[0.15, -0.35, 0.95]])
    >>> int(statuses[0]) == car.vtkCatadioptricCamera.VALID
    True
    """
    from vtkmodules.util.numpy_support import vtk_to_numpy

    np = _numpy()
    solvers = {"quartic": 0, "iterative": 1, "auto": 2}
    if solver not in solvers:
        raise ValueError("project_points: solver must be 'auto', 'quartic' or 'iterative', not %r"
                         % (solver,))
    p = _rows("project_points", points, 3)
    pixels, statuses, mirror = _vtk_out("double"), _vtk_out("int"), _vtk_out("double")
    # The points are lent to VTK, not copied; the results are numpy views of VTK's arrays (they
    # keep them alive): no copy of N points is made on either side.
    if not camera.ProjectWorldPoints(_lend(p), pixels, statuses, mirror,
                                     solvers[solver]):
        _raise_batch_error(camera.GetLastError())
    n = p.shape[0]
    px = vtk_to_numpy(pixels).reshape(n, 2)
    st = vtk_to_numpy(statuses).reshape(n)
    mp = vtk_to_numpy(mirror).reshape(n, 3)
    none = (st != vtkCatadioptricCamera.VALID) & (st != vtkCatadioptricCamera.OUTSIDE_IMAGE)  # noqa: F405
    px[none] = np.nan
    mp[none] = np.nan
    return px, st, mp


def back_project(camera, pixels):
    """The reflected rays of many pixels at once (C++, on the thread pool).

    The same results as ``camera.BackProjectPixel`` pixel by pixel.

    Parameters
    ----------
    camera : vtkCatadioptricCamera
    pixels : array_like
        ``N x 2`` pixel coordinates (or one pixel of 2), OpenCV's convention.

    Returns
    -------
    origins : numpy.ndarray
        ``N x 3`` points where the rays leave the mirror, world frame; NaN where the pixel has
        no ray (status neither ``VALID`` nor ``OUTSIDE_IMAGE``).
    directions : numpy.ndarray
        ``N x 3`` unit directions of the reflected rays, world frame; NaN where no ray.
    statuses : numpy.ndarray
        ``N`` status codes (``vtkCatadioptricCamera.VALID`` = 0 where the pixel sees the mirror).

    Examples
    --------
    >>> import catadioptricar as car
    >>> camera = car.vtkCatadioptricCamera()
    >>> origins, directions, statuses = car.back_project(camera, [[663.5, 523.5]])
    >>> round(float((directions ** 2).sum()), 6)
    1.0
    """
    from vtkmodules.util.numpy_support import vtk_to_numpy

    np = _numpy()
    q = _rows("back_project", pixels, 2)
    origins, directions, statuses = _vtk_out("double"), _vtk_out("double"), _vtk_out("int")
    if not camera.BackProjectPixels(_lend(q), origins, directions, statuses):
        _raise_batch_error(camera.GetLastError())
    n = q.shape[0]
    o = vtk_to_numpy(origins).reshape(n, 3)
    d = vtk_to_numpy(directions).reshape(n, 3)
    st = vtk_to_numpy(statuses).reshape(n)
    none = (st != vtkCatadioptricCamera.VALID) & (st != vtkCatadioptricCamera.OUTSIDE_IMAGE)  # noqa: F405
    o[none] = np.nan
    d[none] = np.nan
    return o, d, st


def render(scene_file=None, bgr=False, antialias=0):
    """Render a scene file and return the frame as numpy (``H x W x 4`` RGBA ``uint8``).

    Parameters
    ----------
    scene_file : str, optional
        A scene file (YAML or JSON, Documentation/file-formats.md); None renders the built-in
        demo scene.
    bgr : bool, optional
        OpenCV's channel order (B, G, R, A).
    antialias : int, optional
        Samples per pixel side of the anti-aliased edges (2 to 4); 0 keeps the scene's setting.

    Returns
    -------
    numpy.ndarray
        The frame, top row first.

    Raises
    ------
    RuntimeError
        When the scene cannot be read or rendered (the renderer's error).

    Examples
    --------
    >>> import catadioptricar as car
    >>> frame = car.render("Data/scenes/two-objects.yaml")
    >>> frame.shape, frame.dtype
    ((524, 664, 4), dtype('uint8'))
    """
    scene = vtkCatadioptricSceneRenderer()  # noqa: F405 (from CatadioptricARScene)
    if scene_file is not None:
        scene.SetSceneFileName(str(scene_file))
    scene.SetAntialias(int(antialias))
    if not scene.Render():
        raise RuntimeError(scene.GetLastError())
    return image_to_numpy(scene.GetOutput(), bgr=bgr)


def marker_poses(scene_file, markers=None, frames=None):
    """The camera pose of each frame of a scene, found from the markers seen in its background.

    Each frame is rendered as ``catadioptric-render`` does; its pose comes with a verdict and
    its one-sigma uncertainty (Documentation/markers.md, "Guards"). A frame without a reliable
    pose keeps the previous frame's pose in the rendering; here its own estimate (if any) is
    returned, with its verdict.

    Parameters
    ----------
    scene_file : str
        A scene file whose background is a video or an image and which names a marker board
        (its ``markers`` key), or any such scene with ``markers`` given here.
    markers : str, optional
        A marker board file, over the scene's ``markers``.
    frames : iterable of int, optional
        The frames to estimate (default: every frame of the scene).

    Returns
    -------
    dict of numpy.ndarray
        ``frame`` (N, int), ``time`` (N, seconds), ``verdict`` (N, str: ``"reliable"``,
        ``"unreliable"`` or ``"missing"``), ``world_to_camera`` (N x 4 x 4; NaN without an
        estimate), ``sigma_position`` (N, metres: the camera centre's one sigma),
        ``sigma_angle`` (N, degrees), ``markers`` (N, int: found in the frame), ``inliers`` and
        ``corners`` (N, int: the corners that fit, of those used), ``rms`` (N, px) and ``note``
        (N, str: why a frame has no reliable pose, "" when it has).

    Raises
    ------
    RuntimeError
        When the scene cannot be read or a frame cannot be rendered.
    ValueError
        When the scene estimates no pose from markers.
    IndexError
        When a frame is outside the scene's frames.
    """
    np = _numpy()
    scene = vtkCatadioptricSceneRenderer()  # noqa: F405 (from CatadioptricARScene)
    scene.SetSceneFileName(str(scene_file))
    if markers is not None:
        scene.SetMarkerBoardFileName(str(markers))
    if not scene.LoadScene():
        raise RuntimeError(scene.GetLastError())
    if not scene.GetUsesMarkers():
        raise ValueError("marker_poses: %s estimates no pose from markers: give markers=BOARD or "
                         "the scene's 'markers' key" % scene_file)
    count = scene.GetNumberOfFrames()
    indices = list(range(count)) if frames is None else [int(k) for k in frames]
    for k in indices:
        if not 0 <= k < count:
            raise IndexError("marker_poses: frame %d is outside the scene's frames 0 to %d"
                             % (k, count - 1))
    n = len(indices)
    out = {
        "frame": np.array(indices, dtype=np.int64),
        "time": np.empty(n),
        "verdict": np.empty(n, dtype=object),
        "world_to_camera": np.full((n, 4, 4), np.nan),
        "sigma_position": np.full(n, np.nan),
        "sigma_angle": np.full(n, np.nan),
        "markers": np.zeros(n, dtype=np.int64),
        "inliers": np.zeros(n, dtype=np.int64),
        "corners": np.zeros(n, dtype=np.int64),
        "rms": np.full(n, np.nan),
        "note": np.empty(n, dtype=object),
    }
    for i, k in enumerate(indices):
        if not scene.RenderFrame(k):
            raise RuntimeError("marker_poses: frame %d: %s" % (k, scene.GetLastError()))
        out["time"][i] = scene.GetFrameTime(k)
        out["verdict"][i] = scene.GetFramePoseVerdict()
        out["note"][i] = scene.GetFramePoseNote()
        estimate = [0.0] * 16
        if scene.GetFramePoseEstimate(estimate):
            out["world_to_camera"][i] = np.array(estimate).reshape(4, 4)
            out["sigma_position"][i] = scene.GetFramePosePositionSigma()
            out["sigma_angle"][i] = scene.GetFramePoseAngleSigma()
            out["rms"][i] = scene.GetFramePoseRMS()
        out["markers"][i] = scene.GetFramePoseMarkers()
        out["inliers"][i] = scene.GetFramePoseInliers()
        out["corners"][i] = scene.GetFramePoseCorners()
    out["verdict"] = out["verdict"].astype(str)
    out["note"] = out["note"].astype(str)
    return out


def render_mesh(vertices, triangles, camera=None, frame=None, color=(0.8, 0.8, 0.8),
                background=(0.0, 0.0, 0.0, 1.0), bgr=False, antialias=0):
    """Draw a triangle mesh given as numpy arrays through the mirror; return the image as numpy.

    The fast path (projection, the paper's painter order, the compositor) in one call: vertices
    in, frame out, no VTK objects to build.

    Parameters
    ----------
    vertices : array_like
        ``N x 3`` world points.
    triangles : array_like
        ``M x 3`` vertex indices (0 to N - 1).
    camera : vtkCatadioptricCamera or str, optional
        A camera, or a calibration file's path; None: the built-in demo camera.
    frame : array_like, optional
        The camera frame to draw onto, ``H x W x 3`` or ``H x W x 4`` ``uint8`` of the camera's
        size, top row first; None: ``background``.
    color : sequence of 3 floats, optional
        The mesh's colour, 0 to 1.
    background : sequence of 4 floats, optional
        RGBA 0 to 1 where there is no frame and no mesh.
    bgr : bool, optional
        ``frame`` and the result in OpenCV's channel order.
    antialias : int, optional
        Samples per pixel side on the edges (2 to 4); 0 is off.

    Returns
    -------
    numpy.ndarray
        ``H x W x 4`` RGBA (BGRA with ``bgr``) ``uint8``, top row first.

    Raises
    ------
    ValueError
        Arrays of the wrong shape, indices out of range.
    RuntimeError
        The pipeline's error (a camera that cannot be loaded, a frame of the wrong size).

    Examples
    --------
    >>> import numpy, catadioptricar as car
    >>> square = numpy.array([[0.1, -0.4, 0.9], [0.2, -0.4, 0.9], [0.2, -0.4, 1.0], [0.1, -0.4, 1.0]])
    >>> image = car.render_mesh(square, [[0, 1, 2], [0, 2, 3]], color=(1, 0, 0))
    >>> image.shape
    (1048, 1328, 4)
    """
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.vtkConstants import VTK_STRING

    np = _numpy()
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError("render_mesh: vertices must be N x 3, not %s" % (v.shape,))
    if t.ndim != 2 or t.shape[1] != 3 or (t.size and not np.issubdtype(t.dtype, np.integer)):
        raise ValueError("render_mesh: triangles must be M x 3 integers, not %s %s"
                         % (t.shape, t.dtype))
    if t.size and (t.min() < 0 or t.max() >= len(v)):
        raise ValueError("render_mesh: triangle indices must be 0 to %d" % (len(v) - 1))
    for name, value, size in (("color", color, 3), ("background", background, 4)):
        c = np.asarray(value, dtype=np.float64)
        if c.shape != (size,) or not np.isfinite(c).all():
            raise ValueError("render_mesh: %s must be %d finite numbers, not %r" % (name, size, value))
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(v), deep=True))
    cells = vtkCellArray()
    offsets = np.arange(0, 3 * len(t) + 1, 3, dtype=np.int64)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_to_vtkIdTypeArray(np.ascontiguousarray(t, dtype=np.int64).ravel(),
                                          deep=True))
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(cells)

    projection = vtkCatadioptricProjection()  # noqa: F405
    if isinstance(camera, str):
        projection.SetCalibrationFileName(camera)
    elif camera is not None:
        projection.SetCamera(camera)
    projection.SetInputData(mesh)
    sort = vtkCatadioptricPainterSort()  # noqa: F405
    sort.SetInputConnection(projection.GetOutputPort())
    compositor = vtkCatadioptricCompositor()  # noqa: F405
    compositor.AddInputConnection(1, sort.GetOutputPort())
    compositor.SetColorArrayName("")
    compositor.SetColor(*color)
    compositor.SetBackgroundColor(*background)
    if antialias:
        compositor.SetAntialias(True)
        compositor.SetAntialiasSamples(int(antialias))
    if frame is not None:
        compositor.SetInputData(0, numpy_to_image(frame, bgr=bgr))
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(caller, event, message):
        # "ERROR: In FILE, line N\nCLASS (ADDRESS): the sentence": keep the sentence.
        errors.append(str(message).split("): ", 1)[-1].strip())

    for algorithm in (projection, sort, compositor):
        algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
    compositor.Update()
    if errors or compositor.GetOutput().GetNumberOfPoints() == 0:
        raise RuntimeError("render_mesh: " + ("; ".join(str(e) for e in errors if e)
                                              or "no image was made"))
    return image_to_numpy(compositor.GetOutput(), bgr=bgr)


__all__ += ["image_to_numpy", "numpy_to_image", "project_points", "back_project", "render",
            "render_mesh", "marker_poses"]
