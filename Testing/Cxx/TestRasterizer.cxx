// CPU triangle rasteriser: coverage against an exact brute-force reference (top-left rule on the
// 1/256 grid), watertightness of shared edges and vertices, statuses, strides, clipping, Gouraud
// interpolation, alpha compositing, the depth test (order independence, the crossing line of
// interpenetrating slanted triangles, read-only buffers), texture mapping (bilinear sampling
// against a reference sampler and hand-computed values, addressing, row order, modulation,
// strides, invalid textures, and clipping / depth of the textured path), and triangle-id buffers.
//
// The reference below never normalises the winding and never steps edge functions: for each pixel
// centre it evaluates exact integer orientations (coordinates in units of 1/256 px) in the
// caller's vertex order and applies the geometric form of the tie rule documented in
// Rasterizer.h (top edge: horizontal with the third vertex below; left edge: non-horizontal with
// the third vertex strictly to its right).
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

namespace catar
{
void PrintTo(RasterResult r, std::ostream* os)
{
  *os << toString(r);
}
}

using namespace catar;

namespace
{
// ---------------------------------------------------------------------------------------------
// Buffers.

struct Image
{
  int w = 0;
  int h = 0;
  std::vector<std::uint8_t> buf; // top-down rows, 4 bytes per pixel

  Image(int width, int height, std::uint8_t fill = 0)
    : w(width)
    , h(height)
    , buf(static_cast<std::size_t>(4 * width * height), fill)
  {
  }

  ImageView view() { return ImageView{ buf.data(), w, h, 4 * static_cast<std::ptrdiff_t>(w) }; }

  // Bottom-up storage: logical row y lives at memory row h-1-y.
  ImageView flippedView()
  {
    return ImageView{ buf.data() + 4 * static_cast<std::ptrdiff_t>(w) * (h - 1), w, h,
      -4 * static_cast<std::ptrdiff_t>(w) };
  }

  // Logical pixel of a top-down image.
  const std::uint8_t* at(int x, int y) const
  {
    return &buf[4 * (static_cast<std::size_t>(y) * w + x)];
  }

  void fill(std::uint8_t v) { std::fill(buf.begin(), buf.end(), v); }

  // Deterministic varied contents.
  void pattern(unsigned seed)
  {
    std::mt19937 rng(seed);
    for (auto& b : buf)
    {
      b = static_cast<std::uint8_t>(rng() & 0xFF);
    }
  }
};

struct Depth
{
  int w = 0;
  int h = 0;
  std::vector<float> buf;

  Depth(int width, int height, float fill = std::numeric_limits<float>::infinity())
    : w(width)
    , h(height)
    , buf(static_cast<std::size_t>(width * height), fill)
  {
  }

  DepthView view() { return DepthView{ buf.data(), w, h, w }; }

  DepthView flippedView()
  {
    return DepthView{ buf.data() + static_cast<std::ptrdiff_t>(w) * (h - 1), w, h, -w };
  }

  float at(int x, int y) const { return buf[static_cast<std::size_t>(y) * w + x]; }
};

// ---------------------------------------------------------------------------------------------
// Exact reference.

// A point on the 1/256 pixel grid, in grid units.
struct GridPt
{
  std::int64_t x;
  std::int64_t y;
};

// Rounding rule documented in Rasterizer.h: nearest, exact halves up.
GridPt SnapRef(double x, double y)
{
  return GridPt{ static_cast<std::int64_t>(std::floor(x * 256.0 + 0.5)),
    static_cast<std::int64_t>(std::floor(y * 256.0 + 0.5)) };
}

// Twice the signed area of (a, b, p); positive when p is clockwise from a->b on screen (y down).
std::int64_t Orient(const GridPt& a, const GridPt& b, const GridPt& p)
{
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Tie rule, geometrically: is edge (a, b) of the triangle with third vertex c a top or left edge?
bool RefTopOrLeft(const GridPt& a, const GridPt& b, const GridPt& c)
{
  if (a.y == b.y)
  {
    return c.y > a.y; // top: horizontal with the interior below
  }
  // Left: c strictly right of the edge's line at height c.y, i.e.
  // c.x > a.x + (c.y - a.y)(b.x - a.x)/(b.y - a.y); multiply out by (b.y - a.y) keeping the sign.
  const std::int64_t s = (c.x - a.x) * (b.y - a.y) - (c.y - a.y) * (b.x - a.x);
  return (b.y > a.y) ? s > 0 : s < 0;
}

bool RefCovered(const GridPt t[3], int px, int py)
{
  const GridPt p{ static_cast<std::int64_t>(px) * 256, static_cast<std::int64_t>(py) * 256 };
  if (Orient(t[0], t[1], t[2]) == 0)
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    const GridPt& a = t[(i + 1) % 3];
    const GridPt& b = t[(i + 2) % 3];
    const GridPt& c = t[i];
    const std::int64_t e = Orient(a, b, p);
    const std::int64_t ec = Orient(a, b, c);
    if (e == 0)
    {
      if (!RefTopOrLeft(a, b, c))
      {
        return false;
      }
    }
    else if ((e > 0) != (ec > 0))
    {
      return false;
    }
  }
  return true;
}

// Barycentric coordinates of pixel centre (px, py), exact inputs, long double arithmetic.
void RefBarycentric(const GridPt t[3], int px, int py, long double l[3])
{
  const long double x = px * 256.0L;
  const long double y = py * 256.0L;
  const long double area = static_cast<long double>(Orient(t[0], t[1], t[2]));
  for (int i = 0; i < 3; ++i)
  {
    const GridPt& a = t[(i + 1) % 3];
    const GridPt& b = t[(i + 2) % 3];
    l[i] = ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / area;
  }
}

RasterVertex Vtx(const GridPt& p, float r = 1, float g = 1, float b = 1, float a = 1, float z = 0)
{
  RasterVertex v;
  v.x = static_cast<double>(p.x) / 256.0; // exact
  v.y = static_cast<double>(p.y) / 256.0;
  v.r = r;
  v.g = g;
  v.b = b;
  v.a = a;
  v.depth = z;
  return v;
}

RasterVertex Vtx(
  double x, double y, float r = 1, float g = 1, float b = 1, float a = 1, float z = 0)
{
  RasterVertex v;
  v.x = x;
  v.y = y;
  v.r = r;
  v.g = g;
  v.b = b;
  v.a = a;
  v.depth = z;
  return v;
}

// Expected byte for an exact value v in [0, 255]: returns true if `actual` is acceptable, i.e.
// round-to-nearest of v, or either neighbour when v is within 1e-3 of a rounding tie.
bool ByteMatches(long double v, int actual)
{
  const long double f = v - std::floor(v);
  if (std::fabs(f - 0.5L) < 1e-3L)
  {
    return actual == static_cast<int>(std::floor(v)) || actual == static_cast<int>(std::ceil(v));
  }
  return actual == static_cast<int>(std::floor(v + 0.5L));
}

// Compares an opaque-white drawing of t (on a zero image) with the reference. Returns the number
// of mismatching pixels and the number of reference-covered pixels.
std::pair<int, int> CompareCoverage(const Image& img, const GridPt t[3], std::string* firstBad)
{
  int bad = 0;
  int covered = 0;
  for (int y = 0; y < img.h; ++y)
  {
    for (int x = 0; x < img.w; ++x)
    {
      const bool ref = RefCovered(t, x, y);
      const bool got = img.at(x, y)[3] != 0;
      covered += ref ? 1 : 0;
      if (ref != got)
      {
        if (bad == 0 && firstBad)
        {
          std::ostringstream os;
          os << "pixel (" << x << "," << y << ") ref=" << ref << " got=" << got
             << " triangle (grid units) (" << t[0].x << "," << t[0].y << ") (" << t[1].x << ","
             << t[1].y << ") (" << t[2].x << "," << t[2].y << ")";
          *firstBad = os.str();
        }
        ++bad;
      }
    }
  }
  return { bad, covered };
}

// Random grid coordinate in [lo, hi] px, with a bias towards pixel centres and half pixels.
std::int64_t RandomCoord(std::mt19937& rng, double lo, double hi)
{
  const int mode = std::uniform_int_distribution<int>(0, 3)(rng);
  const std::int64_t glo = static_cast<std::int64_t>(std::ceil(lo * 256));
  const std::int64_t ghi = static_cast<std::int64_t>(std::floor(hi * 256));
  std::int64_t g = std::uniform_int_distribution<std::int64_t>(glo, ghi)(rng);
  if (mode == 1)
  {
    g = static_cast<std::int64_t>(std::floor(static_cast<double>(g) / 256.0 + 0.5)) *
      256; // pixel centre
  }
  else if (mode == 2)
  {
    g = static_cast<std::int64_t>(std::floor(static_cast<double>(g) / 128.0 + 0.5)) *
      128; // centre or boundary
  }
  return g;
}

// A random triangle on the grid: large or small, frequently with axis-aligned edges.
void RandomTriangle(std::mt19937& rng, int w, int h, GridPt t[3])
{
  const bool small = std::uniform_int_distribution<int>(0, 1)(rng) == 0;
  double cx = std::uniform_real_distribution<double>(-4, w + 4)(rng);
  double cy = std::uniform_real_distribution<double>(-4, h + 4)(rng);
  const double r = small ? 4.0 : 0.6 * std::max(w, h);
  for (int i = 0; i < 3; ++i)
  {
    t[i].x = RandomCoord(rng, cx - r, cx + r);
    t[i].y = RandomCoord(rng, cy - r, cy + r);
  }
  const int axis = std::uniform_int_distribution<int>(0, 5)(rng);
  if (axis == 0)
  {
    t[1].y = t[0].y; // horizontal edge
  }
  else if (axis == 1)
  {
    t[2].x = t[1].x; // vertical edge
  }
  else if (axis == 2)
  {
    t[1].y = t[0].y; // right angle
    t[2].x = t[0].x;
  }
}

int CountNonZeroAlpha(const Image& img)
{
  int n = 0;
  for (int y = 0; y < img.h; ++y)
  {
    for (int x = 0; x < img.w; ++x)
    {
      n += img.at(x, y)[3] != 0 ? 1 : 0;
    }
  }
  return n;
}

// ---------------------------------------------------------------------------------------------
// Coverage.

TEST(Rasterizer, RandomGridTrianglesMatchBruteForce)
{
  std::mt19937 rng(12345);
  const int w = 48, h = 40;
  Image img(w, h);
  int totalBad = 0, drawn = 0, degenerate = 0, empty = 0;
  std::string firstBad;
  for (int n = 0; n < 6000; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    img.fill(0);
    const RasterResult res = rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2]));
    std::string bad;
    const auto cmp = CompareCoverage(img, t, &bad);
    if (cmp.first && firstBad.empty())
    {
      firstBad = bad;
    }
    totalBad += cmp.first;
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      EXPECT_EQ(res, RasterResult::Degenerate);
      ++degenerate;
    }
    else if (cmp.second == 0)
    {
      EXPECT_EQ(res, RasterResult::Empty);
      ++empty;
    }
    else
    {
      EXPECT_EQ(res, RasterResult::Drawn);
      ++drawn;
    }
  }
  EXPECT_EQ(totalBad, 0) << firstBad;
  // The sample must actually exercise all the outcomes.
  EXPECT_GT(drawn, 3000);
  EXPECT_GT(empty, 50);
  EXPECT_GT(degenerate, 5);
}

TEST(Rasterizer, RandomOffGridTrianglesMatchBruteForceAfterSnapping)
{
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> ux(-10, 50), uy(-10, 40);
  const int w = 40, h = 30;
  Image img(w, h);
  int totalBad = 0;
  std::string firstBad;
  for (int n = 0; n < 2000; ++n)
  {
    RasterVertex v[3];
    GridPt t[3];
    for (int i = 0; i < 3; ++i)
    {
      v[i] = Vtx(ux(rng), uy(rng));
      t[i] = SnapRef(v[i].x, v[i].y);
    }
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2]);
    std::string bad;
    const int b = CompareCoverage(img, t, &bad).first;
    if (b && firstBad.empty())
    {
      firstBad = bad;
    }
    totalBad += b;
  }
  EXPECT_EQ(totalBad, 0) << firstBad;
}

// Known triangles with pixel centres on their edges, in all 6 vertex orders.
TEST(Rasterizer, TopLeftRuleOnKnownTriangles)
{
  const int w = 8, h = 8;
  Image img(w, h);
  // Legs on x = 1 (left edge) and y = 1 (top edge), hypotenuse x + y = 6 (a right edge).
  const RasterVertex a[3] = { Vtx(1, 1), Vtx(5, 1), Vtx(1, 5) };
  // Legs on x = 5 (right edge) and y = 5 (bottom edge), hypotenuse x + y = 6 (a left edge).
  const RasterVertex b[3] = { Vtx(5, 1), Vtx(5, 5), Vtx(1, 5) };
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (const auto& p : perms)
  {
    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), a[p[0]], a[p[1]], a[p[2]]), RasterResult::Drawn);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool expected = x >= 1 && y >= 1 && x + y < 6;
        EXPECT_EQ(img.at(x, y)[3] != 0, expected) << "A, pixel " << x << "," << y;
      }
    }
    EXPECT_NE(img.at(1, 1)[3], 0) << "vertex where a top and a left edge meet";
    EXPECT_NE(img.at(3, 1)[3], 0) << "centre on a top edge";
    EXPECT_NE(img.at(1, 3)[3], 0) << "centre on a left edge";
    EXPECT_EQ(img.at(3, 3)[3], 0) << "centre on a right edge";
    EXPECT_EQ(CountNonZeroAlpha(img), 10);

    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), b[p[0]], b[p[1]], b[p[2]]), RasterResult::Drawn);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool expected = x < 5 && y < 5 && x + y >= 6;
        EXPECT_EQ(img.at(x, y)[3] != 0, expected) << "B, pixel " << x << "," << y;
      }
    }
    EXPECT_EQ(img.at(5, 3)[3], 0) << "centre on a right edge";
    EXPECT_EQ(img.at(3, 5)[3], 0) << "centre on a bottom edge";
    EXPECT_NE(img.at(3, 3)[3], 0) << "centre on a left (sloped) edge";
    EXPECT_EQ(CountNonZeroAlpha(img), 6);
  }
}

