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
// Texturing has its own scan loop (ScanTextured, instantiated per channel count and depth test)
// and its own out-of-line copy of the set-up (RasterizeTextured = Rasterize<true>), so the
// untextured code (Rasterize<false> with Scan) has no texture test in its loops. The small helpers
// used by both are declared inline: without the hint GCC stops inlining them into the untextured
// loops once the textured code makes the file larger (measured: ~10% slower Gouraud).
// The depth test and the id buffer are template parameters of the scans (kDepth, kIds), so the
// painter path (no depth, no ids) tests neither per pixel; the untextured scans with a depth or id
// buffer are instantiated out of line (ScanWithBuffers), so only the two painter scans are inlined
// into rasterizeTriangle.
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

// Nearest grid value, exact halves rounded up: floor(256 c + 0.5) (|c| <= 2^20, so exact).
std::int64_t Snap(double c)
{
  const double v = c * static_cast<double>(kOne) + 0.5;
  const std::int64_t t = static_cast<std::int64_t>(v); // truncates towards zero
  return static_cast<double>(t) > v ? t - 1 : t;
}

// floor(a / kOne) and ceil(a / kOne) for any sign of a.
std::int64_t FloorToPixel(std::int64_t a)
{
  std::int64_t q = a / kOne;
  if (a % kOne < 0)
  {
    --q;
  }
  return q;
}

std::int64_t CeilToPixel(std::int64_t a)
{
  return -FloorToPixel(-a);
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

struct Setup
{
  int xMin, xMax, yMin, yMax;     // inclusive pixel range to scan (already clipped)
  std::int64_t w[3];              // biased edge functions at (xMin, yMin)
  std::int64_t stepX[3];          // change per pixel to the right
  std::int64_t stepY[3];          // change per row down
  Plane colour[4];                // r, g, b, a (used when not flat)
  Plane depth;                    // used with a depth buffer
  BlendSource flat;               // used when flat
  std::uint8_t flatBytes[4] = {}; // opaque flat colour
  bool opaque = false;            // alpha == 1 at every vertex (so at every pixel)
};

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

// Scans the bounding box; returns true when at least one pixel centre is covered. Everything
// the inner loop needs is copied to locals first: stores through the uint8_t pixel pointer may
// alias anything, which would otherwise force reloads from s.
template<bool kFlat, bool kDepth, bool kIds>
bool Scan(const ImageView& img, const DepthView* depthView, const IdView* idView, RasterId id,
  const Setup& s)
{
  const int xMin = s.xMin;
  const int xMax = s.xMax;
  const std::int64_t sx0 = s.stepX[0], sx1 = s.stepX[1], sx2 = s.stepX[2];
  const std::int64_t sy0 = s.stepY[0], sy1 = s.stepY[1], sy2 = s.stepY[2];
  const BlendSource flat = s.flat;
  const bool opaque = s.opaque;
  std::uint32_t packed;
  std::memcpy(&packed, s.flatBytes, 4);
  const Plane cr = s.colour[0], cg = s.colour[1], cb = s.colour[2], ca = s.colour[3];
  const Plane cz = s.depth;
  const bool writeDepth = kDepth && depthView->write;

  bool any = false;
  std::int64_t r0 = s.w[0], r1 = s.w[1], r2 = s.w[2];
  for (int y = s.yMin; y <= s.yMax; ++y, r0 += sy0, r1 += sy1, r2 += sy2)
  {
    std::int64_t w0 = r0, w1 = r1, w2 = r2;
    std::uint8_t* p = img.pixel(xMin, y);
    float* zp = kDepth ? depthView->at(xMin, y) : nullptr;
    RasterId* ip = kIds ? idView->at(xMin, y) : nullptr;
    const double rowIndex = static_cast<double>(y - s.yMin);
    const double rRow = kFlat ? 0.0 : cr.origin + cr.dy * rowIndex;
    const double gRow = kFlat ? 0.0 : cg.origin + cg.dy * rowIndex;
    const double bRow = kFlat ? 0.0 : cb.origin + cb.dy * rowIndex;
    const double aRow = kFlat ? 0.0 : ca.origin + ca.dy * rowIndex;
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
        if (!(z < *zq))
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
      if (kFlat)
      {
        if (opaque)
        {
          std::memcpy(p, &packed, 4);
        }
        else
        {
          Blend(p, flat);
        }
      }
      else
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
    }
    any = any || inSpan;
  }
  return any;
}

