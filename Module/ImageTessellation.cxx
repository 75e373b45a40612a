#include "ImageTessellation.h"

#include "EdgeBend.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace catar
{
namespace
{
bool Seen(const ProjectedPoint& q)
{
  return HasProjection(q.status);
}

// The bend of the edge between two seen points whose midpoint projects to `mid`: the distance of
// the midpoint's image from the straight segment; infinite when the midpoint is not seen (the
// edge crosses the boundary).
double Bend(const ProjectedPoint& a, const ProjectedPoint& b, const ProjectedPoint& mid)
{
  if (!Seen(mid))
  {
    return std::numeric_limits<double>::infinity();
  }
  return DistanceToSegment(mid.pixel, a.pixel, b.pixel);
}

// One input triangle's tessellation: nodes (points given by barycentric weights), the midpoints
// made so far (shared by the pieces on either side of an edge), the pieces.
class Tessellator
{
public:
  Tessellator(const Projector& projector, const std::array<std::int64_t, 3>& ids,
    const std::array<Vec3, 3>& world, const std::array<ProjectedPoint, 3>& projected,
    std::int64_t cell, std::int64_t inputPointCount, const TessellationOptions& options,
    Tessellation& out)
    : Proj(projector)
    , World(world)
    , Cell(cell)
    , InputPoints(inputPointCount)
    , Options(options)
    , Out(out)
  {
    for (int i = 0; i < 3; ++i)
    {
      Node n;
      n.weights = Vec3::Zero();
      n.weights[i] = 1.0;
      n.world = world[i];
      n.projected = projected[i];
      n.id = ids[i];
      this->Nodes.push_back(n);
    }
  }

  std::size_t Run()
  {
    const std::size_t before = this->Out.triangles.size();
    this->Refine(0, 1, 2, 0);
    return this->Out.triangles.size() - before;
  }

private:
  struct Node
  {
    Vec3 weights;
    Vec3 world;
    ProjectedPoint projected;
    std::int64_t id = -1; // the output id, once a piece uses it
  };

  // A new point at these weights; guess: a reflection point near its own (camera frame), which
  // gives the same answer in fewer steps (Projector::ProjectWorldNear), or null.
  int Make(const Vec3& weights, const Vec3* guess = nullptr)
  {
    Node n;
    n.weights = weights;
    n.world =
      weights[0] * this->World[0] + weights[1] * this->World[1] + weights[2] * this->World[2];
    n.projected = guess ? this->Proj.ProjectWorldNear(n.world, *guess)
                        : this->Proj.ProjectWorld(n.world, this->Options.solver);
    this->Nodes.push_back(n);
    return static_cast<int>(this->Nodes.size()) - 1;
  }

  int Midpoint(int a, int b)
  {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    const auto found = this->Midpoints.find(key);
    if (found != this->Midpoints.end())
    {
      return found->second;
    }
    const Node &na = this->Nodes[a], &nb = this->Nodes[b];
    const Vec3 guess = 0.5 * (na.projected.mirrorPoint + nb.projected.mirrorPoint);
    const bool near = Seen(na.projected) && Seen(nb.projected);
    const int m = this->Make(0.5 * (na.weights + nb.weights), near ? &guess : nullptr);
    this->Midpoints.emplace(key, m);
    return m;
  }

  bool IsSeen(int n) const { return Seen(this->Nodes[n].projected); }
  const Vec2& Pixel(int n) const { return this->Nodes[n].projected.pixel; }

  std::int64_t Id(int n)
  {
    Node& node = this->Nodes[n];
    if (node.id < 0)
    {
      TessellatedPoint p;
      // The input triangle's vertices are the first three nodes.
      for (int i = 0; i < 3; ++i)
      {
        p.parents[i] = this->Nodes[i].id;
        p.weights[i] = node.weights[i];
      }
      p.world = node.world;
      p.projected = node.projected;
      node.id = this->InputPoints + static_cast<std::int64_t>(this->Out.points.size());
      this->Out.points.push_back(p);
    }
    return node.id;
  }

  void Emit(int a, int b, int c)
  {
    TessellatedTriangle t;
    t.cell = this->Cell;
    t.points = { { this->Id(a), this->Id(b), this->Id(c) } };
    this->Out.triangles.push_back(t);
    ++this->Pieces;
  }

  // The seen end of edge good-bad moved towards the boundary by bisection until a step moves its
  // image by less than a quarter of the tolerance (made once for an edge).
  int Boundary(int good, int bad)
  {
    const std::pair<int, int> key(good, bad);
    const auto found = this->Boundaries.find(key);
    if (found != this->Boundaries.end())
    {
      return found->second;
    }
    const int made = this->Bisect(good, bad);
    this->Boundaries.emplace(key, made);
    return made;
  }

  int Bisect(int good, int bad)
  {
    Vec3 lo = this->Nodes[good].weights, hi = this->Nodes[bad].weights;
    ProjectedPoint seen = this->Nodes[good].projected;
    const double stop = 0.25 * std::max(this->Options.boundaryTolerance, 1e-6);
    for (int k = 0; k < 60; ++k)
    {
      const Vec3 mid = 0.5 * (lo + hi);
      const Vec3 world =
        mid[0] * this->World[0] + mid[1] * this->World[1] + mid[2] * this->World[2];
      const ProjectedPoint q = this->Proj.ProjectWorldNear(world, seen.mirrorPoint);
      if (Seen(q))
      {
        const double moved = (q.pixel - seen.pixel).norm();
        lo = mid;
        seen = q;
        if (moved < stop)
        {
          break;
        }
      }
      else
      {
        hi = mid;
      }
    }
    Node n;
    n.weights = lo;
    n.world = lo[0] * this->World[0] + lo[1] * this->World[1] + lo[2] * this->World[2];
    n.projected = seen;
    this->Nodes.push_back(n);
    return static_cast<int>(this->Nodes.size()) - 1;
  }

  // The seen part of a piece that crosses the boundary, cut at it: its seen corners and the
  // boundary points on its edges, in order.
  std::vector<int> Clipped(int a, int b, int c)
  {
    const int corners[3] = { a, b, c };
    std::vector<int> polygon;
    for (int i = 0; i < 3; ++i)
    {
      const int p = corners[i], q = corners[(i + 1) % 3];
      if (this->IsSeen(p))
      {
        polygon.push_back(p);
      }
      if (this->IsSeen(p) != this->IsSeen(q))
      {
        polygon.push_back(this->IsSeen(p) ? this->Boundary(p, q) : this->Boundary(q, p));
      }
    }
    return polygon;
  }

  // The largest distance between the images of the polygon's points.
  double Extent(const std::vector<int>& polygon) const
  {
    double e = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
    {
      for (std::size_t j = i + 1; j < polygon.size(); ++j)
      {
        e = std::max(e, (this->Pixel(polygon[i]) - this->Pixel(polygon[j])).norm());
      }
    }
    return e;
  }

  void Split(int a, int b, int c, int depth)
  {
    const int ab = this->Midpoint(a, b), bc = this->Midpoint(b, c), ca = this->Midpoint(c, a);
    this->Refine(a, ab, ca, depth + 1);
    this->Refine(ab, b, bc, depth + 1);
    this->Refine(ca, bc, c, depth + 1);
    this->Refine(ab, bc, ca, depth + 1);
  }

  // Splits exactly the edges of seen triangle (a, b, c) that bend more than the tolerance, at
  // their midpoints (one edge: two pieces; two: three; three: four), and refines the pieces. The
  // decision is the edge's own, so the triangle across it splits it too, at the same point: the
  // pieces meet their neighbours' without cracks. False when no edge bends too much.
  bool SplitBentEdges(int a, int b, int c, int depth)
  {
    const int corner[3] = { a, b, c };
    int mid[3];
    bool bent[3];
    int count = 0;
    for (int i = 0; i < 3; ++i)
    {
      const int p = corner[i], q = corner[(i + 1) % 3];
      mid[i] = this->Midpoint(p, q);
      bent[i] = Bend(this->Nodes[p].projected, this->Nodes[q].projected,
                  this->Nodes[mid[i]].projected) > this->Options.bendTolerance;
      count += bent[i] ? 1 : 0;
    }
    if (count == 0)
    {
      return false;
    }
    if (count == 3)
    {
      this->Split(a, b, c, depth);
      return true;
    }
    // Turned so that edge (p, q) bends and, with two bent edges, (q, r) too; (r, p) does not.
    int k = 0;
    while (!(bent[k] && !bent[(k + 2) % 3]))
    {
      ++k;
    }
    const int p = corner[k], q = corner[(k + 1) % 3], r = corner[(k + 2) % 3];
    const int pq = mid[k];
    if (count == 1)
    {
      this->Refine(p, pq, r, depth + 1);
      this->Refine(pq, q, r, depth + 1);
      return true;
    }
    const int qr = mid[(k + 1) % 3];
    this->Refine(pq, q, qr, depth + 1);
    // The quadrilateral p, pq, qr, r cut along its shorter diagonal in the image.
    if ((this->Pixel(p) - this->Pixel(qr)).squaredNorm() <=
      (this->Pixel(pq) - this->Pixel(r)).squaredNorm())
    {
      this->Refine(p, pq, qr, depth + 1);
      this->Refine(p, qr, r, depth + 1);
    }
    else
    {
      this->Refine(p, pq, r, depth + 1);
      this->Refine(pq, qr, r, depth + 1);
    }
    return true;
  }

  void Refine(int a, int b, int c, int depth)
  {
    const int seen = int(this->IsSeen(a)) + int(this->IsSeen(b)) + int(this->IsSeen(c));
    const bool deeper = depth < this->Options.maxDepth &&
      this->Pieces + 4 <= static_cast<std::size_t>(this->Options.maxPiecesPerTriangle);
    if (seen == 3)
    {
      if (deeper && this->Options.bendTolerance > 0.0 && this->SplitBentEdges(a, b, c, depth))
      {
        return;
      }
      this->Emit(a, b, c);
      return;
    }
    if (seen == 0)
    {
      // The whole input triangle unseen at its corners (its fate said something inside is
      // seen): split once more; smaller unseen pieces are dropped.
      if (depth == 0)
      {
        this->Split(a, b, c, depth);
      }
      return;
    }
    const std::vector<int> polygon = this->Clipped(a, b, c);
    if (!deeper || this->Extent(polygon) <= this->Options.boundaryTolerance)
    {
      for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      {
        this->Emit(polygon[0], polygon[i], polygon[i + 1]);
      }
      return;
    }
    this->Split(a, b, c, depth);
  }

  const Projector& Proj;
  std::array<Vec3, 3> World;
  std::int64_t Cell;
  std::int64_t InputPoints;
  const TessellationOptions& Options;
  Tessellation& Out;
  std::vector<Node> Nodes;
  std::map<std::pair<int, int>, int> Midpoints;
  std::map<std::pair<int, int>, int> Boundaries; // (seen end, unseen end) -> the boundary point
  std::size_t Pieces = 0;
};
} // namespace

TriangleFate TriangleFateOf(const Projector& projector, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, const TessellationOptions& options)
{
  for (int i = 0; i < 3; ++i)
  {
    if (projected[i].status == ProjectionStatus::InvalidInput || !world[i].allFinite())
    {
      return TriangleFate::Drop; // a corner that is not a point (NaN, Inf)
    }
  }
  const int seen = int(Seen(projected[0])) + int(Seen(projected[1])) + int(Seen(projected[2]));
  if (seen == 3)
  {
    if (!(options.bendTolerance > 0.0))
    {
      return TriangleFate::Keep;
    }
    // The three edge midpoints side by side, each from its ends' reflection points.
    Vec3 mids[3], guesses[3];
    ProjectedPoint mid[3];
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      mids[i] = 0.5 * (world[i] + world[j]);
      guesses[i] = 0.5 * (projected[i].mirrorPoint + projected[j].mirrorPoint);
    }
    projector.ProjectWorldNear(3, mids, guesses, mid);
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      if (Bend(projected[i], projected[j], mid[i]) > options.bendTolerance &&
        (Seen(mid[i]) || options.boundaryTolerance > 0.0))
      {
        return TriangleFate::Tessellate;
      }
    }
    return TriangleFate::Keep;
  }
  if (!(options.boundaryTolerance > 0.0))
  {
    return TriangleFate::Drop;
  }
  if (seen > 0)
  {
    return TriangleFate::Tessellate;
  }
  // No corner seen: the edge midpoints and the centroid.
  const Vec3 samples[4] = { 0.5 * (world[0] + world[1]), 0.5 * (world[1] + world[2]),
    0.5 * (world[2] + world[0]), (world[0] + world[1] + world[2]) / 3.0 };
  for (const Vec3& s : samples)
  {
    if (Seen(projector.ProjectWorld(s, options.solver)))
    {
      return TriangleFate::Tessellate;
    }
  }
  return TriangleFate::Drop;
}

