// CatadioptricAR MeshPrep: making arbitrary triangle input safe for remeshing.
//
// The repair works on the indexed triangle list itself (a "polygon soup"), so that it can count
// exactly what it changes and keep point data with their points; CGAL is used only to cut
// non-orientable surfaces open (orient_polygon_soup). The steps, in order:
//   1. drop point attributes whose size does not match the points;
//   2. drop triangles with out-of-range or repeated indices and triangles using NaN/Inf points;
//   3. merge coincident points (within 1e-10 of the bounding box diagonal);
//   4. drop degenerate triangles: repeated points after merging, or collinear points; a collinear
//      "cap" that fills a T-junction is replaced by splitting its neighbour at the middle point,
//      so that closed surfaces stay closed;
//   5. drop duplicate triangles (same three points, either orientation);
//   6. make edges manifold: of more than two triangles on an edge keep the two best connected,
//      consistently oriented ones;
//   7. make vertices manifold: a pinched vertex gets one copy per fan of triangles;
//   8. orient consistently: outward on closed components (positive volume), on open components
//      the orientation most of their triangles had (non-orientable surfaces are cut open first);
//   9. drop points no triangle uses, and count boundary loops.
#include "MeshRepair.h"

#include "MeshConversion.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace catar
{
namespace mesh
{
namespace
{

using Triangle = std::array<int, 3>;

/// Points closer than this fraction of the bounding box diagonal are merged.
constexpr double kMergeTolerance = 1e-10;
/// A triangle is collinear when twice its area is below this fraction of its longest edge
/// squared (its height below that fraction of its longest edge).
constexpr double kCollinearTolerance = 1e-12;

/// "1 triangle", "3 triangles".
std::string Count(std::size_t n, const char* singular, const char* plural)
{
  std::ostringstream stream;
  stream << n << ' ' << (n == 1 ? singular : plural);
  return stream.str();
}

/// A key for the undirected edge {a, b}.
std::uint64_t EdgeKey(int a, int b)
{
  if (a > b)
  {
    std::swap(a, b);
  }
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
    static_cast<std::uint32_t>(b);
}

/// A key for the directed edge a -> b.
std::uint64_t DirectedKey(int a, int b)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
    static_cast<std::uint32_t>(b);
}

/// +1 when triangle t runs a -> b, -1 when it runs b -> a, 0 when it does not have that edge.
int EdgeDirection(const Triangle& t, int a, int b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (t[k] == a && t[(k + 1) % 3] == b)
    {
      return 1;
    }
    if (t[k] == b && t[(k + 1) % 3] == a)
    {
      return -1;
    }
  }
  return 0;
}

using EdgeMap = std::unordered_map<std::uint64_t, std::vector<int>>;

/// Undirected edge -> the triangles using it (indices into `triangles`; those with alive[i] ==
/// false are left out).
EdgeMap BuildEdgeMap(const std::vector<Triangle>& triangles, const std::vector<char>& alive)
{
  EdgeMap edges;
  edges.reserve(triangles.size() * 2);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    if (!alive[i])
    {
      continue;
    }
    const Triangle& t = triangles[i];
    for (int k = 0; k < 3; ++k)
    {
      edges[EdgeKey(t[k], t[(k + 1) % 3])].push_back(static_cast<int>(i));
    }
  }
  return edges;
}

/// Keeps the triangles with alive[i] set.
void Compact(std::vector<Triangle>& triangles, const std::vector<char>& alive)
{
  std::size_t k = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    if (alive[i])
    {
      triangles[k++] = triangles[i];
    }
  }
  triangles.resize(k);
}

/// A grid cell of the coincident-point search.
struct Cell
{
  std::int64_t x, y, z;
  bool operator==(const Cell& other) const
  {
    return this->x == other.x && this->y == other.y && this->z == other.z;
  }
};

