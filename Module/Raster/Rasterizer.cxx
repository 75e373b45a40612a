// CatadioptricAR Core: CPU triangle rasteriser (see Rasterizer.h for the conventions).
//
// Algorithm: the vertices are snapped to the 1/256 grid (64-bit integers) and the winding is
// normalised so that the doubled signed area A = (x1-x0)(y2-y0) - (y1-y0)(x2-x0) is positive
// (clockwise on screen, since y points down). For the directed edge a->b the edge function
//   E_ab(p) = (bx-ax)(py-ay) - (by-ay)(px-ax)
// is then positive on the interior side. With this winding the geometric definitions of the header
// become: top edge <=> (by == ay and bx > ax); left edge <=> by < ay. A pixel centre p is covered
// iff for all three edges E(p) > 0, or E(p) == 0 and the edge is top or left; equivalently
// E(p) - bias >= 0 with bias = 0 for top/left edges and 1 otherwise.
//
// Range: |coordinate| <= 2^20 px = 2^28 grid units, differences <= 2^29, products <= 2^58, so E
// (a difference of two products, <= 2^59 in magnitude) is exact in int64 everywhere in the
// bounding box. The edge functions are stepped incrementally along rows and columns; as the
// covered centres of a row are contiguous (convexity), a row stops at the end of its span.
//
// Attributes (r, g, b, a, depth, and u, v with a texture) are planes c(x, y) evaluated in double
// at each covered pixel from the row start value (no accumulation across rows or pixels).
//
// rasterizeTriangle checks and snaps its vertices and then draws exactly as
// rasterizeSnappedTriangle (DrawSnapped): the two entry points share every drawing decision.
//
// One span walk (Scan) serves every variant: the edge walk, the depth test and the id write are
// written once, and what is done with a drawn pixel is a "shader" template argument (flat,
// Gouraud, textured per channel count), inlined into the walk, so each instantiation tests
// nothing per pixel that it does not use. Texturing has its own out-of-line set-up
// (DrawTextured, reached through RasterizeSnappedTextured), so the untextured code has no texture
// test in its loops. The small helpers used by both are declared inline: without the hint GCC
// stops inlining them into the untextured loops once the textured code makes the file larger
// (measured: ~10% slower Gouraud).
// The depth test and the id buffer are template parameters of the walk (kDepth, kIds), so the
// painter path (no depth, no ids) tests neither per pixel; the untextured walks with a depth or id
// buffer are instantiated out of line (ScanWithBuffers), so only the two painter walks are inlined
// into the untextured entry point.
// The bilinear sampler works on the 0..255 scale with a + f (b - a) interpolations, which stay
// within [min(a, b), max(a, b)] in float and return a exactly for f == 0 (texel centres exact).
#include "Rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__GNUC__) || defined(__clang__)
#define CATAR_NOINLINE __attribute__((noinline))
#define CATAR_ALWAYS_INLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define CATAR_NOINLINE __declspec(noinline)
#define CATAR_ALWAYS_INLINE __forceinline
#else
#define CATAR_NOINLINE
#define CATAR_ALWAYS_INLINE inline
#endif

