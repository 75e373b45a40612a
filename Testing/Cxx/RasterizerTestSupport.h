// Shared by the rasteriser tests (TestRasterizer*.cxx): buffers, the exact brute-force
// reference of coverage and interpolation, and random triangles and scenes.
//
// The reference below never normalises the winding and never steps edge functions: for each pixel
// centre it evaluates exact integer orientations (coordinates in units of 1/256 px) in the
// caller's vertex order and applies the geometric form of the tie rule documented in
// Rasterizer.h (top edge: horizontal with the third vertex below; left edge: non-horizontal with
// the third vertex strictly to its right).
#ifndef catarRasterizerTestSupport_h
#define catarRasterizerTestSupport_h

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
#include <string>
#include <utility>
#include <vector>

namespace catar
{
inline void PrintTo(RasterResult r, std::ostream* os)
{
  *os << toString(r);
}
}

namespace raster_test
{
using namespace catar;

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
inline GridPt SnapRef(double x, double y)
{
  return GridPt{ static_cast<std::int64_t>(std::floor(x * 256.0 + 0.5)),
    static_cast<std::int64_t>(std::floor(y * 256.0 + 0.5)) };
}

// Twice the signed area of (a, b, p); positive when p is clockwise from a->b on screen (y down).
inline std::int64_t Orient(const GridPt& a, const GridPt& b, const GridPt& p)
{
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Tie rule, geometrically: is edge (a, b) of the triangle with third vertex c a top or left edge?
inline bool RefTopOrLeft(const GridPt& a, const GridPt& b, const GridPt& c)
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

inline bool RefCovered(const GridPt t[3], int px, int py)
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
inline void RefBarycentric(const GridPt t[3], int px, int py, long double l[3])
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

inline RasterVertex Vtx(
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

inline RasterVertex Vtx(
  const GridPt& p, float r = 1, float g = 1, float b = 1, float a = 1, float z = 0)
{
  // 1/256 steps: exact in a double.
  return Vtx(static_cast<double>(p.x) / 256.0, static_cast<double>(p.y) / 256.0, r, g, b, a, z);
}

/// The same half-transparent triangle drawn twice into `once` with the depth test (which stops
/// the second: alpha 128) and into `twice` without it (alpha 192): checks every pixel of both and
/// returns how many the triangle covers.
inline int ExpectBlendedOnceAndTwice(const Image& once, const Image& twice)
{
  int drawn = 0;
  for (int y = 0; y < once.h; ++y)
  {
    for (int x = 0; x < once.w; ++x)
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
  return drawn;
}

// Expected byte for an exact value v in [0, 255]: returns true if `actual` is acceptable, i.e.
// round-to-nearest of v, or either neighbour when v is within 1e-3 of a rounding tie.
/// Counts pixels checked against a reference premultiplied RGBA (within one unit per channel)
/// and keeps the first mismatch for the failure message.
struct PixelChecks
{
  int checked = 0;
  int bad = 0;
  std::string firstBad;
  /// value: the reference colour (RGB) and alpha in [0, 1] of triangle n's pixel (x, y).
  void Premultiplied(const Image& img, int n, int x, int y, const long double value[4])
  {
    const long double expected[4] = { 255 * value[0] * value[3], 255 * value[1] * value[3],
      255 * value[2] * value[3], 255 * value[3] };
    for (int c = 0; c < 4; ++c)
    {
      ++this->checked;
      if (std::fabs(static_cast<long double>(img.at(x, y)[c]) - expected[c]) > 1.0L)
      {
        if (!this->bad)
        {
          std::ostringstream os;
          os << "triangle " << n << " pixel " << x << "," << y << " channel " << c << " expected "
             << static_cast<double>(expected[c]) << " got " << static_cast<int>(img.at(x, y)[c]);
          this->firstBad = os.str();
        }
        ++this->bad;
      }
    }
  }
};

inline bool ByteMatches(long double v, int actual)
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
inline std::pair<int, int> CompareCoverage(
  const Image& img, const GridPt t[3], std::string* firstBad)
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
inline std::int64_t RandomCoord(std::mt19937& rng, double lo, double hi)
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
inline void RandomTriangle(std::mt19937& rng, int w, int h, GridPt t[3])
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

inline int CountNonZeroAlpha(const Image& img)
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

// A random scene with Gouraud colours, partial alpha and depth.
struct SceneTri
{
  RasterVertex v[3];
};

inline std::vector<SceneTri> RandomScene(unsigned seed, int w, int h, int count)
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

// Textures: the reference sampler follows the definition in Rasterizer.h (see
// TestRasterizerTextures.cxx).
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
inline void RefSample(
  const Texels& t, long double u, long double v, bool repeat, long double out[4])
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

inline RasterVertex UV(RasterVertex v, float u, float tv)
{
  v.u = u;
  v.v = tv;
  return v;
}

} // namespace raster_test

#endif