// Texture coordinate planes (with the texture) for ScanTextured, and the vertex colour when the
// three are equal.
struct TexSetup
{
  Texture texture;
  Plane u, v;
  bool flat = false;
  float flatColour[4] = {};
};

// ScanTextured relies on an opaque texel (sa = 255) giving alpha exactly 1.
static_assert(255.0f * (1.0f / 255.0f) == 1.0f, "255 * (1 / 255) must round to 1 in float");

// Scan for textured triangles: the edge walk and depth test of Scan, then src = Gouraud colour *
// bilinear texel (s.colour always set). Separate from Scan to keep texturing out of its loops.
template<bool kDepth, bool kIds, int kChannels>
bool ScanTextured(const ImageView& img, const DepthView* depthView, const IdView* idView,
  RasterId id, const Setup& s, const TexSetup& ts)
{
  const int xMin = s.xMin;
  const int xMax = s.xMax;
  const std::int64_t sx0 = s.stepX[0], sx1 = s.stepX[1], sx2 = s.stepX[2];
  const std::int64_t sy0 = s.stepY[0], sy1 = s.stepY[1], sy2 = s.stepY[2];
  // Opaque vertices and a texture without alpha: overwrite, no need to read the target.
  const bool opaque = s.opaque && kChannels != 4;
  // Equal vertex colours (white, typically): no colour planes to evaluate per pixel.
  const bool flat = ts.flat;
  const float flatColour[4] = { ts.flatColour[0], ts.flatColour[1], ts.flatColour[2],
    ts.flatColour[3] };
  const Plane cr = s.colour[0], cg = s.colour[1], cb = s.colour[2], ca = s.colour[3];
  const Plane cz = s.depth;
  const Plane cu = ts.u, cv = ts.v;
  const Texture tex = ts.texture;
  const bool writeDepth = kDepth && depthView->write;

  bool any = false;
  std::int64_t r0 = s.w[0], r1 = s.w[1], r2 = s.w[2];
  for (int y = s.yMin; y <= s.yMax; ++y, r0 += sy0, r1 += sy1, r2 += sy2)
  {
    std::int64_t w0 = r0, w1 = r1, w2 = r2;
    std::uint8_t* p = img.pixel(xMin, y);
    float* zp = kDepth ? depthView->at(xMin, y) : nullptr;
    RasterId* ip = kIds ? idView->at(xMin, y) : nullptr;
    const double rowIndex = static_cast<double>(y - s.yMin);
    const double rRow = cr.origin + cr.dy * rowIndex;
    const double gRow = cg.origin + cg.dy * rowIndex;
    const double bRow = cb.origin + cb.dy * rowIndex;
    const double aRow = ca.origin + ca.dy * rowIndex;
    const double uRow = cu.origin + cu.dy * rowIndex;
    const double vRow = cv.origin + cv.dy * rowIndex;
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
        if (!(z < *zq))
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
    any = any || inSpan;
  }
  return any;
}

template<bool kDepth, bool kIds>
bool ScanTextured(const ImageView& img, const DepthView* depthView, const IdView* idView,
  RasterId id, const Setup& s, const TexSetup& ts, int channels)
{
  switch (channels)
  {
    case 1:
      return ScanTextured<kDepth, kIds, 1>(img, depthView, idView, id, s, ts);
    case 3:
      return ScanTextured<kDepth, kIds, 3>(img, depthView, idView, id, s, ts);
    default:
      return ScanTextured<kDepth, kIds, 4>(img, depthView, idView, id, s, ts);
  }
}