namespace catar
{
namespace
{
constexpr std::int64_t kOne = std::int64_t(1) << kRasterSubPixelBits;

// c - c is 0 for a finite c and NaN otherwise, so the sum is 0 iff every field is finite (one
// test instead of nine; all terms are exact zeros or NaN, so no overflow).
bool IsFinite(const RasterVertex& v)
{
  const float f = (v.r - v.r) + (v.g - v.g) + (v.b - v.b) + (v.a - v.a) + (v.depth - v.depth) +
    (v.u - v.u) + (v.v - v.v);
  return (v.x - v.x) + (v.y - v.y) + static_cast<double>(f) == 0.0;
}

bool IsValid(const TextureView& t)
{
  return t.data && t.width > 0 && t.height > 0 &&
    (t.channels == 1 || t.channels == 3 || t.channels == 4);
}

bool InGuardBand(const RasterVertex& v)
{
  return std::fabs(v.x) <= kRasterGuardBand && std::fabs(v.y) <= kRasterGuardBand;
}

// floor(a / kOne) and ceil(a / kOne) for any sign of a: arithmetic shifts (signed >> shifts in
// the sign with every supported compiler, and by definition since C++20). A division and a
// remainder instead cost ~70 instructions per triangle in the four of CentreRange (measured).
inline std::int64_t FloorToPixel(std::int64_t a)
{
  return a >> kRasterSubPixelBits;
}

inline std::int64_t CeilToPixel(std::int64_t a)
{
  return (a + kOne - 1) >> kRasterSubPixelBits;
}

inline float Clamp01(float v)
{
  return std::min(1.0f, std::max(0.0f, v));
}

inline float Clamp01(double v)
{
  return static_cast<float>(std::min(1.0, std::max(0.0, v)));
}

// v in [0, 255] up to rounding noise (never negative): round to nearest, clamp to 255.
inline std::uint8_t ToByte(float v)
{
  return static_cast<std::uint8_t>(std::min(static_cast<int>(v + 0.5f), 255));
}

// Source colour pre-scaled to 0..255 and premultiplied by alpha, plus the destination weight.
struct BlendSource
{
  float r = 0, g = 0, b = 0, a = 0; // 255 * c * alpha (a: 255 * alpha)
  float keep = 1;                   // 1 - alpha
};

inline BlendSource MakeSource(float r, float g, float b, float a)
{
  const float sa = 255.0f * a;
  return BlendSource{ r * sa, g * sa, b * sa, sa, 1.0f - a };
}

void Blend(std::uint8_t* p, const BlendSource& s)
{
  p[0] = ToByte(s.r + static_cast<float>(p[0]) * s.keep);
  p[1] = ToByte(s.g + static_cast<float>(p[1]) * s.keep);
  p[2] = ToByte(s.b + static_cast<float>(p[2]) * s.keep);
  p[3] = ToByte(s.a + static_cast<float>(p[3]) * s.keep);
}

// A linear function over the bounding box: c(x, y) = origin + dx (x - xMin) + dy (y - yMin).
struct Plane
{
  double origin = 0; // value at (xMin, yMin)
  double dx = 0;     // per pixel to the right
  double dy = 0;     // per row down
};

// The triangle's geometry for attribute planes: vertex 1 and 2 relative to vertex 0 (x10, y10,
// x20, y20, pixels), 1 / doubled area, and (xMin, yMin) relative to vertex 0 (ox, oy).
struct PlaneBasis
{
  double x10, y10, x20, y20, invArea, ox, oy;

