// CatadioptricAR MeshPrep: measurements of triangle meshes.
//
// Every measure works on the triangle list as it is (no halfedge structure needed), so it can be
// applied to any input, repaired or not; triangles with out-of-range indices are ignored.
// Distances are exact point-to-surface (or point-to-segment) distances from CGAL AABB trees.
#include "MeshMetrics.h"

#include "MeshConversion.h"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace catar
{
namespace mesh
{
namespace
{

using detail::Kernel;
using detail::Point3;

using TriangleVector = std::vector<Kernel::Triangle_3>;
using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, TriangleVector::const_iterator>;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;
using SegmentVector = std::vector<Kernel::Segment_3>;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentVector::const_iterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

bool ValidTriangle(const TriangleMesh& mesh, const std::array<int, 3>& t)
{
  const int n = static_cast<int>(mesh.points.size());
  return t[0] >= 0 && t[1] >= 0 && t[2] >= 0 && t[0] < n && t[1] < n && t[2] < n;
}

/// The valid triangles of `mesh` as CGAL triangles.
TriangleVector Triangles(const TriangleMesh& mesh)
{
  TriangleVector triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
  {
    if (ValidTriangle(mesh, t))
    {
      triangles.emplace_back(detail::ToPoint3(mesh.points[t[0]]),
        detail::ToPoint3(mesh.points[t[1]]), detail::ToPoint3(mesh.points[t[2]]));
    }
  }
  return triangles;
}

/// Largest distance from samples of `from` (a barycentric grid with about `precision` between
/// neighbours, vertices and edges included) to the surface in `to`.
double OneSidedDistance(const TriangleVector& from, const TriangleTree& to, double precision)
{
  const bool sampleInside = std::isfinite(precision) && precision > 0.0;
  double maxSquared = 0.0;
  Point3 hint = from.front().vertex(0);
  hint = to.closest_point(hint);
  for (const Kernel::Triangle_3& triangle : from)
  {
    const Vec3 a = detail::ToVec3(triangle.vertex(0));
    const Vec3 ab = detail::ToVec3(triangle.vertex(1)) - a;
    const Vec3 ac = detail::ToVec3(triangle.vertex(2)) - a;
    const double longest = std::max({ ab.norm(), ac.norm(), (ac - ab).norm() });
    const int n = sampleInside ? std::max(1, static_cast<int>(std::ceil(longest / precision))) : 1;
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        const Point3 p = detail::ToPoint3(a + ab * (double(i) / n) + ac * (double(j) / n));
        hint = to.closest_point(p, hint);
        maxSquared = std::max(maxSquared, CGAL::squared_distance(p, hint));
      }
    }
  }
  return std::sqrt(maxSquared);
}

/// The sharp edges (normals more than featureAngle apart, or more than two triangles) and the
/// boundary edges (one triangle) of `mesh`, each once; either output may be null.
void ClassifyEdges(const TriangleMesh& mesh, double featureAngleDegrees, SegmentVector* sharp,
  SegmentVector* boundary)
{
  // Undirected edge -> triangles using it.
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  std::vector<Vec3> normals(mesh.triangles.size(), Vec3::Zero());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
  {
    const auto& t = mesh.triangles[i];
    if (!ValidTriangle(mesh, t))
    {
      continue;
    }
    const Vec3& p0 = mesh.points[t[0]];
    const Vec3 normal = (mesh.points[t[1]] - p0).cross(mesh.points[t[2]] - p0);
    const double length = normal.norm();
    if (length > 0.0)
    {
      normals[i] = normal / length;
    }
    for (int k = 0; k < 3; ++k)
    {
      const int a = std::min(t[k], t[(k + 1) % 3]);
      const int b = std::max(t[k], t[(k + 1) % 3]);
      edges[(static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b)].push_back(
        static_cast<int>(i));
    }
  }

  const double cosFeature = std::cos(featureAngleDegrees * M_PI / 180.0);
  for (const auto& entry : edges)
  {
    const Point3 a = detail::ToPoint3(mesh.points[entry.first >> 32]);
    const Point3 b = detail::ToPoint3(mesh.points[entry.first & 0xffffffffu]);
    const std::vector<int>& faces = entry.second;
    if (faces.size() == 1)
    {
      if (boundary)
      {
        boundary->emplace_back(a, b);
      }
    }
    else if (sharp)
    {
      const Vec3& n0 = normals[faces[0]];
      const Vec3& n1 = normals[faces[1]];
      const bool bent = !n0.isZero() && !n1.isZero() && n0.dot(n1) < cosFeature;
      if (faces.size() > 2 || bent)
      {
        sharp->emplace_back(a, b);
      }
    }
  }
}

double TotalLength(const SegmentVector& segments)
{
  double total = 0.0;
  for (const Kernel::Segment_3& s : segments)
  {
    total += std::sqrt(s.squared_length());
  }
  return total;
}

} // namespace

