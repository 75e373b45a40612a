// CatadioptricAR MeshPrep built without CGAL and OpenMesh (CATAR_WITH_MESHPREP OFF, or either not
// found): every preparation refuses with a sentence that names what is missing and how to get it;
// the measures that need them throw it. Nothing answers as if it had prepared or measured a mesh.
// The two edge-length formulas need no library and are the same as in Remeshing.cxx.
#include "MeshMetrics.h"
#include "MeshRepair.h"
#include "PointSetSurface.h"
#include "Remeshing.h"
#include "ScreenSpaceRemeshing.h"

#include <cmath>
#include <stdexcept>

namespace catar
{
namespace mesh
{
namespace
{
const char* const kWhy =
  "Mesh preparation (repair, remeshing, surfaces from points, mesh measures) is not available: "
  "this build of CatadioptricAR was made without CGAL and OpenMesh (Debian: libcgal-dev, "
  "libopenmesh-dev; then build again with CATAR_WITH_MESHPREP=ON).";

[[noreturn]] void Refuse()
{
  throw std::runtime_error(kWhy);
}
} // namespace

AreaStatistics TriangleAreaStatistics(const TriangleMesh&)
{
  Refuse();
}

double HausdorffDistance(const TriangleMesh&, const TriangleMesh&, double)
{
  Refuse();
}

double SharpEdgeLength(const TriangleMesh&, double)
{
  Refuse();
}

double BoundaryEdgeLength(const TriangleMesh&)
{
  Refuse();
}

double SharpEdgeDeviation(const TriangleMesh&, const TriangleMesh&, double, double)
{
  Refuse();
}

bool RepairMesh(TriangleMesh&, RepairReport&, Warnings&, std::string& error)
{
  error = kWhy;
  return false;
}

PointSetResult SurfaceFromPoints(const std::vector<Vec3>&, const PointSetOptions&)
{
  PointSetResult result;
  result.ok = false;
  result.error = kWhy;
  return result;
}

double EdgeLengthForArea(double area)
{
  return std::sqrt(4.0 * area / std::sqrt(3.0));
}

double AreaForEdgeLength(double length)
{
  return std::sqrt(3.0) / 4.0 * length * length;
}

RemeshResult RemeshToArea(const TriangleMesh&, const RemeshOptions&)
{
  RemeshResult result;
  result.ok = false;
  result.error = kWhy;
  return result;
}

void TransferPointData(const TriangleMesh&, TriangleMesh&)
{
  Refuse();
}

ScreenSpaceResult RemeshToPixelTolerance(
  const TriangleMesh&, const EdgeErrorFunction&, const ScreenSpaceOptions&)
{
  ScreenSpaceResult result;
  result.ok = false;
  result.error = kWhy;
  return result;
}

void MeasureEdgeError(
  const TriangleMesh&, const EdgeErrorFunction&, double&, double&, std::size_t&, int)
{
  Refuse();
}
} // namespace mesh
} // namespace catar