  // The plane through the values c0, c1, c2 at the three vertices.
  CATAR_ALWAYS_INLINE Plane make(double c0, double c1, double c2) const
  {
    const double d1 = c1 - c0;
    const double d2 = c2 - c0;
    Plane p;
    p.dx = (d1 * y20 - d2 * y10) * invArea;
    p.dy = (d2 * x10 - d1 * x20) * invArea;
    p.origin = c0 + p.dx * ox + p.dy * oy;
    return p;
  }
};

// The geometry of one triangle clipped to the area to scan.
struct Setup
{
  int xMin, xMax, yMin, yMax; // inclusive pixel range to scan (already clipped)
  std::int64_t w[3];          // biased edge functions at (xMin, yMin)
  std::int64_t stepX[3];      // change per pixel to the right
  std::int64_t stepY[3];      // change per row down
  Plane depth;                // used with a depth buffer
};

// Snapped vertices in the normalised winding (positive doubled area).
struct Grid
{
  std::int64_t X[3], Y[3];
};

// Edge i is the one opposite vertex i: a = vertex i+1, b = vertex i+2. Its biased edge function
// at the grid point (px, py) (covered iff all three are >= 0) and its steps per pixel.
CATAR_ALWAYS_INLINE void EdgeSetup(const Grid& g, std::int64_t px, std::int64_t py,
  std::int64_t w[3], std::int64_t stepX[3], std::int64_t stepY[3])
{
  for (int i = 0; i < 3; ++i)
  {
    const int a = (i + 1) % 3;
    const int b = (i + 2) % 3;
    const std::int64_t ex = g.X[b] - g.X[a];
    const std::int64_t ey = g.Y[b] - g.Y[a];
    const bool topLeft = ey < 0 || (ey == 0 && ex > 0);
    w[i] = ex * (py - g.Y[a]) - ey * (px - g.X[a]) - (topLeft ? 0 : 1);
    stepX[i] = -ey * kOne;
    stepY[i] = ex * kOne;
  }
}

// Minimum and maximum of three, written so that compilers select (cmov) rather than branch:
// std::min({ a, b, c }) compiles to compare-and-jump chains, which mispredict on triangles at
// random places (measured: a third of coveredPixelBounds' time).
template<typename T>
CATAR_ALWAYS_INLINE T Min3(T a, T b, T c)
{
  const T ab = b < a ? b : a;
  return c < ab ? c : ab;
}

template<typename T>
CATAR_ALWAYS_INLINE T Max3(T a, T b, T c)
{
  const T ab = b > a ? b : a;
  return c > ab ? c : ab;
}

// The inclusive range of pixel centres inside the snapped triangle's bounding box and clip
// (xMin > xMax or yMin > yMax when there is none).
CATAR_ALWAYS_INLINE void CentreRange(
  const Grid& g, const PixelRect& clip, int& xMin, int& yMin, int& xMax, int& yMax)
{
  const std::int64_t bx0 = CeilToPixel(Min3(g.X[0], g.X[1], g.X[2]));
  const std::int64_t by0 = CeilToPixel(Min3(g.Y[0], g.Y[1], g.Y[2]));
  const std::int64_t bx1 = FloorToPixel(Max3(g.X[0], g.X[1], g.X[2]));
  const std::int64_t by1 = FloorToPixel(Max3(g.Y[0], g.Y[1], g.Y[2]));
  xMin = static_cast<int>(std::max<std::int64_t>(bx0, clip.x0));
  yMin = static_cast<int>(std::max<std::int64_t>(by0, clip.y0));
  xMax = static_cast<int>(std::min<std::int64_t>(bx1, static_cast<std::int64_t>(clip.x1) - 1));
  yMax = static_cast<int>(std::min<std::int64_t>(by1, static_cast<std::int64_t>(clip.y1) - 1));
}

// Snaps t's positions into g in the normalised winding; order receives the vertex indices in that
// winding. Returns the doubled area before normalisation (0: degenerate).
CATAR_ALWAYS_INLINE std::int64_t Normalise(
  const std::int32_t x[3], const std::int32_t y[3], Grid& g, int order[3])
{
  for (int i = 0; i < 3; ++i)
  {
    g.X[i] = x[i];
    g.Y[i] = y[i];
    order[i] = i;
  }
  const std::int64_t area =
    (g.X[1] - g.X[0]) * (g.Y[2] - g.Y[0]) - (g.Y[1] - g.Y[0]) * (g.X[2] - g.X[0]);
  if (area < 0)
  {
    std::swap(order[1], order[2]);
    std::swap(g.X[1], g.X[2]);
    std::swap(g.Y[1], g.Y[2]);
  }
  return area;
}

// A valid texture in the form the sampler uses.
struct Texture
{
  const std::uint8_t* data; // texel (0, 0), bottom-left
  std::ptrdiff_t stride;    // bytes from row j to row j+1
  int width, height;
  double fw, fh; // width, height
  bool repeat;
};

Texture MakeTexture(const TextureView& t)
{
  return Texture{ t.data, t.rowStride, t.width, t.height, static_cast<double>(t.width),
    static_cast<double>(t.height), t.repeat };
}

// One axis of the bilinear footprint: texture coordinate c -> the two texel indices i0, i1 whose
// centres surround it and the weight f of i1. Texel i's centre is at (i + 0.5) / n, i.e. at
// s = c n - 0.5 = i. Any finite c (NaN gives the first texel with clamping; callers never pass it).
CATAR_ALWAYS_INLINE void Footprint(
  double c, int n, double fn, bool repeat, int& i0, int& i1, float& f)
{
  if (repeat)
  {
    const double s = (c - std::floor(c)) * fn - 0.5; // in [-0.5, n - 0.5]
    const int i = static_cast<int>(s + 1.0) - 1;     // floor(s), in [-1, n - 1]
    f = static_cast<float>(s - static_cast<double>(i));
    i0 = i < 0 ? n - 1 : i;
    i1 = i + 1 < n ? i + 1 : 0;
  }
  else
  {
    double s = c * fn - 0.5;
    s = s > 0.0 ? s : 0.0; // clamp to edge (and NaN -> 0)
    s = s < fn - 1.0 ? s : fn - 1.0;
    const int i = static_cast<int>(s); // s >= 0: truncation is floor
    f = static_cast<float>(s - static_cast<double>(i));
    i0 = i;
    i1 = i + 1 < n ? i + 1 : i;
  }
}

// Bilinear sample at (u, v) on the 0..255 scale (RGBA; grey -> r = g = b, no alpha -> 255).
template<int kChannels>
CATAR_ALWAYS_INLINE void Bilinear(const Texture& t, double u, double v, float out[4])
{
  int i0, i1, j0, j1;
  float fx, fy;
  Footprint(u, t.width, t.fw, t.repeat, i0, i1, fx);
  Footprint(v, t.height, t.fh, t.repeat, j0, j1, fy);
  const std::uint8_t* lo0 = t.data + j0 * t.stride + kChannels * static_cast<std::ptrdiff_t>(i0);
  const std::uint8_t* lo1 = t.data + j0 * t.stride + kChannels * static_cast<std::ptrdiff_t>(i1);
  const std::uint8_t* hi0 = t.data + j1 * t.stride + kChannels * static_cast<std::ptrdiff_t>(i0);
  const std::uint8_t* hi1 = t.data + j1 * t.stride + kChannels * static_cast<std::ptrdiff_t>(i1);
  for (int c = 0; c < kChannels; ++c)
  {
    const float a = lo0[c], b = lo1[c], d = hi0[c], e = hi1[c];
    const float lo = a + fx * (b - a);
    const float hi = d + fx * (e - d);
    out[c] = lo + fy * (hi - lo);
  }
  if (kChannels == 1)
  {
    out[1] = out[2] = out[0];
  }
  if (kChannels != 4)
  {
    out[3] = 255.0f;
  }
}

// Shaders: what the span walk does with each drawn pixel. row(i) is called at the start of every
// row (i = rows below yMin), pixel(p, k) for every drawn pixel (k = columns right of xMin). They
// are passed to Scan by value, so their fields live in registers rather than behind the pixel
// pointer, through which any store may alias.

// Equal vertex colours: one premultiplied source (or, opaque, one RGBA word) for every pixel.
struct FlatShader
{
  BlendSource source;
  std::uint32_t packed; // opaque colour bytes
  bool opaque;