// A square split along either diagonal, in both windings: drawing both halves with a = 0.5 on a
// transparent image gives alpha 128 where drawn once and 192 where drawn twice.
TEST(Rasterizer, SquareSplitAlongDiagonalDrawsEachPixelOnce)
{
  const int w = 16, h = 16;
  Image img(w, h);
  // Corners on pixel centres: the diagonal passes through pixel centres.
  const RasterVertex c[4] = { Vtx(2, 2, 1, 1, 1, 0.5f), Vtx(12, 2, 1, 1, 1, 0.5f),
    Vtx(12, 12, 1, 1, 1, 0.5f), Vtx(2, 12, 1, 1, 1, 0.5f) };
  for (int diag = 0; diag < 2; ++diag)
  {
    for (int flip = 0; flip < 2; ++flip)
    {
      img.fill(0);
      const int i0 = diag, i1 = diag + 1, i2 = diag + 2, i3 = (diag + 3) % 4;
      if (flip)
      {
        rasterizeTriangle(img.view(), c[i0], c[i2], c[i1]);
        rasterizeTriangle(img.view(), c[i0], c[i2], c[i3]);
      }
      else
      {
        rasterizeTriangle(img.view(), c[i0], c[i1], c[i2]);
        rasterizeTriangle(img.view(), c[i2], c[i3], c[i0]);
      }
      for (int y = 0; y < h; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          // The square's top and left sides are drawn, its bottom and right sides are not.
          const bool inside = x >= 2 && x < 12 && y >= 2 && y < 12;
          EXPECT_EQ(static_cast<int>(img.at(x, y)[3]), inside ? 128 : 0)
            << "diag " << diag << " flip " << flip << " pixel " << x << "," << y;
        }
      }
    }
  }
}

// Fans of triangles around a shared vertex: every pixel centre strictly inside the fan's polygon
// is drawn exactly once (the shared vertex included), none is drawn twice, none outside.
TEST(Rasterizer, FanAroundSharedVertexDrawsEachPixelOnce)
{
  const int w = 48, h = 40;
  Image img(w, h);
  std::mt19937 rng(99);
  struct Fan
  {
    GridPt centre;
    std::vector<GridPt> ring; // convex, in angular order
  };
  std::vector<Fan> fans;
  const double pi = std::acos(-1.0);
  // Circles of points, centre on a pixel centre or not.
  for (int k = 0; k < 6; ++k)
  {
    Fan f;
    const double cx = (k % 2 == 0) ? 20.0 : 20.0 + 93.0 / 256.0;
    const double cy = (k % 2 == 0) ? 17.0 : 17.0 + 200.0 / 256.0;
    f.centre = SnapRef(cx, cy);
    const int n = 5 + 3 * k;
    const double phase = 0.37 * k;
    for (int i = 0; i < n; ++i)
    {
      const double ang = phase + 2 * pi * i / n;
      f.ring.push_back(SnapRef(cx + 14 * std::cos(ang), cy + 14 * std::sin(ang)));
    }
    fans.push_back(f);
  }
  // Spokes along the axes and diagonals, through many pixel centres.
  {
    Fan f;
    f.centre = SnapRef(20, 17);
    const int d[8][2] = { { 1, 0 }, { 1, 1 }, { 0, 1 }, { -1, 1 }, { -1, 0 }, { -1, -1 }, { 0, -1 },
      { 1, -1 } };
    for (const auto& o : d)
    {
      f.ring.push_back(SnapRef(20 + 10 * o[0], 17 + 10 * o[1]));
    }
    fans.push_back(f);
  }

  for (std::size_t fi = 0; fi < fans.size(); ++fi)
  {
    const Fan& f = fans[fi];
    std::vector<int> count(static_cast<std::size_t>(w * h), 0);
    const std::size_t n = f.ring.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      GridPt t[3] = { f.centre, f.ring[i], f.ring[(i + 1) % n] };
      if (rng() & 1)
      {
        std::swap(t[1], t[2]); // random winding
      }
      img.fill(0);
      EXPECT_EQ(
        rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2])), RasterResult::Drawn);
      for (int y = 0; y < h; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          count[static_cast<std::size_t>(y * w + x)] += img.at(x, y)[3] != 0 ? 1 : 0;
        }
      }
    }
    const std::int64_t sign = Orient(f.ring[0], f.ring[1], f.ring[2]) > 0 ? 1 : -1;
    int interior = 0;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const GridPt p{ 256 * static_cast<std::int64_t>(x), 256 * static_cast<std::int64_t>(y) };
        bool strictlyInside = true, outside = false;
        for (std::size_t i = 0; i < n; ++i)
        {
          const std::int64_t o = Orient(f.ring[i], f.ring[(i + 1) % n], p) * sign;
          strictlyInside = strictlyInside && o > 0;
          outside = outside || o < 0;
        }
        const int c = count[static_cast<std::size_t>(y * w + x)];
        if (strictlyInside)
        {
          ++interior;
          EXPECT_EQ(c, 1) << "fan " << fi << " pixel " << x << "," << y;
        }
        else if (outside)
        {
          EXPECT_EQ(c, 0) << "fan " << fi << " pixel " << x << "," << y;
        }
        else
        {
          EXPECT_LE(c, 1) << "fan " << fi << " pixel " << x << "," << y;
        }
      }
    }
    EXPECT_GT(interior, 100);
  }
}

// A jittered triangle mesh that covers more than the image: every pixel drawn exactly once.
TEST(Rasterizer, JitteredMeshCoversImageExactlyOnce)
{
  const int w = 50, h = 40;
  const int nx = 10, ny = 8; // nodes at -6 + 7 i (i < nx) and -6 + 7 j (j < ny)
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 4; ++trial)
  {
    std::vector<GridPt> node(static_cast<std::size_t>(nx * ny));
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        // Jitter up to 1.25 px in each direction (keeps every cell convex); a quarter of the
        // nodes stay on pixel centres so that many edges pass through pixel centres.
        const int jitter = (rng() % 4 == 0) ? 0 : 320;
        std::uniform_int_distribution<int> u(-jitter, jitter);
        node[static_cast<std::size_t>(j * nx + i)] =
          GridPt{ (-6 + 7 * i) * 256 + u(rng), (-6 + 7 * j) * 256 + u(rng) };
      }
    }
    std::vector<int> count(static_cast<std::size_t>(w * h), 0);
    Image img(w, h);
    for (int j = 0; j + 1 < ny; ++j)
    {
      for (int i = 0; i + 1 < nx; ++i)
      {
        const GridPt& p00 = node[static_cast<std::size_t>(j * nx + i)];
        const GridPt& p10 = node[static_cast<std::size_t>(j * nx + i + 1)];
        const GridPt& p01 = node[static_cast<std::size_t>((j + 1) * nx + i)];
        const GridPt& p11 = node[static_cast<std::size_t>((j + 1) * nx + i + 1)];
        GridPt tris[2][3];
        if (rng() & 1)
        {
          tris[0][0] = p00, tris[0][1] = p10, tris[0][2] = p11;
          tris[1][0] = p00, tris[1][1] = p11, tris[1][2] = p01;
        }
        else
        {
          tris[0][0] = p00, tris[0][1] = p10, tris[0][2] = p01;
          tris[1][0] = p10, tris[1][1] = p11, tris[1][2] = p01;
        }
        for (auto& t : tris)
        {
          if (rng() & 1)
          {
            std::swap(t[0], t[2]);
          }
          img.fill(0);
          rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2]));
          for (int y = 0; y < h; ++y)
          {
            for (int x = 0; x < w; ++x)
            {
              count[static_cast<std::size_t>(y * w + x)] += img.at(x, y)[3] != 0 ? 1 : 0;
            }
          }
        }
      }
    }
    int wrong = 0;
    for (int c : count)
    {
      wrong += c != 1 ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0) << "trial " << trial;
  }
}

// ---------------------------------------------------------------------------------------------
// Statuses.

TEST(Rasterizer, DegenerateTrianglesDrawNothing)
{
  Image img(16, 16);
  img.pattern(1);
  const Image before = img;
  // Collinear.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(5, 5), Vtx(10, 10)), RasterResult::Degenerate);
  // Collinear along a row of pixel centres.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(1, 3), Vtx(9, 3), Vtx(4, 3)), RasterResult::Degenerate);
  // Repeated vertex.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(2, 2), Vtx(2, 2), Vtx(10, 4)), RasterResult::Degenerate);
  // Non-degenerate in doubles, but two vertices snap to the same 1/256 grid point.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(5, 5), Vtx(10, 10), Vtx(5.001, 5)), RasterResult::Degenerate);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, EmptyTrianglesDrawNothing)
{
  Image img(16, 16);
  img.pattern(2);
  const Image before = img;
  // Between pixel centres.
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(3.1, 3.1), Vtx(3.9, 3.1), Vtx(3.1, 3.9)),
    RasterResult::Empty);
  // Only touches a centre with its right edge: (4, 4) lies on x + y = 8, a right edge.
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(3.5, 3.5), Vtx(4.5, 3.5), Vtx(3.5, 4.5)),
    RasterResult::Empty);
  // Entirely outside the image.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(-20, -5), Vtx(-10, -5), Vtx(-15, 30)), RasterResult::Empty);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(20, 20), Vtx(40, 20), Vtx(30, 40)), RasterResult::Empty);
  // Inside the image but outside the clip rectangle.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(6, 0), Vtx(0, 6), PixelRect{ 8, 8, 16, 16 }),
    RasterResult::Empty);
  // Empty clip rectangle.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(16, 0), Vtx(0, 16), PixelRect{ 4, 4, 4, 9 }),
    RasterResult::Empty);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, NonFiniteInputIsRejected)
{
  Image img(16, 16);
  img.pattern(3);
  const Image before = img;
  Depth depth(16, 16);
  const std::vector<float> depthBefore = depth.buf;
  const double values[3] = { std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  for (double bad : values)
  {
    for (int vi = 0; vi < 3; ++vi)
    {
      for (int field = 0; field < 7; ++field)
      {
        RasterVertex v[3] = { Vtx(0, 0), Vtx(15, 0), Vtx(0, 15) };
        RasterVertex& t = v[vi];
        switch (field)
        {
          case 0:
            t.x = bad;
            break;
          case 1:
            t.y = bad;
            break;
          case 2:
            t.r = static_cast<float>(bad);
            break;
          case 3:
            t.g = static_cast<float>(bad);
            break;
          case 4:
            t.b = static_cast<float>(bad);
            break;
          case 5:
            t.a = static_cast<float>(bad);
            break;
          default:
            t.depth = static_cast<float>(bad);
            break;
        }
        const DepthView dv = depth.view();
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2]), RasterResult::InvalidInput)
          << "vertex " << vi << " field " << field;
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], &dv), RasterResult::InvalidInput)
          << "vertex " << vi << " field " << field;
      }
    }
  }
  // Invalid buffers.
  ImageView none;
  EXPECT_EQ(rasterizeTriangle(none, Vtx(0, 0), Vtx(15, 0), Vtx(0, 15)), RasterResult::InvalidInput);
  Depth small(8, 16);
  const DepthView sv = small.view();
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(15, 0), Vtx(0, 15), &sv),
    RasterResult::InvalidInput);
  EXPECT_EQ(img.buf, before.buf);
  EXPECT_EQ(depth.buf, depthBefore);
}

TEST(Rasterizer, GuardBand)
{
  const double g = 1 << 20;
  const int w = 64, h = 48;
  Image img(w, h);
  img.pattern(4);
  const Image before = img;
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(g + 1, 0), Vtx(0, 10)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(10, 0), Vtx(0, -g - 0.5)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(-g - 1e-3, 0), Vtx(10, 0), Vtx(0, 10)),
    RasterResult::OutsideGuardBand);
  EXPECT_EQ(img.buf, before.buf);

  // Vertices exactly on the guard band are accepted and are exact: a huge triangle that covers
  // the image, and long thin slivers crossing it.
  const GridPt tris[4][3] = {
    { SnapRef(-g, -g), SnapRef(g, -g), SnapRef(0, g) },
    { SnapRef(-g, 10.3), SnapRef(g, 12.7), SnapRef(-g, 20.1) },
    { SnapRef(-g, 21), SnapRef(g, 25), SnapRef(g, 27) },
    { SnapRef(17, -g), SnapRef(37.5, g), SnapRef(16.25, g) },
  };
  for (const auto& t : tris)
  {
    img.fill(0);
    EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(t[0]), Vtx(t[1]), Vtx(t[2])), RasterResult::Drawn);
    std::string bad;
    const auto cmp = CompareCoverage(img, t, &bad);
    EXPECT_EQ(cmp.first, 0) << bad;
    EXPECT_GT(cmp.second, 0);
  }
  img.fill(0);
  rasterizeTriangle(img.view(), Vtx(tris[0][0]), Vtx(tris[0][1]), Vtx(tris[0][2]));
  EXPECT_EQ(CountNonZeroAlpha(img), w * h);
}

