// CatadioptricAR Core: per-frame tessellation of triangles for this frame's image.
//
// The compositor draws a triangle as the straight-edged triangle between the images of its
// vertices, and only when all of them have a reflection. Two cases need more triangles, decided
// anew every frame from the exact projection:
//  - a triangle that crosses the visibility boundary (some of it reflected, some hidden by the
//    mirror, outside a quadric's z_range, behind the camera, ...): it is split until the pieces
//    along the boundary are within `boundaryTolerance` pixels in the image, and the visible part
//    of each piece is kept, cut at the boundary found by bisection on its edges;
//  - (adaptive) a triangle whose edges bend more than `bendTolerance` pixels (the exact image of
//    the edge's midpoint against the straight segment, EdgeBend.h): it is split in four, again
//    and again, until no edge of a piece bends more.
// Every other triangle is left as it is. New points are given by the input triangle they lie in
// and their barycentric weights there, so that the caller interpolates point data (normals,
// colours, texture coordinates) and copies cell data.
#ifndef catarImageTessellation_h
#define catarImageTessellation_h

#include "Projector.h"

#include <array>
#include <cstdint>
#include <vector>

namespace catar
{
struct TessellationOptions
{
  /// Pixels: triangles crossing the visibility boundary are cut at it to this accuracy; 0 drops
  /// them whole.
  double boundaryTolerance = 0.25;
  /// Pixels: largest bend of a drawn edge (adaptive tessellation); 0 leaves seen triangles as
  /// they are.
  double bendTolerance = 0.0;
  /// Pixels: a triangle seen at its corners whose edge is longer than this in the image is
  /// checked at that edge's midpoint for a hidden middle (the visibility boundary crossing it
  /// between two seen ends), and cut at the boundary when it has one. Smaller triangles are
  /// drawn as they are (with boundaryTolerance 0, none is checked).
  double interiorCheck = 4.0;
  /// The most times an input triangle's edges are halved.
  int maxDepth = 12;
  /// The most triangles one input triangle may become.
  int maxPiecesPerTriangle = 65536;
  SolverType solver = SolverType::Automatic;
};

/// A point the tessellation made: inside input triangle (a, b, c) (input point ids) at
/// barycentric weights (wa, wb, wc), its world position and its projection.
struct TessellatedPoint
{
  std::array<std::int64_t, 3> parents{ { 0, 0, 0 } };
  std::array<double, 3> weights{ { 0.0, 0.0, 0.0 } };
  Vec3 world = Vec3::Zero();
  ProjectedPoint projected;
  /// Placed on the visibility boundary (by bisection), not a split point of an edge.
  bool boundary = false;
};

/// The triangles an input triangle became: point ids below the input's point count are input
/// points, the others new points (id - inputPointCount indexes Tessellation::points).
struct TessellatedTriangle
{
  std::int64_t cell = 0; ///< the input triangle's index (in the caller's numbering)
  std::array<std::int64_t, 3> points{ { 0, 0, 0 } };
};

struct Tessellation
{
  std::vector<TessellatedPoint> points;
  std::vector<TessellatedTriangle> triangles;
};

/// Where pieces split an input triangle's edges: for edge k (from corner k to corner k + 1), the
/// parameters t in (0, 1) from corner k of the midpoints at which a piece's edge on it is split
/// (dyadic: 1/2, 1/4, 3/4, ...). Triangles that share an edge split it alike when each is given
/// the splits the other made (TessellateTriangle's `forced`), so that their pieces meet without
/// T-junctions, whose cracks would show.
struct TriangleEdgeSplits
{
  std::array<std::vector<double>, 3> at;
};

/// What becomes of one input triangle.
enum class TriangleFate : std::uint8_t
{
  Keep,      ///< drawn as it is (seen at its corners and the measured edge midpoints, edges
             ///< within the bend tolerance)
  Drop,      ///< not seen at all (its vertices, edge midpoints and centroid have no reflection),
             ///< or a corner is not a point (NaN, Inf)
  Tessellate ///< split (crosses the boundary, or bends too much)
};

/// Whether a triangle needs TriangleFateOf to decide its fate: any triangle with a corner without
/// a reflection (`allSeen` false), every triangle when there is a bend tolerance, and, with a
/// boundary tolerance, one with an edge longer than interiorCheck pixels (its corners' pixels
/// `px`, two numbers each, in the triangle's order). Every other triangle is kept as it is.
inline bool NeedsFateCheck(
  bool allSeen, const double* const px[3], const TessellationOptions& options)
{
  if (!allSeen || options.bendTolerance > 0.0)
  {
    return true;
  }
  if (!(options.boundaryTolerance > 0.0))
  {
    return false;
  }
  const double check2 = options.interiorCheck * options.interiorCheck;
  bool longEdge = false;
  for (int e = 0; e < 3; ++e)
  {
    const double* p = px[e];
    const double* q = px[(e + 1) % 3];
    const double dx = p[0] - q[0], dy = p[1] - q[1];
    longEdge = longEdge || dx * dx + dy * dy > check2;
  }
  return longEdge;
}

/// The fate of triangle (a, b, c) (world points, their projections: status, pixel and, for the
/// edge midpoints' start, mirror point).
TriangleFate TriangleFateOf(const Projector& projector, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, const TessellationOptions& options);

/// TriangleFateOf for n triangles: out[i] = TriangleFateOf(projector, world[i], projected[i],
/// options), the same fates, the edge midpoints of the triangles seen whole projected side by side
/// (Projector::ProjectWorldNear, each from its edge's ends' reflection points, so `projected`
/// must carry the corners' mirror points).
void TriangleFates(const Projector& projector, std::size_t n, const std::array<Vec3, 3>* world,
  const std::array<ProjectedPoint, 3>* projected, const TessellationOptions& options,
  TriangleFate* out);

/// Tessellates input triangle `cell` with vertices `ids` (input point ids), world points and
/// projections, appending its pieces and new points to `out` (the new points' ids start at
/// inputPointCount + out.points.size()). Returns the number of triangles appended (0: nothing of
/// it is seen).
/// forced (may be null): splits its edges must have (sorted, as the neighbours across them made
/// them); made (may be null) receives the splits it made on its edges.
std::size_t TessellateTriangle(const Projector& projector, std::int64_t cell,
  const std::array<std::int64_t, 3>& ids, const std::array<Vec3, 3>& world,
  const std::array<ProjectedPoint, 3>& projected, std::int64_t inputPointCount,
  const TessellationOptions& options, Tessellation& out, const TriangleEdgeSplits* forced = nullptr,
  TriangleEdgeSplits* made = nullptr);
} // namespace catar

#endif