struct CellHash
{
  std::size_t operator()(const Cell& c) const
  {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

/// Union-find over a small set of elements.
class UnionFind
{
public:
  explicit UnionFind(std::size_t n)
    : Parent(n)
  {
    std::iota(this->Parent.begin(), this->Parent.end(), 0);
  }
  int Find(int i)
  {
    while (this->Parent[i] != i)
    {
      this->Parent[i] = this->Parent[this->Parent[i]];
      i = this->Parent[i];
    }
    return i;
  }
  void Union(int a, int b)
  {
    a = this->Find(a);
    b = this->Find(b);
    // The smaller index becomes the root, so that roots are deterministic.
    if (a < b)
    {
      this->Parent[b] = a;
    }
    else if (b < a)
    {
      this->Parent[a] = b;
    }
  }

private:
  std::vector<int> Parent;
};

/// Runs the repair steps on one mesh; see the file comment for the order.
class Repairer
{
public:
  Repairer(TriangleMesh& mesh, RepairReport& report, Warnings& warnings)
    : Mesh(mesh)
    , Report(report)
    , Messages(warnings)
  {
  }

  bool Run(std::string& error);

private:
  void CheckPointData();
  void RemoveInvalidTriangles();
  void MergeCoincidentPoints();
  void RemoveDegenerateTriangles();
  void RemoveDuplicateTriangles();
  void MakeEdgesManifold();
  void MakeVerticesManifold();
  bool Orient();
  void CutNonOrientable();
  void RemoveUnusedPoints();
  void CountBoundaryLoops();

  /// Appends a copy of point `i` (position and data); returns its index.
  int DuplicatePoint(int i);

  TriangleMesh& Mesh;
  RepairReport& Report;
  Warnings& Messages;
  std::vector<Triangle> Triangles; ///< the working triangle list
  std::size_t InputPoints = 0;
  std::vector<char> Finite; ///< per input point: coordinates are finite
  std::vector<char> Merged; ///< per input point: merged into another point
};

bool Repairer::Run(std::string& error)
{
  this->Report = RepairReport();
  if (this->Mesh.triangles.empty())
  {
    error = "the mesh has no triangles";
    return false;
  }
  const std::size_t inputTriangles = this->Mesh.triangles.size();
  this->InputPoints = this->Mesh.points.size();
  this->Triangles = this->Mesh.triangles;

  this->CheckPointData();
  this->RemoveInvalidTriangles();
  this->MergeCoincidentPoints();
  this->RemoveDegenerateTriangles();
  this->RemoveDuplicateTriangles();
  this->MakeEdgesManifold();
  this->MakeVerticesManifold();
  if (!this->Orient())
  {
    this->CutNonOrientable();
    this->Orient();
  }
  this->RemoveUnusedPoints();
  this->CountBoundaryLoops();

  if (this->Mesh.triangles.empty())
  {
    error = "nothing is left after repair: all " + Count(inputTriangles, "triangle", "triangles") +
      " were invalid, degenerate or duplicates";
    return false;
  }
  return true;
}

void Repairer::CheckPointData()
{
  auto& data = this->Mesh.pointData;
  const std::size_t n = this->Mesh.points.size();
  for (auto it = data.begin(); it != data.end();)
  {
    if (it->components < 1 || it->values.size() != n * static_cast<std::size_t>(it->components))
    {
      std::ostringstream stream;
      stream << "point attribute '" << it->name << "' removed: it has " << it->values.size()
             << " values for " << n << " points of " << it->components << " components";
      this->Messages.push_back(stream.str());
      it = data.erase(it);
    }
    else
    {
      ++it;
    }
  }
}

void Repairer::RemoveInvalidTriangles()
{
  const int n = static_cast<int>(this->InputPoints);
  this->Finite.assign(this->InputPoints, 1);
  for (std::size_t i = 0; i < this->InputPoints; ++i)
  {
    if (!this->Mesh.points[i].allFinite())
    {
      this->Finite[i] = 0;
      ++this->Report.invalidPoints;
    }
  }

  std::size_t onInvalidPoints = 0;
  std::vector<char> alive(this->Triangles.size(), 1);
  for (std::size_t i = 0; i < this->Triangles.size(); ++i)
  {
    const Triangle& t = this->Triangles[i];
    const bool inRange = t[0] >= 0 && t[1] >= 0 && t[2] >= 0 && t[0] < n && t[1] < n && t[2] < n;
    if (!inRange || t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      ++this->Report.invalidTriangles;
      alive[i] = 0;
    }
    else if (!this->Finite[t[0]] || !this->Finite[t[1]] || !this->Finite[t[2]])
    {
      ++onInvalidPoints;
      alive[i] = 0;
    }
  }
  Compact(this->Triangles, alive);

  if (this->Report.invalidPoints > 0)
  {
    this->Messages.push_back(Count(this->Report.invalidPoints, "point", "points") +
      " with NaN or infinite coordinates removed, with the " +
      Count(onInvalidPoints, "triangle", "triangles") + " using them");
  }
  if (this->Report.invalidTriangles > 0)
  {
    this->Messages.push_back(Count(this->Report.invalidTriangles, "triangle", "triangles") +
      " with out-of-range or repeated point indices removed");
  }
}

void Repairer::MergeCoincidentPoints()
{
  const auto& points = this->Mesh.points;
  this->Merged.assign(this->InputPoints, 0);
  std::vector<char> used(this->InputPoints, 0);
  for (const Triangle& t : this->Triangles)
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }

  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < this->InputPoints; ++i)
  {
    if (used[i])
    {
      box.extend(points[i]);
    }
  }
  if (box.isEmpty())
  {
    return;
  }
  const double tolerance = kMergeTolerance * box.diagonal().norm();
  // Cells as large as the tolerance: a point within the tolerance of another lies in one of the
  // 27 cells around it. All points coincide when the tolerance is 0, any cell size does then.
  const double cellSize = tolerance > 0.0 ? tolerance : 1.0;
  const auto cellOf = [&](const Vec3& p) {
    const Vec3 q = (p - box.min()) / cellSize;
    return Cell{ static_cast<std::int64_t>(std::floor(q.x())),
      static_cast<std::int64_t>(std::floor(q.y())), static_cast<std::int64_t>(std::floor(q.z())) };
  };

