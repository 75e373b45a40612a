// Closed triangle surfaces from point sets: the convex hull (the boundary of the 3D Delaunay
// triangulation) for convex objects, CGAL's advancing front reconstruction for general surfaces.
#include "PointSetSurface.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

namespace catar
{
namespace mesh
{
namespace
{
namespace PMP = CGAL::Polygon_mesh_processing;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

/// Points flatter than this fraction of their extent (largest distance to their best-fit plane
/// over their bounding box diagonal) are taken as coplanar: rounding puts points of a tilted plane
/// slightly off it, and their "hull" would be a sliver of no volume.
constexpr double CoplanarTolerance = 1e-9;

/// The usable input: finite, pairwise distinct points, and the input index of each.
struct CleanPoints
{
  std::vector<Point> points;
  std::vector<int> ids;
};

/// Drops NaN/Inf points and exact duplicates (the first occurrence is kept), with a warning each.
CleanPoints CleanInput(const std::vector<Vec3>& input, Warnings& warnings)
{
  std::vector<int> finite;
  finite.reserve(input.size());
  for (std::size_t i = 0; i < input.size(); ++i)
  {
    if (input[i].allFinite())
    {
      finite.push_back(static_cast<int>(i));
    }
  }
  if (finite.size() < input.size())
  {
    warnings.push_back("dropped " + std::to_string(input.size() - finite.size()) + " of " +
      std::to_string(input.size()) + " points with NaN or infinite coordinates");
  }

  // Sort by coordinates (ties by index, so that the first occurrence comes first), mark repeats.
  std::vector<int> order = finite;
  const auto key = [&input](int i) {
    return std::make_tuple(input[i].x(), input[i].y(), input[i].z(), i);
  };
  std::sort(order.begin(), order.end(), [&key](int a, int b) { return key(a) < key(b); });
  std::vector<char> duplicate(input.size(), 0);
  std::size_t duplicates = 0;
  for (std::size_t k = 1; k < order.size(); ++k)
  {
    if (input[order[k]] == input[order[k - 1]])
    {
      duplicate[order[k]] = 1;
      ++duplicates;
    }
  }
  if (duplicates > 0)
  {
    warnings.push_back("dropped " + std::to_string(duplicates) + " duplicate points");
  }

  CleanPoints clean;
  clean.points.reserve(finite.size() - duplicates);
  clean.ids.reserve(finite.size() - duplicates);
  for (int i : finite)
  {
    if (!duplicate[i])
    {
      clean.points.emplace_back(input[i].x(), input[i].y(), input[i].z());
      clean.ids.push_back(i);
    }
  }
  return clean;
}

/// Empty when the points span 3D; otherwise why they cannot bound a volume.
std::string CheckSpansSpace(const std::vector<Point>& points)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Point& p : points)
  {
    const Eigen::Vector3d v(p.x(), p.y(), p.z());
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    centroid += v;
  }
  centroid /= static_cast<double>(points.size());
  const double diagonal = (hi - lo).norm();
  if (!std::isfinite(diagonal) || !centroid.allFinite())
  {
    return "point coordinates are too large to be processed";
  }

