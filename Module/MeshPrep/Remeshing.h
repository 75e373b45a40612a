// CatadioptricAR MeshPrep: remeshing a triangle surface to a target triangle area.
//
// The compositor draws each triangle as a straight-edged 2D triangle, so accuracy rests on small
// triangles where the mirror bends lines and speed on having no more triangles than that. This
// file makes a uniform target size: CGAL's isotropic remeshing (Polygon Mesh Processing) to the
// edge length of an equilateral triangle of the target area, with sharp feature edges and
// boundaries protected; OpenMesh's quadric decimation to coarsen over-dense input fast before
// that; subdivision of too coarse input. ScreenSpaceRemeshing.h chooses sizes per region.
#ifndef catarRemeshing_h
#define catarRemeshing_h

#include "TriangleMesh.h"

#include <string>

namespace catar
{
namespace mesh
{

/// The edge length of an equilateral triangle of the given area: sqrt(4 area / sqrt(3)).
double EdgeLengthForArea(double area);
/// The area of an equilateral triangle of the given edge length: sqrt(3)/4 length^2.
double AreaForEdgeLength(double length);

enum class RemeshStrategy : int
{
  Auto = 0,      ///< decimate first when the input is much denser than the target, subdivide
                 ///< first when it is much coarser, then isotropic remeshing
  Isotropic = 1, ///< CGAL isotropic remeshing only
  Decimate = 2,  ///< OpenMesh quadric decimation only (to the target's triangle count)
  Subdivide = 3  ///< midpoint subdivision only (until the target area is reached)
};

struct RemeshOptions
{
  double targetArea = 0.0;     ///< target triangle area, model units squared; must be > 0
  int iterations = 3;          ///< isotropic remeshing iterations (split, collapse, flip, smooth)
  bool protectFeatures = true; ///< keep sharp edges and corners (a box keeps its edges)
  double featureAngle = 60.0;  ///< degrees: edges whose dihedral angle deviates more from flat
                               ///< are sharp
  bool preserveBoundaries = true; ///< keep the boundary polylines where they are
  RemeshStrategy strategy = RemeshStrategy::Auto;
  ProgressFunction progress = nullptr;
  StopFunction stop = nullptr; ///< asked at each progress step; true stops (error kAbortedError)
  void* progressData = nullptr;
};

struct RemeshResult
{
  bool ok = false;
  std::string error; ///< why it failed (ok == false)
  Warnings warnings; ///< repairs made, input ignored
  TriangleMesh mesh; ///< the remeshed surface, point data carried over
  std::string steps; ///< what was done, e.g. "decimate, isotropic"
};

/// Remeshes `input` so that its triangles have about `options.targetArea`. The input is repaired
/// first (see MeshRepair.h); point data are carried over with TransferPointData. Never throws.
RemeshResult RemeshToArea(const TriangleMesh& input, const RemeshOptions& options);

/// Sets target.pointData from source.pointData: each target point is projected onto the source
/// surface (closest point, CGAL AABB tree) and its attributes are interpolated barycentrically in
/// the source triangle it lands in. Target points keep their positions.
void TransferPointData(const TriangleMesh& source, TriangleMesh& target);

} // namespace mesh
} // namespace catar

#endif
