// CatadioptricAR MeshPrep: making arbitrary triangle input safe for remeshing.
#ifndef catarMeshRepair_h
#define catarMeshRepair_h

#include "TriangleMesh.h"

#include <string>

namespace catar
{
namespace mesh
{

struct RepairReport
{
  std::size_t invalidPoints = 0;       ///< NaN/Inf coordinates: their triangles removed
  std::size_t invalidTriangles = 0;    ///< indices out of range or repeated
  std::size_t mergedPoints = 0;        ///< coincident points merged
  std::size_t degenerateTriangles = 0; ///< zero-area (collinear) triangles removed
  std::size_t duplicateTriangles = 0;  ///< same three points as another triangle, removed
  std::size_t nonManifoldEdges = 0;    ///< edges with more than two triangles (made manifold)
  std::size_t nonManifoldVertices = 0; ///< pinched vertices (duplicated)
  std::size_t unusedPoints = 0;        ///< points no triangle uses, removed
  std::size_t boundaryLoops = 0;       ///< holes/borders (kept; reported)
  bool reoriented = false;             ///< triangle orientation made consistent
};

/// Repairs `mesh` in place so that it is a manifold, consistently oriented triangle surface
/// without degenerate or duplicate triangles; point data follow their points. Every repair made
/// adds a line to `warnings`. Returns false with `error` set when nothing usable is left (empty
/// input, every triangle degenerate...). Never throws.
bool RepairMesh(TriangleMesh& mesh, RepairReport& report, Warnings& warnings, std::string& error);

} // namespace mesh
} // namespace catar

#endif