// ---------------------------------------------------------------------------------------------
// Addressing and clipping.

// A random scene with Gouraud colours, partial alpha and depth.
struct SceneTri
{
  RasterVertex v[3];
};

std::vector<SceneTri> RandomScene(unsigned seed, int w, int h, int count)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-5, w + 5), uy(-5, h + 5), off(-9, 9);
  std::uniform_real_distribution<float> uc(-0.2f, 1.2f), ua(0.3f, 1.0f), uz(0, 1);
  std::vector<SceneTri> scene;
  for (int n = 0; n < count; ++n)
  {
    SceneTri t;
    const double cx = ux(rng), cy = uy(rng);
    const bool flat = rng() % 3 == 0;
    for (int i = 0; i < 3; ++i)
    {
      t.v[i] = Vtx(cx + off(rng), cy + off(rng), uc(rng), uc(rng), uc(rng),
        rng() % 2 ? 1.0f : ua(rng), uz(rng));
      if (flat && i > 0)
      {
        t.v[i].r = t.v[0].r, t.v[i].g = t.v[0].g, t.v[i].b = t.v[0].b, t.v[i].a = t.v[0].a;
      }
    }
    scene.push_back(t);
  }
  return scene;
}

TEST(Rasterizer, NegativeRowStrideDrawsTheSamePictureFlipped)
{
  const int w = 37, h = 29;
  const auto scene = RandomScene(5, w, h, 300);
  for (int useDepth = 0; useDepth < 2; ++useDepth)
  {
    Image top(w, h), bottom(w, h);
    top.pattern(6);
    // bottom holds the same logical picture stored bottom-up.
    for (int y = 0; y < h; ++y)
    {
      std::copy_n(top.buf.begin() + 4 * w * y, 4 * w, bottom.buf.begin() + 4 * w * (h - 1 - y));
    }
    Depth dTop(w, h, 0.7f), dBottom(w, h, 0.7f);
    const DepthView dvTop = dTop.view(), dvBottom = dBottom.flippedView();
    int drawn = 0;
    for (const auto& t : scene)
    {
      const RasterResult a =
        rasterizeTriangle(top.view(), t.v[0], t.v[1], t.v[2], useDepth ? &dvTop : nullptr);
      const RasterResult b = rasterizeTriangle(
        bottom.flippedView(), t.v[0], t.v[1], t.v[2], useDepth ? &dvBottom : nullptr);
      EXPECT_EQ(a, b);
      drawn += a == RasterResult::Drawn ? 1 : 0;
    }
    EXPECT_GT(drawn, 200);
    for (int y = 0; y < h; ++y)
    {
      EXPECT_TRUE(std::equal(top.buf.begin() + 4 * w * y, top.buf.begin() + 4 * w * (y + 1),
        bottom.buf.begin() + 4 * w * (h - 1 - y)))
        << "row " << y;
      EXPECT_TRUE(std::equal(dTop.buf.begin() + w * y, dTop.buf.begin() + w * (y + 1),
        dBottom.buf.begin() + w * (h - 1 - y)))
        << "depth row " << y;
    }
  }
  // And the flipped view really is bottom-up: pixel (0, 0) is in the last memory row.
  Image img(4, 3);
  rasterizeTriangle(img.flippedView(), Vtx(-0.5, -0.5), Vtx(1, -0.5), Vtx(-0.5, 1));
  EXPECT_EQ(img.buf[4 * 4 * 2 + 3], 255);
  EXPECT_EQ(CountNonZeroAlpha(img), 1);
}

TEST(Rasterizer, ClipTilesEqualTheWholeImage)
{
  const int w = 61, h = 47;
  const auto scene = RandomScene(7, w, h, 400);
  Image whole(w, h), tiled(w, h);
  whole.pattern(8);
  tiled.buf = whole.buf;
  Depth dWhole(w, h, 0.8f), dTiled(w, h, 0.8f);
  const DepthView dvWhole = dWhole.view(), dvTiled = dTiled.view();
  std::vector<RasterResult> wholeResult;
  for (const auto& t : scene)
  {
    wholeResult.push_back(rasterizeTriangle(whole.view(), t.v[0], t.v[1], t.v[2], &dvWhole));
  }
  const int tw = 16, th = 12; // uneven last tiles
  std::vector<bool> anyDrawn(scene.size(), false);
  for (int ty = 0; ty < h; ty += th)
  {
    for (int tx = 0; tx < w; tx += tw)
    {
      const PixelRect clip{ tx, ty, std::min(tx + tw, w), std::min(ty + th, h) };
      for (std::size_t i = 0; i < scene.size(); ++i)
      {
        const auto& t = scene[i];
        const RasterResult r =
          rasterizeTriangle(tiled.view(), t.v[0], t.v[1], t.v[2], clip, &dvTiled);
        anyDrawn[i] = anyDrawn[i] || r == RasterResult::Drawn;
      }
    }
  }
  EXPECT_EQ(whole.buf, tiled.buf);
  EXPECT_EQ(dWhole.buf, dTiled.buf);
  for (std::size_t i = 0; i < scene.size(); ++i)
  {
    EXPECT_EQ(wholeResult[i] == RasterResult::Drawn, anyDrawn[i]) << "triangle " << i;
  }

  // A clip rectangle larger than the image is the whole image; pixels outside a clip rectangle
  // are untouched and pixels inside equal the unclipped drawing.
  const RasterVertex a = Vtx(-3.3, 2.2, 0.9f, 0.2f, 0.1f, 0.6f);
  const RasterVertex b = Vtx(70.1, 10.4, 0.1f, 0.8f, 0.3f, 1.0f);
  const RasterVertex c = Vtx(20.7, 52.9, 0.4f, 0.4f, 0.9f, 0.8f);
  Image ref(w, h), big(w, h), part(w, h);
  ref.pattern(9);
  big.buf = ref.buf;
  part.buf = ref.buf;
  const Image background = ref;
  rasterizeTriangle(ref.view(), a, b, c);
  EXPECT_EQ(rasterizeTriangle(big.view(), a, b, c, PixelRect{ -100, -50, 1000, 2000 }),
    RasterResult::Drawn);
  EXPECT_EQ(big.buf, ref.buf);
  const PixelRect clip{ 13, 9, 40, 31 };
  EXPECT_EQ(rasterizeTriangle(part.view(), a, b, c, clip), RasterResult::Drawn);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool in = x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1;
      const Image& expected = in ? ref : background;
      EXPECT_TRUE(std::equal(part.at(x, y), part.at(x, y) + 4, expected.at(x, y)))
        << "pixel " << x << "," << y;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Shading and compositing.

TEST(Rasterizer, GouraudColourIsTheBarycentricInterpolation)
{
  const int w = 40, h = 32;
  Image img(w, h);
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> uc(-0.3f, 1.3f), ua(0.0f, 1.0f);
  int checked = 0, bad = 0;
  std::string firstBad;
  for (int n = 0; n < 300; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      continue;
    }
    float col[3][4];
    RasterVertex v[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        col[i][c] = uc(rng);
      }
      col[i][3] = (n % 2 == 0) ? 1.0f : ua(rng);
      v[i] = Vtx(t[i], col[i][0], col[i][1], col[i][2], col[i][3]);
    }
    // On a transparent black target: out.rgb = 255 c a, out.a = 255 a.
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2]);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        if (!RefCovered(t, x, y))
        {
          continue;
        }
        long double l[3];
        RefBarycentric(t, x, y, l);
        long double value[4] = { 0, 0, 0, 0 };
        for (int c = 0; c < 4; ++c)
        {
          for (int i = 0; i < 3; ++i)
          {
            value[c] += l[i] * std::min(1.0L, std::max(0.0L, static_cast<long double>(col[i][c])));
          }
        }
        const long double expected[4] = { 255 * value[0] * value[3], 255 * value[1] * value[3],
          255 * value[2] * value[3], 255 * value[3] };
        for (int c = 0; c < 4; ++c)
        {
          ++checked;
          if (std::fabs(static_cast<long double>(img.at(x, y)[c]) - expected[c]) > 1.0L)
          {
            if (!bad)
            {
              std::ostringstream os;
              os << "triangle " << n << " pixel " << x << "," << y << " channel " << c
                 << " expected " << static_cast<double>(expected[c]) << " got "
                 << static_cast<int>(img.at(x, y)[c]);
              firstBad = os.str();
            }
            ++bad;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_EQ(bad, 0) << firstBad;
}

TEST(Rasterizer, AlphaBlendingFormula)
{
  const int w = 24, h = 20;
  Image img(w, h);
  img.pattern(10);
  const Image before = img;
  const float src[4] = { 0.2f, 0.7f, 0.9f, 0.35f };
  // Covers the whole image.
  EXPECT_EQ(
    rasterizeTriangle(img.view(), Vtx(-50, -50, src[0], src[1], src[2], src[3]),
      Vtx(200, -50, src[0], src[1], src[2], src[3]), Vtx(-50, 200, src[0], src[1], src[2], src[3])),
    RasterResult::Drawn);
  const long double a = src[3];
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 4; ++c)
      {
        const long double s = c < 3 ? static_cast<long double>(src[c]) : 1.0L;
        const long double d = before.at(x, y)[c];
        const long double exact = 255.0L * s * a + d * (1.0L - a);
        EXPECT_TRUE(ByteMatches(exact, img.at(x, y)[c]))
          << "pixel " << x << "," << y << " channel " << c << " exact "
          << static_cast<double>(exact) << " got " << static_cast<int>(img.at(x, y)[c]);
      }
    }
  }

  // Gouraud alpha over an opaque background: out.a stays 255, rgb is the formula.
  Image bg(w, h, 255);
  bg.pattern(11);
  for (std::size_t i = 3; i < bg.buf.size(); i += 4)
  {
    bg.buf[i] = 255;
  }
  const Image bgBefore = bg;
  const GridPt t[3] = { SnapRef(0, 0), SnapRef(23, 2), SnapRef(5, 19) };
  const float al[3] = { 0.1f, 0.5f, 0.95f };
  rasterizeTriangle(bg.view(), Vtx(t[0], 1, 0, 0.5f, al[0]), Vtx(t[1], 1, 0, 0.5f, al[1]),
    Vtx(t[2], 1, 0, 0.5f, al[2]));
  int covered = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      if (!RefCovered(t, x, y))
      {
        EXPECT_TRUE(std::equal(bg.at(x, y), bg.at(x, y) + 4, bgBefore.at(x, y)));
        continue;
      }
      ++covered;
      long double l[3];
      RefBarycentric(t, x, y, l);
      const long double alpha = l[0] * al[0] + l[1] * al[1] + l[2] * al[2];
      const long double s[3] = { 1.0L, 0.0L, 0.5L };
      for (int c = 0; c < 3; ++c)
      {
        const long double exact = 255 * s[c] * alpha + bgBefore.at(x, y)[c] * (1 - alpha);
        EXPECT_LE(std::fabs(exact - bg.at(x, y)[c]), 1.0L) << x << "," << y << " c" << c;
      }
      EXPECT_EQ(bg.at(x, y)[3], 255);
    }
  }
  EXPECT_GT(covered, 100);
}

TEST(Rasterizer, OpaqueOverwritesAndTransparentKeeps)
{
  const int w = 10, h = 10;
  Image img(w, h);
  img.pattern(12);
  const Image before = img;
  const float c[3] = { 0.2f, 0.4f, 0.6f };
  // Opaque flat colour: round(255 c) and alpha 255, whatever was there.
  rasterizeTriangle(img.view(), Vtx(-20, -20, c[0], c[1], c[2], 1),
    Vtx(40, -20, c[0], c[1], c[2], 1), Vtx(-20, 40, c[0], c[1], c[2], 1));
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(img.at(x, y)[k],
          static_cast<int>(std::floor(255.0L * static_cast<long double>(c[k]) + 0.5L)));
      }
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Gouraud opaque: a colour gradient whose values at pixel centres are exact multiples of 1/255.
  img.pattern(13);
  // r = x / 255: red 0 on the left edge x = 0 (drawn: a left edge), 1 at x = 255.
  rasterizeTriangle(
    img.view(), Vtx(0, -20, 0, 0, 1, 1), Vtx(255, -20, 1, 0, 1, 1), Vtx(0, 40, 0, 0, 1, 1));
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], x) << x << "," << y;
      EXPECT_EQ(img.at(x, y)[1], 0);
      EXPECT_EQ(img.at(x, y)[2], 255);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Alpha 0 leaves the target unchanged.
  img = before;
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 1, 1, 1, 0), Vtx(40, -20, 1, 1, 1, 0), Vtx(-20, 40, 1, 1, 1, 0));
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, ColoursAreClamped)
{
  Image img(8, 8);
  img.pattern(14);
  // Flat: (1.5, -0.5, 0.25, 3.0) -> (1, 0, 0.25, 1) -> (255, 0, 64, 255).
  rasterizeTriangle(img.view(), Vtx(-20, -20, 1.5f, -0.5f, 0.25f, 3.0f),
    Vtx(40, -20, 1.5f, -0.5f, 0.25f, 3.0f), Vtx(-20, 40, 1.5f, -0.5f, 0.25f, 3.0f));
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 255);
      EXPECT_EQ(img.at(x, y)[1], 0);
      EXPECT_EQ(img.at(x, y)[2], 64);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // Gouraud: vertex colours are clamped before interpolation (red 2 -> 1 at every vertex, alpha
  // -1 -> 0 at every vertex: nothing changes).
  img.pattern(15);
  const Image before = img;
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 2, 0, 0, -1), Vtx(40, -20, 5, 1, 0, -2), Vtx(-20, 40, 3, 0, 1, -1));
  EXPECT_EQ(img.buf, before.buf);
  rasterizeTriangle(
    img.view(), Vtx(-20, -20, 2, 0, 0, 1), Vtx(40, -20, 5, 0, 0, 1), Vtx(-20, 40, 3, 0, 0, 1));
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 255);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Depth.