  CATAR_ALWAYS_INLINE void row(double) {}
  CATAR_ALWAYS_INLINE void pixel(std::uint8_t* p, double) const
  {
    if (opaque)
    {
      std::memcpy(p, &packed, 4);
    }
    else
    {
      Blend(p, source);
    }
  }
};

// Gouraud: colour planes evaluated at every pixel.
struct GouraudShader
{
  Plane cr, cg, cb, ca;
  bool opaque;
  double rRow = 0, gRow = 0, bRow = 0, aRow = 0;

  CATAR_ALWAYS_INLINE void row(double i)
  {
    rRow = cr.origin + cr.dy * i;
    gRow = cg.origin + cg.dy * i;
    bRow = cb.origin + cb.dy * i;
    aRow = ca.origin + ca.dy * i;
  }
  CATAR_ALWAYS_INLINE void pixel(std::uint8_t* p, double k) const
  {
    const float r = Clamp01(rRow + cr.dx * k);
    const float g = Clamp01(gRow + cg.dx * k);
    const float b = Clamp01(bRow + cb.dx * k);
    if (opaque) // out = round(255 c), alpha 255, whatever was there
    {
      p[0] = ToByte(255.0f * r);
      p[1] = ToByte(255.0f * g);
      p[2] = ToByte(255.0f * b);
      p[3] = 255;
    }
    else
    {
      Blend(p, MakeSource(r, g, b, Clamp01(aRow + ca.dx * k)));
    }
  }
};

// The textured shader relies on an opaque texel (sa = 255) giving alpha exactly 1.
static_assert(255.0f * (1.0f / 255.0f) == 1.0f, "255 * (1 / 255) must round to 1 in float");

// Textured: src = Gouraud colour (or the equal vertex colour, flat) * bilinear texel.
template<int kChannels>
struct TexturedShader
{
  Texture tex;
  Plane cr, cg, cb, ca, cu, cv;
  bool opaque; // opaque vertices and a texture without alpha: overwrite, no need to read
  bool flat;   // equal vertex colours (white, typically): no colour planes per pixel
  float flatColour[4];
  double rRow = 0, gRow = 0, bRow = 0, aRow = 0, uRow = 0, vRow = 0;

