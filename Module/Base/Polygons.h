// CatadioptricAR Core: the rules every stage applies to a mesh's polygons, once each: Newell's
// normal, a polygon's triangles (a fan) and a strip's (alternating), and cell values averaged at
// the points.
#ifndef catarPolygons_h
#define catarPolygons_h

#include "Types.h"

#include <Eigen/Geometry> // cross products

#include <algorithm>
#include <cstddef>
#include <vector>

namespace catar
{
/// Newell's normal of a polygon, accumulated one point at a time: after Start(last point) and
/// Add(p0), ..., Add(p_{n-1}) in order, Sum() = sum of p_{k-1} x p_k (k = 0..n-1, p_{-1} the last
/// point), whose length is twice the polygon's area and whose direction follows the points'
/// order (counter-clockwise seen from the front).
class NewellNormal
{
public:
  explicit NewellNormal(const Vec3& lastPoint)
    : Last(lastPoint)
  {
  }
  void Add(const Vec3& p)
  {
    this->Total += this->Last.cross(p);
    this->Last = p;
  }
  const Vec3& Sum() const { return this->Total; }

private:
  Vec3 Total = Vec3::Zero();
  Vec3 Last;
};

/// Newell's normal (not normalised) of the polygon whose n points are pointAt(ids[0]), ...
template<typename Id, typename PointAt>
Vec3 PolygonNormal(const Id* ids, std::size_t n, PointAt&& pointAt)
{
  if (n == 0)
  {
    return Vec3::Zero();
  }
  NewellNormal normal(pointAt(ids[n - 1]));
  for (std::size_t k = 0; k < n; ++k)
  {
    normal.Add(pointAt(ids[k]));
  }
  return normal.Sum();
}

/// The triangles of a polygon of n points: the fan (ids[0], ids[k], ids[k+1]), k = 1..n-2, each
/// given to triangle(a, b, c).
template<typename Id, typename Triangle>
void PolygonTriangles(const Id* ids, std::size_t n, Triangle&& triangle)
{
  for (std::size_t k = 1; k + 1 < n; ++k)
  {
    triangle(ids[0], ids[k], ids[k + 1]);
  }
}

/// The triangles of a triangle strip of n points, each facing the way the first does:
/// (ids[k], ids[k+1], ids[k+2]) for even k, (ids[k+1], ids[k], ids[k+2]) for odd k.
template<typename Id, typename Triangle>
void StripTriangles(const Id* ids, std::size_t n, Triangle&& triangle)
{
  for (std::size_t k = 0; k + 2 < n; ++k)
  {
    if (k % 2 == 0)
    {
      triangle(ids[k], ids[k + 1], ids[k + 2]);
    }
    else
    {
      triangle(ids[k + 1], ids[k], ids[k + 2]);
    }
  }
}

/// Cell values averaged at the points: for each cell c of cellCount (its points given by
/// forEachCell(c, visit), which calls visit(pointId) for each), its `components` values
/// cellValue(c, v) are summed at its points; each point's sum is divided by the number of cells
/// that met it (points no cell meets get zeros). Returns pointCount x components values.
template<typename T, typename ForEachPoint, typename CellValue>
std::vector<T> AverageAtPoints(std::size_t pointCount, std::size_t cellCount, int components,
  ForEachPoint&& forEachPoint, CellValue&& cellValue)
{
  std::vector<T> sums(pointCount * static_cast<std::size_t>(components), T(0));
  std::vector<int> count(pointCount, 0);
  std::vector<T> v(static_cast<std::size_t>(components));
  for (std::size_t c = 0; c < cellCount; ++c)
  {
    cellValue(c, v.data());
    forEachPoint(c, [&](std::size_t id) {
      for (int j = 0; j < components; ++j)
      {
        sums[components * id + j] += v[j];
      }
      ++count[id];
    });
  }
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    for (int j = 0; j < components; ++j)
    {
      sums[components * i + j] /= std::max(1, count[i]);
    }
  }
  return sums;
}
} // namespace catar

#endif
