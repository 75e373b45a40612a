// CatadioptricAR MeshPrep: remeshing a triangle surface to a target triangle area.
//
// Constraints. Sharp edges (CGAL detect_sharp_edges, normals more than featureAngle apart) and,
// with preserveBoundaries, boundary edges form constrained polylines. Their corners are pinned:
// ends of polylines, vertices on three or more of them, and vertices where a polyline turns by
// more than featureAngle. CGAL's isotropic remeshing runs with protect_constraints = false:
// constrained edges are split and collapsed along their polyline (so that they reach the target
// length too, even where the input is dense) but never flipped, their vertices are not smoothed
// off them, and pinned vertices never move. A box keeps its edges and corners exactly. (With
// protect_constraints = true CGAL would keep every input feature edge as it is, which requires
// them all to be shorter than 4/3 of the target length and leaves dense input dense along its
// features.) OpenMesh's decimation gets the same constraints: pinned vertices are locked, and
// vertices on constrained polylines may only collapse along them.
#include "Remeshing.h"

#include "MeshConversion.h"
#include "MeshRepair.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace catar
{
namespace mesh
{

double EdgeLengthForArea(double area)
{
  return std::sqrt(4.0 * area / std::sqrt(3.0));
}

double AreaForEdgeLength(double length)
{
  return std::sqrt(3.0) / 4.0 * length * length;
}

namespace
{

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::Kernel;
using detail::OpenTriMesh;
using detail::SurfaceMesh;

/// Auto decimates first when the mean triangle area is below target / kDenseRatio...
constexpr double kDenseRatio = 4.0;
/// ... and the input has more triangles than this (small inputs are remeshed directly, fast).
constexpr std::size_t kDenseMinTriangles = 2000;
/// Auto decimates to this many times the target triangle count, leaving isotropic remeshing
/// some detail to sample (it projects onto the decimated surface).
constexpr double kDecimationHeadroom = 2.0;
/// Refuse targets that would make more triangles than this (memory).
constexpr double kMaxTriangles = 2e7;

/// Calls the user's progress function, if any, and asks the stop function: false when the work
/// must stop (then Stopped() stays true).
class Progress
{
public:
  explicit Progress(const RemeshOptions& options)
    : Function(options.progress)
    , Stop(options.stop)
    , Data(options.progressData)
  {
  }
  [[nodiscard]] bool operator()(double fraction) const
  {
    if (this->Function)
    {
      this->Function(std::min(1.0, std::max(0.0, fraction)), this->Data);
    }
    this->Stopped = this->Stopped || (this->Stop && this->Stop(this->Data));
    return !this->Stopped;
  }
  bool Aborted() const { return this->Stopped; }

private:
  ProgressFunction Function;
  StopFunction Stop;
  void* Data;
  mutable bool Stopped = false;
};

/// Reports decimation progress between two fractions of the whole run.
class DecimationObserver : public OpenMesh::Decimater::Observer
{
public:
  DecimationObserver(const Progress& progress, std::size_t collapses, double from, double to)
    : Observer(std::max<std::size_t>(1, collapses / 20))
    , Report(progress)
    , Collapses(static_cast<double>(std::max<std::size_t>(1, collapses)))
    , From(from)
    , To(to)
  {
  }
  void notify(size_t step) override
  {
    (void)this->Report(
      this->From + (this->To - this->From) * static_cast<double>(step) / this->Collapses);
  }
  bool abort() const override { return this->Report.Aborted(); }

private:
  const Progress& Report;
  double Collapses;
  double From;
  double To;
};

double TotalArea(const TriangleMesh& mesh)
{
  double total = 0.0;
  for (const auto& t : mesh.triangles)
  {
    const Vec3& p0 = mesh.points[t[0]];
    total += 0.5 * (mesh.points[t[1]] - p0).cross(mesh.points[t[2]] - p0).norm();
  }
  return total;
}

using EdgeConstraintMap = SurfaceMesh::Property_map<SurfaceMesh::Edge_index, bool>;
using VertexConstraintMap = SurfaceMesh::Property_map<SurfaceMesh::Vertex_index, bool>;

/// Marks the constrained edges and pinned vertices of `sm` (see the file comment).
void MarkConstraints(const SurfaceMesh& sm, const RemeshOptions& options, EdgeConstraintMap ecm,
  VertexConstraintMap vcm)
{
  if (options.protectFeatures)
  {
    PMP::detect_sharp_edges(sm, options.featureAngle, ecm);
  }
  // detect_sharp_edges marks boundary edges too; they are constrained only when preserved.
  for (SurfaceMesh::Edge_index e : sm.edges())
  {
    if (sm.is_border(e))
    {
      ecm[e] = options.preserveBoundaries;
    }
  }

  const double cosTurn = std::cos(options.featureAngle * M_PI / 180.0);
  for (SurfaceMesh::Vertex_index v : sm.vertices())
  {
    std::vector<Kernel::Vector_3> directions;
    for (SurfaceMesh::Halfedge_index h : sm.halfedges_around_target(sm.halfedge(v)))
    {
      if (ecm[sm.edge(h)])
      {
        directions.push_back(sm.point(sm.source(h)) - sm.point(v));
      }
    }
    if (directions.size() == 2)
    {
      // The polyline goes on straight when the two directions are opposite; it turns by the
      // angle between the first direction and the reverse of the second.
      const double cosine = -directions[0] * directions[1] /
        std::sqrt(directions[0].squared_length() * directions[1].squared_length());
      vcm[v] = cosine < cosTurn;
    }
    else
    {
      vcm[v] = !directions.empty();
    }
  }
}

/// Builds `sm` from `mesh` and adds its constraint maps.
bool PrepareSurfaceMesh(const TriangleMesh& mesh, const RemeshOptions& options, SurfaceMesh& sm,
  EdgeConstraintMap& ecm, VertexConstraintMap& vcm)
{
  if (!detail::ToSurfaceMesh(mesh, sm))
  {
    return false;
  }
  ecm = sm.add_property_map<SurfaceMesh::Edge_index, bool>("e:catar_constrained", false).first;
  vcm = sm.add_property_map<SurfaceMesh::Vertex_index, bool>("v:catar_constrained", false).first;
  MarkConstraints(sm, options, ecm, vcm);
  return true;
}

/// OpenMesh quadric decimation (collapses onto existing vertices) down to `targetTriangles`.
bool Decimate(TriangleMesh& mesh, std::size_t targetTriangles, const RemeshOptions& options,
  const Progress& progress, double from, double to, std::string& error)
{
  SurfaceMesh sm;
  EdgeConstraintMap ecm;
  VertexConstraintMap vcm;
  OpenTriMesh om;
  if (!PrepareSurfaceMesh(mesh, options, sm, ecm, vcm) || !detail::ToOpenMesh(mesh, om))
  {
    error = "the repaired mesh could not be converted for decimation";
    return false;
  }
  om.request_vertex_status();
  om.request_edge_status();
  om.request_face_status();
  om.request_face_normals();
  om.update_face_normals();
  // A feature vertex may only collapse along a feature edge; a locked one never.
  for (SurfaceMesh::Edge_index e : sm.edges())
  {
    if (!ecm[e])
    {
      continue;
    }
    const OpenTriMesh::VertexHandle a(static_cast<int>(sm.vertex(e, 0).idx()));
    const OpenTriMesh::VertexHandle b(static_cast<int>(sm.vertex(e, 1).idx()));
    const OpenTriMesh::HalfedgeHandle h = om.find_halfedge(a, b);
    if (h.is_valid())
    {
      om.status(om.edge_handle(h)).set_feature(true);
      om.status(a).set_feature(true);
      om.status(b).set_feature(true);
    }
  }
  for (SurfaceMesh::Vertex_index v : sm.vertices())
  {
    if (vcm[v])
    {
      om.status(OpenTriMesh::VertexHandle(static_cast<int>(v.idx()))).set_locked(true);
    }
  }

  using Decimater = OpenMesh::Decimater::DecimaterT<OpenTriMesh>;
  Decimater decimater(om);
  OpenMesh::Decimater::ModQuadricT<OpenTriMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<OpenTriMesh>::Handle normalFlipping;
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();
  decimater.add(normalFlipping);
  if (!decimater.initialize())
  {
    error = "OpenMesh decimation could not be initialized";
    return false;
  }
  // Each collapse removes two triangles (one on a boundary).
  const std::size_t faces = om.n_faces();
  DecimationObserver observer(
    progress, faces > targetTriangles ? (faces - targetTriangles) / 2 : 0, from, to);
  decimater.set_observer(&observer);
  decimater.decimate_to_faces(0, targetTriangles);
  decimater.set_observer(nullptr);
  if (progress.Aborted())
  {
    error = kAbortedError;
    return false;
  }
  mesh = detail::FromOpenMesh(om);
  return true;
}

/// One level of 1:4 midpoint subdivision; point data are interpolated at the midpoints.
void SubdivideOnce(TriangleMesh& mesh)
{
  std::unordered_map<std::uint64_t, int> midpoints;
  const auto midpoint = [&](int a, int b) {
    const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
      static_cast<std::uint32_t>(std::max(a, b));
    const auto found = midpoints.find(key);
    if (found != midpoints.end())
    {
      return found->second;
    }
    const int m = static_cast<int>(mesh.points.size());
    const Vec3 p = 0.5 * (mesh.points[a] + mesh.points[b]);
    mesh.points.push_back(p);
    for (PointAttribute& attribute : mesh.pointData)
    {
      const std::size_t c = static_cast<std::size_t>(attribute.components);
      for (std::size_t k = 0; k < c; ++k)
      {
        attribute.values.push_back(
          0.5 * (attribute.values[a * c + k] + attribute.values[b * c + k]));
      }
    }
    midpoints.emplace(key, m);
    return m;
  };
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(4 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
  {
    const int ab = midpoint(t[0], t[1]);
    const int bc = midpoint(t[1], t[2]);
    const int ca = midpoint(t[2], t[0]);
    triangles.push_back({ { t[0], ab, ca } });
    triangles.push_back({ { ab, t[1], bc } });
    triangles.push_back({ { ca, bc, t[2] } });
    triangles.push_back({ { ab, bc, ca } });
  }
  mesh.triangles = std::move(triangles);
}

/// CGAL isotropic remeshing to the given edge length (see the file comment for constraints).
bool IsotropicRemesh(
  TriangleMesh& mesh, double edgeLength, const RemeshOptions& options, std::string& error)
{
  SurfaceMesh sm;
  EdgeConstraintMap ecm;
  VertexConstraintMap vcm;
  if (!PrepareSurfaceMesh(mesh, options, sm, ecm, vcm))
  {
    error = "the repaired mesh could not be converted for isotropic remeshing";
    return false;
  }
  PMP::isotropic_remeshing(sm.faces(), edgeLength, sm,
    CGAL::parameters::number_of_iterations(static_cast<unsigned int>(options.iterations))
      .edge_is_constrained_map(ecm)
      .vertex_is_constrained_map(vcm)
      .protect_constraints(false));
  mesh = detail::FromSurfaceMesh(sm);
  return true;
}

/// Isotropic remeshing whose mean triangle area lands on the target. CGAL splits edges longer
/// than 4/3 and collapses edges shorter than 4/5 of the requested length, which leaves triangles
/// smaller than the equilateral triangle of that length (about 0.82-0.87 of its area on boxes
/// and spheres). So the requested length starts a little longer than EdgeLengthForArea, and
/// while the measured mean area is more than kAreaTolerance off, the remeshing is redone from
/// the same input with a corrected length: scaled by sqrt(target / mean) until the target is
/// bracketed, then interpolated (in logarithms) between the closest lengths below and above.
/// The response is a step function of the length, so after kAreaPasses the closest is kept.
bool CalibratedIsotropicRemesh(TriangleMesh& mesh, const RemeshOptions& options,
  const Progress& progress, double from, double to, std::string& error)
{
  constexpr double kInitialLengthFactor = 1.08;
  constexpr double kAreaTolerance = 0.04;
  constexpr int kAreaPasses = 5;
  const TriangleMesh input = mesh;
  const double target = options.targetArea;
  double length = kInitialLengthFactor * EdgeLengthForArea(target);
  double bestDeviation = std::numeric_limits<double>::infinity();
  // Closest lengths whose mean area came out below / above the target, and those means.
  double below = 0.0, belowMean = 0.0, above = 0.0, aboveMean = 0.0;
  for (int pass = 0; pass < kAreaPasses; ++pass)
  {
    TriangleMesh candidate = input;
    if (!IsotropicRemesh(candidate, length, options, error))
    {
      return false;
    }
    if (!progress(from + (to - from) * (pass + 1) / kAreaPasses))
    {
      error = kAbortedError;
      return false;
    }
    const std::size_t count = candidate.NumberOfTriangles();
    if (count == 0)
    {
      error = "isotropic remeshing left no triangles";
      return false;
    }
    const double mean = TotalArea(candidate) / static_cast<double>(count);
    const double deviation = std::abs(mean / target - 1.0);
    if (deviation < bestDeviation)
    {
      bestDeviation = deviation;
      mesh = std::move(candidate);
    }
    if (deviation <= kAreaTolerance || !(mean > 0.0))
    {
      break;
    }
    if (mean < target && (below == 0.0 || length > below))
    {
      below = length;
      belowMean = mean;
    }
    else if (mean > target && (above == 0.0 || length < above))
    {
      above = length;
      aboveMean = mean;
    }
    if (below > 0.0 && above > 0.0 && above > below)
    {
      const double t = std::log(target / belowMean) / std::log(aboveMean / belowMean);
      length = below * std::pow(above / below, std::min(0.9, std::max(0.1, t)));
    }
    else
    {
      length *= std::sqrt(target / mean);
    }
  }
  return true;
}

std::string Format(double value)
{
  std::ostringstream stream;
  stream << value;
  return stream.str();
}

/// The body of RemeshToArea; may throw (CGAL, allocation), RemeshToArea catches.
void Remesh(const TriangleMesh& input, const RemeshOptions& options, RemeshResult& result)
{
  const Progress progress(options);
  if (!std::isfinite(options.targetArea) || options.targetArea <= 0.0)
  {
    result.error = "invalid options: targetArea must be a positive finite number (got " +
      Format(options.targetArea) + ")";
    return;
  }
  if (options.iterations < 1)
  {
    result.error = "invalid options: iterations must be at least 1 (got " +
      std::to_string(options.iterations) + ")";
    return;
  }
  if (!(options.featureAngle >= 0.0 && options.featureAngle <= 180.0))
  {
    result.error = "invalid options: featureAngle must be between 0 and 180 degrees (got " +
      Format(options.featureAngle) + ")";
    return;
  }
  const int strategy = static_cast<int>(options.strategy);
  if (strategy < static_cast<int>(RemeshStrategy::Auto) ||
    strategy > static_cast<int>(RemeshStrategy::Subdivide))
  {
    result.error = "invalid options: unknown strategy " + std::to_string(strategy);
    return;
  }
  if (!progress(0.0))
  {
    result.error = kAbortedError;
    return;
  }

  TriangleMesh repaired = input;
  RepairReport report;
  std::string error;
  if (!RepairMesh(repaired, report, result.warnings, error))
  {
    result.error = "cannot remesh: " + error;
    return;
  }
  if (!progress(0.1))
  {
    result.error = kAbortedError;
    return;
  }

  const double area = TotalArea(repaired);
  const std::size_t triangles = repaired.NumberOfTriangles();
  const double meanArea = area / static_cast<double>(triangles);
  const double targetCount = area / options.targetArea;
  if (targetCount > kMaxTriangles)
  {
    result.error = "targetArea " + Format(options.targetArea) + " is too small: about " +
      Format(targetCount) + " triangles for a surface of area " + Format(area) + " (the limit is " +
      Format(kMaxTriangles) + ")";
    return;
  }

  TriangleMesh mesh = repaired;
  std::vector<std::string> steps;
  bool carried = false; // point data already carried by the steps
  switch (options.strategy)
  {
    case RemeshStrategy::Decimate:
    {
      const std::size_t target = static_cast<std::size_t>(std::max(1.0, std::round(targetCount)));
      if (triangles <= target)
      {
        result.warnings.push_back("not decimated: the input has " + std::to_string(triangles) +
          " triangles, not more than the target's " + std::to_string(target));
      }
      else
      {
        if (!Decimate(mesh, target, options, progress, 0.1, 0.9, result.error))
        {
          return;
        }
        steps.emplace_back("decimate");
      }
      break;
    }
    case RemeshStrategy::Subdivide:
    {
      // Until the mean area is at or below the target.
      int levels = 0;
      for (double mean = meanArea; mean > options.targetArea; mean /= 4.0)
      {
        ++levels;
      }
      if (levels == 0)
      {
        result.warnings.push_back("not subdivided: the mean triangle area " + Format(meanArea) +
          " is already at or below the target");
      }
      for (int level = 0; level < levels; ++level)
      {
        SubdivideOnce(mesh);
        if (!progress(0.1 + 0.8 * (level + 1) / levels))
        {
          result.error = kAbortedError;
          return;
        }
      }
      if (levels > 0)
      {
        steps.emplace_back("subdivide x" + std::to_string(levels));
      }
      carried = true;
      break;
    }
    case RemeshStrategy::Auto:
    case RemeshStrategy::Isotropic:
    {
      // Too coarse input needs no subdivision first: isotropic remeshing splits long edges
      // until they are all short enough.
      double from = 0.1;
      if (options.strategy == RemeshStrategy::Auto && meanArea < options.targetArea / kDenseRatio &&
        triangles > kDenseMinTriangles)
      {
        const std::size_t target =
          static_cast<std::size_t>(std::ceil(kDecimationHeadroom * targetCount));
        if (!Decimate(mesh, target, options, progress, 0.1, 0.4, result.error))
        {
          return;
        }
        steps.emplace_back("decimate");
        from = 0.4;
      }
      if (!progress(from))
      {
        result.error = kAbortedError;
        return;
      }
      if (!CalibratedIsotropicRemesh(mesh, options, progress, from, 0.9, result.error))
      {
        return;
      }
      steps.emplace_back("isotropic");
      break;
    }
  }
  if (!progress(0.9))
  {
    result.error = kAbortedError;
    return;
  }

  if (!carried)
  {
    TransferPointData(repaired, mesh);
  }
  result.mesh = std::move(mesh);
  for (std::size_t i = 0; i < steps.size(); ++i)
  {
    result.steps += (i > 0 ? ", " : "") + steps[i];
  }
  result.ok = true;
  (void)progress(1.0);
}

using TriangleVector = std::vector<Kernel::Triangle_3>;
using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, TriangleVector::const_iterator>;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;

/// Barycentric coordinates of p (on the triangle's plane) in triangle a, b, c, clamped to the
/// triangle.
std::array<double, 3> Barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 v0 = b - a;
  const Vec3 v1 = c - a;
  const Vec3 v2 = p - a;
  const double d00 = v0.dot(v0);
  const double d01 = v0.dot(v1);
  const double d11 = v1.dot(v1);
  const double d20 = v2.dot(v0);
  const double d21 = v2.dot(v1);
  const double denominator = d00 * d11 - d01 * d01;
  const double v = (d11 * d20 - d01 * d21) / denominator;
  const double w = (d00 * d21 - d01 * d20) / denominator;
  std::array<double, 3> weights{ { std::max(0.0, 1.0 - v - w), std::max(0.0, v),
    std::max(0.0, w) } };
  const double sum = weights[0] + weights[1] + weights[2];
  for (double& weight : weights)
  {
    weight /= sum;
  }
  return weights;
}

} // namespace

RemeshResult RemeshToArea(const TriangleMesh& input, const RemeshOptions& options)
{
  RemeshResult result;
  try
  {
    Remesh(input, options, result);
  }
  catch (const std::exception& e)
  {
    result.ok = false;
    result.error = std::string("remeshing failed: ") + e.what();
  }
  catch (...)
  {
    result.ok = false;
    result.error = "remeshing failed with an unknown exception";
  }
  if (!result.ok)
  {
    result.mesh = TriangleMesh();
    result.steps.clear();
  }
  return result;
}

void TransferPointData(const TriangleMesh& source, TriangleMesh& target)
{
  const std::size_t n = source.points.size();
  const int points = static_cast<int>(n);
  // Usable attributes (sizes matching the points) and triangles (indices in range, finite,
  // non-degenerate).
  std::vector<const PointAttribute*> inputs;
  std::vector<PointAttribute> data;
  for (const PointAttribute& attribute : source.pointData)
  {
    if (attribute.components >= 1 &&
      attribute.values.size() == n * static_cast<std::size_t>(attribute.components))
    {
      PointAttribute out;
      out.name = attribute.name;
      out.components = attribute.components;
      out.values.assign(target.points.size() * static_cast<std::size_t>(out.components), 0.0);
      inputs.push_back(&attribute);
      data.push_back(std::move(out));
    }
  }
  TriangleVector triangles;
  std::vector<std::size_t> sourceTriangle;
  for (std::size_t i = 0; i < source.triangles.size(); ++i)
  {
    const auto& t = source.triangles[i];
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= points || t[1] >= points || t[2] >= points)
    {
      continue;
    }
    const Vec3& a = source.points[t[0]];
    const Vec3& b = source.points[t[1]];
    const Vec3& c = source.points[t[2]];
    if (!a.allFinite() || !b.allFinite() || !c.allFinite())
    {
      continue;
    }
    const Kernel::Triangle_3 triangle(
      detail::ToPoint3(a), detail::ToPoint3(b), detail::ToPoint3(c));
    if (!triangle.is_degenerate())
    {
      triangles.push_back(triangle);
      sourceTriangle.push_back(i);
    }
  }

  if (!data.empty() && !triangles.empty())
  {
    TriangleTree tree(triangles.cbegin(), triangles.cend());
    TriangleTree::Point_and_primitive_id hint(triangles.front().vertex(0), triangles.cbegin());
    for (std::size_t i = 0; i < target.points.size(); ++i)
    {
      const Vec3& p = target.points[i];
      if (!p.allFinite())
      {
        continue;
      }
      hint = tree.closest_point_and_primitive(detail::ToPoint3(p), hint);
      const auto& t = source.triangles[sourceTriangle[hint.second - triangles.cbegin()]];
      const std::array<double, 3> weights = Barycentric(
        detail::ToVec3(hint.first), source.points[t[0]], source.points[t[1]], source.points[t[2]]);
      for (std::size_t d = 0; d < data.size(); ++d)
      {
        const std::vector<double>& values = inputs[d]->values;
        const std::size_t c = static_cast<std::size_t>(data[d].components);
        for (std::size_t k = 0; k < c; ++k)
        {
          data[d].values[i * c + k] = weights[0] * values[t[0] * c + k] +
            weights[1] * values[t[1] * c + k] + weights[2] * values[t[2] * c + k];
        }
      }
    }
  }
  target.pointData = std::move(data);
}

} // namespace mesh
} // namespace catar