// The textured end of Rasterize<true>: colour, depth and (u, v) planes, then the scan. s and basis
// come from the common set-up (s is completed here); a, b, c are the vertices in the normalised
// winding. Out of line, and s is taken by reference: inlined, the textured scans ran slower, and a
// copy of s cost ~10% on 2-pixel triangles (measured).
RasterResult DrawTextured(const ImageView& target, const DepthView* depth, const IdView* ids,
  RasterId id, const TextureView& texture, Setup& s, const PlaneBasis& basis, const RasterVertex* a,
  const RasterVertex* b, const RasterVertex* c)
{
  const RasterVertex* v[3] = { a, b, c };
  TexSetup ts;
  ts.flat = true;
  for (int k = 0; k < 4; ++k)
  {
    float col[3];
    for (int i = 0; i < 3; ++i)
    {
      const RasterVertex& p = *v[i];
      col[i] = Clamp01(k == 0 ? p.r : k == 1 ? p.g : k == 2 ? p.b : p.a);
    }
    s.colour[k] = basis.make(col[0], col[1], col[2]);
    ts.flat = ts.flat && col[0] == col[1] && col[0] == col[2];
    ts.flatColour[k] = col[0];
  }
  if (depth)
  {
    s.depth = basis.make(v[0]->depth, v[1]->depth, v[2]->depth);
  }
  ts.texture = MakeTexture(texture);
  ts.u = basis.make(v[0]->u, v[1]->u, v[2]->u);
  ts.v = basis.make(v[0]->v, v[1]->v, v[2]->v);
  const int n = texture.channels;
  bool any;
  if (ids)
  {
    any = depth ? ScanTextured<true, true>(target, depth, ids, id, s, ts, n)
                : ScanTextured<false, true>(target, depth, ids, id, s, ts, n);
  }
  else
  {
    any = depth ? ScanTextured<true, false>(target, depth, ids, id, s, ts, n)
                : ScanTextured<false, false>(target, depth, ids, id, s, ts, n);
  }
  return any ? RasterResult::Drawn : RasterResult::Empty;
}
}

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

namespace
{
// The untextured scans with a depth and/or an id buffer, out of line: the public function inlines
// only the two painter scans (no depth, no ids), so their register allocation does not depend on
// the other variants (measured: inlined together, Gouraud ran ~6% slower).
CATAR_NOINLINE bool ScanWithBuffers(const ImageView& target, const DepthView* depth,
  const IdView* ids, RasterId id, const Setup& s, bool flat)
{
  if (flat)
  {
    if (ids)
    {
      return depth ? Scan<true, true, true>(target, depth, ids, id, s)
                   : Scan<true, false, true>(target, depth, ids, id, s);
    }
    return Scan<true, true, false>(target, depth, ids, id, s);
  }
  if (ids)
  {
    return depth ? Scan<false, true, true>(target, depth, ids, id, s)
                 : Scan<false, false, true>(target, depth, ids, id, s);
  }
  return Scan<false, true, false>(target, depth, ids, id, s);
}

// rasterizeTriangle without (kTextured = false) or with a texture (non-null).
template<bool kTextured>
CATAR_ALWAYS_INLINE RasterResult Rasterize(const ImageView& target, const RasterVertex& v0,
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
  if (kTextured && !IsValid(*texture))
  {
    return RasterResult::InvalidInput;
  }
  if (!InGuardBand(v0) || !InGuardBand(v1) || !InGuardBand(v2))
  {
    return RasterResult::OutsideGuardBand;
  }

  // Snap and normalise the winding to a positive doubled area.
  const RasterVertex* v[3] = { &v0, &v1, &v2 };
  std::int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i)
  {
    X[i] = Snap(v[i]->x);
    Y[i] = Snap(v[i]->y);
  }
  const std::int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
  if (area == 0)
  {
    return RasterResult::Degenerate;
  }
  if (area < 0)
  {
    std::swap(v[1], v[2]);
    std::swap(X[1], X[2]);
    std::swap(Y[1], Y[2]);
  }

  // Bounding box of the covered pixel centres, clipped to the clip rectangle and the image.
  const int cx0 = std::max(clip.x0, 0);
  const int cy0 = std::max(clip.y0, 0);
  const int cx1 = std::min(clip.x1, target.width);  // exclusive
  const int cy1 = std::min(clip.y1, target.height); // exclusive
  const std::int64_t bx0 = CeilToPixel(std::min({ X[0], X[1], X[2] }));
  const std::int64_t by0 = CeilToPixel(std::min({ Y[0], Y[1], Y[2] }));
  const std::int64_t bx1 = FloorToPixel(std::max({ X[0], X[1], X[2] }));
  const std::int64_t by1 = FloorToPixel(std::max({ Y[0], Y[1], Y[2] }));
  Setup s;
  s.xMin = static_cast<int>(std::max<std::int64_t>(bx0, cx0));
  s.yMin = static_cast<int>(std::max<std::int64_t>(by0, cy0));
  s.xMax = static_cast<int>(std::min<std::int64_t>(bx1, cx1 - 1));
  s.yMax = static_cast<int>(std::min<std::int64_t>(by1, cy1 - 1));
  if (s.xMin > s.xMax || s.yMin > s.yMax)
  {
    return RasterResult::Empty;
  }

