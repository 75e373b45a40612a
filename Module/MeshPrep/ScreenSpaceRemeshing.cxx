// Remeshing to a pixel tolerance (see ScreenSpaceRemeshing.h).
//
// The surface is held in an OpenMesh triangle mesh and goes through rounds of
//  - refinement: every edge that bends more than the tolerance (or is longer than maxEdgeLength)
//    is bisected at its midpoint by Rivara's longest-edge propagation path (LEPP) bisection, which
//    keeps the mesh conforming and the triangles' angles bounded below. Midpoints lie on the
//    current surface, so refinement never changes the geometry;
//  - coarsening: OpenMesh's greedy halfedge-collapse decimation, driven by one module that allows
//    a collapse only when every edge it creates bends at most the tolerance and is at most
//    maxEdgeLength long, the surface stays within maxGeometricError of the input, no triangle
//    flips over, and sharp edges, boundaries and corners stay. Collapses whose new edges bend
//    least go first;
//  - relaxation: edges flip to the other diagonal of their quad when it bends less, and vertices
//    slide along the surface towards their neighbours (pulled harder by the edges that bend more)
//    when that lowers the worst bend of their edges, so that the next coarsening finds more
//    collapses.
// Every triangle carries a bound on its distance to the input (0 at first; children of a split
// inherit it). A collapse, flip or move replaces a fan of triangles by another; the new ones get
// the old ones' largest bound plus the distance between the two fans (sampled two-sided Hausdorff
// distance, exactly 0 for a planar fan that keeps its outline), and the change is refused when
// that exceeds maxGeometricError.
// Rounds stop when they no longer remove triangles. Vertices do not move during refinement and
// coarsening, so the bend of a vertex pair is computed once (a cache cleared whenever vertices move
// or are renumbered). A last refinement guarantees the bound and the result is measured afresh.
#include "ScreenSpaceRemeshing.h"

#include "Parallel.h"

#include "MeshRepair.h"
#include "Remeshing.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

// OpenMesh appends a property value as T(), and VectorT's default constructor leaves its numbers
// uninitialised: growing the points and normals copied indeterminate values (GCC's
// -Wmaybe-uninitialized said so). This mesh's vectors start at zero instead; every one is
// written before it is read, so results are unchanged.
template<>
inline void OpenMesh::PropertyT<OpenMesh::Vec3d>::push_back()
{
  this->data_.push_back(OpenMesh::Vec3d(0.0, 0.0, 0.0));
}

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <sstream>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

