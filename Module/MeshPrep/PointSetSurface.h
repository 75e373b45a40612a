// CatadioptricAR MeshPrep: closed triangle surfaces from objects defined by their points (the
// paper triangulates such objects with Delaunay).
#ifndef catarPointSetSurface_h
#define catarPointSetSurface_h

#include "TriangleMesh.h"

#include <string>

namespace catar
{
namespace mesh
{

enum class PointSetMethod : int
{
  ConvexHull = 0,    ///< convex objects: the boundary of the 3D Delaunay triangulation (CGAL
                     ///< convex_hull_3)
  AdvancingFront = 1 ///< general surfaces from samples (CGAL advancing front reconstruction)
};

struct PointSetOptions
{
  PointSetMethod method = PointSetMethod::ConvexHull;
  /// Advancing front: largest radius/edge ratio of accepted candidate triangles (CGAL's
  /// radius_ratio_bound), and the beta angle (radians) controlling sharp turns.
  double radiusRatioBound = 5.0;
  double beta = 0.52;
  /// Progress between the stages (cleaning, the CGAL construction, orientation, extraction: CGAL
  /// runs each as one step); stop is asked at each and true ends in error kAbortedError.
  ProgressFunction progress = nullptr;
  StopFunction stop = nullptr;
  void* progressData = nullptr;
};

struct PointSetResult
{
  bool ok = false;
  std::string error;
  Warnings warnings;
  TriangleMesh mesh; ///< outward oriented; points are input points (NaN/Inf and duplicates
                     ///< dropped with a warning)
  /// Index in the input of each mesh point (mesh.points[i] == points[pointIds[i]]), to carry
  /// per-point data over. Input points not on the surface (interior points of a convex hull,
  /// outliers of a reconstruction) have no mesh point.
  std::vector<int> pointIds;
  /// The surface has no boundary edges: always so for ConvexHull; AdvancingFront may leave holes
  /// where the sampling is too sparse (then a warning says how many).
  bool closed = false;
};

/// Never throws. Fewer than 4 non-coplanar points is an error with a clear message.
PointSetResult SurfaceFromPoints(const std::vector<Vec3>& points, const PointSetOptions& options);

} // namespace mesh
} // namespace catar

#endif
