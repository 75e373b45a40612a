// CatadioptricAR MeshPrep: measurements of triangle meshes (size statistics, distance between
// surfaces, sharp edges) used by the tests, the benchmarks and the filters' field data.
#ifndef catarMeshMetrics_h
#define catarMeshMetrics_h

#include "TriangleMesh.h"

namespace catar
{
namespace mesh
{

struct AreaStatistics
{
  std::size_t count = 0;
  double total = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double p95 = 0.0; ///< 95th percentile
  double min = 0.0;
  double max = 0.0;
};

AreaStatistics TriangleAreaStatistics(const TriangleMesh& mesh);

/// Symmetric Hausdorff distance between two surfaces, approximated by sampling both (CGAL PMP,
/// samples about every `precision` apart on each surface) and exact point-to-surface distances.
double HausdorffDistance(const TriangleMesh& a, const TriangleMesh& b, double precision);

/// Total length of the sharp edges (dihedral angle deviating more than featureAngle degrees from
/// flat) and of the boundary edges.
double SharpEdgeLength(const TriangleMesh& mesh, double featureAngleDegrees);
double BoundaryEdgeLength(const TriangleMesh& mesh);

/// Longest distance from a point on the sharp edges of `reference` to the sharp edges of `mesh`
/// (sampled every `step`): 0 when every sharp edge of the reference is kept.
double SharpEdgeDeviation(
  const TriangleMesh& reference, const TriangleMesh& mesh, double featureAngleDegrees, double step);

} // namespace mesh
} // namespace catar

#endif