namespace catar
{
namespace mesh
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

struct MeshTraits : public OpenMesh::DefaultTraits
{
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using Point = OMesh::Point;
using VH = OMesh::VertexHandle;
using EH = OMesh::EdgeHandle;
using HH = OMesh::HalfedgeHandle;
using FH = OMesh::FaceHandle;

Vec3 ToEigen(const Point& p)
{
  return Vec3(p[0], p[1], p[2]);
}

/// Runs body(i) for i in [0, n) on Core's thread pool (`threads` threads, < 1: the default),
/// ranges of at least 256; rethrows the first exception a body threw.
template<typename Body>
void ParallelFor(std::size_t n, int threads, const Body& body)
{
  catar::parallel::ForCatching(
    0, static_cast<std::int64_t>(n), 256, threads, [&](std::int64_t b, std::int64_t e) {
      for (std::int64_t i = b; i < e; ++i)
      {
        body(static_cast<std::size_t>(i));
      }
    });
}

using Triangle = std::array<Point, 3>;

/// Distance from p to the triangle t (Ericson, Real-Time Collision Detection, 5.1.5).
double PointTriangleDistance(const Point& p, const Triangle& t)
{
  const Point ab = t[1] - t[0], ac = t[2] - t[0], ap = p - t[0];
  const double d1 = ab | ap, d2 = ac | ap;
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return ap.norm();
  }
  const Point bp = p - t[1];
  const double d3 = ab | bp, d4 = ac | bp;
  if (d3 >= 0.0 && d4 <= d3)
  {
    return bp.norm();
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return (p - (t[0] + ab * (d1 / (d1 - d3)))).norm();
  }
  const Point cp = p - t[2];
  const double d5 = ab | cp, d6 = ac | cp;
  if (d6 >= 0.0 && d5 <= d6)
  {
    return cp.norm();
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return (p - (t[0] + ac * (d2 / (d2 - d6)))).norm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
  {
    return (p - (t[1] + (t[2] - t[1]) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (t[0] + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Largest distance from the edge midpoints and centroids of the triangles `from` to the
/// triangles `to` (their corners are shared, so they need no sample).
double OneSidedDistance(const std::vector<Triangle>& from, const std::vector<Triangle>& to)
{
  double distance = 0.0;
  for (const Triangle& t : from)
  {
    const Point samples[4] = { 0.5 * (t[0] + t[1]), 0.5 * (t[1] + t[2]), 0.5 * (t[2] + t[0]),
      (t[0] + t[1] + t[2]) / 3.0 };
    for (const Point& p : samples)
    {
      double nearest = std::numeric_limits<double>::infinity();
      for (const Triangle& u : to)
      {
        nearest = std::min(nearest, PointTriangleDistance(p, u));
      }
      distance = std::max(distance, nearest);
    }
  }
  return distance;
}

/// Options with their defaults resolved.
struct Settings
{
  double tolerance = 0.5;
  double minEdgeLength = 0.0;
  double maxEdgeLength = 0.0;
  double maxGeometricError = 0.0;
  bool protectFeatures = true;
  double featureAngle = 60.0; ///< degrees
  std::size_t maxTriangles = 0;
  bool relax = true;
  int threads = 0;
};

class Remesher;

/// The decimation module: every check and the priority live in Remesher (CollapsePriority); the
/// decimater constructs modules from the mesh alone, so the remesher is attached afterwards.
class ScreenSpaceModule : public OpenMesh::Decimater::ModBaseT<OMesh>
{
public:
  using Base = OpenMesh::Decimater::ModBaseT<OMesh>;
  using Handle = OpenMesh::Decimater::ModHandleT<ScreenSpaceModule>;

  explicit ScreenSpaceModule(OMesh& mesh)
    : Base(mesh, false)
  {
  }

  const std::string& name() const override
  {
    static const std::string moduleName("ScreenSpace");
    return moduleName;
  }

  void SetRemesher(Remesher* remesher) { this->Owner = remesher; }

  float collapse_priority(const CollapseInfo& ci) override;
  void preprocess_collapse(const CollapseInfo& ci) override;
  void postprocess_collapse(const CollapseInfo& ci) override;

private:
  Remesher* Owner = nullptr;
};

/// The adaptive remesher: the OpenMesh surface, the triangles' deviation bounds and the bend
/// cache.
class Remesher
{
public:
  Remesher(const EdgeErrorFunction& edgeError, const Settings& settings)
    : EdgeError(edgeError)
    , Set(settings)
  {
    this->Mesh.add_property(this->DeviationProp);
  }

  /// Builds the OpenMesh surface; false when no triangle could be added.
  bool Load(const TriangleMesh& input, Warnings& warnings);

  /// Marks boundary edges, and sharp edges when features are protected, as features; locks the
  /// corners (vertices with one or more than two feature edges, or where a feature line turns by
  /// more than the feature angle).
  void Prepare();

  /// Bisects too bent or too long edges until none is left (or the triangle budget is spent).
  /// Returns the number of splits; sets budgetSpent when it stopped at maxTriangles.
  std::size_t Refine(bool& budgetSpent);

  /// Collapses every edge it may; returns the number of collapses.
  std::size_t Coarsen();

  /// Edge flips and vertex moves that lower the bend; returns how many were made.
  std::size_t Relax();

  std::size_t NumberOfTriangles() const { return this->Mesh.n_faces(); }

  /// About how many triangles refinement would make: an edge that bends b pixels is cut into
  /// about sqrt(b / tolerance) pieces (a bend falls with the square of the length), no shorter
  /// than minEdgeLength, and a triangle into the square of its most cut edge's pieces.
  double EstimateTriangles();

  void Export(TriangleMesh& out) const;

  // Decimation module callbacks: the collapse's priority (ILLEGAL_COLLAPSE when not allowed),
  // and the triangles' deviation bounds around it.
  float CollapsePriority(const ScreenSpaceModule::CollapseInfo& ci);
  void BeforeCollapse(const ScreenSpaceModule::CollapseInfo& ci);
  void AfterCollapse();

private:
  /// Bend of the vertex pair in pixels, negative when not visible (cached).
  double Bend(VH a, VH b);
  /// Computes the missing bends of the given pairs on several threads.
  void Prefetch(const std::vector<std::pair<VH, VH>>& pairs);
  /// Prefetch for every edge of the mesh.
  void PrefetchEdges();
  /// How close an edge between the two points is to its limits: the larger of length /
  /// maxEdgeLength and, when visible, bend / tolerance. An edge is acceptable when <= 1.
  double Ratio(double length, double bend) const
  {
    double r = length / this->Set.maxEdgeLength;
    if (bend >= 0.0)
    {
      r = std::max(r, bend / this->Set.tolerance);
    }
    return r;
  }
  double Ratio(VH a, VH b)
  {
    return this->Ratio((this->Mesh.point(a) - this->Mesh.point(b)).norm(), this->Bend(a, b));
  }
  bool NeedsSplit(EH e);
  /// Splits e by LEPP bisection: first the longer edges its triangles lead to.
  std::size_t SplitLepp(EH e);
  void SplitAtMidpoint(EH e);
  bool FlipIfBetter(EH e);
  bool MoveIfBetter(VH v);
  /// True when the triangle is not degenerate and its normal deviates from `reference` (unit) by
  /// less than the allowed angle.
  bool NormalKept(const Triangle& t, const Point& reference) const;
  Point FaceNormal(FH f) const;
  Triangle FaceTriangle(FH f, VH moved = VH(), const Point& to = Point()) const;
  double& Deviation(FH f) { return this->Mesh.property(this->DeviationProp, f); }
  /// The deviation bound of `replacement` taking the place of the triangles `faces`: their
  /// largest bound plus the distance between both. A planar fan that keeps its outline (the
  /// caller says so) is replaced exactly.
  double ReplacementDeviation(
    const std::vector<FH>& faces, const std::vector<Triangle>& replacement, bool sameOutline);
  /// The triangles around v0 that remain after collapsing v0 onto v1, and all those around v0.
  void CollapseFans(const ScreenSpaceModule::CollapseInfo& ci, std::vector<FH>& before,
    std::vector<Triangle>& after) const;
  static std::uint64_t Key(VH a, VH b)
  {
    const auto i = static_cast<std::uint32_t>(std::min(a.idx(), b.idx()));
    const auto j = static_cast<std::uint32_t>(std::max(a.idx(), b.idx()));
    return (static_cast<std::uint64_t>(i) << 32) | j;
  }

  OMesh Mesh;
  /// Per triangle: a bound on its distance to the input surface.
  OpenMesh::FPropHandleT<double> DeviationProp;
  const EdgeErrorFunction& EdgeError;
  Settings Set;
  std::unordered_map<std::uint64_t, double> BendCache;
  /// Between BeforeCollapse and AfterCollapse: the triangles around v0 that remain, and their
  /// new deviation bound.
  std::vector<FH> CollapseFaces;
  double CollapseDeviation = 0.0;
};

float ScreenSpaceModule::collapse_priority(const CollapseInfo& ci)
{
  return this->Owner->CollapsePriority(ci);
}

void ScreenSpaceModule::preprocess_collapse(const CollapseInfo& ci)
{
  this->Owner->BeforeCollapse(ci);
}

void ScreenSpaceModule::postprocess_collapse(const CollapseInfo&)
{
  this->Owner->AfterCollapse();
}

bool Remesher::Load(const TriangleMesh& input, Warnings& warnings)
{
  std::vector<VH> vertices;
  vertices.reserve(input.points.size());
  for (const Vec3& p : input.points)
  {
    vertices.push_back(this->Mesh.add_vertex(Point(p.x(), p.y(), p.z())));
  }
  std::size_t rejected = 0;
  for (const auto& t : input.triangles)
  {
    if (!this->Mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]).is_valid())
    {
      ++rejected;
    }
  }
  if (rejected > 0)
  {
    warnings.push_back(std::to_string(rejected) +
      " triangle(s) could not be added to the half-edge mesh (non-manifold) and were dropped");
  }
  // Points no triangle uses (none after repair, but cheap to be sure of).
  for (VH v : this->Mesh.vertices())
  {
    if (this->Mesh.is_isolated(v))
    {
      this->Mesh.delete_vertex(v, false);
    }
  }
  this->Mesh.garbage_collection();
  return this->Mesh.n_faces() > 0;
}

Point Remesher::FaceNormal(FH f) const
{
  auto fv = this->Mesh.cfv_iter(f);
  const Point a = this->Mesh.point(*fv);
  const Point b = this->Mesh.point(*++fv);
  const Point c = this->Mesh.point(*++fv);
  Point n = (b - a) % (c - a);
  const double len = n.norm();
  return len > 0.0 ? n / len : Point(0.0, 0.0, 0.0);
}

Triangle Remesher::FaceTriangle(FH f, VH moved, const Point& to) const
{
  Triangle t;
  int i = 0;
  for (VH v : this->Mesh.fv_range(f))
  {
    t[i++] = v == moved ? to : this->Mesh.point(v);
  }
  return t;
}

double Remesher::ReplacementDeviation(
  const std::vector<FH>& faces, const std::vector<Triangle>& replacement, bool sameOutline)
{
  double bound = 0.0;
  bool planar = sameOutline;
  const Point n0 = this->FaceNormal(faces.front());
  std::vector<Triangle> original;
  for (FH f : faces)
  {
    bound = std::max(bound, this->Deviation(f));
    planar = planar && (this->FaceNormal(f) | n0) >= 1.0 - 1e-12;
    original.push_back(this->FaceTriangle(f));
  }
  if (planar)
  {
    return bound;
  }
  return bound +
    std::max(OneSidedDistance(original, replacement), OneSidedDistance(replacement, original));
}

void Remesher::PrefetchEdges()
{
  std::vector<std::pair<VH, VH>> pairs;
  pairs.reserve(this->Mesh.n_edges());
  for (EH e : this->Mesh.edges())
  {
    const HH h = this->Mesh.halfedge_handle(e, 0);
    pairs.emplace_back(this->Mesh.from_vertex_handle(h), this->Mesh.to_vertex_handle(h));
  }
  this->Prefetch(pairs);
}

double Remesher::EstimateTriangles()
{
  this->PrefetchEdges();
  double total = 0.0;
  for (FH f : this->Mesh.faces())
  {
    double pieces = 1.0;
    for (HH h : this->Mesh.fh_range(f))
    {
      const VH a = this->Mesh.from_vertex_handle(h), b = this->Mesh.to_vertex_handle(h);
      const double bend = this->Bend(a, b);
      const double length = (this->Mesh.point(a) - this->Mesh.point(b)).norm();
      const double byBend =
        bend > this->Set.tolerance ? std::sqrt(bend / this->Set.tolerance) : 1.0;
      const double byLength = std::max(1.0, length / this->Set.minEdgeLength);
      pieces = std::max(pieces, std::min(byBend, byLength));
    }
    total += pieces * pieces;
  }
  return total;
}

void Remesher::Prepare()
{
  const double cosFeature = std::cos(this->Set.featureAngle * Pi / 180.0);
  for (EH e : this->Mesh.edges())
  {
    bool feature = this->Mesh.is_boundary(e);
    if (!feature && this->Set.protectFeatures)
    {
      const Point n0 = this->FaceNormal(this->Mesh.face_handle(this->Mesh.halfedge_handle(e, 0)));
      const Point n1 = this->FaceNormal(this->Mesh.face_handle(this->Mesh.halfedge_handle(e, 1)));
      feature = (n0 | n1) < cosFeature;
    }
    this->Mesh.status(e).set_feature(feature);
  }
  for (VH v : this->Mesh.vertices())
  {
    std::vector<VH> ends;
    for (HH h : this->Mesh.voh_range(v))
    {
      if (this->Mesh.status(this->Mesh.edge_handle(h)).feature())
      {
        ends.push_back(this->Mesh.to_vertex_handle(h));
      }
    }
    bool corner = ends.size() == 1 || ends.size() > 2;
    if (ends.size() == 2)
    {
      const Point p = this->Mesh.point(v);
      const Point d0 = (p - this->Mesh.point(ends[0])).normalized();
      const Point d1 = (this->Mesh.point(ends[1]) - p).normalized();
      corner = (d0 | d1) < cosFeature;
    }
    this->Mesh.status(v).set_feature(!ends.empty());
    this->Mesh.status(v).set_locked(corner);
  }
  for (FH f : this->Mesh.faces())
  {
    this->Deviation(f) = 0.0;
  }
}

double Remesher::Bend(VH a, VH b)
{
  const std::uint64_t key = Key(a, b);
  const auto found = this->BendCache.find(key);
  if (found != this->BendCache.end())
  {
    return found->second;
  }
  const double bend = this->EdgeError(ToEigen(this->Mesh.point(a)), ToEigen(this->Mesh.point(b)));
  this->BendCache.emplace(key, bend);
  return bend;
}

void Remesher::Prefetch(const std::vector<std::pair<VH, VH>>& pairs)
{
  std::vector<std::pair<VH, VH>> missing;
  for (const auto& pair : pairs)
  {
    if (this->BendCache.count(Key(pair.first, pair.second)) == 0)
    {
      missing.push_back(pair);
    }
  }
  std::sort(missing.begin(), missing.end(),
    [](const auto& x, const auto& y) { return Key(x.first, x.second) < Key(y.first, y.second); });
  missing.erase(std::unique(missing.begin(), missing.end(),
                  [](const auto& x, const auto& y) {
                    return Key(x.first, x.second) == Key(y.first, y.second);
                  }),
    missing.end());
  std::vector<double> bends(missing.size());
  ParallelFor(missing.size(), this->Set.threads, [&](std::size_t i) {
    bends[i] = this->EdgeError(
      ToEigen(this->Mesh.point(missing[i].first)), ToEigen(this->Mesh.point(missing[i].second)));
  });
  for (std::size_t i = 0; i < missing.size(); ++i)
  {
    this->BendCache.emplace(Key(missing[i].first, missing[i].second), bends[i]);
  }
}

bool Remesher::NeedsSplit(EH e)
{
  const HH h = this->Mesh.halfedge_handle(e, 0);
  const VH a = this->Mesh.from_vertex_handle(h);
  const VH b = this->Mesh.to_vertex_handle(h);
  const double length = (this->Mesh.point(a) - this->Mesh.point(b)).norm();
  if (length <= this->Set.minEdgeLength)
  {
    return false;
  }
  return this->Ratio(length, this->Bend(a, b)) > 1.0;
}

void Remesher::SplitAtMidpoint(EH e)
{
  const HH h = this->Mesh.halfedge_handle(e, 0);
  const VH a = this->Mesh.from_vertex_handle(h);
  const VH b = this->Mesh.to_vertex_handle(h);
  const bool feature = this->Mesh.status(e).feature();
  // The halves of a triangle lie on it: they keep its deviation bound (the larger of the two
  // triangles', as the split does not say which new triangle comes from which).
  double deviation = 0.0;
  for (int side = 0; side < 2; ++side)
  {
    const HH hs = this->Mesh.halfedge_handle(e, side);
    if (!this->Mesh.is_boundary(hs))
    {
      deviation = std::max(deviation, this->Deviation(this->Mesh.face_handle(hs)));
    }
  }
  const Point midpoint = 0.5 * (this->Mesh.point(a) + this->Mesh.point(b));
  const VH v = this->Mesh.split(e, midpoint);
  for (FH f : this->Mesh.vf_range(v))
  {
    this->Deviation(f) = deviation;
  }
  this->Mesh.status(v).set_feature(feature);
  this->Mesh.status(v).set_locked(false);
  for (HH out : this->Mesh.voh_range(v))
  {
    const VH to = this->Mesh.to_vertex_handle(out);
    this->Mesh.status(this->Mesh.edge_handle(out)).set_feature(feature && (to == a || to == b));
  }
}

std::size_t Remesher::SplitLepp(EH e0)
{
  const auto longer = [this](EH x, EH y) {
    const double lx = this->Mesh.calc_edge_sqr_length(x);
    const double ly = this->Mesh.calc_edge_sqr_length(y);
    return lx > ly || (lx == ly && x.idx() > y.idx());
  };
  std::size_t splits = 0;
  std::vector<EH> path{ e0 };
  while (!path.empty())
  {
    const EH e = path.back();
    EH longest = e;
    for (int side = 0; side < 2; ++side)
    {
      const HH h = this->Mesh.halfedge_handle(e, side);
      if (this->Mesh.is_boundary(h))
      {
        continue;
      }
      for (EH g : this->Mesh.fe_range(this->Mesh.face_handle(h)))
      {
        if (longer(g, longest))
        {
          longest = g;
        }
      }
    }
    if (longest == e)
    {
      this->SplitAtMidpoint(e);
      ++splits;
      path.pop_back();
    }
    else
    {
      path.push_back(longest);
    }
  }
  return splits;
}

std::size_t Remesher::Refine(bool& budgetSpent)
{
  budgetSpent = false;
  std::size_t splits = 0;
  for (;;)
  {
    this->PrefetchEdges();
    std::vector<std::pair<double, EH>> pending;
    for (EH e : this->Mesh.edges())
    {
      if (this->NeedsSplit(e))
      {
        pending.emplace_back(this->Mesh.calc_edge_sqr_length(e), e);
      }
    }
    if (pending.empty())
    {
      return splits;
    }
    // Longest first: their LEPP bisections also shorten many of the shorter ones.
    std::sort(pending.begin(), pending.end(),
      [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& item : pending)
    {
      if (this->Mesh.n_faces() >= this->Set.maxTriangles)
      {
        budgetSpent = true;
        return splits;
      }
      // An edge split earlier in this pass keeps its handle for one of its halves: check again.
      if (this->NeedsSplit(item.second))
      {
        splits += this->SplitLepp(item.second);
      }
    }
  }
}

bool Remesher::NormalKept(const Triangle& t, const Point& reference) const
{
  const Point n = (t[1] - t[0]) % (t[2] - t[0]);
  const double scale =
    std::max({ (t[1] - t[0]).sqrnorm(), (t[2] - t[0]).sqrnorm(), (t[2] - t[1]).sqrnorm() });
  const double length = n.norm();
  // Reject degenerate triangles (area relative to the longest edge squared) and folds.
  const double maxNormalDeviation = std::min(this->Set.featureAngle, 45.0) * Pi / 180.0;
  return length > 1e-6 * scale && (n | reference) > std::cos(maxNormalDeviation) * length;
}

float Remesher::CollapsePriority(const ScreenSpaceModule::CollapseInfo& ci)
{
  constexpr float illegal = static_cast<float>(ScreenSpaceModule::ILLEGAL_COLLAPSE);
  // A feature vertex may only slide along its feature line (the decimater checks that the
  // collapsed edge is a feature edge). The collapse deletes the edges (v0, vl) and (v0, vr) and
  // keeps (v1, vl) and (v1, vr): none of the deleted may be a feature edge, so that no feature is
  // lost (a feature edge there would mean the line turns at v0 within one triangle).
  if (this->Mesh.status(ci.v0).feature())
  {
    for (HH h : { ci.v0vl, ci.vrv0 })
    {
      if (h.is_valid() && this->Mesh.status(this->Mesh.edge_handle(h)).feature())
      {
        return illegal;
      }
    }
  }
  // The triangles around v0 that remain, with v0 moved onto v1, must keep their orientation.
  for (FH f : this->Mesh.vf_range(ci.v0))
  {
    if (f != ci.fl && f != ci.fr &&
      !this->NormalKept(this->FaceTriangle(f, ci.v0, ci.p1), this->FaceNormal(f)))
    {
      return illegal;
    }
  }
  // Every edge v1 gets must stay within the tolerance and the length limit.
  double worst = 0.0;
  for (VH v : this->Mesh.vv_range(ci.v0))
  {
    if (v == ci.v1)
    {
      continue;
    }
    const double r = this->Ratio(v, ci.v1);
    if (!(r <= 1.0))
    {
      return illegal;
    }
    worst = std::max(worst, r);
  }
  // Last, as the dearest check: the surface stays close to the input.
  std::vector<FH> before;
  std::vector<Triangle> after;
  this->CollapseFans(ci, before, after);
  if (!(this->ReplacementDeviation(before, after, !this->Mesh.is_boundary(ci.v0)) <=
        this->Set.maxGeometricError))
  {
    return illegal;
  }
  return static_cast<float>(worst);
}

void Remesher::CollapseFans(const ScreenSpaceModule::CollapseInfo& ci, std::vector<FH>& before,
  std::vector<Triangle>& after) const
{
  for (FH f : this->Mesh.vf_range(ci.v0))
  {
    before.push_back(f);
    if (f != ci.fl && f != ci.fr)
    {
      after.push_back(this->FaceTriangle(f, ci.v0, ci.p1));
    }
  }
}

void Remesher::BeforeCollapse(const ScreenSpaceModule::CollapseInfo& ci)
{
  std::vector<FH> before;
  std::vector<Triangle> after;
  this->CollapseFans(ci, before, after);
  this->CollapseDeviation =
    this->ReplacementDeviation(before, after, !this->Mesh.is_boundary(ci.v0));
  this->CollapseFaces.clear();
  for (FH f : before)
  {
    if (f != ci.fl && f != ci.fr)
    {
      this->CollapseFaces.push_back(f);
    }
  }
}

void Remesher::AfterCollapse()
{
  for (FH f : this->CollapseFaces)
  {
    this->Deviation(f) = this->CollapseDeviation;
  }
}

std::size_t Remesher::Coarsen()
{
  // Most candidate collapses of the first heap fill: the pairs (v1, w) for w around v0.
  std::vector<std::pair<VH, VH>> pairs;
  for (VH v0 : this->Mesh.vertices())
  {
    if (this->Mesh.status(v0).locked())
    {
      continue;
    }
    for (VH v1 : this->Mesh.vv_range(v0))
    {
      for (VH w : this->Mesh.vv_range(v0))
      {
        if (w.idx() < v1.idx())
        {
          pairs.emplace_back(v1, w);
        }
      }
    }
  }
  this->Prefetch(pairs);

  OpenMesh::Decimater::DecimaterT<OMesh> decimater(this->Mesh);
  ScreenSpaceModule::Handle handle;
  decimater.add(handle);
  decimater.module(handle).SetRemesher(this);
  if (!decimater.initialize())
  {
    return 0;
  }
  const std::size_t collapses = decimater.decimate();
  this->Mesh.garbage_collection();
  this->BendCache.clear(); // vertex numbers changed
  return collapses;
}

bool Remesher::FlipIfBetter(EH e)
{
  if (this->Mesh.status(e).feature() || this->Mesh.is_boundary(e) || !this->Mesh.is_flip_ok(e))
  {
    return false;
  }
  const HH h = this->Mesh.halfedge_handle(e, 0);
  const HH o = this->Mesh.opposite_halfedge_handle(h);
  const VH a = this->Mesh.from_vertex_handle(h);
  const VH b = this->Mesh.to_vertex_handle(h);
  const VH c = this->Mesh.to_vertex_handle(this->Mesh.next_halfedge_handle(h));
  const VH d = this->Mesh.to_vertex_handle(this->Mesh.next_halfedge_handle(o));
  const double before = this->Ratio(a, b);
  const double after = this->Ratio(c, d);
  if (!(after <= 1.0) || !(after < 0.95 * before))
  {
    return false;
  }
  // The quad b, c, a, d split along c-d instead of a-b.
  const FH f0 = this->Mesh.face_handle(h);
  const FH f1 = this->Mesh.face_handle(o);
  const Point pa = this->Mesh.point(a), pb = this->Mesh.point(b);
  const Point pc = this->Mesh.point(c), pd = this->Mesh.point(d);
  const std::vector<Triangle> flipped = { Triangle{ pc, pa, pd }, Triangle{ pd, pb, pc } };
  Point reference = this->FaceNormal(f0) + this->FaceNormal(f1);
  if (reference.norm() == 0.0)
  {
    return false;
  }
  reference.normalize();
  if (!this->NormalKept(flipped[0], reference) || !this->NormalKept(flipped[1], reference))
  {
    return false;
  }
  const double deviation = this->ReplacementDeviation({ f0, f1 }, flipped, true);
  if (!(deviation <= this->Set.maxGeometricError))
  {
    return false;
  }
  this->Mesh.flip(e);
  this->Deviation(f0) = deviation;
  this->Deviation(f1) = deviation;
  return true;
}

bool Remesher::MoveIfBetter(VH v)
{
  if (this->Mesh.status(v).locked())
  {
    return false;
  }
  const Point p = this->Mesh.point(v);
  const bool feature = this->Mesh.status(v).feature();
  // Pull towards the neighbours (feature vertices: their two neighbours on the feature line),
  // each weighted by how close its edge is to the limits, so that the worst edges shorten.
  Point target(0.0, 0.0, 0.0);
  double weights = 0.0;
  double worst = 0.0;
  for (HH h : this->Mesh.voh_range(v))
  {
    const VH w = this->Mesh.to_vertex_handle(h);
    const double r = this->Ratio(v, w);
    worst = std::max(worst, r);
    if (!feature || this->Mesh.status(this->Mesh.edge_handle(h)).feature())
    {
      const double weight = std::max(r, 1e-3);
      target += weight * this->Mesh.point(w);
      weights += weight;
    }
  }
  if (weights == 0.0)
  {
    return false;
  }
  target /= weights;
  std::vector<FH> faces;
  Point normal(0.0, 0.0, 0.0);
  for (FH f : this->Mesh.vf_range(v))
  {
    faces.push_back(f);
    normal += this->Mesh.calc_face_normal(f) * this->Mesh.calc_face_area(f);
  }
  if (!feature)
  {
    // Slide in the tangent plane.
    const double length = normal.norm();
    if (length == 0.0)
    {
      return false;
    }
    normal /= length;
    target -= normal * ((target - p) | normal);
  }
  for (double step : { 1.0, 0.5, 0.25 })
  {
    const Point candidate = p + step * (target - p);
    std::vector<Triangle> moved;
    bool kept = true;
    for (FH f : faces)
    {
      moved.push_back(this->FaceTriangle(f, v, candidate));
      kept = kept && this->NormalKept(moved.back(), this->FaceNormal(f));
    }
    if (!kept)
    {
      continue;
    }
    double worstAfter = 0.0;
    for (VH w : this->Mesh.vv_range(v))
    {
      const Point pw = this->Mesh.point(w);
      const double r =
        this->Ratio((candidate - pw).norm(), this->EdgeError(ToEigen(candidate), ToEigen(pw)));
      worstAfter = std::max(worstAfter, r);
    }
    const double deviation = worstAfter < worst
      ? this->ReplacementDeviation(faces, moved, !this->Mesh.is_boundary(v))
      : 0.0;
    if (worstAfter < worst && deviation <= this->Set.maxGeometricError)
    {
      this->Mesh.set_point(v, candidate);
      for (FH f : faces)
      {
        this->Deviation(f) = deviation;
      }
      for (VH w : this->Mesh.vv_range(v))
      {
        this->BendCache.erase(Key(v, w));
      }
      return true;
    }
  }
  return false;
}

std::size_t Remesher::Relax()
{
  std::size_t changes = 0;
  for (EH e : this->Mesh.edges())
  {
    changes += this->FlipIfBetter(e) ? 1 : 0;
  }
  for (VH v : this->Mesh.vertices())
  {
    changes += this->MoveIfBetter(v) ? 1 : 0;
  }
  // Moves leave stale bends of vertex pairs that are not edges.
  this->BendCache.clear();
  return changes;
}

void Remesher::Export(TriangleMesh& out) const
{
  out.points.clear();
  out.triangles.clear();
  out.pointData.clear();
  out.points.reserve(this->Mesh.n_vertices());
  for (VH v : this->Mesh.vertices())
  {
    out.points.push_back(ToEigen(this->Mesh.point(v)));
  }
  out.triangles.reserve(this->Mesh.n_faces());
  for (FH f : this->Mesh.faces())
  {
    std::array<int, 3> t;
    int i = 0;
    for (VH v : this->Mesh.fv_range(f))
    {
      t[i++] = v.idx();
    }
    out.triangles.push_back(t);
  }
}

/// Empty when the options are usable, else what is wrong with them.
std::string ValidateOptions(const ScreenSpaceOptions& options)
{
  const auto finiteNonNegative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!(std::isfinite(options.tolerance) && options.tolerance > 0.0))
  {
    return "the pixel tolerance must be a finite number > 0";
  }
  if (!finiteNonNegative(options.minEdgeLength) || !finiteNonNegative(options.maxEdgeLength) ||
    !finiteNonNegative(options.maxGeometricError))
  {
    return "minEdgeLength, maxEdgeLength and maxGeometricError must be finite and >= 0";
  }
  if (options.minEdgeLength > 0.0 && options.maxEdgeLength > 0.0 &&
    options.minEdgeLength > options.maxEdgeLength)
  {
    return "minEdgeLength must not exceed maxEdgeLength";
  }
  if (!(options.featureAngle >= 0.0 && options.featureAngle <= 180.0))
  {
    return "the feature angle must be between 0 and 180 degrees";
  }
  if (options.maxIterations < 1)
  {
    return "maxIterations must be at least 1";
  }
  if (options.maxTriangles < 1)
  {
    return "maxTriangles must be at least 1";
  }
  return std::string();
}

/// Valid options with their defaults resolved against the bounding box diagonal (> 0).
Settings ResolveSettings(const ScreenSpaceOptions& options, double diagonal)
{
  Settings settings;
  settings.tolerance = options.tolerance;
  settings.minEdgeLength = options.minEdgeLength > 0.0 ? options.minEdgeLength : 1e-4 * diagonal;
  settings.maxEdgeLength = options.maxEdgeLength > 0.0 ? options.maxEdgeLength : 0.25 * diagonal;
  settings.maxGeometricError =
    options.maxGeometricError > 0.0 ? options.maxGeometricError : 1e-3 * diagonal;
  // A default bound must not contradict a given one.
  settings.minEdgeLength = std::min(settings.minEdgeLength, settings.maxEdgeLength);
  settings.protectFeatures = options.protectFeatures;
  settings.featureAngle = options.featureAngle;
  settings.maxTriangles = options.maxTriangles;
  settings.relax = options.relax;
  settings.threads = options.threads;
  return settings;
}

// Reports progress; false when the stop function asks to stop.
[[nodiscard]] bool Report(const ScreenSpaceOptions& options, double fraction)
{
  if (options.progress)
  {
    options.progress(std::min(std::max(fraction, 0.0), 1.0), options.progressData);
  }
  return !(options.stop && options.stop(options.progressData));
}

ScreenSpaceResult Remesh(
  const TriangleMesh& input, const EdgeErrorFunction& edgeError, const ScreenSpaceOptions& options)
{
  ScreenSpaceResult result;
  if (!edgeError)
  {
    result.error = "no edge error function given";
    return result;
  }
  result.error = ValidateOptions(options);
  if (!result.error.empty())
  {
    return result;
  }
  if (input.Empty())
  {
    result.error = "the input mesh has no triangles";
    return result;
  }
  if (!Report(options, 0.0))
  {
    result.error = kAbortedError;
    return result;
  }

  TriangleMesh repaired = input;
  RepairReport repairReport;
  if (!RepairMesh(repaired, repairReport, result.warnings, result.error))
  {
    if (result.error.empty())
    {
      result.error = "the input mesh could not be repaired";
    }
    return result;
  }
  Vec3 lo = repaired.points.front(), hi = lo;
  for (const Vec3& p : repaired.points)
  {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0 && std::isfinite(diagonal)))
  {
    result.error = "the input mesh has no finite extent";
    return result;
  }
  const Settings settings = ResolveSettings(options, diagonal);

  Remesher remesher(edgeError, settings);
  if (!remesher.Load(repaired, result.warnings))
  {
    result.error = "no triangle of the repaired input could be used";
    return result;
  }
  remesher.Prepare();
  if (!Report(options, 0.05))
  {
    result.error = kAbortedError;
    return result;
  }
  // A tolerance far below what the mesh needs would refine for minutes towards the budget: refused
  // at once, with the estimate, when that is more than twice the budget (the estimate runs about
  // 1.5 times what one round of refinement makes: TestScreenSpaceRemeshing).
  const double estimate = remesher.EstimateTriangles();
  result.estimatedTriangles = estimate;
  if (estimate > 2.0 * static_cast<double>(settings.maxTriangles))
  {
    char text[320];
    std::snprintf(text, sizeof text,
      "a pixel tolerance of %g would need about %.3g triangles, more than twice the budget of "
      "%zu (maxTriangles): raise the tolerance, or the budget (a scene's remesh: { max_triangles: "
      "N }, "
      "vtkCatadioptricRemesher's MaximumTriangles)",
      settings.tolerance, estimate, settings.maxTriangles);
    result.error = text;
    return result;
  }

  // Rounds of refine, coarsen, relax, until a round removes (almost) no triangles.
  bool budgetSpent = false;
  std::size_t previous = std::numeric_limits<std::size_t>::max();
  for (int round = 0; round < options.maxIterations; ++round)
  {
    result.iterations = round + 1;
    remesher.Refine(budgetSpent);
    if (budgetSpent)
    {
      break;
    }
    remesher.Coarsen();
    const std::size_t triangles = remesher.NumberOfTriangles();
    if (!Report(options, 0.05 + 0.85 * (round + 1.0) / options.maxIterations))
    {
      result.error = kAbortedError;
      return result;
    }
    // Without relaxation a second round would find nothing to do.
    const bool converged = triangles >= 0.99 * static_cast<double>(previous);
    if (converged || !settings.relax || remesher.Relax() == 0)
    {
      break;
    }
    previous = triangles;
  }
  // Relaxation and coarsening keep every edge within bounds; this last refinement guarantees it
  // (and costs one pass over the bends when nothing needs splitting).
  if (!budgetSpent)
  {
    remesher.Refine(budgetSpent);
  }
  if (budgetSpent)
  {
    result.warnings.push_back("refinement stopped at maxTriangles (" +
      std::to_string(settings.maxTriangles) + " triangles); some edges bend more than the " +
      "tolerance");
  }
  if (!Report(options, 0.92))
  {
    result.error = kAbortedError;
    return result;
  }

  remesher.Export(result.mesh);
  if (!repaired.pointData.empty())
  {
    TransferPointData(repaired, result.mesh);
  }
  MeasureEdgeError(result.mesh, edgeError, result.maxError, result.meanError, result.visibleEdges,
    options.threads);
  if (result.maxError > settings.tolerance && !budgetSpent)
  {
    std::ostringstream message;
    message << "some edges bend up to " << result.maxError << " px (tolerance "
            << settings.tolerance << " px) at the minimum edge length " << settings.minEdgeLength;
    result.warnings.push_back(message.str());
  }
  result.ok = true;
  (void)Report(options, 1.0);
  return result;
}
} // namespace

ScreenSpaceResult RemeshToPixelTolerance(
  const TriangleMesh& input, const EdgeErrorFunction& edgeError, const ScreenSpaceOptions& options)
{
  try
  {
    return Remesh(input, edgeError, options);
  }
  catch (const std::exception& e)
  {
    ScreenSpaceResult result;
    result.error = std::string("screen-space remeshing failed: ") + e.what();
    return result;
  }
  catch (...)
  {
    ScreenSpaceResult result;
    result.error = "screen-space remeshing failed with an unknown exception";
    return result;
  }
}

void MeasureEdgeError(const TriangleMesh& mesh, const EdgeErrorFunction& edgeError,
  double& maxError, double& meanError, std::size_t& visibleEdges, int threads)
{
  maxError = 0.0;
  meanError = 0.0;
  visibleEdges = 0;
  if (!edgeError)
  {
    return;
  }
  const int n = static_cast<int>(mesh.points.size());
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k], b = t[(k + 1) % 3];
      if (a >= 0 && b >= 0 && a < n && b < n && a != b)
      {
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> bends(edges.size());
  ParallelFor(edges.size(), threads, [&](std::size_t i) {
    bends[i] = edgeError(mesh.points[edges[i].first], mesh.points[edges[i].second]);
  });
  double sum = 0.0;
  for (double bend : bends)
  {
    if (bend >= 0.0)
    {
      maxError = std::max(maxError, bend);
      sum += bend;
      ++visibleEdges;
    }
  }
  meanError = visibleEdges > 0 ? sum / static_cast<double>(visibleEdges) : 0.0;
}

} // namespace mesh
} // namespace catar