  std::unordered_map<Cell, std::vector<int>, CellHash> grid;
  std::vector<int> representative(this->InputPoints);
  std::iota(representative.begin(), representative.end(), 0);
  for (std::size_t i = 0; i < this->InputPoints; ++i)
  {
    if (!used[i])
    {
      continue;
    }
    const Cell c = cellOf(points[i]);
    int found = -1;
    for (std::int64_t dx = -1; dx <= 1 && found < 0; ++dx)
    {
      for (std::int64_t dy = -1; dy <= 1 && found < 0; ++dy)
      {
        for (std::int64_t dz = -1; dz <= 1 && found < 0; ++dz)
        {
          const auto it = grid.find(Cell{ c.x + dx, c.y + dy, c.z + dz });
          if (it == grid.end())
          {
            continue;
          }
          for (int j : it->second)
          {
            if ((points[j] - points[i]).norm() <= tolerance)
            {
              found = j;
              break;
            }
          }
        }
      }
    }
    if (found >= 0)
    {
      representative[i] = found;
      this->Merged[i] = 1;
      ++this->Report.mergedPoints;
    }
    else
    {
      grid[c].push_back(static_cast<int>(i));
    }
  }

  if (this->Report.mergedPoints == 0)
  {
    return;
  }
  for (Triangle& t : this->Triangles)
  {
    for (int& v : t)
    {
      v = representative[v];
    }
  }
  this->Messages.push_back(
    Count(this->Report.mergedPoints, "coincident point", "coincident points") + " merged");
}

