#include "ImageTessellation.h"

#include "EdgeBend.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
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

// Whether the edge between seen points a and b is measured at its midpoint: for its bend
// (adaptive), or, when its image is longer than options.interiorCheck pixels, for a hidden middle.
bool Measured(const ProjectedPoint& a, const ProjectedPoint& b, const TessellationOptions& options)
{
  return options.bendTolerance > 0.0 ||
    (options.boundaryTolerance > 0.0 && (a.pixel - b.pixel).norm() > options.interiorCheck);
}

// Whether that edge is split at its midpoint `mid`: it bends more than the bend tolerance, or its
// middle is hidden (the visibility boundary crosses it between two seen ends). The edge's own
// decision, the same in the triangles on either side.
bool NeedsSplit(const ProjectedPoint& a, const ProjectedPoint& b, const ProjectedPoint& mid,
  const TessellationOptions& options)
{
  if (!Seen(mid))
  {
    return options.boundaryTolerance > 0.0;
  }
  return options.bendTolerance > 0.0 && Bend(a, b, mid) > options.bendTolerance;
}

// One input triangle's tessellation: nodes (points given by barycentric weights), the midpoints
// made so far (shared by the pieces on either side of an edge), the pieces.
class Tessellator
{
public:
  Tessellator(const Projector& projector, const std::array<std::int64_t, 3>& ids,
    const std::array<Vec3, 3>& world, const std::array<ProjectedPoint, 3>& projected,
    std::int64_t cell, std::int64_t inputPointCount, const TessellationOptions& options,
    Tessellation& out, const TriangleEdgeSplits* forced, TriangleEdgeSplits* made)
    : Proj(projector)
    , World(world)
    , Cell(cell)
    , InputPoints(inputPointCount)
    , Options(options)
    , Out(out)
    , ForcedSplits(forced)
    , MadeSplits(made)
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

  // Tessellates, again with the edges a piece split forced on the pieces across them, until no
  // piece splits an edge its neighbour does not (a T-junction, whose crack would show).
  std::size_t Run()
  {
    const std::size_t triangles = this->Out.triangles.size(), points = this->Out.points.size();
    for (int pass = 0; pass < 8; ++pass)
    {
      this->Out.triangles.resize(triangles);
      this->Out.points.resize(points);
      this->Nodes.resize(3);
      this->Midpoints.clear();
      this->Boundaries.clear();
      this->Pieces = 0;
      if (this->MadeSplits)
      {
        *this->MadeSplits = TriangleEdgeSplits();
      }
      this->Refine(0, 1, 2, 0);
      if (this->Fresh.empty())
      {
        break;
      }
      this->Known.insert(this->Fresh.begin(), this->Fresh.end());
      this->Fresh.clear();
    }
    return this->Out.triangles.size() - triangles;
  }

private:
  struct Node
  {
    Vec3 weights;
    Vec3 world;
    ProjectedPoint projected;
    std::int64_t id = -1;  // the output id, once a piece uses it
    bool boundary = false; // found on the visibility boundary by bisection
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
      p.boundary = node.boundary;
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
    return this->Bisect(
      this->Nodes[good].weights, this->Nodes[good].projected, this->Nodes[bad].weights);
  }