  CATAR_ALWAYS_INLINE void row(double i)
  {
    rRow = cr.origin + cr.dy * i;
    gRow = cg.origin + cg.dy * i;
    bRow = cb.origin + cb.dy * i;
    aRow = ca.origin + ca.dy * i;
    uRow = cu.origin + cu.dy * i;
    vRow = cv.origin + cv.dy * i;
  }
  CATAR_ALWAYS_INLINE void pixel(std::uint8_t* p, double k) const
  {
    float t[4];
    Bilinear<kChannels>(tex, uRow + cu.dx * k, vRow + cv.dx * k, t);
    const float r = flat ? flatColour[0] : Clamp01(rRow + cr.dx * k);
    const float g = flat ? flatColour[1] : Clamp01(gRow + cg.dx * k);
    const float b = flat ? flatColour[2] : Clamp01(bRow + cb.dx * k);
    if (opaque) // texel alpha 255, vertex alpha 1: out = round(c * texel), alpha 255
    {
      p[0] = ToByte(r * t[0]);
      p[1] = ToByte(g * t[1]);
      p[2] = ToByte(b * t[2]);
      p[3] = 255;
    }
    else
    {
      const float a = flat ? flatColour[3] : Clamp01(aRow + ca.dx * k);
      const float sa = a * t[3];                // 255 * alpha
      const float alpha = sa * (1.0f / 255.0f); // exactly 1 when sa == 255 (static_assert)
      Blend(
        p, BlendSource{ r * t[0] * alpha, g * t[1] * alpha, b * t[2] * alpha, sa, 1.0f - alpha });
    }
  }
};

// The span walk over the clipped bounding box: coverage, then (kDepth) the depth test and write,
// then (kIds) the id, then the shader. Returns true when at least one pixel centre is covered.
// Everything the inner loop needs is copied to locals first: stores through the uint8_t pixel
// pointer may alias anything, which would otherwise force reloads from s.
template<bool kDepth, bool kIds, typename Shader>
bool Scan(const ImageView& img, const DepthView* depthView, const IdView* idView, RasterId id,
  const Setup& s, Shader shader)
{
  const int xMin = s.xMin;
  const int xMax = s.xMax;
  const std::int64_t sx0 = s.stepX[0], sx1 = s.stepX[1], sx2 = s.stepX[2];
  const std::int64_t sy0 = s.stepY[0], sy1 = s.stepY[1], sy2 = s.stepY[2];
  const Plane cz = s.depth;
  const bool writeDepth = kDepth && depthView->write;
  const bool testDepth = kDepth && depthView->test;

  // One pixel centre in the box (most triangles of dense meshes that draw anything): the walk's
  // work for it, without the loops (rowIndex = k = 0, the same arithmetic).
  if (s.xMin == xMax && s.yMin == s.yMax)
  {
    if ((s.w[0] | s.w[1] | s.w[2]) < 0)
    {
      return false;
    }
    if (kDepth)
    {
      const float z = static_cast<float>((cz.origin + cz.dy * 0.0) + cz.dx * 0.0);
      float* zq = depthView->at(xMin, s.yMin);
      if (testDepth && !(z < *zq))
      {
        return true;
      }
      if (writeDepth)
      {
        *zq = z;
      }
    }
    if (kIds)
    {
      *idView->at(xMin, s.yMin) = id;
    }
    shader.row(0.0);
    shader.pixel(img.pixel(xMin, s.yMin), 0.0);
    return true;
  }

  bool any = false;
  std::int64_t r0 = s.w[0], r1 = s.w[1], r2 = s.w[2];
  for (int y = s.yMin; y <= s.yMax; ++y, r0 += sy0, r1 += sy1, r2 += sy2)
  {
    std::int64_t w0 = r0, w1 = r1, w2 = r2;
    std::uint8_t* p = img.pixel(xMin, y);
    float* zp = kDepth ? depthView->at(xMin, y) : nullptr;
    RasterId* ip = kIds ? idView->at(xMin, y) : nullptr;
    const double rowIndex = static_cast<double>(y - s.yMin);
    shader.row(rowIndex);
    const double zRow = kDepth ? cz.origin + cz.dy * rowIndex : 0.0;
    bool inSpan = false;
    for (int x = xMin; x <= xMax; ++x, w0 += sx0, w1 += sx1, w2 += sx2, p += 4)
    {
      if ((w0 | w1 | w2) < 0)
      {
        if (inSpan)
        {
          break; // convex: the span of this row is over
        }
        continue;
      }
      inSpan = true;
      const double k = static_cast<double>(x - xMin);
      if (kDepth)
      {
        const float z = static_cast<float>(zRow + cz.dx * k);
        float* zq = zp + (x - xMin);
        if (testDepth && !(z < *zq))
        {
          continue;
        }
        if (writeDepth)
        {
          *zq = z;
        }
      }
      if (kIds)
      {
        ip[x - xMin] = id;
      }
      shader.pixel(p, k);
    }
    any = any || inSpan;
  }
  return any;
}

template<bool kDepth, bool kIds, int kChannels>
bool ScanTextured(const ImageView& img, const DepthView* depthView, const IdView* idView,
  RasterId id, const Setup& s, const TexturedShader<4>& shader)
{
  TexturedShader<kChannels> sh;
  sh.tex = shader.tex;
  sh.cr = shader.cr;
  sh.cg = shader.cg;
  sh.cb = shader.cb;
  sh.ca = shader.ca;
  sh.cu = shader.cu;
  sh.cv = shader.cv;
  sh.opaque = shader.opaque && kChannels != 4;
  sh.flat = shader.flat;
  std::copy(shader.flatColour, shader.flatColour + 4, sh.flatColour);
  return Scan<kDepth, kIds>(img, depthView, idView, id, s, sh);
}

template<bool kDepth, bool kIds>
bool ScanTextured(const ImageView& img, const DepthView* depthView, const IdView* idView,
  RasterId id, const Setup& s, const TexturedShader<4>& shader, int channels)
{
  switch (channels)
  {
    case 1:
      return ScanTextured<kDepth, kIds, 1>(img, depthView, idView, id, s, shader);
    case 3:
      return ScanTextured<kDepth, kIds, 3>(img, depthView, idView, id, s, shader);
    default:
      return ScanTextured<kDepth, kIds, 4>(img, depthView, idView, id, s, shader);
  }
}

// The vertex data DrawSnapped has gathered: colours clamped, in the normalised winding (order).
struct Vertices
{
  float col[3][4];  // clamped RGBA
  const int* order; // index in the SnappedTriangle of each vertex
};

// The textured end of DrawSnapped<true>: colour, depth and (u, v) planes, then the walk. s and
// basis come from the common set-up (s is completed here). Out of line, and s is taken by
// reference: inlined, the textured scans ran slower, and a copy of s cost ~10% on 2-pixel
// triangles (measured).
RasterResult DrawTextured(const ImageView& target, const DepthView* depth, const IdView* ids,
  RasterId id, const TextureView& texture, Setup& s, const PlaneBasis& basis,
  const SnappedTriangle& t, const Vertices& vx)
{
  const int* o = vx.order;
  // Built as the 4-channel shader; ScanTextured copies it into the right channel count.
  TexturedShader<4> sh;
  sh.flat = true;
  Plane* planes[4] = { &sh.cr, &sh.cg, &sh.cb, &sh.ca };
  for (int k = 0; k < 4; ++k)
  {
    const float c0 = vx.col[0][k], c1 = vx.col[1][k], c2 = vx.col[2][k];
    *planes[k] = basis.make(c0, c1, c2);
    sh.flat = sh.flat && c0 == c1 && c0 == c2;
    sh.flatColour[k] = c0;
  }
  sh.opaque = vx.col[0][3] == 1.0f && vx.col[1][3] == 1.0f && vx.col[2][3] == 1.0f;
  if (depth)
  {
    s.depth = basis.make(t.depth[o[0]], t.depth[o[1]], t.depth[o[2]]);
  }
  sh.tex = MakeTexture(texture);
  sh.cu = basis.make(t.u[o[0]], t.u[o[1]], t.u[o[2]]);
  sh.cv = basis.make(t.v[o[0]], t.v[o[1]], t.v[o[2]]);
  const int n = texture.channels;
  bool any;
  if (ids)
  {
    any = depth ? ScanTextured<true, true>(target, depth, ids, id, s, sh, n)
                : ScanTextured<false, true>(target, depth, ids, id, s, sh, n);
  }
  else
  {
    any = depth ? ScanTextured<true, false>(target, depth, ids, id, s, sh, n)
                : ScanTextured<false, false>(target, depth, ids, id, s, sh, n);
  }
  return any ? RasterResult::Drawn : RasterResult::Empty;
}

// The untextured walks with a depth and/or an id buffer, out of line: the untextured entry point
// inlines only the two painter walks (no depth, no ids), so their register allocation does not
// depend on the other variants (measured: inlined together, Gouraud ran ~6% slower).
template<typename Shader>
CATAR_NOINLINE bool ScanWithBuffers(const ImageView& target, const DepthView* depth,
  const IdView* ids, RasterId id, const Setup& s, const Shader& shader)
{
  if (ids)
  {
    return depth ? Scan<true, true>(target, depth, ids, id, s, shader)
                 : Scan<false, true>(target, depth, ids, id, s, shader);
  }
  return Scan<true, false>(target, depth, ids, id, s, shader);
}

// rasterizeSnappedTriangle without (kTextured = false) or with a texture (non-null).
template<bool kTextured>
CATAR_ALWAYS_INLINE RasterResult DrawSnapped(const ImageView& target, const SnappedTriangle& t,
  const PixelRect& clip, const DepthView* depth, const TextureView* texture, const IdView* ids,
  RasterId id)
{
  // Normalise the winding to a positive doubled area.
  Grid g;
  int order[3];
  if (Normalise(t.x, t.y, g, order) == 0)
  {
    return RasterResult::Degenerate;
  }

  // Bounding box of the covered pixel centres, clipped to the clip rectangle and the image.
  const PixelRect area{ std::max(clip.x0, 0), std::max(clip.y0, 0), std::min(clip.x1, target.width),
    std::min(clip.y1, target.height) };
  Setup s;
  CentreRange(g, area, s.xMin, s.yMin, s.xMax, s.yMax);
  if (s.xMin > s.xMax || s.yMin > s.yMax)
  {
    return RasterResult::Empty;
  }
  EdgeSetup(g, static_cast<std::int64_t>(s.xMin) * kOne, static_cast<std::int64_t>(s.yMin) * kOne,
    s.w, s.stepX, s.stepY);

  // Attribute planes in pixel units, relative to the (snapped) vertex 0.
  const double inv = 1.0 / static_cast<double>(kOne);
  const double x10 = static_cast<double>(g.X[1] - g.X[0]) * inv;
  const double y10 = static_cast<double>(g.Y[1] - g.Y[0]) * inv;
  const double x20 = static_cast<double>(g.X[2] - g.X[0]) * inv;
  const double y20 = static_cast<double>(g.Y[2] - g.Y[0]) * inv;
  const PlaneBasis basis{ x10, y10, x20, y20, 1.0 / (x10 * y20 - y10 * x20),
    static_cast<double>(s.xMin) - static_cast<double>(g.X[0]) * inv,
    static_cast<double>(s.yMin) - static_cast<double>(g.Y[0]) * inv };

  Vertices vx;
  vx.order = order;
  for (int i = 0; i < 3; ++i)
  {
    const float* c = t.rgba[order[i]];
    vx.col[i][0] = Clamp01(c[0]);
    vx.col[i][1] = Clamp01(c[1]);
    vx.col[i][2] = Clamp01(c[2]);
    vx.col[i][3] = Clamp01(c[3]);
  }
  if constexpr (kTextured)
  {
    return DrawTextured(target, depth, ids, id, *texture, s, basis, t, vx);
  }
  const float(&col)[3][4] = vx.col;
  bool flat = true;
  for (int c = 0; c < 4; ++c)
  {
    flat = flat && col[0][c] == col[1][c] && col[0][c] == col[2][c];
  }
  const bool opaque = col[0][3] == 1.0f && col[1][3] == 1.0f && col[2][3] == 1.0f;
  if (depth)
  {
    s.depth = basis.make(t.depth[order[0]], t.depth[order[1]], t.depth[order[2]]);
  }

  bool any;
  if (flat)
  {
    FlatShader sh;
    sh.source = MakeSource(col[0][0], col[0][1], col[0][2], col[0][3]);
    const std::uint8_t bytes[4] = { ToByte(sh.source.r), ToByte(sh.source.g), ToByte(sh.source.b),
      255 };
    std::memcpy(&sh.packed, bytes, 4);
    sh.opaque = opaque;
    any = depth || ids ? ScanWithBuffers(target, depth, ids, id, s, sh)
                       : Scan<false, false>(target, depth, ids, id, s, sh);
  }
  else
  {
    GouraudShader sh;
    sh.cr = basis.make(col[0][0], col[1][0], col[2][0]);
    sh.cg = basis.make(col[0][1], col[1][1], col[2][1]);
    sh.cb = basis.make(col[0][2], col[1][2], col[2][2]);
    if (!opaque) // the opaque shader never reads alpha
    {
      sh.ca = basis.make(col[0][3], col[1][3], col[2][3]);
    }
    sh.opaque = opaque;
    any = depth || ids ? ScanWithBuffers(target, depth, ids, id, s, sh)
                       : Scan<false, false>(target, depth, ids, id, s, sh);
  }
  return any ? RasterResult::Drawn : RasterResult::Empty;
}

// The textured variant, out of line: the public function inlines only the untextured one.
CATAR_NOINLINE RasterResult RasterizeSnappedTextured(const ImageView& target,
  const SnappedTriangle& t, const PixelRect& clip, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  return DrawSnapped<true>(target, t, clip, depth, texture, ids, id);
}
} // namespace

const char* toString(RasterResult result)
{
  switch (result)
  {
    case RasterResult::Drawn:
      return "Drawn";
    case RasterResult::Empty:
      return "Empty";
    case RasterResult::Degenerate:
      return "Degenerate";
    case RasterResult::OutsideGuardBand:
      return "OutsideGuardBand";
    case RasterResult::InvalidInput:
      return "InvalidInput";
  }
  return "Unknown";
}

void sampleTexture(const TextureView& texture, float u, float v, float rgba[4])
{
  if (!IsValid(texture) || !std::isfinite(u) || !std::isfinite(v))
  {
    rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
    return;
  }
  const Texture t = MakeTexture(texture);
  switch (texture.channels)
  {
    case 1:
      Bilinear<1>(t, u, v, rgba);
      break;
    case 3:
      Bilinear<3>(t, u, v, rgba);
      break;
    default:
      Bilinear<4>(t, u, v, rgba);
      break;
  }
  for (int c = 0; c < 4; ++c)
  {
    rgba[c] /= 255.0f;
  }
}

RasterResult rasterizeSnappedTriangle(const ImageView& target, const SnappedTriangle& t,
  const PixelRect& clip, const DepthView* depth, const TextureView* texture, const IdView* ids,
  RasterId id)
{
  if (texture)
  {
    return RasterizeSnappedTextured(target, t, clip, depth, texture, ids, id);
  }
  return DrawSnapped<false>(target, t, clip, depth, nullptr, ids, id);
}

RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const PixelRect& clip, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  if (!target.data || target.width <= 0 || target.height <= 0 || !IsFinite(v0) || !IsFinite(v1) ||
    !IsFinite(v2))
  {
    return RasterResult::InvalidInput;
  }
  if (depth && (!depth->data || depth->width < target.width || depth->height < target.height))
  {
    return RasterResult::InvalidInput;
  }
  if (ids && (!ids->data || ids->width < target.width || ids->height < target.height))
  {
    return RasterResult::InvalidInput;
  }
  if (texture && !IsValid(*texture))
  {
    return RasterResult::InvalidInput;
  }
  if (!InGuardBand(v0) || !InGuardBand(v1) || !InGuardBand(v2))
  {
    return RasterResult::OutsideGuardBand;
  }
  const RasterVertex* v[3] = { &v0, &v1, &v2 };
  SnappedTriangle t;
  for (int i = 0; i < 3; ++i)
  {
    t.x[i] = snapToGrid(v[i]->x);
    t.y[i] = snapToGrid(v[i]->y);
    t.rgba[i][0] = v[i]->r;
    t.rgba[i][1] = v[i]->g;
    t.rgba[i][2] = v[i]->b;
    t.rgba[i][3] = v[i]->a;
    t.depth[i] = v[i]->depth;
    t.u[i] = v[i]->u;
    t.v[i] = v[i]->v;
  }
  return rasterizeSnappedTriangle(target, t, clip, depth, texture, ids, id);
}

RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  return rasterizeTriangle(
    target, v0, v1, v2, PixelRect{ 0, 0, target.width, target.height }, depth, texture, ids, id);
}

namespace
{
// t's positions on the sample grid of pixel (x, y), relative to its first sample (S x, S y);
// false when a vertex is more than 2^18 pixels away.
bool LocalSamplePositions(
  const SnappedTriangle& t, int x, int y, int samples, std::int32_t lx[3], std::int32_t ly[3])
{
  constexpr std::int64_t kReach = std::int64_t(1) << (18 + kRasterSubPixelBits);
  const std::int64_t ox = static_cast<std::int64_t>(x) * kOne;
  const std::int64_t oy = static_cast<std::int64_t>(y) * kOne;
  for (int k = 0; k < 3; ++k)
  {
    const std::int64_t dx = t.x[k] - ox, dy = t.y[k] - oy;
    if (dx > kReach || dx < -kReach || dy > kReach || dy < -kReach)
    {
      return false;
    }
    lx[k] = SampleGridPosition(static_cast<std::int32_t>(dx), samples);
    ly[k] = SampleGridPosition(static_cast<std::int32_t>(dy), samples);
  }
  return true;
}
} // namespace

std::uint32_t sampleCoverage(const SnappedTriangle& t, int x, int y, int samples, bool& reachable)
{
  std::int32_t lx[3], ly[3];
  reachable = LocalSamplePositions(t, x, y, samples, lx, ly);
  Grid g;
  int order[3];
  if (!reachable || Normalise(lx, ly, g, order) == 0)
  {
    return 0;
  }
  int xMin, yMin, xMax, yMax;
  CentreRange(g, PixelRect{ 0, 0, samples, samples }, xMin, yMin, xMax, yMax);
  if (xMin > xMax || yMin > yMax)
  {
    return 0;
  }
  std::int64_t w[3], stepX[3], stepY[3];
  EdgeSetup(g, static_cast<std::int64_t>(xMin) * kOne, static_cast<std::int64_t>(yMin) * kOne, w,
    stepX, stepY);
  std::uint32_t mask = 0;
  for (int j = yMin; j <= yMax; ++j)
  {
    std::int64_t a = w[0], b = w[1], c = w[2];
    for (int i = xMin; i <= xMax; ++i)
    {
      mask |= ((a | b | c) >= 0 ? 1u : 0u) << (i + samples * j);
      a += stepX[0];
      b += stepX[1];
      c += stepX[2];
    }
    for (int k = 0; k < 3; ++k)
    {
      w[k] += stepY[k];
    }
  }
  return mask;
}

bool rasterizeSamples(const ImageView& block, const SnappedTriangle& t, int x, int y, int samples,
  const DepthView* depth, const TextureView* texture, RasterResult& result)
{
  SnappedTriangle local = t;
  if (!LocalSamplePositions(t, x, y, samples, local.x, local.y))
  {
    return false;
  }
  result = rasterizeSnappedTriangle(
    block, local, PixelRect{ 0, 0, samples, samples }, depth, texture, nullptr, 0);
  return true;
}

bool IsOpaque(const TextureView& texture)
{
  if (texture.channels != 4)
  {
    return true;
  }
  for (int j = 0; j < texture.height; ++j)
  {
    const std::uint8_t* row = texture.texel(0, j);
    for (int i = 0; i < texture.width; ++i)
    {
      if (row[4 * i + 3] != 255)
      {
        return false;
      }
    }
  }
  return true;
}
} // namespace catar