TEST(Rasterizer, DepthTestKeepsTheNearerTriangleInAnyOrder)
{
  const int w = 40, h = 30;
  // A: constant depth 0.3, red; B: constant 0.6, blue.
  const GridPt ta[3] = { SnapRef(2, 3), SnapRef(30, 5), SnapRef(8, 27) };
  const GridPt tb[3] = { SnapRef(12.5, 1.25), SnapRef(38, 20), SnapRef(10, 29) };
  const RasterVertex a[3] = { Vtx(ta[0], 1, 0, 0, 1, 0.3f), Vtx(ta[1], 1, 0, 0, 1, 0.3f),
    Vtx(ta[2], 1, 0, 0, 1, 0.3f) };
  const RasterVertex b[3] = { Vtx(tb[0], 0, 0, 1, 1, 0.6f), Vtx(tb[1], 0, 0, 1, 1, 0.6f),
    Vtx(tb[2], 0, 0, 1, 1, 0.6f) };
  Image ab(w, h), ba(w, h);
  Depth dab(w, h), dba(w, h);
  const DepthView vab = dab.view(), vba = dba.view();
  rasterizeTriangle(ab.view(), a[0], a[1], a[2], &vab);
  rasterizeTriangle(ab.view(), b[0], b[1], b[2], &vab);
  rasterizeTriangle(ba.view(), b[0], b[1], b[2], &vba);
  rasterizeTriangle(ba.view(), a[0], a[1], a[2], &vba);
  EXPECT_EQ(ab.buf, ba.buf);
  EXPECT_EQ(dab.buf, dba.buf);
  int overlap = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool inA = RefCovered(ta, x, y), inB = RefCovered(tb, x, y);
      overlap += inA && inB ? 1 : 0;
      const std::uint8_t* p = ab.at(x, y);
      if (inA)
      {
        EXPECT_TRUE(p[0] == 255 && p[2] == 0) << x << "," << y;
        EXPECT_FLOAT_EQ(dab.at(x, y), 0.3f);
      }
      else if (inB)
      {
        EXPECT_TRUE(p[0] == 0 && p[2] == 255) << x << "," << y;
        EXPECT_FLOAT_EQ(dab.at(x, y), 0.6f);
      }
      else
      {
        EXPECT_EQ(p[3], 0);
        EXPECT_EQ(dab.at(x, y), std::numeric_limits<float>::infinity());
      }
    }
  }
  EXPECT_GT(overlap, 50);
}

TEST(Rasterizer, DepthIsInterpolatedTestedStrictlyAndWritten)
{
  const int w = 40, h = 30;
  // A slopes from depth 0 (left) to 1 (right); B is flat at 0.5: they intersect near x = 20.
  const GridPt ta[3] = { SnapRef(-5, -5), SnapRef(45, -5), SnapRef(-5, 35) };
  const float za[3] = { 0.0f, 1.0f, 0.0f };
  const GridPt tb[3] = { SnapRef(-5, -5), SnapRef(45, 35), SnapRef(-5, 35) };
  for (int order = 0; order < 2; ++order)
  {
    Image img(w, h);
    Depth depth(w, h);
    const DepthView dv = depth.view();
    for (int k = 0; k < 2; ++k)
    {
      if ((k == 0) == (order == 0))
      {
        rasterizeTriangle(img.view(), Vtx(ta[0], 1, 0, 0, 1, za[0]), Vtx(ta[1], 1, 0, 0, 1, za[1]),
          Vtx(ta[2], 1, 0, 0, 1, za[2]), &dv);
      }
      else
      {
        rasterizeTriangle(img.view(), Vtx(tb[0], 0, 0, 1, 1, 0.5f), Vtx(tb[1], 0, 0, 1, 1, 0.5f),
          Vtx(tb[2], 0, 0, 1, 1, 0.5f), &dv);
      }
    }
    int nearA = 0, nearB = 0;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool inA = RefCovered(ta, x, y), inB = RefCovered(tb, x, y);
        long double l[3];
        RefBarycentric(ta, x, y, l);
        const long double zA = l[0] * za[0] + l[1] * za[1] + l[2] * za[2];
        const std::uint8_t* p = img.at(x, y);
        bool expectA = inA;
        if (inA && inB)
        {
          if (std::fabs(zA - 0.5L) < 1e-4L)
          {
            continue; // too close to call in float
          }
          expectA = zA < 0.5L;
        }
        if (expectA)
        {
          ++nearA;
          EXPECT_EQ(p[0], 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_NEAR(depth.at(x, y), static_cast<double>(zA), 1e-5);
        }
        else if (inB)
        {
          ++nearB;
          EXPECT_EQ(p[2], 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_FLOAT_EQ(depth.at(x, y), 0.5f);
        }
      }
    }
    EXPECT_GT(nearA, 100);
    EXPECT_GT(nearB, 100);
  }

  // Strictly less: the same triangle drawn twice with a = 0.5 blends once with the depth test
  // (alpha 128) and twice without it (alpha 192).
  const RasterVertex t[3] = { Vtx(1, 1, 1, 1, 1, 0.5f, 0.25f), Vtx(9, 2, 1, 1, 1, 0.5f, 0.75f),
    Vtx(3, 8, 1, 1, 1, 0.5f, 0.5f) };
  Image once(12, 12), twice(12, 12);
  Depth depth(12, 12);
  const DepthView dv = depth.view();
  for (int k = 0; k < 2; ++k)
  {
    rasterizeTriangle(once.view(), t[0], t[1], t[2], &dv);
    rasterizeTriangle(twice.view(), t[0], t[1], t[2]);
  }
  int drawn = 0;
  for (int y = 0; y < 12; ++y)
  {
    for (int x = 0; x < 12; ++x)
    {
      if (once.at(x, y)[3] != 0)
      {
        ++drawn;
        EXPECT_EQ(once.at(x, y)[3], 128);
        EXPECT_EQ(twice.at(x, y)[3], 192);
      }
      else
      {
        EXPECT_EQ(twice.at(x, y)[3], 0);
      }
    }
  }
  EXPECT_GT(drawn, 15);
}

TEST(Rasterizer, InterpenetratingTrianglesCrossAtTheExpectedColumn)
{
  // Two large triangles covering the whole image, both slanted in depth:
  //   A (red):  zA(x, y) = 0.2 + 0.02 x + 0.0045 y   (the vertex depths are this plane's values)
  //   B (blue): zB(x, y) = 1.0 - 0.01 x
  // They cross where 0.8 - 0.0045 y = 0.03 x, i.e. at x_c(y) = 26.667 - 0.15 y (23.82 on row 19):
  // A is nearer left of the line, B right of it. Whatever the order, each row must show A up to
  // the column before ceil(x_c) and B from there (+-1 for float depths).
  const int w = 60, h = 20;
  auto zA = [](double x, double y) { return static_cast<float>(0.2 + 0.02 * x + 0.0045 * y); };
  auto zB = [](double x, double) { return static_cast<float>(1.0 - 0.01 * x); };
  const double pa[3][2] = { { -10, -10 }, { 150, -10 }, { -10, 100 } };
  const double pb[3][2] = { { -15, -12 }, { 160, -5 }, { -15, 90 } };
  RasterVertex a[3], b[3];
  for (int i = 0; i < 3; ++i)
  {
    a[i] = Vtx(pa[i][0], pa[i][1], 1, 0, 0, 1, zA(pa[i][0], pa[i][1]));
    b[i] = Vtx(pb[i][0], pb[i][1], 0, 0, 1, 1, zB(pb[i][0], pb[i][1]));
  }
  Image ab(w, h), ba(w, h);
  Depth dab(w, h), dba(w, h);
  const DepthView vab = dab.view(), vba = dba.view();
  ASSERT_EQ(rasterizeTriangle(ab.view(), a[0], a[1], a[2], &vab), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ab.view(), b[0], b[1], b[2], &vab), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ba.view(), b[0], b[1], b[2], &vba), RasterResult::Drawn);
  ASSERT_EQ(rasterizeTriangle(ba.view(), a[0], a[1], a[2], &vba), RasterResult::Drawn);
  EXPECT_EQ(ab.buf, ba.buf);
  EXPECT_EQ(dab.buf, dba.buf);
  int exact = 0;
  for (int y = 0; y < h; ++y)
  {
    const double xc = (0.8 - 0.0045 * y) / 0.03;
    const int expectedFirstB = static_cast<int>(std::ceil(xc));
    // The row is A ... A B ... B: find where it switches and check nothing else appears.
    int firstB = w;
    for (int x = 0; x < w; ++x)
    {
      const std::uint8_t* p = ab.at(x, y);
      ASSERT_EQ(p[3], 255) << "uncovered pixel " << x << "," << y;
      const bool isB = p[2] == 255 && p[0] == 0;
      const bool isA = p[0] == 255 && p[2] == 0;
      ASSERT_TRUE(isA || isB) << x << "," << y;
      if (isB && firstB == w)
      {
        firstB = x;
      }
      if (firstB < w)
      {
        EXPECT_TRUE(isB) << "A right of the crossing at " << x << "," << y;
      }
      // The stored depth is the nearer surface's.
      const double zNear = std::min(zA(x, y), zB(x, y));
      EXPECT_NEAR(dab.at(x, y), zNear, 1e-5) << x << "," << y;
    }
    EXPECT_NEAR(firstB, expectedFirstB, 1) << "row " << y << " crossing at x = " << xc;
    exact += firstB == expectedFirstB ? 1 : 0;
  }
  // The crossing comes no nearer than 0.016 px to a pixel centre (row 11: 25.017), a depth
  // difference of 5e-4, far above float resolution: the float depths decide exactly.
  EXPECT_EQ(exact, h);
}

TEST(Rasterizer, ReadOnlyDepthBufferTestsWithoutWriting)
{
  // An opaque red square at depth 0.5 writes depth; a half-transparent blue triangle behind it
  // (0.7) drawn with write = false shows only outside the square and leaves the buffer as it was;
  // a half-transparent green one in front (0.3) blends over the square, again without writing.
  const int w = 24, h = 16;
  Image img(w, h);
  Depth depth(w, h);
  const DepthView dv = depth.view();
  DepthView ro = dv;
  ro.write = false;
  const RasterVertex red[4] = { Vtx(3.5, 3.5, 1, 0, 0, 1, 0.5f), Vtx(11.5, 3.5, 1, 0, 0, 1, 0.5f),
    Vtx(11.5, 11.5, 1, 0, 0, 1, 0.5f), Vtx(3.5, 11.5, 1, 0, 0, 1, 0.5f) };
  rasterizeTriangle(img.view(), red[0], red[1], red[2], &dv);
  rasterizeTriangle(img.view(), red[0], red[2], red[3], &dv);
  const std::vector<float> afterOpaque = depth.buf;
  ASSERT_EQ(rasterizeTriangle(img.view(), Vtx(-5, -5, 0, 0, 1, 0.5f, 0.7f),
              Vtx(40, -5, 0, 0, 1, 0.5f, 0.7f), Vtx(-5, 40, 0, 0, 1, 0.5f, 0.7f), &ro),
    RasterResult::Drawn);
  EXPECT_EQ(depth.buf, afterOpaque);
  ASSERT_EQ(rasterizeTriangle(img.view(), Vtx(5.5, 5.5, 0, 1, 0, 0.5f, 0.3f),
              Vtx(9.5, 5.5, 0, 1, 0, 0.5f, 0.3f), Vtx(5.5, 9.5, 0, 1, 0, 0.5f, 0.3f), &ro),
    RasterResult::Drawn);
  EXPECT_EQ(depth.buf, afterOpaque);
  const GridPt blue[3] = { SnapRef(-5, -5), SnapRef(40, -5), SnapRef(-5, 40) };
  const GridPt green[3] = { SnapRef(5.5, 5.5), SnapRef(9.5, 5.5), SnapRef(5.5, 9.5) };
  int blended = 0, behind = 0, front = 0;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool inRed = x >= 4 && x <= 11 && y >= 4 && y <= 11;
      const std::uint8_t* p = img.at(x, y);
      if (inRed && RefCovered(green, x, y))
      {
        ++front; // green over red: (128, 128, 0)
        EXPECT_EQ(p[0], 128) << x << "," << y;
        EXPECT_EQ(p[1], 128) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      }
      else if (inRed)
      {
        ++behind; // the blue triangle behind is rejected
        EXPECT_EQ(p[0], 255) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      }
      else if (RefCovered(blue, x, y))
      {
        ++blended; // blue over nothing
        EXPECT_EQ(p[2], 128) << x << "," << y;
        EXPECT_EQ(p[3], 128) << x << "," << y;
        EXPECT_EQ(depth.at(x, y), std::numeric_limits<float>::infinity());
      }
    }
  }
  EXPECT_GT(front, 5);
  EXPECT_GT(behind, 30);
  EXPECT_GT(blended, 100);
}