void TriangleFates(const Projector& projector, std::size_t n, const std::array<Vec3, 3>* world,
  const std::array<ProjectedPoint, 3>* projected, const TessellationOptions& options,
  TriangleFate* out)
{
  // The triangles seen whole, measured for bending: their midpoints, all together.
  std::vector<std::size_t> bent;
  std::vector<Vec3> mids, guesses;
  for (std::size_t t = 0; t < n; ++t)
  {
    bool whole = options.bendTolerance > 0.0;
    for (int i = 0; i < 3 && whole; ++i)
    {
      whole = Seen(projected[t][i]) && world[t][i].allFinite();
    }
    if (!whole)
    {
      out[t] = TriangleFateOf(projector, world[t], projected[t], options);
      continue;
    }
    bent.push_back(t);
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      mids.push_back(0.5 * (world[t][i] + world[t][j]));
      guesses.push_back(0.5 * (projected[t][i].mirrorPoint + projected[t][j].mirrorPoint));
    }
  }
  std::vector<ProjectedPoint> mid(mids.size());
  projector.ProjectWorldNear(mids.size(), mids.data(), guesses.data(), mid.data());
  for (std::size_t k = 0; k < bent.size(); ++k)
  {
    const std::size_t t = bent[k];
    out[t] = TriangleFate::Keep;
    for (int i = 0; i < 3; ++i)
    {
      const ProjectedPoint& m = mid[3 * k + i];
      if (Bend(projected[t][i], projected[t][(i + 1) % 3], m) > options.bendTolerance &&
        (Seen(m) || options.boundaryTolerance > 0.0))
      {
        out[t] = TriangleFate::Tessellate;
        break;
      }
    }
  }
}

std::size_t TessellateTriangle(const Projector& projector, std::int64_t cell,
  const std::array<std::int64_t, 3>& ids, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, std::int64_t inputPointCount,
  const TessellationOptions& options, Tessellation& out)
{
  Tessellator t(projector, ids, world, projected, cell, inputPointCount, options, out);
  return t.Run();
}
} // namespace catar
