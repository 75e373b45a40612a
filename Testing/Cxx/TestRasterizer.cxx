// CPU triangle rasteriser: coverage against an exact brute-force reference (top-left rule on the
// 1/256 grid), watertightness of shared edges and vertices, statuses, strides, clipping, Gouraud
// interpolation, alpha compositing and the depth test.
//
// The reference below never normalises the winding and never steps edge functions: for each pixel
// centre it evaluates exact integer orientations (coordinates in units of 1/256 px) in the
// caller's vertex order and applies the geometric form of the tie rule documented in
// Rasterizer.h (top edge: horizontal with the third vertex below; left edge: non-horizontal with
// the third vertex strictly to its right).
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <algorithm>
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
}