// ---------------------------------------------------------------------------------------------
// Textures.
//
// The reference sampler below follows the definition in Rasterizer.h, written the textbook way:
// s = u * width - 0.5 (texel i's centre at s = i), the two texels floor(s) and floor(s) + 1 with
// their indices wrapped (repeat) or clamped to [0, width - 1] (clamp to edge), weight of the
// second s - floor(s); likewise along v with rows counted from the bottom; long double throughout.

// A texture stored bottom row first, rows packed: texel (i, j) at (j * w + i) * ch.
struct Texels
{
  int w = 0;
  int h = 0;
  int ch = 4;
  std::vector<std::uint8_t> buf;

  Texels(int width, int height, int channels, unsigned seed = 0)
    : w(width)
    , h(height)
    , ch(channels)
    , buf(static_cast<std::size_t>(width * height * channels), 0)
  {
    std::mt19937 rng(seed);
    for (auto& b : buf)
    {
      b = static_cast<std::uint8_t>(rng() & 0xFF);
    }
  }

  std::uint8_t* texel(int i, int j) { return &buf[static_cast<std::size_t>((j * w + i) * ch)]; }
  const std::uint8_t* texel(int i, int j) const
  {
    return &buf[static_cast<std::size_t>((j * w + i) * ch)];
  }

  TextureView view(bool repeat = false) const
  {
    return TextureView{ buf.data(), w, h, ch, static_cast<std::ptrdiff_t>(w * ch), repeat };
  }

  // RGBA on the 0..255 scale of texel (i, j): grey -> r = g = b, no alpha -> 255.
  void rgba(int i, int j, long double out[4]) const
  {
    const std::uint8_t* t = texel(i, j);
    for (int c = 0; c < 3; ++c)
    {
      out[c] = ch == 1 ? t[0] : t[c];
    }
    out[3] = ch == 4 ? t[3] : 255;
  }
};

// Reference bilinear sample, RGBA in [0, 1].
void RefSample(const Texels& t, long double u, long double v, bool repeat, long double out[4])
{
  auto index = [&](long double i, int n) {
    if (repeat)
    {
      long double m = std::fmod(i, static_cast<long double>(n));
      if (m < 0)
      {
        m += n;
      }
      return static_cast<int>(m);
    }
    return static_cast<int>(std::min<long double>(std::max<long double>(i, 0), n - 1));
  };
  const long double s = u * t.w - 0.5L;
  const long double r = v * t.h - 0.5L;
  const long double fs = std::floor(s), fr = std::floor(r);
  const long double a = s - fs, b = r - fr;
  const int i0 = index(fs, t.w), i1 = index(fs + 1, t.w);
  const int j0 = index(fr, t.h), j1 = index(fr + 1, t.h);
  long double t00[4], t10[4], t01[4], t11[4];
  t.rgba(i0, j0, t00);
  t.rgba(i1, j0, t10);
  t.rgba(i0, j1, t01);
  t.rgba(i1, j1, t11);
  for (int c = 0; c < 4; ++c)
  {
    out[c] =
      ((1 - a) * (1 - b) * t00[c] + a * (1 - b) * t10[c] + (1 - a) * b * t01[c] + a * b * t11[c]) /
      255.0L;
  }
}

RasterVertex UV(RasterVertex v, float u, float tv)
{
  v.u = u;
  v.v = tv;
  return v;
}

TEST(Rasterizer, SampleTextureAtTexelCentresIsExact)
{
  // Power-of-two sizes: the texel centres (i + 0.5) / n are exact floats, so the result must be
  // the texel exactly (byte / 255 as a float); other sizes are within float rounding.
  const int sizes[5][2] = { { 4, 2 }, { 8, 4 }, { 1, 1 }, { 2, 8 }, { 5, 3 } };
  for (const int ch : { 1, 3, 4 })
  {
    for (const auto& size : sizes)
    {
      const Texels t(size[0], size[1], ch, 100u + static_cast<unsigned>(ch));
      const bool exact = (size[0] & (size[0] - 1)) == 0 && (size[1] & (size[1] - 1)) == 0;
      for (int repeat = 0; repeat < 2; ++repeat)
      {
        const TextureView view = t.view(repeat != 0);
        for (int j = 0; j < t.h; ++j)
        {
          for (int i = 0; i < t.w; ++i)
          {
            float got[4];
            sampleTexture(
              view, static_cast<float>((i + 0.5) / t.w), static_cast<float>((j + 0.5) / t.h), got);
            const std::uint8_t* p = t.texel(i, j);
            const float expected[4] = { (ch == 1 ? p[0] : p[0]) / 255.0f,
              (ch == 1 ? p[0] : p[1]) / 255.0f, (ch == 1 ? p[0] : p[2]) / 255.0f,
              ch == 4 ? p[3] / 255.0f : 1.0f };
            for (int c = 0; c < 4; ++c)
            {
              if (exact)
              {
                EXPECT_EQ(got[c], expected[c]) << "ch " << ch << " size " << t.w << "x" << t.h
                                               << " texel " << i << "," << j << " c" << c;
              }
              else
              {
                EXPECT_NEAR(got[c], expected[c], 1e-6)
                  << "ch " << ch << " texel " << i << "," << j << " c" << c;
              }
            }
          }
        }
      }
    }
  }
}

TEST(Rasterizer, SampleTextureBetweenTexelCentresIsTheBilinearAverage)
{
  const Texels t(4, 4, 4, 7);
  const TextureView view = t.view();
  for (int j = 0; j + 1 < t.h; ++j)
  {
    for (int i = 0; i + 1 < t.w; ++i)
    {
      const std::uint8_t* a = t.texel(i, j);
      const std::uint8_t* b = t.texel(i + 1, j);
      const std::uint8_t* c = t.texel(i, j + 1);
      const std::uint8_t* d = t.texel(i + 1, j + 1);
      float horizontal[4], vertical[4], centre[4], quarter[4];
      // All these coordinates are exact binary fractions.
      sampleTexture(view, (i + 1) / 4.0f, (j + 0.5f) / 4.0f, horizontal);
      sampleTexture(view, (i + 0.5f) / 4.0f, (j + 1) / 4.0f, vertical);
      sampleTexture(view, (i + 1) / 4.0f, (j + 1) / 4.0f, centre);
      // s = 4u - 0.5 = i + 0.25: a quarter of the way from texel i to i + 1.
      sampleTexture(view, (i + 0.75f) / 4.0f, (j + 0.5f) / 4.0f, quarter);
      for (int k = 0; k < 4; ++k)
      {
        EXPECT_FLOAT_EQ(horizontal[k], (a[k] + b[k]) / 510.0f) << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(vertical[k], (a[k] + c[k]) / 510.0f) << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(centre[k], (a[k] + b[k] + c[k] + d[k]) / 1020.0f)
          << i << "," << j << " c" << k;
        EXPECT_FLOAT_EQ(quarter[k], (0.75f * a[k] + 0.25f * b[k]) / 255.0f)
          << i << "," << j << " c" << k;
      }
    }
  }
}

TEST(Rasterizer, SampleTextureClampAndRepeatAtAndBeyondTheEdges)
{
  const Texels t(4, 2, 4, 8);
  const TextureView clamp = t.view(false), wrap = t.view(true);
  const float vRow0 = 0.25f; // centre of the bottom row
  float got[4];
  for (int k = 0; k < 4; ++k)
  {
    const std::uint8_t first = t.texel(0, 0)[k], last = t.texel(3, 0)[k];
    // Clamp: at the edge and anywhere beyond it, the edge texel.
    for (const float u : { 0.0f, 0.1f, -0.01f, -5.3f, -1e30f })
    {
      sampleTexture(clamp, u, vRow0, got);
      EXPECT_EQ(got[k], first / 255.0f) << "u " << u;
    }
    for (const float u : { 1.0f, 0.9f, 1.01f, 7.2f, 1e30f })
    {
      sampleTexture(clamp, u, vRow0, got);
      EXPECT_EQ(got[k], last / 255.0f) << "u " << u;
    }
    // Repeat: at u = 0 (or any integer) the first and last columns meet half-way.
    for (const float u : { 0.0f, 1.0f, -1.0f, 3.0f })
    {
      sampleTexture(wrap, u, vRow0, got);
      EXPECT_FLOAT_EQ(got[k], (first + last) / 510.0f) << "u " << u;
    }
    // Rows: clamp below / above, wrap between the top and bottom rows.
    const std::uint8_t bottom = t.texel(1, 0)[k], top = t.texel(1, 1)[k];
    sampleTexture(clamp, 0.375f, -2.0f, got);
    EXPECT_EQ(got[k], bottom / 255.0f);
    sampleTexture(clamp, 0.375f, 3.5f, got);
    EXPECT_EQ(got[k], top / 255.0f);
    sampleTexture(wrap, 0.375f, 0.0f, got);
    EXPECT_FLOAT_EQ(got[k], (bottom + top) / 510.0f);
    sampleTexture(wrap, 0.375f, 5.25f, got); // = v 0.25: the bottom row's centre
    EXPECT_EQ(got[k], bottom / 255.0f);
  }
  // Repeat is periodic: u and u + n sample the same.
  float a[4], b[4];
  sampleTexture(wrap, 0.3f, 0.6f, a);
  for (const float du : { 1.0f, -1.0f, 4.0f, -17.0f })
  {
    sampleTexture(wrap, 0.3f + du, 0.6f + du, b);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_NEAR(a[k], b[k], 1e-5) << "shift " << du;
    }
  }

  // Against the reference, anywhere in [-3, 3]^2, for each channel count, odd sizes and both
  // addressing modes.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uc(-3, 3);
  const int sizes[3][2] = { { 5, 3 }, { 4, 4 }, { 1, 3 } };
  for (const int ch : { 1, 3, 4 })
  {
    for (const auto& size : sizes)
    {
      const Texels tex(size[0], size[1], ch, 11u + static_cast<unsigned>(ch));
      for (int repeat = 0; repeat < 2; ++repeat)
      {
        for (int n = 0; n < 500; ++n)
        {
          const float u = uc(rng), v = uc(rng);
          long double ref[4];
          RefSample(tex, u, v, repeat != 0, ref);
          sampleTexture(tex.view(repeat != 0), u, v, got);
          for (int k = 0; k < 4; ++k)
          {
            EXPECT_NEAR(got[k], static_cast<double>(ref[k]), 1e-5)
              << "ch " << ch << " size " << size[0] << "x" << size[1] << " repeat " << repeat
              << " uv " << u << "," << v << " c" << k;
          }
        }
      }
    }
  }
  // Huge coordinates stay in range.
  for (int repeat = 0; repeat < 2; ++repeat)
  {
    sampleTexture(t.view(repeat != 0), 3e38f, -3e38f, got);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_TRUE(got[k] >= 0.0f && got[k] <= 1.0f);
    }
  }
}

TEST(Rasterizer, TextureRowsCountFromTheBottom)
{
  // 2x2 RGB: the bottom row (texel row 0, stored first) is red, the top row blue.
  const std::uint8_t bottomUp[12] = { 255, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0, 255 };
  // The same image stored top row first, addressed with a negative stride.
  const std::uint8_t topDown[12] = { 0, 0, 255, 0, 0, 255, 255, 0, 0, 255, 0, 0 };
  const TextureView views[2] = { TextureView{ bottomUp, 2, 2, 3, 6, false },
    TextureView{ topDown + 6, 2, 2, 3, -6, false } };
  for (const TextureView& view : views)
  {
    float got[4];
    sampleTexture(view, 0.5f, 0.05f, got); // v near 0: bottom
    EXPECT_EQ(got[0], 1.0f);
    EXPECT_EQ(got[2], 0.0f);
    sampleTexture(view, 0.3f, 0.25f, got);
    EXPECT_EQ(got[0], 1.0f);
    EXPECT_EQ(got[2], 0.0f);
    sampleTexture(view, 0.7f, 0.95f, got); // v near 1: top
    EXPECT_EQ(got[0], 0.0f);
    EXPECT_EQ(got[2], 1.0f);
    sampleTexture(view, 0.5f, 0.5f, got); // half-way
    EXPECT_FLOAT_EQ(got[0], 0.5f);
    EXPECT_FLOAT_EQ(got[2], 0.5f);
    EXPECT_EQ(got[1], 0.0f);
    EXPECT_EQ(got[3], 1.0f);

    // Drawn on a square whose bottom image edge has v = 0 and top edge v = 1: the image is
    // upright (red at the bottom rows, blue at the top rows: image y points down, v up).
    const int n = 16;
    Image img(n, n);
    const RasterVertex tl = UV(Vtx(-0.5, -0.5), 0, 1), tr = UV(Vtx(n - 0.5, -0.5), 1, 1),
                       br = UV(Vtx(n - 0.5, n - 0.5), 1, 0), bl = UV(Vtx(-0.5, n - 0.5), 0, 0);
    EXPECT_EQ(rasterizeTriangle(img.view(), tl, tr, br, nullptr, &view), RasterResult::Drawn);
    EXPECT_EQ(rasterizeTriangle(img.view(), tl, br, bl, nullptr, &view), RasterResult::Drawn);
    for (int x = 0; x < n; ++x)
    {
      for (int y : { 0, 1, 2, 3 })
      {
        EXPECT_EQ(img.at(x, y)[0], 0) << x << "," << y;
        EXPECT_EQ(img.at(x, y)[2], 255) << x << "," << y;
      }
      for (int y : { 12, 13, 14, 15 })
      {
        EXPECT_EQ(img.at(x, y)[0], 255) << x << "," << y;
        EXPECT_EQ(img.at(x, y)[2], 0) << x << "," << y;
      }
      EXPECT_EQ(img.at(x, 8)[3], 255);
    }
  }
}