void Repairer::RemoveDegenerateTriangles()
{
  const auto& points = this->Mesh.points;
  const std::size_t count = this->Triangles.size();
  std::vector<char> alive(count, 1);
  // Collinear triangles with three distinct points, as (triangle, middle point corner).
  std::vector<std::pair<int, int>> caps;
  for (std::size_t i = 0; i < count; ++i)
  {
    const Triangle& t = this->Triangles[i];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      alive[i] = 0;
      continue;
    }
    const Vec3& p0 = points[t[0]];
    const Vec3& p1 = points[t[1]];
    const Vec3& p2 = points[t[2]];
    // Corner k is opposite edge k+1 -> k+2.
    const double opposite[3] = { (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm(),
      (p1 - p0).squaredNorm() };
    const int longest = static_cast<int>(std::max_element(opposite, opposite + 3) - opposite);
    if ((p1 - p0).cross(p2 - p0).norm() <= kCollinearTolerance * opposite[longest])
    {
      alive[i] = 0;
      caps.emplace_back(static_cast<int>(i), longest);
    }
  }

  // A cap (a, b, c) with c between a and b often fills a T-junction: the triangle across a-b
  // does not use c while a-c and c-b each have one triangle. Splitting that neighbour at c keeps
  // the surface closed once the cap is gone.
  std::size_t splits = 0;
  if (!caps.empty())
  {
    EdgeMap edges = BuildEdgeMap(this->Triangles, alive);
    const auto single = [&](int a, int b) {
      const auto it = edges.find(EdgeKey(a, b));
      return it != edges.end() && it->second.size() == 1;
    };
    const auto replace = [&](int a, int b, int from, int to) {
      auto& list = edges[EdgeKey(a, b)];
      std::replace(list.begin(), list.end(), from, to);
    };
    for (const auto& cap : caps)
    {
      const Triangle& t = this->Triangles[cap.first];
      const int c = t[cap.second];
      const int a = t[(cap.second + 1) % 3];
      const int b = t[(cap.second + 2) % 3];
      if (!single(a, b) || !single(a, c) || !single(c, b))
      {
        continue;
      }
      const int n = edges[EdgeKey(a, b)].front();
      const Triangle neighbour = this->Triangles[n];
      if (neighbour[0] == c || neighbour[1] == c || neighbour[2] == c)
      {
        continue;
      }
      int k = 0;
      while (EdgeKey(neighbour[k], neighbour[(k + 1) % 3]) != EdgeKey(a, b))
      {
        ++k;
      }
      const int x = neighbour[k];
      const int y = neighbour[(k + 1) % 3];
      const int z = neighbour[(k + 2) % 3];
      // (x, y, z) becomes (x, c, z) (same index) and (c, y, z) (appended).
      const int added = static_cast<int>(this->Triangles.size());
      this->Triangles[n] = Triangle{ { x, c, z } };
      this->Triangles.push_back(Triangle{ { c, y, z } });
      alive.push_back(1);
      edges.erase(EdgeKey(a, b));
      edges[EdgeKey(x, c)].push_back(n);
      edges[EdgeKey(c, y)].push_back(added);
      replace(y, z, n, added);
      edges[EdgeKey(c, z)].push_back(n);
      edges[EdgeKey(c, z)].push_back(added);
      ++splits;
    }
  }

  this->Report.degenerateTriangles =
    count - static_cast<std::size_t>(std::count(alive.begin(), alive.begin() + count, char(1)));
  Compact(this->Triangles, alive);
  if (this->Report.degenerateTriangles > 0)
  {
    std::string message = Count(this->Report.degenerateTriangles, "degenerate (zero-area) triangle",
                            "degenerate (zero-area) triangles") +
      " removed";
    if (splits > 0)
    {
      message += "; " + Count(splits, "neighbouring triangle", "neighbouring triangles") +
        " split at the collinear point to keep the surface closed";
    }
    this->Messages.push_back(message);
  }
}

void Repairer::RemoveDuplicateTriangles()
{
  std::set<Triangle> seen;
  std::vector<char> alive(this->Triangles.size(), 1);
  for (std::size_t i = 0; i < this->Triangles.size(); ++i)
  {
    Triangle key = this->Triangles[i];
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second)
    {
      alive[i] = 0;
      ++this->Report.duplicateTriangles;
    }
  }
  Compact(this->Triangles, alive);
  if (this->Report.duplicateTriangles > 0)
  {
    this->Messages.push_back(
      Count(this->Report.duplicateTriangles, "duplicate triangle", "duplicate triangles") +
      " removed (same three points as another triangle)");
  }
}