  // Edge i is the one opposite vertex i: a = vertex i+1, b = vertex i+2.
  const std::int64_t px = static_cast<std::int64_t>(s.xMin) * kOne;
  const std::int64_t py = static_cast<std::int64_t>(s.yMin) * kOne;
  for (int i = 0; i < 3; ++i)
  {
    const int a = (i + 1) % 3;
    const int b = (i + 2) % 3;
    const std::int64_t ex = X[b] - X[a];
    const std::int64_t ey = Y[b] - Y[a];
    const bool topLeft = ey < 0 || (ey == 0 && ex > 0);
    s.w[i] = ex * (py - Y[a]) - ey * (px - X[a]) - (topLeft ? 0 : 1);
    s.stepX[i] = -ey * kOne;
    s.stepY[i] = ex * kOne;
  }

  // Attribute planes in pixel units, relative to the (snapped) vertex 0.
  const double inv = 1.0 / static_cast<double>(kOne);
  const double x10 = static_cast<double>(X[1] - X[0]) * inv;
  const double y10 = static_cast<double>(Y[1] - Y[0]) * inv;
  const double x20 = static_cast<double>(X[2] - X[0]) * inv;
  const double y20 = static_cast<double>(Y[2] - Y[0]) * inv;
  const PlaneBasis basis{ x10, y10, x20, y20, 1.0 / (x10 * y20 - y10 * x20),
    static_cast<double>(s.xMin) - static_cast<double>(X[0]) * inv,
    static_cast<double>(s.yMin) - static_cast<double>(Y[0]) * inv };

  float col[3][4];
  for (int i = 0; i < 3; ++i)
  {
    col[i][0] = Clamp01(v[i]->r);
    col[i][1] = Clamp01(v[i]->g);
    col[i][2] = Clamp01(v[i]->b);
    col[i][3] = Clamp01(v[i]->a);
  }
  bool flat = true;
  for (int c = 0; c < 4; ++c)
  {
    flat = flat && col[0][c] == col[1][c] && col[0][c] == col[2][c];
  }
  s.opaque = col[0][3] == 1.0f && col[1][3] == 1.0f && col[2][3] == 1.0f;
  if constexpr (kTextured)
  {
    return DrawTextured(target, depth, ids, id, *texture, s, basis, v[0], v[1], v[2]);
  }
  if (flat)
  {
    s.flat = MakeSource(col[0][0], col[0][1], col[0][2], col[0][3]);
    s.flatBytes[0] = ToByte(s.flat.r);
    s.flatBytes[1] = ToByte(s.flat.g);
    s.flatBytes[2] = ToByte(s.flat.b);
    s.flatBytes[3] = 255;
  }
  else
  {
    for (int c = 0; c < 4; ++c)
    {
      s.colour[c] = basis.make(col[0][c], col[1][c], col[2][c]);
    }
  }
  if (depth)
  {
    s.depth = basis.make(v[0]->depth, v[1]->depth, v[2]->depth);
  }

  bool any;
  if (depth || ids)
  {
    any = ScanWithBuffers(target, depth, ids, id, s, flat);
  }
  else
  {
    any = flat ? Scan<true, false, false>(target, depth, ids, id, s)
               : Scan<false, false, false>(target, depth, ids, id, s);
  }
  return any ? RasterResult::Drawn : RasterResult::Empty;
}

// The textured variant, out of line: the public function inlines only the untextured one.
CATAR_NOINLINE RasterResult RasterizeTextured(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const PixelRect& clip, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  return Rasterize<true>(target, v0, v1, v2, clip, depth, texture, ids, id);
}
}

RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const PixelRect& clip, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  if (texture)
  {
    return RasterizeTextured(target, v0, v1, v2, clip, depth, texture, ids, id);
  }
  return Rasterize<false>(target, v0, v1, v2, clip, depth, nullptr, ids, id);
}

RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const DepthView* depth,
  const TextureView* texture, const IdView* ids, RasterId id)
{
  return rasterizeTriangle(
    target, v0, v1, v2, PixelRect{ 0, 0, target.width, target.height }, depth, texture, ids, id);
}
}