// A textured triangle with white vertices shows the bilinear sample of the interpolated (u, v),
// checked at pixels whose values are worked out by hand.
TEST(Rasterizer, TexturedTriangleShowsTheBilinearTexelAtHandPickedPixels)
{
  // 2x2 RGBA, bottom row first: (0,0) red, (1,0) green, (0,1) blue, (1,1) white.
  const std::uint8_t texels[16] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255,
    255 };
  const TextureView tex{ texels, 2, 2, 4, 8, false };
  // Vertices on pixel centres: u = x / 64 and v = 1 - y / 64 at pixel (x, y), so the texel
  // coordinates are s = 2u - 0.5 = x / 32 - 0.5 and t = 2v - 0.5 = 1.5 - y / 32.
  const RasterVertex a = UV(Vtx(0, 0), 0, 1), b = UV(Vtx(64, 0), 1, 1), c = UV(Vtx(0, 64), 0, 0);
  struct Expect
  {
    int x, y;
    double rgb[3]; // exact value on the 0..255 scale
  };
  const Expect expected[] = {
    // s = 0, t = 1: texel (0, 1), blue.
    { 16, 16, { 0, 0, 255 } },
    // s = 0.5, t = 1: half blue, half white.
    { 32, 16, { 127.5, 127.5, 255 } },
    // s = -0.25, t = 1.25: clamped to texel (0, 1).
    { 8, 8, { 0, 0, 255 } },
    // s = 0.25, t = 0.75: weights red 0.75*0.25, green 0.25*0.25, blue 0.75*0.75, white
    // 0.25*0.75 -> r = 255 (0.1875 + 0.1875), g = 255 (0.0625 + 0.1875), b = 255 (0.5625 + 0.1875).
    { 24, 24, { 95.625, 63.75, 191.25 } },
    // s = 0.125, t = 0.375: red 0.875*0.625, green 0.125*0.625, blue 0.875*0.375, white
    // 0.125*0.375 -> r = 255 * 0.59375, g = 255 * 0.125, b = 255 * 0.375.
    { 20, 36, { 151.40625, 31.875, 95.625 } },
    // s = -0.5 (clamped to 0), t = -0.4375 (clamped to 0): texel (0, 0), red.
    { 0, 62, { 255, 0, 0 } },
    // s = 1.3125 (clamped to 1), t = 1.5 (clamped to 1): texel (1, 1), white.
    { 58, 0, { 255, 255, 255 } },
  };
  for (int order = 0; order < 2; ++order)
  {
    Image img(64, 64);
    img.pattern(21); // opaque texels overwrite whatever is there
    if (order == 0)
    {
      EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, nullptr, &tex), RasterResult::Drawn);
    }
    else
    {
      EXPECT_EQ(rasterizeTriangle(img.view(), c, b, a, nullptr, &tex), RasterResult::Drawn);
    }
    for (const Expect& e : expected)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_TRUE(ByteMatches(e.rgb[k], img.at(e.x, e.y)[k]))
          << "pixel " << e.x << "," << e.y << " c" << k << " expected " << e.rgb[k] << " got "
          << static_cast<int>(img.at(e.x, e.y)[k]);
      }
      EXPECT_EQ(img.at(e.x, e.y)[3], 255);
    }
  }
}

// Random triangles, textures, (u, v), colours and alpha against the reference: the drawn colour
// is the barycentric colour times the bilinear texel of the barycentric (u, v).
TEST(Rasterizer, TexturedColourIsTheModulatedBilinearSample)
{
  const int w = 40, h = 32;
  Image img(w, h);
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> uc(-0.2f, 1.2f), ua(0.0f, 1.0f), ut(-1.5f, 2.5f);
  int checked = 0, bad = 0;
  std::string firstBad;
  for (int n = 0; n < 300; ++n)
  {
    GridPt t[3];
    RandomTriangle(rng, w, h, t);
    if (Orient(t[0], t[1], t[2]) == 0)
    {
      continue;
    }
    const int ch = n % 3 == 0 ? 1 : (n % 3 == 1 ? 3 : 4);
    const Texels tex(2 + n % 4, 1 + n % 5, ch, static_cast<unsigned>(n));
    const bool repeat = (n / 3) % 2 == 0;
    const TextureView view = tex.view(repeat);
    float col[3][4], uv[3][2];
    RasterVertex v[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        col[i][c] = (n % 5 == 0) ? 1.0f : uc(rng); // some white
      }
      col[i][3] = (n % 2 == 0) ? 1.0f : ua(rng);
      uv[i][0] = ut(rng);
      uv[i][1] = ut(rng);
      v[i] = UV(Vtx(t[i], col[i][0], col[i][1], col[i][2], col[i][3]), uv[i][0], uv[i][1]);
    }
    // On a transparent black target: out.rgb = 255 c a, out.a = 255 a.
    img.fill(0);
    rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &view);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        if (!RefCovered(t, x, y))
        {
          EXPECT_EQ(img.at(x, y)[3], 0);
          continue;
        }
        long double l[3];
        RefBarycentric(t, x, y, l);
        long double value[4] = { 0, 0, 0, 0 }, u = 0, tv = 0;
        for (int i = 0; i < 3; ++i)
        {
          for (int c = 0; c < 4; ++c)
          {
            value[c] += l[i] * std::min(1.0L, std::max(0.0L, static_cast<long double>(col[i][c])));
          }
          u += l[i] * uv[i][0];
          tv += l[i] * uv[i][1];
        }
        long double texel[4];
        RefSample(tex, u, tv, repeat, texel);
        for (int c = 0; c < 4; ++c)
        {
          value[c] *= texel[c];
        }
        const long double expected[4] = { 255 * value[0] * value[3], 255 * value[1] * value[3],
          255 * value[2] * value[3], 255 * value[3] };
        for (int c = 0; c < 4; ++c)
        {
          ++checked;
          if (std::fabs(static_cast<long double>(img.at(x, y)[c]) - expected[c]) > 1.0L)
          {
            if (!bad)
            {
              std::ostringstream os;
              os << "triangle " << n << " pixel " << x << "," << y << " channel " << c
                 << " expected " << static_cast<double>(expected[c]) << " got "
                 << static_cast<int>(img.at(x, y)[c]);
              firstBad = os.str();
            }
            ++bad;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_EQ(bad, 0) << firstBad;
}

TEST(Rasterizer, TexturedModulationByColourAndAlpha)
{
  const int w = 12, h = 10;
  Image img(w, h);
  img.pattern(31);
  const Image before = img;
  // One RGBA texel: the sample is that texel everywhere.
  const std::uint8_t texel[4] = { 200, 100, 50, 128 };
  const TextureView tex{ texel, 1, 1, 4, 4, true };
  const float col[4] = { 0.5f, 1.0f, 0.25f, 0.8f };
  const RasterVertex v[3] = { UV(Vtx(-20, -20, col[0], col[1], col[2], col[3]), 0.3f, 0.1f),
    UV(Vtx(60, -20, col[0], col[1], col[2], col[3]), 5.0f, -2.0f),
    UV(Vtx(-20, 60, col[0], col[1], col[2], col[3]), -3.0f, 0.7f) };
  EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &tex), RasterResult::Drawn);
  // src = colour * texel / 255, alpha = 0.8 * 128 / 255, then source-over.
  const long double alpha = 0.8L * 128.0L / 255.0L;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 4; ++c)
      {
        const long double src = c < 3 ? static_cast<long double>(col[c]) * texel[c] / 255.0L : 1;
        const long double exact = 255 * src * alpha + before.at(x, y)[c] * (1 - alpha);
        EXPECT_LE(std::fabs(exact - img.at(x, y)[c]), 1.0L)
          << x << "," << y << " c" << c << " exact " << static_cast<double>(exact) << " got "
          << static_cast<int>(img.at(x, y)[c]);
      }
    }
  }

  // Grey texture: r = g = b = L, alpha 1; with opaque vertices it overwrites:
  // out = round(255 * colour * L / 255) = round(colour * L), alpha 255.
  const std::uint8_t grey = 90;
  const TextureView greyTex{ &grey, 1, 1, 1, 1, false };
  const float c2[3] = { 1.0f, 0.5f, 0.2f };
  img = before;
  rasterizeTriangle(img.view(), Vtx(-20, -20, c2[0], c2[1], c2[2], 1),
    Vtx(60, -20, c2[0], c2[1], c2[2], 1), Vtx(-20, 60, c2[0], c2[1], c2[2], 1), nullptr, &greyTex);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      EXPECT_EQ(img.at(x, y)[0], 90);
      EXPECT_EQ(img.at(x, y)[1], 45);
      EXPECT_EQ(img.at(x, y)[2], 18);
      EXPECT_EQ(img.at(x, y)[3], 255);
    }
  }
  // A transparent texel leaves the target unchanged; a transparent vertex colour too.
  const std::uint8_t clear[4] = { 255, 255, 255, 0 };
  const TextureView clearTex{ clear, 1, 1, 4, 4, false };
  img = before;
  rasterizeTriangle(img.view(), Vtx(-20, -20), Vtx(60, -20), Vtx(-20, 60), nullptr, &clearTex);
  EXPECT_EQ(img.buf, before.buf);
  rasterizeTriangle(img.view(), Vtx(-20, -20, 1, 1, 1, 0), Vtx(60, -20, 1, 1, 1, 0),
    Vtx(-20, 60, 1, 1, 1, 0), nullptr, &greyTex);
  EXPECT_EQ(img.buf, before.buf);
}

TEST(Rasterizer, TexturedNegativeRowStrideMatchesTheFlippedTexture)
{
  const int w = 37, h = 29;
  auto scene = RandomScene(51, w, h, 200);
  std::mt19937 rng(52);
  std::uniform_real_distribution<float> ut(-1.2f, 2.2f);
  for (auto& t : scene)
  {
    for (auto& v : t.v)
    {
      v.u = ut(rng);
      v.v = ut(rng);
    }
  }
  for (const int ch : { 1, 3, 4 })
  {
    for (int repeat = 0; repeat < 2; ++repeat)
    {
      const int tw = 5, th = 4, pad = 3; // rows padded: stride != width * channels
      const std::ptrdiff_t stride = tw * ch + pad;
      std::vector<std::uint8_t> up(static_cast<std::size_t>(stride * th), 0xAB);
      std::vector<std::uint8_t> down(up.size(), 0xCD);
      std::mt19937 trng(53u + static_cast<unsigned>(ch));
      for (int j = 0; j < th; ++j)
      {
        for (int k = 0; k < tw * ch; ++k)
        {
          const std::uint8_t b = static_cast<std::uint8_t>(trng() & 0xFF);
          up[static_cast<std::size_t>(j * stride + k)] = b;              // row j from the start
          down[static_cast<std::size_t>((th - 1 - j) * stride + k)] = b; // row j from the end
        }
      }
      const TextureView tUp{ up.data(), tw, th, ch, stride, repeat != 0 };
      const TextureView tDown{ down.data() + (th - 1) * stride, tw, th, ch, -stride, repeat != 0 };
      Image a(w, h), b(w, h);
      a.pattern(54);
      b.buf = a.buf;
      Depth da(w, h), db(w, h);
      const DepthView dva = da.view(), dvb = db.view();
      int drawn = 0;
      for (const auto& t : scene)
      {
        const RasterResult ra = rasterizeTriangle(a.view(), t.v[0], t.v[1], t.v[2], &dva, &tUp);
        const RasterResult rb = rasterizeTriangle(b.view(), t.v[0], t.v[1], t.v[2], &dvb, &tDown);
        EXPECT_EQ(ra, rb);
        drawn += ra == RasterResult::Drawn ? 1 : 0;
      }
      EXPECT_GT(drawn, 100);
      EXPECT_EQ(a.buf, b.buf) << "channels " << ch << " repeat " << repeat;
      EXPECT_EQ(da.buf, db.buf);
      // And the texture really is sampled: the picture differs from an untextured drawing.
      Image plain(w, h);
      plain.pattern(54);
      for (const auto& t : scene)
      {
        rasterizeTriangle(plain.view(), t.v[0], t.v[1], t.v[2]);
      }
      EXPECT_NE(plain.buf, a.buf);
    }
  }
}

