// CatadioptricAR MeshPrep (private, not installed): conversions between the exchange format
// TriangleMesh and the mesh types the algorithms run on, CGAL's Surface_mesh and OpenMesh's
// TriMesh. In every conversion vertex i is point i of the TriangleMesh, so constraints and
// attributes found on one representation can be mapped to the others by index.
#ifndef catarMeshConversion_h
#define catarMeshConversion_h

#include "TriangleMesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <vector>

namespace catar
{
namespace mesh
{
namespace detail
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;

/// OpenMesh's default traits store float coordinates; the algorithms here need doubles.
struct OpenMeshTraits : public OpenMesh::DefaultTraits
{
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OpenTriMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

inline Point3 ToPoint3(const Vec3& p)
{
  return Point3(p.x(), p.y(), p.z());
}

inline Vec3 ToVec3(const Point3& p)
{
  return Vec3(p.x(), p.y(), p.z());
}

/// Fills `sm` (cleared first) with the points and triangles of `mesh`. Returns false when a
/// triangle cannot be added (out-of-range index, non-manifold or inconsistently oriented input:
/// run RepairMesh first).
inline bool ToSurfaceMesh(const TriangleMesh& mesh, SurfaceMesh& sm)
{
  sm.clear();
  sm.reserve(static_cast<SurfaceMesh::size_type>(mesh.points.size()),
    static_cast<SurfaceMesh::size_type>(3 * mesh.triangles.size() / 2),
    static_cast<SurfaceMesh::size_type>(mesh.triangles.size()));
  for (const Vec3& p : mesh.points)
  {
    sm.add_vertex(ToPoint3(p));
  }
  const int n = static_cast<int>(mesh.points.size());
  for (const auto& t : mesh.triangles)
  {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= n || t[1] >= n || t[2] >= n)
    {
      return false;
    }
    const SurfaceMesh::Face_index f = sm.add_face(SurfaceMesh::Vertex_index(t[0]),
      SurfaceMesh::Vertex_index(t[1]), SurfaceMesh::Vertex_index(t[2]));
    if (f == SurfaceMesh::null_face())
    {
      return false;
    }
  }
  return true;
}

/// The points and triangles of `sm`, removed elements skipped, vertices numbered in order.
/// Point data are left empty.
inline TriangleMesh FromSurfaceMesh(const SurfaceMesh& sm)
{
  TriangleMesh mesh;
  std::vector<int> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
  mesh.points.reserve(sm.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices())
  {
    index[v.idx()] = static_cast<int>(mesh.points.size());
    mesh.points.push_back(ToVec3(sm.point(v)));
  }
  mesh.triangles.reserve(sm.number_of_faces());
  for (SurfaceMesh::Face_index f : sm.faces())
  {
    std::array<int, 3> t{ { -1, -1, -1 } };
    int k = 0;
    for (SurfaceMesh::Vertex_index v : sm.vertices_around_face(sm.halfedge(f)))
    {
      if (k < 3)
      {
        t[k] = index[v.idx()];
      }
      ++k;
    }
    if (k == 3)
    {
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

/// Fills `om` (cleared first) with the points and triangles of `mesh`; false when a triangle
/// cannot be added (see ToSurfaceMesh).
inline bool ToOpenMesh(const TriangleMesh& mesh, OpenTriMesh& om)
{
  om.clear();
  std::vector<OpenTriMesh::VertexHandle> handles;
  handles.reserve(mesh.points.size());
  for (const Vec3& p : mesh.points)
  {
    handles.push_back(om.add_vertex(OpenTriMesh::Point(p.x(), p.y(), p.z())));
  }
  const int n = static_cast<int>(mesh.points.size());
  for (const auto& t : mesh.triangles)
  {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= n || t[1] >= n || t[2] >= n)
    {
      return false;
    }
    if (!om.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid())
    {
      return false;
    }
  }
  return true;
}

/// The points and triangles of `om`, deleted elements skipped (no garbage collection needed),
/// vertices numbered in order. Point data are left empty.
inline TriangleMesh FromOpenMesh(const OpenTriMesh& om)
{
  TriangleMesh mesh;
  std::vector<int> index(om.n_vertices(), -1);
  for (const auto vh : om.vertices())
  {
    if (om.has_vertex_status() && om.status(vh).deleted())
    {
      continue;
    }
    index[vh.idx()] = static_cast<int>(mesh.points.size());
    const OpenTriMesh::Point& p = om.point(vh);
    mesh.points.emplace_back(p[0], p[1], p[2]);
  }
  for (const auto fh : om.faces())
  {
    if (om.has_face_status() && om.status(fh).deleted())
    {
      continue;
    }
    std::array<int, 3> t{ { -1, -1, -1 } };
    int k = 0;
    for (const auto vh : om.fv_range(fh))
    {
      if (k < 3)
      {
        t[k] = index[vh.idx()];
      }
      ++k;
    }
    if (k == 3)
    {
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

} // namespace detail
} // namespace mesh
} // namespace catar

#endif
