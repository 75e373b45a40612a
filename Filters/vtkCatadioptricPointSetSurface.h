/**
 * @class   vtkCatadioptricPointSetSurface
 * @brief   closed triangle surface of an object defined by its points
 *
 * The paper triangulates objects defined by points (e.g. the corners of its parallelepiped) with
 * Delaunay. Method CONVEX_HULL: the boundary of the 3D Delaunay triangulation, i.e. the convex
 * hull (CGAL), for convex objects. Method ADVANCING_FRONT: CGAL's advancing front surface
 * reconstruction, for samples of general (non-convex) surfaces; RadiusRatioBound and Beta steer
 * which candidate triangles it accepts. Output triangles are oriented outwards and use the input
 * points (invalid and duplicate points are dropped with a warning). Fewer than 4 points, or all
 * on a plane, is an error. Feed the output to vtkCatadioptricRemesher to get triangles of the
 * size the scene needs.
 */
#ifndef vtkCatadioptricPointSetSurface_h
#define vtkCatadioptricPointSetSurface_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricPointSetSurface : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricPointSetSurface* New();
  vtkTypeMacro(vtkCatadioptricPointSetSurface, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    CONVEX_HULL = 0,
    ADVANCING_FRONT = 1
  };
  ///@{
  /// Default CONVEX_HULL.
  vtkSetClampMacro(Method, int, CONVEX_HULL, ADVANCING_FRONT);
  vtkGetMacro(Method, int);
  void SetMethodToConvexHull() { this->SetMethod(CONVEX_HULL); }
  void SetMethodToAdvancingFront() { this->SetMethod(ADVANCING_FRONT); }
  ///@}

  ///@{
  /// ADVANCING_FRONT: the largest radius/edge ratio of accepted triangles (default 5) and the
  /// angle beta in radians bounding sharp turns (default 0.52).
  vtkSetClampMacro(RadiusRatioBound, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadiusRatioBound, double);
  vtkSetClampMacro(Beta, double, 0.0, 3.14159265358979);
  vtkGetMacro(Beta, double);
  ///@}

protected:
  vtkCatadioptricPointSetSurface();
  ~vtkCatadioptricPointSetSurface() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Method = CONVEX_HULL;
  double RadiusRatioBound = 5.0;
  double Beta = 0.52;

private:
  vtkCatadioptricPointSetSurface(const vtkCatadioptricPointSetSurface&) = delete;
  void operator=(const vtkCatadioptricPointSetSurface&) = delete;
};

#endif