TEST(Rasterizer, InvalidTexturesAreRejected)
{
  Image img(16, 16);
  img.pattern(61);
  const Image before = img;
  Depth depth(16, 16);
  const std::vector<float> depthBefore = depth.buf;
  const DepthView dv = depth.view();
  const std::uint8_t texels[16] = {};
  const TextureView good{ texels, 2, 2, 4, 8, false };
  TextureView bad[8] = { good, good, good, good, good, good, good, good };
  bad[0].data = nullptr;
  bad[1].width = 0;
  bad[2].height = 0;
  bad[3].width = -2;
  bad[4].height = -1;
  bad[5].channels = 0;
  bad[6].channels = 2;
  bad[7].channels = 5;
  const RasterVertex a = Vtx(0, 0), b = Vtx(15, 0), c = Vtx(0, 15);
  for (int k = 0; k < 8; ++k)
  {
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, nullptr, &bad[k]), RasterResult::InvalidInput)
      << k;
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, &dv, &bad[k]), RasterResult::InvalidInput)
      << k;
    EXPECT_EQ(rasterizeTriangle(img.view(), a, b, c, PixelRect{ 0, 0, 8, 8 }, nullptr, &bad[k]),
      RasterResult::InvalidInput)
      << k;
    // InvalidInput comes before the other outcomes.
    EXPECT_EQ(rasterizeTriangle(img.view(), a, a, a, nullptr, &bad[k]), RasterResult::InvalidInput);
    EXPECT_EQ(rasterizeTriangle(img.view(), Vtx(0, 0), Vtx(1e7, 0), c, nullptr, &bad[k]),
      RasterResult::InvalidInput);
    float rgba[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
    sampleTexture(bad[k], 0.5f, 0.5f, rgba);
    for (float x : rgba)
    {
      EXPECT_EQ(x, 0.0f) << k;
    }
  }
  // Non-finite texture coordinates, with or without a texture (every vertex field must be
  // finite, as for the depth).
  const float values[3] = { std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity() };
  for (float value : values)
  {
    for (int vi = 0; vi < 3; ++vi)
    {
      for (int field = 0; field < 2; ++field)
      {
        RasterVertex v[3] = { a, b, c };
        (field == 0 ? v[vi].u : v[vi].v) = value;
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2], nullptr, &good),
          RasterResult::InvalidInput);
        EXPECT_EQ(
          rasterizeTriangle(img.view(), v[0], v[1], v[2], &dv, &good), RasterResult::InvalidInput);
        EXPECT_EQ(rasterizeTriangle(img.view(), v[0], v[1], v[2]), RasterResult::InvalidInput);
      }
    }
    float rgba[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
    sampleTexture(good, value, 0.5f, rgba);
    EXPECT_EQ(rgba[0], 0.0f);
    EXPECT_EQ(rgba[3], 0.0f);
    sampleTexture(good, 0.5f, value, rgba);
    EXPECT_EQ(rgba[1], 0.0f);
  }
  EXPECT_EQ(img.buf, before.buf);
  EXPECT_EQ(depth.buf, depthBefore);
  // A null texture is the untextured drawing.
  Image x(16, 16), y(16, 16);
  rasterizeTriangle(x.view(), Vtx(1, 1, 0.2f, 0.4f, 0.6f, 0.7f), Vtx(14, 3, 0.9f, 0.1f, 0, 1),
    Vtx(4, 13, 0, 1, 0.5f, 0.3f), nullptr, nullptr);
  rasterizeTriangle(y.view(), Vtx(1, 1, 0.2f, 0.4f, 0.6f, 0.7f), Vtx(14, 3, 0.9f, 0.1f, 0, 1),
    Vtx(4, 13, 0, 1, 0.5f, 0.3f));
  EXPECT_EQ(x.buf, y.buf);
  EXPECT_GT(CountNonZeroAlpha(x), 20);
}

// The textured path covers, clips and depth-tests exactly like the untextured one.
TEST(Rasterizer, TexturedCoverageClipAndDepthMatchTheUntexturedRules)
{
  // Coverage against the brute-force reference: an opaque RGB texture on a transparent image
  // sets alpha 255 exactly on the covered pixels.
  {
    std::mt19937 rng(71);
    std::uniform_real_distribution<float> ut(-2, 3);
    const int w = 48, h = 40;
    Image img(w, h);
    const Texels tex(3, 3, 3, 72);
    int totalBad = 0, drawn = 0;
    std::string firstBad;
    for (int n = 0; n < 2000; ++n)
    {
      GridPt t[3];
      RandomTriangle(rng, w, h, t);
      img.fill(0);
      const TextureView view = tex.view(n % 2 == 0);
      const RasterResult res = rasterizeTriangle(img.view(), UV(Vtx(t[0]), ut(rng), ut(rng)),
        UV(Vtx(t[1]), ut(rng), ut(rng)), UV(Vtx(t[2]), ut(rng), ut(rng)), nullptr, &view);
      std::string bad;
      const auto cmp = CompareCoverage(img, t, &bad);
      if (cmp.first && firstBad.empty())
      {
        firstBad = bad;
      }
      totalBad += cmp.first;
      const RasterResult expected = Orient(t[0], t[1], t[2]) == 0
        ? RasterResult::Degenerate
        : (cmp.second == 0 ? RasterResult::Empty : RasterResult::Drawn);
      EXPECT_EQ(res, expected) << "triangle " << n;
      drawn += res == RasterResult::Drawn ? 1 : 0;
    }
    EXPECT_EQ(totalBad, 0) << firstBad;
    EXPECT_GT(drawn, 1000);
  }

  // Clip tiles give the same picture and depth as the whole image.
  const int w = 61, h = 47;
  auto scene = RandomScene(73, w, h, 400);
  std::mt19937 rng(74);
  std::uniform_real_distribution<float> ut(-1, 2);
  for (auto& t : scene)
  {
    for (auto& v : t.v)
    {
      v.u = ut(rng);
      v.v = ut(rng);
    }
  }
  const Texels tex(7, 5, 4, 75);
  const TextureView view = tex.view(true);
  Image whole(w, h), tiled(w, h);
  whole.pattern(76);
  tiled.buf = whole.buf;
  Depth dWhole(w, h, 0.8f), dTiled(w, h, 0.8f);
  const DepthView dvWhole = dWhole.view(), dvTiled = dTiled.view();
  for (const auto& t : scene)
  {
    rasterizeTriangle(whole.view(), t.v[0], t.v[1], t.v[2], &dvWhole, &view);
  }
  const int tw = 16, th = 12;
  for (int ty = 0; ty < h; ty += th)
  {
    for (int tx = 0; tx < w; tx += tw)
    {
      const PixelRect clip{ tx, ty, std::min(tx + tw, w), std::min(ty + th, h) };
      for (const auto& t : scene)
      {
        rasterizeTriangle(tiled.view(), t.v[0], t.v[1], t.v[2], clip, &dvTiled, &view);
      }
    }
  }
  EXPECT_EQ(whole.buf, tiled.buf);
  EXPECT_EQ(dWhole.buf, dTiled.buf);
  // Pixels outside a clip rectangle are untouched.
  {
    Image part(w, h);
    part.pattern(77);
    const Image background = part;
    const PixelRect clip{ 13, 9, 40, 31 };
    const RasterVertex a = UV(Vtx(-3.3, 2.2, 0.9f, 0.2f, 0.1f, 0.6f), 0, 0);
    const RasterVertex b = UV(Vtx(70.1, 10.4, 0.1f, 0.8f, 0.3f, 1.0f), 2, 0);
    const RasterVertex c = UV(Vtx(20.7, 52.9, 0.4f, 0.4f, 0.9f, 0.8f), 0, 2);
    Image ref = background;
    rasterizeTriangle(ref.view(), a, b, c, nullptr, &view);
    EXPECT_EQ(rasterizeTriangle(part.view(), a, b, c, clip, nullptr, &view), RasterResult::Drawn);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        const bool in = x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1;
        const Image& expected = in ? ref : background;
        EXPECT_TRUE(std::equal(part.at(x, y), part.at(x, y) + 4, expected.at(x, y)))
          << "pixel " << x << "," << y;
      }
    }
  }

  // The depth test and the depth written are those of the untextured drawing.
  Image plain(w, h);
  Depth dPlain(w, h, 0.8f);
  const DepthView dvPlain = dPlain.view();
  for (const auto& t : scene)
  {
    rasterizeTriangle(plain.view(), t.v[0], t.v[1], t.v[2], &dvPlain);
  }
  EXPECT_EQ(dPlain.buf, dWhole.buf);

  // Two textured triangles with depth against the reference: A (red texture) slopes from depth
  // 0 to 1, B (blue texture) is flat at 0.5; in both drawing orders the nearer one is shown.
  const GridPt ta[3] = { SnapRef(-5, -5), SnapRef(45, -5), SnapRef(-5, 35) };
  const float za[3] = { 0.0f, 1.0f, 0.0f };
  const GridPt tb[3] = { SnapRef(-5, -5), SnapRef(45, 35), SnapRef(-5, 35) };
  const std::uint8_t red[3] = { 255, 0, 0 }, blue[3] = { 0, 0, 255 };
  const TextureView redTex{ red, 1, 1, 3, 3, false }, blueTex{ blue, 1, 1, 3, 3, true };
  for (int order = 0; order < 2; ++order)
  {
    Image img(40, 30);
    Depth depth(40, 30);
    const DepthView dv = depth.view();
    for (int k = 0; k < 2; ++k)
    {
      if ((k == 0) == (order == 0))
      {
        rasterizeTriangle(img.view(), UV(Vtx(ta[0], 1, 1, 1, 1, za[0]), 0, 0),
          UV(Vtx(ta[1], 1, 1, 1, 1, za[1]), 1, 0), UV(Vtx(ta[2], 1, 1, 1, 1, za[2]), 0, 1), &dv,
          &redTex);
      }
      else
      {
        rasterizeTriangle(img.view(), UV(Vtx(tb[0], 1, 1, 1, 1, 0.5f), 3, 0),
          UV(Vtx(tb[1], 1, 1, 1, 1, 0.5f), 0, 4), UV(Vtx(tb[2], 1, 1, 1, 1, 0.5f), 1, 1), &dv,
          &blueTex);
      }
    }
    int nearA = 0, nearB = 0;
    for (int y = 0; y < 30; ++y)
    {
      for (int x = 0; x < 40; ++x)
      {
        const bool inA = RefCovered(ta, x, y), inB = RefCovered(tb, x, y);
        long double l[3];
        RefBarycentric(ta, x, y, l);
        const long double zA = l[0] * za[0] + l[1] * za[1] + l[2] * za[2];
        const std::uint8_t* p = img.at(x, y);
        bool expectA = inA;
        if (inA && inB)
        {
          if (std::fabs(zA - 0.5L) < 1e-4L)
          {
            continue; // too close to call in float
          }
          expectA = zA < 0.5L;
        }
        if (expectA)
        {
          ++nearA;
          EXPECT_TRUE(p[0] == 255 && p[2] == 0) << "order " << order << " pixel " << x << "," << y;
          EXPECT_NEAR(depth.at(x, y), static_cast<double>(zA), 1e-5);
        }
        else if (inB)
        {
          ++nearB;
          EXPECT_TRUE(p[0] == 0 && p[2] == 255) << "order " << order << " pixel " << x << "," << y;
          EXPECT_FLOAT_EQ(depth.at(x, y), 0.5f);
        }
        else
        {
          EXPECT_EQ(p[3], 0);
        }
      }
    }
    EXPECT_GT(nearA, 100);
    EXPECT_GT(nearB, 100);
  }

  // Strictly less: the same half-transparent textured triangle drawn twice blends once with the
  // depth test (alpha 128) and twice without it (alpha 192).
  const std::uint8_t half[4] = { 255, 255, 255, 255 };
  const TextureView halfTex{ half, 1, 1, 4, 4, false };
  const RasterVertex t3[3] = { Vtx(1, 1, 1, 1, 1, 0.5f, 0.25f), Vtx(9, 2, 1, 1, 1, 0.5f, 0.75f),
    Vtx(3, 8, 1, 1, 1, 0.5f, 0.5f) };
  Image once(12, 12), twice(12, 12);
  Depth depth(12, 12);
  const DepthView dv = depth.view();
  for (int k = 0; k < 2; ++k)
  {
    rasterizeTriangle(once.view(), t3[0], t3[1], t3[2], &dv, &halfTex);
    rasterizeTriangle(twice.view(), t3[0], t3[1], t3[2], nullptr, &halfTex);
  }
  int drawn = 0;
  for (int y = 0; y < 12; ++y)
  {
    for (int x = 0; x < 12; ++x)
    {
      if (once.at(x, y)[3] != 0)
      {
        ++drawn;
        EXPECT_EQ(once.at(x, y)[3], 128);
        EXPECT_EQ(twice.at(x, y)[3], 192);
      }
      else
      {
        EXPECT_EQ(twice.at(x, y)[3], 0);
      }
    }
  }
  EXPECT_GT(drawn, 15);
}
}

// ---------------------------------------------------------------------------------------------
// Triangle ids.

namespace
{
struct Ids
{
  int w = 0;
  int h = 0;
  std::vector<RasterId> buf;

  Ids(int width, int height)
    : w(width)
    , h(height)
    , buf(static_cast<std::size_t>(width * height), -1)
  {
  }

  IdView view() { return IdView{ buf.data(), w, h, w }; }

  IdView flippedView()
  {
    return IdView{ buf.data() + static_cast<std::ptrdiff_t>(w) * (h - 1), w, h, -w };
  }

  RasterId at(int x, int y) const { return buf[static_cast<std::size_t>(y) * w + x]; }
};
} // namespace