void Repairer::MakeEdgesManifold()
{
  std::vector<char> alive(this->Triangles.size(), 1);
  const EdgeMap edges = BuildEdgeMap(this->Triangles, alive);
  std::vector<std::uint64_t> complex;
  for (const auto& entry : edges)
  {
    if (entry.second.size() > 2)
    {
      complex.push_back(entry.first);
    }
  }
  if (complex.empty())
  {
    return;
  }
  std::sort(complex.begin(), complex.end());
  this->Report.nonManifoldEdges = complex.size();

  // How well a triangle is connected: the number of its edges shared with another triangle. A
  // fin or a stray triangle on a surface edge scores lower than the surface's own triangles.
  const auto connectivity = [&](int i) {
    const Triangle& t = this->Triangles[i];
    int shared = 0;
    for (int k = 0; k < 3; ++k)
    {
      shared += edges.at(EdgeKey(t[k], t[(k + 1) % 3])).size() > 1 ? 1 : 0;
    }
    return shared;
  };

  std::size_t removed = 0;
  for (const std::uint64_t key : complex)
  {
    std::vector<int> candidates;
    for (int i : edges.at(key))
    {
      if (alive[i])
      {
        candidates.push_back(i);
      }
    }
    if (candidates.size() <= 2)
    {
      continue;
    }
    std::stable_sort(candidates.begin(), candidates.end(),
      [&](int a, int b) { return connectivity(a) > connectivity(b); });
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    // Keep the best connected triangle and the best one that runs the edge the other way.
    const int first = candidates.front();
    const int direction = EdgeDirection(this->Triangles[first], a, b);
    int second = candidates[1];
    for (std::size_t k = 1; k < candidates.size(); ++k)
    {
      if (EdgeDirection(this->Triangles[candidates[k]], a, b) == -direction)
      {
        second = candidates[k];
        break;
      }
    }
    for (int i : candidates)
    {
      if (i != first && i != second)
      {
        alive[i] = 0;
        ++removed;
      }
    }
  }
  Compact(this->Triangles, alive);
  this->Messages.push_back(
    Count(this->Report.nonManifoldEdges, "non-manifold edge", "non-manifold edges") +
    " (more than two triangles) made manifold: " + Count(removed, "triangle", "triangles") +
    " removed");
}

int Repairer::DuplicatePoint(int i)
{
  const int added = static_cast<int>(this->Mesh.points.size());
  const Vec3 p = this->Mesh.points[i];
  this->Mesh.points.push_back(p);
  for (PointAttribute& attribute : this->Mesh.pointData)
  {
    const std::size_t c = static_cast<std::size_t>(attribute.components);
    for (std::size_t k = 0; k < c; ++k)
    {
      attribute.values.push_back(attribute.values[i * c + k]);
    }
  }
  return added;
}

void Repairer::MakeVerticesManifold()
{
  // Triangles around each point (compressed rows).
  const std::size_t n = this->Mesh.points.size();
  std::vector<int> offsets(n + 1, 0);
  for (const Triangle& t : this->Triangles)
  {
    for (int v : t)
    {
      ++offsets[v + 1];
    }
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<int> around(offsets.back());
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t i = 0; i < this->Triangles.size(); ++i)
  {
    for (int v : this->Triangles[i])
    {
      around[fill[v]++] = static_cast<int>(i);
    }
  }

  std::size_t duplicated = 0;
  for (std::size_t v = 0; v < n; ++v)
  {
    const int begin = offsets[v];
    const int size = offsets[v + 1] - begin;
    if (size < 2)
    {
      continue;
    }
    // Triangles around v sharing an edge v-w belong to the same fan. Edges are manifold now, so
    // at most two triangles share one.
    UnionFind fans(static_cast<std::size_t>(size));
    std::unordered_map<int, int> firstWithNeighbour;
    for (int j = 0; j < size; ++j)
    {
      for (int w : this->Triangles[around[begin + j]])
      {
        if (w == static_cast<int>(v))
        {
          continue;
        }
        const auto inserted = firstWithNeighbour.emplace(w, j);
        if (!inserted.second)
        {
          fans.Union(j, inserted.first->second);
        }
      }
    }
    // The fan of the first triangle keeps the point; every other fan gets a copy.
    std::map<int, int> copyOfFan;
    for (int j = 0; j < size; ++j)
    {
      const int fan = fans.Find(j);
      if (fan == 0)
      {
        continue;
      }
      auto it = copyOfFan.find(fan);
      if (it == copyOfFan.end())
      {
        it = copyOfFan.emplace(fan, this->DuplicatePoint(static_cast<int>(v))).first;
        ++duplicated;
      }
      for (int& w : this->Triangles[around[begin + j]])
      {
        if (w == static_cast<int>(v))
        {
          w = it->second;
        }
      }
    }
    if (!copyOfFan.empty())
    {
      ++this->Report.nonManifoldVertices;
    }
  }
  if (this->Report.nonManifoldVertices > 0)
  {
    this->Messages.push_back(Count(this->Report.nonManifoldVertices,
                               "non-manifold (pinched) vertex", "non-manifold (pinched) vertices") +
      " made manifold: " + Count(duplicated, "point", "points") + " duplicated");
  }
}

