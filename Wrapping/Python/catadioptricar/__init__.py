"""CatadioptricAR: augmented reality for non-central catadioptric cameras, as VTK classes.

    import catadioptricar as car
    camera = car.vtkCatadioptricCamera()
    camera.Load("calibration.yaml")
    projection = car.vtkCatadioptricProjection()
    projection.SetCamera(camera)

The classes come from the wrapped VTK modules CatadioptricARFilters and CatadioptricARRendering;
VTK itself (ParaView's vtkmodules) is imported as needed.
"""

from .CatadioptricARFilters import *  # noqa: F401,F403
from .CatadioptricARRendering import *  # noqa: F401,F403

__all__ = [name for name in dir() if name.startswith("vtk")]
