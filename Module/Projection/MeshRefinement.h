// CatadioptricAR Core: the triangles of a mesh this frame's image needs split, and their pieces.
//
// The mesh side of the per-frame tessellation (ImageTessellation.h): which triangles of a polygon
// mesh cross the visibility boundary or bend more than a tolerance (ChooseTriangles), and their
// pieces, tessellated so that triangles sharing an edge split it alike (TessellateAlike: the
// splits each makes on its edges are passed to the triangles across them, which are tessellated
// again with those splits forced, until no triangle makes a split its neighbour lacks; no crack).
// Edges are matched by their end points' positions, so faces that do not share point ids (a box
// with a normal per face) still share their edges. vtkCatadioptricTessellatedMesh reads the
// vtkPolyData and assembles the refined mesh.
#ifndef catarMeshRefinement_h
#define catarMeshRefinement_h

#include "ImageTessellation.h"

#include <cstdint>
#include <vector>

namespace catar
{
/// A polygon mesh as the refinement reads it: point i at points[3 i .. 3 i + 2] (Real: float or
/// double); polygon c is connectivity[offsets[c]] ... connectivity[offsets[c + 1] - 1] (Index:
/// int, long or long long, as a cell array stores them).
template<typename Index, typename Real>
struct PolygonMeshView
{
  const Real* points = nullptr;
  std::int64_t numberOfPoints = 0;
  const Index* offsets = nullptr;
  const Index* connectivity = nullptr;
  std::int64_t numberOfPolygons = 0;
};

/// The projections of a mesh's points this frame: one ProjectionStatus per point, pixels (two per
/// point) and mirror points (three per point, camera frame: where new points' reflections are
/// searched from).
struct PointProjections
{
  const unsigned char* status = nullptr;
  const double* pixels = nullptr;
  const double* mirrorPoints = nullptr;
};

/// The triangles to split this frame, in polygon order: a quick pass on the corners' statuses and
/// edge lengths (NeedsFateCheck), then the fate of each triangle that needs it (TriangleFates).
/// Polygons of more sides are left alone. threads: the loops' threads (Parallel.h).
template<typename Index, typename Real>
std::vector<std::int64_t> ChooseTriangles(const PolygonMeshView<Index, Real>& mesh,
  const Projector& projector, const TessellationOptions& options, const PointProjections& at,
  int threads);

/// The pieces of the chosen triangles, in polygon order, and of the neighbours that must split a
/// shared edge too (added to `chosen`, which comes back sorted). At most maxPieces pieces are made
/// in all (each chosen triangle's share of that bounds its depth). New points' ids in each
/// tessellation start at mesh.numberOfPoints.
template<typename Index, typename Real>
std::vector<Tessellation> TessellateAlike(const PolygonMeshView<Index, Real>& mesh,
  const Projector& projector, const TessellationOptions& options, const PointProjections& at,
  std::vector<std::int64_t>& chosen, std::size_t maxPieces, int threads);
} // namespace catar

#endif