  // Best-fit plane: through the centroid, normal to the direction of least variance.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Point& p : points)
  {
    const Eigen::Vector3d d = Eigen::Vector3d(p.x(), p.y(), p.z()) - centroid;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0); // eigenvalues are increasing
  double thickness = 0.0;
  for (const Point& p : points)
  {
    thickness =
      std::max(thickness, std::abs((Eigen::Vector3d(p.x(), p.y(), p.z()) - centroid).dot(normal)));
  }
  if (!(thickness > CoplanarTolerance * diagonal))
  {
    std::ostringstream message;
    message << std::setprecision(3) << "the " << points.size()
            << " points are coplanar (largest distance to their plane " << thickness << ", extent "
            << diagonal << "): a closed surface needs points that span a volume";
    return message.str();
  }
  return std::string();
}

/// Ordering of points by their coordinates, to find the input point a surface vertex copies.
struct PointLess
{
  bool operator()(const Point& a, const Point& b) const
  {
    return std::make_tuple(a.x(), a.y(), a.z()) < std::make_tuple(b.x(), b.y(), b.z());
  }
};

/// Copies the faces of a triangle surface, with the vertices they use, into result.mesh and
/// result.pointIds. Every vertex is a copy of one of the clean points.
void ExtractSurface(const SurfaceMesh& surface, const CleanPoints& clean, PointSetResult& result)
{
  std::map<Point, int, PointLess> cleanIndex;
  for (std::size_t i = 0; i < clean.points.size(); ++i)
  {
    cleanIndex.emplace(clean.points[i], static_cast<int>(i));
  }

  std::vector<int> meshIndex(surface.number_of_vertices(), -1);
  result.mesh = TriangleMesh();
  result.pointIds.clear();
  result.mesh.triangles.reserve(surface.number_of_faces());
  for (const SurfaceMesh::Face_index f : surface.faces())
  {
    std::array<int, 3> triangle;
    int corner = 0;
    for (const SurfaceMesh::Vertex_index v :
      CGAL::vertices_around_face(surface.halfedge(f), surface))
    {
      int& index = meshIndex[v];
      if (index < 0)
      {
        const int id = clean.ids[cleanIndex.at(surface.point(v))];
        index = static_cast<int>(result.mesh.points.size());
        result.mesh.points.emplace_back(
          surface.point(v).x(), surface.point(v).y(), surface.point(v).z());
        result.pointIds.push_back(id);
      }
      triangle[corner++] = index;
    }
    result.mesh.triangles.push_back(triangle);
  }
}

/// The convex hull of the points, outward oriented (CGAL's quickhull over the points).
bool ConvexHullSurface(const CleanPoints& clean, PointSetResult& result)
{
  SurfaceMesh hull;
  CGAL::convex_hull_3(clean.points.begin(), clean.points.end(), hull);
  // CGAL gives a triangulated polygon for coplanar points, which CheckSpansSpace already turned
  // away with a margin: a guard only.
  if (hull.number_of_faces() < 4 || !CGAL::is_closed(hull))
  {
    result.error = "the convex hull of the points is degenerate";
    return false;
  }
  result.closed = true;
  ExtractSurface(hull, clean, result);
  return true;
}

/// Six times the signed volume enclosed by a set of faces, seen from their centroid: positive when
/// they are outward oriented.
double SignedVolume(const SurfaceMesh& surface, const std::vector<SurfaceMesh::Face_index>& faces)
{
  Kernel::Vector_3 centroid = CGAL::NULL_VECTOR;
  std::size_t count = 0;
  for (const SurfaceMesh::Face_index f : faces)
  {
    for (const SurfaceMesh::Vertex_index v :
      CGAL::vertices_around_face(surface.halfedge(f), surface))
    {
      centroid = centroid + (surface.point(v) - CGAL::ORIGIN);
      ++count;
    }
  }
  const Point center = CGAL::ORIGIN + centroid / static_cast<double>(count);
  double volume = 0.0;
  for (const SurfaceMesh::Face_index f : faces)
  {
    const SurfaceMesh::Halfedge_index h = surface.halfedge(f);
    const Kernel::Vector_3 a = surface.point(surface.source(h)) - center;
    const Kernel::Vector_3 b = surface.point(surface.target(h)) - center;
    const Kernel::Vector_3 c = surface.point(surface.target(surface.next(h))) - center;
    volume += CGAL::scalar_product(a, CGAL::cross_product(b, c));
  }
  return volume;
}

/// Orients an open surface: each connected component so that it encloses a positive volume seen
/// from its centroid (the outward side, for a closed surface with a few holes).
void OrientOpenSurface(SurfaceMesh& surface)
{
  auto component =
    surface.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:component", 0).first;
  const std::size_t count = PMP::connected_components(surface, component);
  std::vector<std::vector<SurfaceMesh::Face_index>> faces(count);
  for (const SurfaceMesh::Face_index f : surface.faces())
  {
    faces[component[f]].push_back(f);
  }
  for (const auto& componentFaces : faces)
  {
    if (SignedVolume(surface, componentFaces) < 0.0)
    {
      PMP::reverse_face_orientations(componentFaces, surface);
    }
  }
  surface.remove_property_map(component);
}

/// Reports progress; false when the caller asked to stop (the error is then kAbortedError).
bool Step(const PointSetOptions& options, double fraction, PointSetResult& result)
{
  if (options.progress)
  {
    options.progress(fraction, options.progressData);
  }
  if (options.stop && options.stop(options.progressData))
  {
    result.error = kAbortedError;
    return false;
  }
  return true;
}

/// A surface through the points by CGAL's advancing front reconstruction, consistently oriented.
bool AdvancingFrontSurface(
  const CleanPoints& clean, const PointSetOptions& options, PointSetResult& result)
{
  if (!std::isfinite(options.radiusRatioBound) || options.radiusRatioBound <= 0.0)
  {
    result.error = "radiusRatioBound must be a positive number";
    return false;
  }
  if (!std::isfinite(options.beta) || options.beta <= 0.0 || options.beta >= M_PI)
  {
    result.error = "beta must be an angle in (0, pi) radians";
    return false;
  }

  std::vector<std::array<std::size_t, 3>> facets;
  CGAL::advancing_front_surface_reconstruction(clean.points.begin(), clean.points.end(),
    std::back_inserter(facets), options.radiusRatioBound, options.beta);
  if (facets.empty())
  {
    result.error = "the advancing front reconstruction produced no triangles";
    return false;
  }
  if (!Step(options, 0.7, result))
  {
    return false;
  }

  // The reconstruction's triangles come unoriented: orient the soup consistently (duplicating
  // the points where the surface is not a manifold), then each component outward.
  std::vector<Point> soupPoints = clean.points;
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(facets.size());
  for (const auto& facet : facets)
  {
    polygons.emplace_back(facet.begin(), facet.end());
  }
  if (!PMP::orient_polygon_soup(soupPoints, polygons))
  {
    result.warnings.push_back("the reconstructed surface is not a manifold: it was cut at " +
      std::to_string(soupPoints.size() - clean.points.size()) + " points to be oriented");
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
  {
    result.error = "the reconstructed triangles do not form an orientable surface";
    return false;
  }
  SurfaceMesh surface;
  PMP::polygon_soup_to_polygon_mesh(soupPoints, polygons, surface);
  if (!Step(options, 0.8, result))
  {
    return false;
  }

  result.closed = CGAL::is_closed(surface);
  if (result.closed)
  {
    PMP::orient_to_bound_a_volume(surface);
  }
  else
  {
    OrientOpenSurface(surface);
    std::vector<SurfaceMesh::Halfedge_index> loops;
    PMP::extract_boundary_cycles(surface, std::back_inserter(loops));
    std::size_t boundaryEdges = 0;
    for (const SurfaceMesh::Halfedge_index h : surface.halfedges())
    {
      boundaryEdges += surface.is_border(h) ? 1 : 0;
    }
    result.warnings.push_back("the reconstructed surface is not closed: " +
      std::to_string(boundaryEdges) + " boundary edges around " + std::to_string(loops.size()) +
      (loops.size() == 1 ? " hole" : " holes") + " (the sampling may be too sparse there)");
  }

  ExtractSurface(surface, clean, result);
  if (result.mesh.points.size() < clean.points.size())
  {
    result.warnings.push_back(std::to_string(clean.points.size() - result.mesh.points.size()) +
      " of " + std::to_string(clean.points.size()) +
      " points are not on the reconstructed surface (outliers or too sparse samples)");
  }
  return true;
}

} // namespace

PointSetResult SurfaceFromPoints(const std::vector<Vec3>& points, const PointSetOptions& options)
{
  PointSetResult result;
  try
  {
    if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    {
      result.error = "too many points";
      return result;
    }
    const CleanPoints clean = CleanInput(points, result.warnings);
    if (clean.points.size() < 4)
    {
      result.error = "a closed surface needs at least 4 distinct finite points, got " +
        std::to_string(clean.points.size()) +
        (clean.points.size() < points.size() ? " (of " + std::to_string(points.size()) + ")"
                                             : std::string());
      return result;
    }
    result.error = CheckSpansSpace(clean.points);
    if (!result.error.empty() || !Step(options, 0.1, result))
    {
      return result;
    }

    switch (options.method)
    {
      case PointSetMethod::ConvexHull:
        result.ok = ConvexHullSurface(clean, result);
        break;
      case PointSetMethod::AdvancingFront:
        result.ok = AdvancingFrontSurface(clean, options, result);
        break;
      default:
        result.error =
          "unknown point set method " + std::to_string(static_cast<int>(options.method));
        break;
    }
    result.ok = result.ok && Step(options, 1.0, result);
  }
  catch (const std::exception& e)
  {
    result.error = std::string("surface from points failed: ") + e.what();
  }
  catch (...)
  {
    result.error = "surface from points failed: unknown error";
  }
  if (!result.ok)
  {
    result.mesh = TriangleMesh();
    result.pointIds.clear();
    result.closed = false;
  }
  return result;
}

} // namespace mesh
} // namespace catar