bool Repairer::Orient()
{
  const auto& points = this->Mesh.points;
  const std::size_t count = this->Triangles.size();
  const std::vector<char> all(count, 1);
  const EdgeMap edges = BuildEdgeMap(this->Triangles, all);

  // flip[i]: triangle i must be reversed. Each connected component is walked from its first
  // triangle; a neighbour must run the shared edge the other way.
  std::vector<char> flip(count, 0);
  std::vector<char> visited(count, 0);
  std::vector<int> component;
  const auto oriented = [&](int i) {
    Triangle t = this->Triangles[i];
    if (flip[i])
    {
      std::swap(t[1], t[2]);
    }
    return t;
  };
  for (std::size_t seed = 0; seed < count; ++seed)
  {
    if (visited[seed])
    {
      continue;
    }
    component.assign(1, static_cast<int>(seed));
    visited[seed] = 1;
    bool closed = true;
    for (std::size_t next = 0; next < component.size(); ++next)
    {
      const int f = component[next];
      const Triangle t = oriented(f);
      for (int k = 0; k < 3; ++k)
      {
        const int a = t[k];
        const int b = t[(k + 1) % 3];
        const std::vector<int>& shared = edges.at(EdgeKey(a, b));
        if (shared.size() < 2)
        {
          closed = false;
          continue;
        }
        const int g = shared[0] == f ? shared[1] : shared[0];
        if (visited[g])
        {
          if (EdgeDirection(oriented(g), a, b) != -1)
          {
            return false; // not orientable
          }
          continue;
        }
        flip[g] = EdgeDirection(this->Triangles[g], a, b) == 1 ? 1 : 0;
        visited[g] = 1;
        component.push_back(g);
      }
    }

    // Closed components point outward (positive enclosed volume, computed about the centroid
    // for accuracy); open ones keep the orientation most of their triangles had.
    bool reverse;
    if (closed)
    {
      Vec3 centroid = Vec3::Zero();
      for (int f : component)
      {
        for (int v : this->Triangles[f])
        {
          centroid += points[v];
        }
      }
      centroid /= 3.0 * static_cast<double>(component.size());
      double volume = 0.0;
      for (int f : component)
      {
        const Triangle t = oriented(f);
        volume +=
          (points[t[0]] - centroid).dot((points[t[1]] - centroid).cross(points[t[2]] - centroid));
      }
      reverse = volume < 0.0;
    }
    else
    {
      const std::size_t flipped = static_cast<std::size_t>(
        std::count_if(component.begin(), component.end(), [&](int f) { return flip[f] != 0; }));
      reverse = 2 * flipped > component.size();
    }
    if (reverse)
    {
      for (int f : component)
      {
        flip[f] = !flip[f];
      }
    }
  }

  std::size_t flipped = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (flip[i])
    {
      std::swap(this->Triangles[i][1], this->Triangles[i][2]);
      ++flipped;
    }
  }
  if (flipped > 0)
  {
    this->Report.reoriented = true;
    this->Messages.push_back(Count(flipped, "triangle", "triangles") +
      " flipped for a consistent orientation (outward on closed surfaces)");
  }
  return true;
}

