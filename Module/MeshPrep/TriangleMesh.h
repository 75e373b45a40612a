// CatadioptricAR MeshPrep: a plain indexed triangle mesh, the exchange format between the VTK
// filters and the mesh-preparation algorithms (CGAL, OpenMesh). VTK-free.
#ifndef catarTriangleMesh_h
#define catarTriangleMesh_h

#include "Types.h"

#include <Eigen/Geometry> // Vec3::cross

#include <array>
#include <string>
#include <vector>

namespace catar
{
namespace mesh
{

/// A per-point attribute carried through remeshing (texture coordinates, normals, colours...):
/// `components` values per point, point after point.
struct PointAttribute
{
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// An indexed triangle mesh with per-point attributes. Triangles are counter-clockwise seen from
/// outside (their normal (p1-p0)x(p2-p0) points out) when the surface is oriented.
struct TriangleMesh
{
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<PointAttribute> pointData; ///< each with points.size() * components values

  std::size_t NumberOfPoints() const { return this->points.size(); }
  std::size_t NumberOfTriangles() const { return this->triangles.size(); }
  bool Empty() const { return this->triangles.empty(); }
};

/// Messages a mesh algorithm reports without failing (repairs made, input ignored): shown to the
/// user as warnings by the VTK filters.
using Warnings = std::vector<std::string>;

/// Progress callback: fraction in [0, 1]. May be empty.
using ProgressFunction = void (*)(double fraction, void* clientData);

/// Abort callback, asked (with the progress callback's client data) at every progress step:
/// true stops the algorithm, which then fails with kAbortedError. May be empty.
using StopFunction = bool (*)(void* clientData);

/// The error of an algorithm stopped by its StopFunction.
constexpr const char* kAbortedError = "aborted";

} // namespace mesh
} // namespace catar

#endif