AreaStatistics TriangleAreaStatistics(const TriangleMesh& mesh)
{
  AreaStatistics statistics;
  std::vector<double> areas;
  areas.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
  {
    if (ValidTriangle(mesh, t))
    {
      const Vec3& p0 = mesh.points[t[0]];
      areas.push_back(0.5 * (mesh.points[t[1]] - p0).cross(mesh.points[t[2]] - p0).norm());
    }
  }
  if (areas.empty())
  {
    return statistics;
  }
  std::sort(areas.begin(), areas.end());
  const std::size_t n = areas.size();
  statistics.count = n;
  for (double area : areas)
  {
    statistics.total += area;
  }
  statistics.mean = statistics.total / static_cast<double>(n);
  statistics.median = n % 2 == 1 ? areas[n / 2] : 0.5 * (areas[n / 2 - 1] + areas[n / 2]);
  // Nearest rank: the smallest area that at least 95% of the triangles do not exceed.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n)));
  statistics.p95 = areas[std::max<std::size_t>(rank, 1) - 1];
  statistics.min = areas.front();
  statistics.max = areas.back();
  return statistics;
}

double HausdorffDistance(const TriangleMesh& a, const TriangleMesh& b, double precision)
{
  const TriangleVector trianglesA = Triangles(a);
  const TriangleVector trianglesB = Triangles(b);
  if (trianglesA.empty() || trianglesB.empty())
  {
    return trianglesA.empty() && trianglesB.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  }
  // Degenerate triangles are left out of the trees: their points lie on their edges, which
  // their neighbours have (and they are still sampled).
  const auto nonDegenerate = [](const TriangleVector& triangles) {
    TriangleVector kept;
    for (const Kernel::Triangle_3& t : triangles)
    {
      if (!t.is_degenerate())
      {
        kept.push_back(t);
      }
    }
    return kept;
  };
  const TriangleVector surfaceA = nonDegenerate(trianglesA);
  const TriangleVector surfaceB = nonDegenerate(trianglesB);
  if (surfaceA.empty() || surfaceB.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  const TriangleTree treeA(surfaceA.cbegin(), surfaceA.cend());
  const TriangleTree treeB(surfaceB.cbegin(), surfaceB.cend());
  return std::max(
    OneSidedDistance(trianglesA, treeB, precision), OneSidedDistance(trianglesB, treeA, precision));
}

double SharpEdgeLength(const TriangleMesh& mesh, double featureAngleDegrees)
{
  SegmentVector sharp;
  ClassifyEdges(mesh, featureAngleDegrees, &sharp, nullptr);
  return TotalLength(sharp);
}

double BoundaryEdgeLength(const TriangleMesh& mesh)
{
  SegmentVector boundary;
  ClassifyEdges(mesh, 180.0, nullptr, &boundary);
  return TotalLength(boundary);
}

double SharpEdgeDeviation(
  const TriangleMesh& reference, const TriangleMesh& mesh, double featureAngleDegrees, double step)
{
  SegmentVector referenceEdges;
  SegmentVector meshEdges;
  ClassifyEdges(reference, featureAngleDegrees, &referenceEdges, nullptr);
  ClassifyEdges(mesh, featureAngleDegrees, &meshEdges, nullptr);
  if (referenceEdges.empty())
  {
    return 0.0;
  }
  meshEdges.erase(std::remove_if(meshEdges.begin(), meshEdges.end(),
                    [](const Kernel::Segment_3& s) { return s.is_degenerate(); }),
    meshEdges.end());
  if (meshEdges.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  const SegmentTree tree(meshEdges.cbegin(), meshEdges.cend());
  const bool sampleInside = std::isfinite(step) && step > 0.0;
  double maxSquared = 0.0;
  Point3 hint = tree.closest_point(referenceEdges.front().source());
  for (const Kernel::Segment_3& s : referenceEdges)
  {
    const Vec3 a = detail::ToVec3(s.source());
    const Vec3 ab = detail::ToVec3(s.target()) - a;
    const int n = sampleInside ? std::max(1, static_cast<int>(std::ceil(ab.norm() / step))) : 1;
    for (int i = 0; i <= n; ++i)
    {
      const Point3 p = detail::ToPoint3(a + ab * (double(i) / n));
      hint = tree.closest_point(p, hint);
      maxSquared = std::max(maxSquared, CGAL::squared_distance(p, hint));
    }
  }
  return std::sqrt(maxSquared);
}

} // namespace mesh
} // namespace catar