void Repairer::CutNonOrientable()
{
  // CGAL duplicates points along a cut that makes every component orientable.
  std::vector<detail::Point3> soupPoints;
  soupPoints.reserve(this->Mesh.points.size());
  for (const Vec3& p : this->Mesh.points)
  {
    soupPoints.push_back(detail::ToPoint3(p));
  }
  std::vector<std::vector<std::size_t>> soup;
  soup.reserve(this->Triangles.size());
  for (const Triangle& t : this->Triangles)
  {
    soup.push_back({ static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
      static_cast<std::size_t>(t[2]) });
  }
  const std::size_t before = soupPoints.size();
  CGAL::Polygon_mesh_processing::orient_polygon_soup(soupPoints, soup);

  // The new points are copies of existing ones; coincident points were merged, so a position
  // names its original point, whose data the copy takes.
  std::map<std::array<double, 3>, int> byPosition;
  for (std::size_t i = 0; i < before; ++i)
  {
    const Vec3& p = this->Mesh.points[i];
    byPosition.emplace(std::array<double, 3>{ { p.x(), p.y(), p.z() } }, static_cast<int>(i));
  }
  std::vector<int> index(soupPoints.size());
  std::iota(index.begin(), index.begin() + before, 0);
  for (std::size_t i = before; i < soupPoints.size(); ++i)
  {
    const detail::Point3& p = soupPoints[i];
    index[i] = this->DuplicatePoint(byPosition.at({ { p.x(), p.y(), p.z() } }));
  }
  this->Triangles.resize(soup.size());
  for (std::size_t i = 0; i < soup.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      this->Triangles[i][k] = index[soup[i][k]];
    }
  }
  this->Messages.push_back(
    "the surface is not orientable (like a Moebius strip): cut open by duplicating " +
    Count(soupPoints.size() - before, "point", "points"));
}

void Repairer::RemoveUnusedPoints()
{
  const std::size_t n = this->Mesh.points.size();
  std::vector<int> index(n, -1);
  for (const Triangle& t : this->Triangles)
  {
    for (int v : t)
    {
      index[v] = 0;
    }
  }
  int kept = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (index[i] == 0)
    {
      index[i] = kept++;
    }
    else if (i < this->InputPoints && this->Finite[i] && !this->Merged[i])
    {
      ++this->Report.unusedPoints;
    }
  }

  for (std::size_t i = 0; i < n; ++i)
  {
    if (index[i] >= 0)
    {
      this->Mesh.points[index[i]] = this->Mesh.points[i];
    }
  }
  this->Mesh.points.resize(static_cast<std::size_t>(kept));
  for (PointAttribute& attribute : this->Mesh.pointData)
  {
    const std::size_t c = static_cast<std::size_t>(attribute.components);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (index[i] >= 0)
      {
        std::copy_n(attribute.values.begin() + i * c, c,
          attribute.values.begin() + static_cast<std::size_t>(index[i]) * c);
      }
    }
    attribute.values.resize(static_cast<std::size_t>(kept) * c);
  }
  for (Triangle& t : this->Triangles)
  {
    for (int& v : t)
    {
      v = index[v];
    }
  }
  this->Mesh.triangles = this->Triangles;

  if (this->Report.unusedPoints > 0)
  {
    this->Messages.push_back(
      Count(this->Report.unusedPoints, "unused point", "unused points") + " removed");
  }
}

void Repairer::CountBoundaryLoops()
{
  // Boundary half-edges are those whose reverse no triangle has; on an oriented manifold they
  // form closed loops, followed here from each half-edge's end point.
  std::unordered_set<std::uint64_t> directed;
  directed.reserve(3 * this->Mesh.triangles.size());
  for (const Triangle& t : this->Mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      directed.insert(DirectedKey(t[k], t[(k + 1) % 3]));
    }
  }
  std::unordered_multimap<int, int> outgoing; // boundary half-edge start -> end
  for (const Triangle& t : this->Mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      if (directed.count(DirectedKey(b, a)) == 0)
      {
        outgoing.emplace(a, b);
      }
    }
  }
  while (!outgoing.empty())
  {
    ++this->Report.boundaryLoops;
    auto it = outgoing.begin();
    while (it != outgoing.end())
    {
      const int next = it->second;
      outgoing.erase(it);
      it = outgoing.find(next);
    }
  }
  if (this->Report.boundaryLoops > 0)
  {
    this->Messages.push_back(Count(this->Report.boundaryLoops, "boundary loop", "boundary loops") +
      " (holes or open borders) kept: the surface is not closed");
  }
}

} // namespace

bool RepairMesh(TriangleMesh& mesh, RepairReport& report, Warnings& warnings, std::string& error)
{
  error.clear();
  try
  {
    Repairer repairer(mesh, report, warnings);
    return repairer.Run(error);
  }
  catch (const std::exception& e)
  {
    error = std::string("mesh repair failed: ") + e.what();
  }
  catch (...)
  {
    error = "mesh repair failed with an unknown exception";
  }
  return false;
}

} // namespace mesh
} // namespace catar
