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

from .CatadioptricARCommon import *  # noqa: F401,F403
from .CatadioptricARFilters import *  # noqa: F401,F403
from .CatadioptricARRendering import *  # noqa: F401,F403
from .CatadioptricARScene import *  # noqa: F401,F403

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
