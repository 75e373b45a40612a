// CatadioptricAR MeshPrep: remeshing to a pixel tolerance: model only what the scene requires.
//
// The compositor draws the image of a 3D edge as the straight segment between the images of its
// ends, while the mirror bends it into a curve. The bend of an edge is the largest distance in
// pixels between the exact image of points along the edge and that segment (EdgeBend.h in Core
// measures it through the camera). It grows with the square of the edge length and with the
// mirror's magnification, so triangles must be small where the mirror magnifies and may be large
// elsewhere. RemeshToPixelTolerance finds sizes per region such that every visible edge bends
// less than the tolerance, with as few triangles as it can: it splits edges that bend too much
// and collapses edges (OpenMesh decimation, with geometric error bounded) while the bend of every
// edge the collapse creates stays within the tolerance.
#ifndef catarScreenSpaceRemeshing_h
#define catarScreenSpaceRemeshing_h

#include "TriangleMesh.h"

#include <functional>
#include <string>

namespace catar
{
namespace mesh
{

/// Bend of the straight edge a-b in pixels; negative when the edge is not visible (then its size
/// is bound only by ScreenSpaceOptions::maxEdgeLength). Must be thread-safe.
using EdgeErrorFunction = std::function<double(const Vec3& a, const Vec3& b)>;

struct ScreenSpaceOptions
{
  double tolerance = 0.5;         ///< pixels; > 0
  double minEdgeLength = 0.0;     ///< never split edges shorter than this (0: 1e-4 x bounding box
                                  ///< diagonal)
  double maxEdgeLength = 0.0;     ///< never make edges longer than this (0: 0.25 x diagonal)
  double maxGeometricError = 0.0; ///< bound on the distance to the input surface when coarsening
                                  ///< (0: 1e-3 x diagonal)
  bool protectFeatures = true;
  double featureAngle = 60.0;
  int maxIterations = 8; ///< refine/coarsen rounds
  /// Between rounds, flip edges and slide vertices along the surface where that lowers the bend,
  /// so that the next round can collapse more edges.
  bool relax = true;
  /// The triangle budget. Before any work, the triangles the tolerance needs are estimated
  /// (estimatedTriangles); past twice the budget the remeshing is refused with the estimate.
  /// Refinement also stops at this many triangles (a warning says so; maxError tells what was
  /// reached).
  std::size_t maxTriangles = 4000000;
  /// Threads of the edge-bend loops (Core's pool, Module/Base/Parallel.h); < 1: its default, the
  /// hardware's. vtkCatadioptricRemesher passes VTK's (vtkCatadioptricParallel).
  int threads = 0;
  ProgressFunction progress = nullptr;
  StopFunction stop = nullptr; ///< asked at each progress step; true stops (error kAbortedError)
  void* progressData = nullptr;
};

struct ScreenSpaceResult
{
  bool ok = false;
  std::string error;
  Warnings warnings;
  TriangleMesh mesh;
  double maxError = 0.0;  ///< largest bend of a visible edge of the result, pixels
  double meanError = 0.0; ///< mean bend over visible edges
  std::size_t visibleEdges = 0;
  int iterations = 0;
  /// The triangles refinement was estimated to need (each edge cut into sqrt(bend / tolerance)
  /// pieces), before any work.
  double estimatedTriangles = 0.0;
};

/// Remeshes `input` so that every visible edge bends at most `options.tolerance` pixels (as far as
/// minEdgeLength allows; maxError reports what was achieved). Input is repaired first; point data
/// are carried over. Never throws.
ScreenSpaceResult RemeshToPixelTolerance(
  const TriangleMesh& input, const EdgeErrorFunction& edgeError, const ScreenSpaceOptions& options);

/// The largest and mean bend over the edges of `mesh` for which edgeError is >= 0, measured on
/// `threads` threads (< 1: catar::parallel::DefaultThreads()).
void MeasureEdgeError(const TriangleMesh& mesh, const EdgeErrorFunction& edgeError,
  double& maxError, double& meanError, std::size_t& visibleEdges, int threads = 0);

} // namespace mesh
} // namespace catar

#endif