  // The boundary point between the seen point at weights `good` (projection `seen`) and the
  // unseen one at `bad`, by bisection until a step moves its image by less than a quarter of the
  // tolerance: a new node.
  int Bisect(const Vec3& good, ProjectedPoint seen, const Vec3& bad)
  {
    Vec3 lo = good, hi = bad;
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
    n.boundary = true;
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

  // The input triangle's edge k that nodes p and q both lie on, with their parameters from
  // corner k; -1 when they are not on one edge.
  int EdgeOf(int p, int q, double& tp, double& tq) const
  {
    const Vec3 &wp = this->Nodes[p].weights, &wq = this->Nodes[q].weights;
    for (int k = 0; k < 3; ++k)
    {
      const int off = (k + 2) % 3;
      if (wp[off] == 0.0 && wq[off] == 0.0)
      {
        tp = wp[(k + 1) % 3];
        tq = wq[(k + 1) % 3];
        return k;
      }
    }
    return -1;
  }

  // An edge between two nodes, by their weights (the smaller first).
  using EdgeWeights = std::pair<std::array<double, 3>, std::array<double, 3>>;
  EdgeWeights KeyOf(int p, int q) const
  {
    const Vec3 &a = this->Nodes[p].weights, &b = this->Nodes[q].weights;
    const std::array<double, 3> wa{ { a[0], a[1], a[2] } }, wb{ { b[0], b[1], b[2] } };
    return wa < wb ? EdgeWeights(wa, wb) : EdgeWeights(wb, wa);
  }

  // Whether the piece edge (p, q) must be split: a piece across it split it in an earlier pass,
  // or it lies on an input edge that a neighbouring triangle splits at its midpoint.
  bool Forced(int p, int q) const
  {
    if (this->Known.count(this->KeyOf(p, q)))
    {
      return true;
    }
    double tp = 0, tq = 0;
    const int k = this->ForcedSplits ? this->EdgeOf(p, q, tp, tq) : -1;
    if (k < 0)
    {
      return false;
    }
    const std::vector<double>& at = this->ForcedSplits->at[k];
    return std::binary_search(at.begin(), at.end(), 0.5 * (tp + tq));
  }

  void Record(int p, int q)
  {
    double tp = 0, tq = 0;
    const int k = this->MadeSplits ? this->EdgeOf(p, q, tp, tq) : -1;
    if (k >= 0)
    {
      this->MadeSplits->at[k].push_back(0.5 * (tp + tq));
    }
  }

  // Splits exactly the edges of piece (a, b, c) marked in `split` at their midpoints (one edge:
  // two pieces; two: three; three: four) and refines the pieces. An edge's split is the edge's
  // own decision (it bends too much, or a neighbour splits it), or made for the whole piece and
  // passed on to the neighbours (TriangleEdgeSplits), so the piece across an edge splits it at
  // the same point and the pieces meet without cracks.
  void SplitEdges(int a, int b, int c, const bool split[3], int depth)
  {
    const int corner[3] = { a, b, c };
    int count = 0;
    for (int i = 0; i < 3; ++i)
    {
      if (split[i])
      {
        this->Record(corner[i], corner[(i + 1) % 3]);
        const EdgeWeights key = this->KeyOf(corner[i], corner[(i + 1) % 3]);
        if (!this->Known.count(key))
        {
          this->Fresh.insert(key);
        }
        ++count;
      }
    }
    if (count == 3)
    {
      const int ab = this->Midpoint(a, b), bc = this->Midpoint(b, c), ca = this->Midpoint(c, a);
      this->Refine(a, ab, ca, depth + 1);
      this->Refine(ab, b, bc, depth + 1);
      this->Refine(ca, bc, c, depth + 1);
      this->Refine(ab, bc, ca, depth + 1);
      return;
    }
    // Turned so that edge (p, q) is split and, with two split edges, (q, r) too; (r, p) is not.
    int k = 0;
    while (!(split[k] && !split[(k + 2) % 3]))
    {
      ++k;
    }
    const int p = corner[k], q = corner[(k + 1) % 3], r = corner[(k + 2) % 3];
    const int pq = this->Midpoint(p, q);
    if (count == 1)
    {
      this->Refine(p, pq, r, depth + 1);
      this->Refine(pq, q, r, depth + 1);
      return;
    }
    const int qr = this->Midpoint(q, r);
    this->Refine(pq, q, qr, depth + 1);
    // The quadrilateral p, pq, qr, r cut along its shorter diagonal in the image (any one where a
    // corner is not seen).
    const bool seen = this->IsSeen(p) && this->IsSeen(qr) && this->IsSeen(pq) && this->IsSeen(r);
    if (!seen ||
      (this->Pixel(p) - this->Pixel(qr)).squaredNorm() <=
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
  }

  // Whether the seen part of edge (s seen, u not), from s to its boundary point, bends more than
  // the bend tolerance (its midpoint's image from the straight segment). The edge's own decision.
  bool SeenPartBends(int s, int u)
  {
    if (!(this->Options.bendTolerance > 0.0))
    {
      return false;
    }
    const int boundary = this->Boundary(s, u);
    const Node &ns = this->Nodes[s], &nb = this->Nodes[boundary];
    if ((ns.projected.pixel - nb.projected.pixel).norm() <= this->Options.boundaryTolerance)
    {
      return false;
    }
    const Vec3 w = 0.5 * (ns.weights + nb.weights);
    const Vec3 guess = 0.5 * (ns.projected.mirrorPoint + nb.projected.mirrorPoint);
    const ProjectedPoint a = ns.projected, b = nb.projected;
    const ProjectedPoint mid = this->Proj.ProjectWorldNear(
      w[0] * this->World[0] + w[1] * this->World[1] + w[2] * this->World[2], guess);
    return !Seen(mid) || Bend(a, b, mid) > this->Options.bendTolerance;
  }

  // Whether the cut of a piece across the boundary -- the segment between the boundary points on
  // its two edges across it -- is more than the boundary tolerance from the boundary point found
  // halfway along it (by bisection from the cut towards the unseen side, or from the seen side
  // towards the cut where that is hidden).
  bool CutStraysFromTheBoundary(int a, int b, int c)
  {
    const int corner[3] = { a, b, c };
    int ends[2], n = 0;
    Vec3 seenSide = Vec3::Zero(), unseenSide = Vec3::Zero();
    int seen = 0;
    for (int i = 0; i < 3; ++i)
    {
      const int p = corner[i], q = corner[(i + 1) % 3];
      if (this->IsSeen(p) != this->IsSeen(q) && n < 2)
      {
        ends[n++] = this->IsSeen(p) ? this->Boundary(p, q) : this->Boundary(q, p);
      }
      if (this->IsSeen(p))
      {
        seenSide += this->Nodes[p].weights;
        ++seen;
      }
      else
      {
        unseenSide += this->Nodes[p].weights;
      }
    }
    if (n < 2 || seen == 0 || seen == 3)
    {
      return false;
    }
    seenSide /= seen;
    unseenSide /= 3 - seen;
    const Node &e0 = this->Nodes[ends[0]], &e1 = this->Nodes[ends[1]];
    const Vec2 p0 = e0.projected.pixel, p1 = e1.projected.pixel;
    if ((p0 - p1).norm() <= this->Options.boundaryTolerance)
    {
      return false;
    }
    // The boundary halfway along the cut (a quarter and three quarters more found nothing the
    // half missed in the tests' placements, at a third more time).
    const Vec3 w0 = e0.weights, w1 = e1.weights;
    const Vec3 m0 = e0.projected.mirrorPoint, m1 = e1.projected.mirrorPoint;
    for (const double f : { 0.5 })
    {
      const Vec3 middle = (1.0 - f) * w0 + f * w1;
      const Vec3 guess = (1.0 - f) * m0 + f * m1;
      const ProjectedPoint m = this->Proj.ProjectWorldNear(
        middle[0] * this->World[0] + middle[1] * this->World[1] + middle[2] * this->World[2],
        guess);
      int found;
      if (Seen(m))
      {
        found = this->Bisect(middle, m, unseenSide);
      }
      else
      {
        const ProjectedPoint start = this->Proj.ProjectWorldNear(seenSide[0] * this->World[0] +
            seenSide[1] * this->World[1] + seenSide[2] * this->World[2],
          guess);
        if (!Seen(start))
        {
          return true; // the seen side's middle is hidden too: split
        }
        found = this->Bisect(seenSide, start, middle);
      }
      if (DistanceToSegment(this->Nodes[found].projected.pixel, p0, p1) >
        this->Options.boundaryTolerance)
      {
        return true;
      }
    }
    return false;
  }

  void Refine(int a, int b, int c, int depth)
  {
    const int corner[3] = { a, b, c };
    const int seen = int(this->IsSeen(a)) + int(this->IsSeen(b)) + int(this->IsSeen(c));
    const bool deeper = depth < this->Options.maxDepth &&
      this->Pieces + 4 <= static_cast<std::size_t>(this->Options.maxPiecesPerTriangle);
    bool split[3] = { false, false, false };
    bool any = false;
    if (seen > 0)
    {
      // The splits the neighbours made on the input triangle's edges, whatever the depth.
      for (int i = 0; i < 3; ++i)
      {
        split[i] = this->Forced(corner[i], corner[(i + 1) % 3]);
        any = any || split[i];
      }
    }
    if (seen == 3)
    {
      // The edges that bend too much (adaptive) or whose middle is hidden.
      for (int i = 0; i < 3 && deeper; ++i)
      {
        // Copies: Midpoint may add nodes (and move them).
        const ProjectedPoint p = this->Nodes[corner[i]].projected;
        const ProjectedPoint q = this->Nodes[corner[(i + 1) % 3]].projected;
        if (split[i] || !Measured(p, q, this->Options))
        {
          continue;
        }
        const int m = this->Midpoint(corner[i], corner[(i + 1) % 3]);
        if (NeedsSplit(p, q, this->Nodes[m].projected, this->Options))
        {
          split[i] = any = true;
        }
      }
      if (any)
      {
        this->SplitEdges(a, b, c, split, depth);
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
        const bool all[3] = { true, true, true };
        this->SplitEdges(a, b, c, all, depth);
      }
      return;
    }
    if (!(this->Options.boundaryTolerance > 0.0))
    {
      return; // crossing pieces dropped
    }
    // Across the boundary. Each edge's own decisions first: a seen edge (or the seen part of an
    // edge across the boundary, up to its boundary point) that bends too much.
    for (int i = 0; i < 3 && deeper; ++i)
    {
      const int p = corner[i], q = corner[(i + 1) % 3];
      if (split[i] || (!this->IsSeen(p) && !this->IsSeen(q)))
      {
        continue;
      }
      const ProjectedPoint pp = this->Nodes[p].projected, pq = this->Nodes[q].projected;
      if (this->IsSeen(p) && this->IsSeen(q))
      {
        if (Measured(pp, pq, this->Options))
        {
          const int m = this->Midpoint(p, q);
          split[i] = NeedsSplit(pp, pq, this->Nodes[m].projected, this->Options);
        }
      }
      else
      {
        const int s = this->IsSeen(p) ? p : q, u = this->IsSeen(p) ? q : p;
        split[i] = this->SeenPartBends(s, u);
      }
      any = any || split[i];
    }
    if (any)
    {
      this->SplitEdges(a, b, c, split, depth);
      return;
    }
    // Then the piece's: its cut (the straight segment between the boundary points on its two
    // edges across the boundary) must be within the tolerance of the boundary between them.
    if (deeper && this->CutStraysFromTheBoundary(a, b, c))
    {
      const bool all[3] = { true, true, true };
      this->SplitEdges(a, b, c, all, depth);
      return;
    }
    const std::vector<int> polygon = this->Clipped(a, b, c);
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
    {
      this->Emit(polygon[0], polygon[i], polygon[i + 1]);
    }
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
  const TriangleEdgeSplits* ForcedSplits;
  TriangleEdgeSplits* MadeSplits;
  std::set<EdgeWeights> Known; // edges split by a piece in an earlier pass
  std::set<EdgeWeights> Fresh; // edges split in this pass and not known before
};
} // namespace

namespace
{
// The fate of a triangle not seen at every corner (or with a corner that is not a point).
TriangleFate FateNotSeenWhole(const Projector& projector, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, const TessellationOptions& options)
{
  for (int i = 0; i < 3; ++i)
  {
    if (projected[i].status == ProjectionStatus::InvalidInput || !world[i].allFinite())
    {
      return TriangleFate::Drop; // a corner that is not a point (NaN, Inf)
    }
  }
  if (!(options.boundaryTolerance > 0.0))
  {
    return TriangleFate::Drop;
  }
  if (Seen(projected[0]) || Seen(projected[1]) || Seen(projected[2]))
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
} // namespace

TriangleFate TriangleFateOf(const Projector& projector, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, const TessellationOptions& options)
{
  TriangleFate fate;
  TriangleFates(projector, 1, &world, &projected, options, &fate);
  return fate;
}

void TriangleFates(const Projector& projector, std::size_t n, const std::array<Vec3, 3>* world,
  const std::array<ProjectedPoint, 3>* projected, const TessellationOptions& options,
  TriangleFate* out)
{
  // The triangles seen at their corners: their measured edges' midpoints (each from its ends'
  // reflection points), all together, side by side.
  std::vector<int> edges; // per midpoint: triangle * 3 + edge
  std::vector<Vec3> mids, guesses;
  for (std::size_t t = 0; t < n; ++t)
  {
    bool seen = true;
    for (int i = 0; i < 3 && seen; ++i)
    {
      seen = Seen(projected[t][i]) && world[t][i].allFinite();
    }
    if (!seen)
    {
      out[t] = FateNotSeenWhole(projector, world[t], projected[t], options);
      continue;
    }
    out[t] = TriangleFate::Keep;
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      if (Measured(projected[t][i], projected[t][j], options))
      {
        edges.push_back(static_cast<int>(3 * t + i));
        mids.push_back(0.5 * (world[t][i] + world[t][j]));
        guesses.push_back(0.5 * (projected[t][i].mirrorPoint + projected[t][j].mirrorPoint));
      }
    }
  }
  std::vector<ProjectedPoint> mid(mids.size());
  projector.ProjectWorldNear(mids.size(), mids.data(), guesses.data(), mid.data());
  for (std::size_t k = 0; k < mid.size(); ++k)
  {
    const std::size_t t = static_cast<std::size_t>(edges[k]) / 3;
    const int i = edges[k] % 3;
    if (NeedsSplit(projected[t][i], projected[t][(i + 1) % 3], mid[k], options))
    {
      out[t] = TriangleFate::Tessellate;
    }
  }
}

std::size_t TessellateTriangle(const Projector& projector, std::int64_t cell,
  const std::array<std::int64_t, 3>& ids, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, std::int64_t inputPointCount,
  const TessellationOptions& options, Tessellation& out, const TriangleEdgeSplits* forced,
  TriangleEdgeSplits* made)
{
  // A triangle cut at the boundary (or split by its neighbours) has its seen pieces drawn within
  // the boundary tolerance too when there is no bend tolerance: their straight edges are part of
  // the boundary drawn.
  TessellationOptions pieces = options;
  if (!(pieces.bendTolerance > 0.0))
  {
    pieces.bendTolerance = options.boundaryTolerance;
  }
  Tessellator t(projector, ids, world, projected, cell, inputPointCount, pieces, out, forced, made);
  return t.Run();
}
} // namespace catar