TEST(Rasterizer, IdBufferHoldsTheLastTriangleDrawnInEachPixel)
{
  // Random triangles drawn in sequence, with ids: each pixel's id is that of the last triangle
  // (in draw order) that covers it per the reference coverage, -1 where none does; the image
  // drawn with ids is the image drawn without them. Gouraud, flat, transparent and textured
  // triangles, with and without a depth buffer.
  const int w = 48, h = 36;
  std::mt19937 rng(4711);
  Texels tex(5, 4, 4, 99);
  const TextureView tv = tex.view();
  for (int round = 0; round < 40; ++round)
  {
    const bool useDepth = round % 2 == 1;
    Image plain(w, h), withIds(w, h);
    Depth dPlain(w, h), dIds(w, h);
    const DepthView dvPlain = dPlain.view(), dvIds = dIds.view();
    Ids ids(w, h);
    const IdView iv = round % 4 < 2 ? ids.view() : ids.flippedView();
    std::vector<std::array<GridPt, 3>> tris;
    std::vector<float> depths;
    for (int k = 0; k < 6; ++k)
    {
      std::array<GridPt, 3> t;
      RandomTriangle(rng, w, h, t.data());
      const int kind = std::uniform_int_distribution<int>(0, 3)(rng);
      const float z = std::uniform_real_distribution<float>(0.1f, 1.0f)(rng);
      RasterVertex v[3];
      for (int i = 0; i < 3; ++i)
      {
        const float c = kind == 1 ? 0.5f : 0.2f * static_cast<float>(i + 1);
        v[i] = Vtx(t[i], c, 1 - c, 0.3f, kind == 2 ? 0.4f : 1.0f, z);
        v[i].u = 0.3f * static_cast<float>(i);
        v[i].v = 0.5f;
      }
      const TextureView* texture = kind == 3 ? &tv : nullptr;
      const RasterResult r1 =
        rasterizeTriangle(plain.view(), v[0], v[1], v[2], useDepth ? &dvPlain : nullptr, texture);
      const RasterResult r2 = rasterizeTriangle(
        withIds.view(), v[0], v[1], v[2], useDepth ? &dvIds : nullptr, texture, &iv, 1000 + k);
      EXPECT_EQ(r1, r2);
      tris.push_back(t);
      depths.push_back(z);
    }
    ASSERT_EQ(plain.buf, withIds.buf) << "round " << round;
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        // Expected: the last covering triangle (painter), or the nearest one, the first drawn
        // among equal depths (strict depth test).
        RasterId expected = -1;
        float best = std::numeric_limits<float>::infinity();
        for (int k = 0; k < static_cast<int>(tris.size()); ++k)
        {
          if (!RefCovered(tris[k].data(), x, y))
          {
            continue;
          }
          if (!useDepth)
          {
            expected = 1000 + k;
          }
          else if (depths[k] < best)
          {
            best = depths[k];
            expected = 1000 + k;
          }
        }
        const int row = round % 4 < 2 ? y : h - 1 - y;
        ASSERT_EQ(ids.at(x, row), expected) << "round " << round << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(Rasterizer, InvalidIdBuffersAreRejected)
{
  Image img(10, 10);
  Ids small(9, 10);
  const IdView sv = small.view();
  IdView none = sv;
  none.data = nullptr;
  const RasterVertex a = Vtx(0, 0), b = Vtx(9, 0), c = Vtx(0, 9);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), a, b, c, nullptr, nullptr, &sv, 1), RasterResult::InvalidInput);
  EXPECT_EQ(
    rasterizeTriangle(img.view(), a, b, c, nullptr, nullptr, &none, 1), RasterResult::InvalidInput);
  EXPECT_EQ(CountNonZeroAlpha(img), 0);
  for (RasterId v : small.buf)
  {
    EXPECT_EQ(v, -1);
  }
}

// ---------------------------------------------------------------------------------------------
// Batches: snapToGrid, rasterizeSnappedTriangle, coveredPixelBounds.

TEST(Rasterizer, SnapToGridIsTheDocumentedRounding)
{
  EXPECT_EQ(snapToGrid(0.0), 0);
  EXPECT_EQ(snapToGrid(1.0), 256);
  EXPECT_EQ(snapToGrid(-1.0), -256);
  EXPECT_EQ(snapToGrid(0.5 / 256), 1);   // exact half: up
  EXPECT_EQ(snapToGrid(-0.5 / 256), 0);  // exact half: up, towards +inf
  EXPECT_EQ(snapToGrid(-1.5 / 256), -1); // likewise
  EXPECT_EQ(snapToGrid(kRasterGuardBand), 1 << 28);
  EXPECT_EQ(snapToGrid(-kRasterGuardBand), -(1 << 28));
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-kRasterGuardBand, kRasterGuardBand), small(-3, 3);
  for (int i = 0; i < 100000; ++i)
  {
    const double c = i % 2 ? u(rng) : small(rng);
    ASSERT_EQ(snapToGrid(c), SnapRef(c, 0).x) << c;
  }
}

TEST(Rasterizer, SnappedTrianglesDrawExactlyAsRasterizeTriangle)
{
  // Random scenes drawn twice, once with rasterizeTriangle and once with the vertices snapped
  // first (snapToGrid) and rasterizeSnappedTriangle: same pixels, depths, ids and results, with
  // and without depth (written or read-only), ids and textures of each channel count, over the
  // whole image and tile by tile (uneven tiles and 32-row bands), with either row order.
  const int w = 61, h = 83;
  const std::vector<Texels> textures{ Texels(7, 5, 1, 1), Texels(6, 9, 3, 2), Texels(8, 8, 4, 3) };
  for (int round = 0; round < 48; ++round)
  {
    const bool useDepth = round % 2 == 1;
    const bool readOnly = round % 4 == 3;
    const bool useIds = round % 3 == 0;
    const int texture = round % 8 < 4 ? -1 : round % 3;
    const bool flipped = round % 5 == 0;
    const int tiling = round % 3; // whole image, uneven tiles, 32-row bands
    auto scene = RandomScene(100 + round, w, h, 150);
    std::mt19937 rng(round);
    std::uniform_real_distribution<float> ut(-0.3f, 1.3f);
    for (auto& t : scene)
    {
      for (auto& v : t.v)
      {
        v.u = ut(rng);
        v.v = ut(rng);
      }
    }
    const TextureView tv = texture >= 0 ? textures[texture].view(round % 2 == 0) : TextureView{};
    Image a(w, h), b(w, h);
    a.pattern(round);
    b.buf = a.buf;
    Depth da(w, h, 0.9f), db(w, h, 0.9f);
    DepthView dva = flipped ? da.flippedView() : da.view();
    DepthView dvb = flipped ? db.flippedView() : db.view();
    dva.write = dvb.write = !readOnly;
    Ids ia(w, h), ib(w, h);
    const IdView iva = ia.view(), ivb = ib.view();
    std::vector<PixelRect> tiles;
    if (tiling == 0)
    {
      tiles.push_back(PixelRect{ 0, 0, w, h });
    }
    for (int ty = 0; tiling != 0 && ty < h; ty += tiling == 1 ? 13 : 32)
    {
      for (int tx = 0; tx < w; tx += tiling == 1 ? 17 : w)
      {
        tiles.push_back(PixelRect{ tx, ty, std::min(w, tx + (tiling == 1 ? 17 : w)),
          std::min(h, ty + (tiling == 1 ? 13 : 32)) });
      }
    }
    for (std::size_t k = 0; k < scene.size(); ++k)
    {
      const RasterVertex* v = scene[k].v;
      SnappedTriangle s;
      for (int i = 0; i < 3; ++i)
      {
        s.x[i] = snapToGrid(v[i].x);
        s.y[i] = snapToGrid(v[i].y);
        s.rgba[i][0] = v[i].r;
        s.rgba[i][1] = v[i].g;
        s.rgba[i][2] = v[i].b;
        s.rgba[i][3] = v[i].a;
        s.depth[i] = v[i].depth;
        s.u[i] = v[i].u;
        s.v[i] = v[i].v;
      }
      for (const PixelRect& tile : tiles)
      {
        const RasterResult ra = rasterizeTriangle(flipped ? a.flippedView() : a.view(), v[0], v[1],
          v[2], tile, useDepth ? &dva : nullptr, texture >= 0 ? &tv : nullptr,
          useIds ? &iva : nullptr, static_cast<RasterId>(k));
        const RasterResult rb = rasterizeSnappedTriangle(flipped ? b.flippedView() : b.view(), s,
          tile, useDepth ? &dvb : nullptr, texture >= 0 ? &tv : nullptr, useIds ? &ivb : nullptr,
          static_cast<RasterId>(k));
        ASSERT_EQ(ra, rb) << "round " << round << " triangle " << k;
      }
    }
    ASSERT_EQ(a.buf, b.buf) << "round " << round;
    ASSERT_EQ(da.buf, db.buf) << "round " << round;
    ASSERT_EQ(ia.buf, ib.buf) << "round " << round;
  }
}

TEST(Rasterizer, CoveredPixelBoundsHoldEveryCoveredPixel)
{
  // Against the reference coverage: the bounds hold every covered centre of the clip rectangle;
  // they are exactly the covered centres' bounding box (empty when none) whenever the centres of
  // the clip rectangle inside the triangle's bounding box span at most 2 x 2 pixels, and empty
  // for a degenerate triangle. Tiny triangles (most of a detailed mesh seen in the mirror),
  // large ones, clip rectangles cutting them, either winding.
  const int w = 40, h = 30;
  std::mt19937 rng(2024);
  int exact = 0, exactEmpty = 0, coarse = 0;
  for (int n = 0; n < 30000; ++n)
  {
    GridPt t[3];
    if (n % 3 == 0)
    {
      RandomTriangle(rng, w, h, t);
    }
    else
    {
      // Within about a pixel of a random point, often on centres or half pixels.
      const double cx = std::uniform_real_distribution<double>(-2, w + 2)(rng);
      const double cy = std::uniform_real_distribution<double>(-2, h + 2)(rng);
      const double r = n % 3 == 1 ? 0.7 : 1.6;
      for (auto& p : t)
      {
        p.x = RandomCoord(rng, cx - r, cx + r);
        p.y = RandomCoord(rng, cy - r, cy + r);
      }
      if (n % 17 == 0)
      {
        t[2] = t[1]; // degenerate
      }
    }
    PixelRect clip{ 0, 0, w, h };
    if (n % 4 == 3)
    {
      clip = PixelRect{ std::uniform_int_distribution<int>(-3, w / 2)(rng),
        std::uniform_int_distribution<int>(-3, h / 2)(rng),
        std::uniform_int_distribution<int>(w / 2, w + 3)(rng),
        std::uniform_int_distribution<int>(h / 2, h + 3)(rng) };
    }
    const std::int32_t x[3] = { static_cast<std::int32_t>(t[0].x),
      static_cast<std::int32_t>(t[1].x), static_cast<std::int32_t>(t[2].x) };
    const std::int32_t y[3] = { static_cast<std::int32_t>(t[0].y),
      static_cast<std::int32_t>(t[1].y), static_cast<std::int32_t>(t[2].y) };
    const PixelRect got = coveredPixelBounds(x, y, clip);
    // The centres inside the triangle's bounding box and the clip rectangle.
    const auto floorDiv = [](std::int64_t a) {
      return static_cast<int>(std::floor(static_cast<double>(a) / 256.0));
    };
    const auto ceilDiv = [](std::int64_t a) {
      return static_cast<int>(std::ceil(static_cast<double>(a) / 256.0));
    };
    const int bx0 = std::max(clip.x0, ceilDiv(std::min({ t[0].x, t[1].x, t[2].x })));
    const int by0 = std::max(clip.y0, ceilDiv(std::min({ t[0].y, t[1].y, t[2].y })));
    const int bx1 = std::min(clip.x1 - 1, floorDiv(std::max({ t[0].x, t[1].x, t[2].x })));
    const int by1 = std::min(clip.y1 - 1, floorDiv(std::max({ t[0].y, t[1].y, t[2].y })));
    PixelRect ref{ bx1 + 1, by1 + 1, bx0, by0 }; // bounding box of the covered centres
    int covered = 0;
    for (int py = by0; py <= by1; ++py)
    {
      for (int px = bx0; px <= bx1; ++px)
      {
        if (RefCovered(t, px, py))
        {
          ++covered;
          ref.x0 = std::min(ref.x0, px);
          ref.y0 = std::min(ref.y0, py);
          ref.x1 = std::max(ref.x1, px + 1);
          ref.y1 = std::max(ref.y1, py + 1);
        }
      }
    }
    const bool none = covered == 0;
    const bool gotEmpty = got.x0 >= got.x1 || got.y0 >= got.y1;
    const bool small = bx1 - bx0 <= 1 && by1 - by0 <= 1;
    const bool degenerate = Orient(t[0], t[1], t[2]) == 0;
    std::ostringstream what;
    what << "triangle (" << t[0].x << "," << t[0].y << ") (" << t[1].x << "," << t[1].y << ") ("
         << t[2].x << "," << t[2].y << ") clip " << clip.x0 << "," << clip.y0 << " " << clip.x1
         << "," << clip.y1 << " got " << got.x0 << "," << got.y0 << " " << got.x1 << "," << got.y1;
    if (degenerate || (small && none))
    {
      ASSERT_TRUE(gotEmpty) << what.str();
      exactEmpty += none && !degenerate ? 1 : 0;
    }
    else if (small)
    {
      ASSERT_EQ(got.x0, ref.x0) << what.str();
      ASSERT_EQ(got.y0, ref.y0) << what.str();
      ASSERT_EQ(got.x1, ref.x1) << what.str();
      ASSERT_EQ(got.y1, ref.y1) << what.str();
      ++exact;
    }
    else if (!none)
    {
      ASSERT_FALSE(gotEmpty) << what.str();
      ASSERT_LE(got.x0, ref.x0) << what.str();
      ASSERT_LE(got.y0, ref.y0) << what.str();
      ASSERT_GE(got.x1, ref.x1) << what.str();
      ASSERT_GE(got.y1, ref.y1) << what.str();
      ++coarse;
    }
  }
  // The sample must exercise every case.
  EXPECT_GT(exact, 1000);
  EXPECT_GT(exactEmpty, 1000);
  EXPECT_GT(coarse, 1000);
}
