// CatadioptricAR Core: a dependency-free CPU triangle rasteriser (RGBA8 target, optional depth and
// triangle-id buffers, optional bilinear texture).
//
// Conventions
//  - Pixel (x, y): x to the right, y DOWN (row 0 is the top row, as OpenCV). The centre of pixel
//    (x, y) is at the real coordinates (x, y); the pixel covers [x-0.5, x+0.5] x [y-0.5, y+0.5].
//  - Vertex positions are snapped to fixed point with 8 sub-pixel bits (1/256 px), rounding to the
//    nearest grid value with exact halves rounded up (towards +inf): X = floor(256 x + 0.5).
//    All coverage decisions are then exact 64-bit integer computations.
//  - Coverage: a pixel is drawn iff its centre lies inside the (snapped) triangle. A centre exactly
//    on an edge is drawn only if that edge is a TOP or a LEFT edge (the Direct3D top-left rule):
//      * top edge:  an exactly horizontal edge with the triangle's interior below it (larger y),
//                   i.e. the third vertex has a larger y than the edge;
//      * left edge: a non-horizontal edge with the triangle's interior on its +x side, i.e. the
//                   third vertex lies strictly to the right of the edge's line at the same y.
//    Both definitions are geometric and so independent of the winding. A centre on a vertex is
//    drawn only if both edges meeting there are top or left edges. Consequently two triangles that
//    share an edge (same snapped end points, interiors on opposite sides) never both draw, and
//    never both miss, a pixel centre on that edge; a fan of triangles around a shared vertex covers
//    each pixel centre of its union exactly once.
//  - Colours are RGBA in [0, 1] (vertex values outside are clamped before interpolation),
//    interpolated linearly in screen space (Gouraud) and composited source-over onto the target:
//      out.rgb = src.rgb * a + dst.rgb * (1 - a),  out.a = a + dst.a * (1 - a),
//    computed on the 0..255 scale, rounded to nearest and clamped. a == 1 overwrites rgb with
//    round(255 * src.rgb) and alpha with 255.
//  - Texture mapping (optional): texture coordinates (u, v) are interpolated linearly in screen
//    space like the colours, the texture is sampled bilinearly at each drawn pixel (see
//    sampleTexture) and src = vertex colour * texel, channel by channel, alpha included
//    (modulate); src is then composited as above. Texture space follows VTK / OpenGL: (0, 0) is
//    the bottom-left corner of the texture image, (1, 1) its top-right corner, texel rows are
//    counted from the BOTTOM row.
#ifndef catarRasterizer_h
#define catarRasterizer_h

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace catar
{
/// Number of sub-pixel bits of the fixed-point vertex positions (1/256 px).
constexpr int kRasterSubPixelBits = 8;

/// Guard band: vertex coordinates must satisfy |x|, |y| <= kRasterGuardBand pixels.
constexpr double kRasterGuardBand = static_cast<double>(1 << 20);

/// An RGBA8 image the rasteriser draws into (not owned). Pixel (x, y): x right, y DOWN (row 0 =
/// top row, as OpenCV). rowStride is the byte offset from row y to row y+1 and MAY BE NEGATIVE, so
/// a bottom-up vtkImageData buffer is addressed with data = start of its last row and rowStride =
/// -4 * width. Pixels are 4 consecutive bytes R, G, B, A.
struct ImageView
{
  std::uint8_t* data = nullptr; ///< address of pixel (0, 0)
  int width = 0;                ///< number of columns
  int height = 0;               ///< number of rows
  std::ptrdiff_t rowStride = 0; ///< bytes from row y to row y+1 (may be negative)

  /// Address of the first (R) byte of pixel (x, y); no bounds check.
  std::uint8_t* pixel(int x, int y) const
  {
    return data + y * rowStride + 4 * static_cast<std::ptrdiff_t>(x);
  }
};

/// Optional depth buffer (not owned), one float per pixel, addressed like ImageView with rowStride
/// counted in floats (may be negative). It must be at least as large as the target image.
/// write = false makes the buffer read-only: pixels are still depth-tested but the stored depth
/// is left as it was (how semi-transparent surfaces are drawn after the opaque ones). test = false
/// draws every covered pixel and writes its depth (the depth of the last triangle drawn, as the
/// ids: painter order with a per-pixel path length kept beside it).
struct DepthView
{
  float* data = nullptr;        ///< address of the depth of pixel (0, 0)
  int width = 0;                ///< number of columns
  int height = 0;               ///< number of rows
  std::ptrdiff_t rowStride = 0; ///< floats from row y to row y+1 (may be negative)
  bool write = true;            ///< store the depth of every drawn pixel (false: test only)
  bool test = true;             ///< draw only where nearer than the stored depth

  /// Address of the depth of pixel (x, y); no bounds check.
  float* at(int x, int y) const { return data + y * rowStride + static_cast<std::ptrdiff_t>(x); }
};

/// A triangle id: a 64-bit signed integer, declared long long (not std::int64_t, which is long on
/// LP64 Linux) so that the buffers of VTK's 64-bit integer arrays (vtkTypeInt64 is long long) are
/// written as they are, without a copy.
using RasterId = long long;
static_assert(sizeof(RasterId) == 8, "RasterId must be a 64-bit integer");

/// Optional id buffer (not owned), one RasterId per pixel, addressed like ImageView with rowStride
/// counted in values (may be negative). It must be at least as large as the target image. The
/// rasteriser writes the triangle's id into every pixel it draws (the pixels whose colour it
/// composites, after the coverage, clip and depth tests), whatever the alpha: after a sequence of
/// triangles each pixel holds the id of the last triangle drawn there.
struct IdView
{
  RasterId* data = nullptr;     ///< address of the id of pixel (0, 0)
  int width = 0;                ///< number of columns
  int height = 0;               ///< number of rows
  std::ptrdiff_t rowStride = 0; ///< values from row y to row y+1 (may be negative)

  /// Address of the id of pixel (x, y); no bounds check.
  RasterId* at(int x, int y) const { return data + y * rowStride + static_cast<std::ptrdiff_t>(x); }
};

/// Integer clip rectangle [x0, x1) x [y0, y1) in pixels; used to split work into tiles.
struct PixelRect
{
  int x0 = 0; ///< first column inside
  int y0 = 0; ///< first row inside
  int x1 = 0; ///< one past the last column inside
  int y1 = 0; ///< one past the last row inside
};

/// A texture image the rasteriser reads (not owned): width x height texels of `channels` bytes
/// each -- grey (1: L), RGB (3) or RGBA (4). Texel (i, j): i = column from the left, j = row
/// counted from the BOTTOM row (VTK / OpenGL order, as vtkImageData stores images), so data is the
/// address of the bottom-left texel and a vtkImageData scalar buffer is used as is with rowStride
/// = channels * width. rowStride is the byte offset from row j to row j+1 and MAY BE NEGATIVE: a
/// top-down buffer (OpenCV) is addressed with data = start of its last row and rowStride =
/// -channels * width.
/// Texture coordinates: (u, v) = (0, 0) is the bottom-left corner of the image and (1, 1) its
/// top-right corner; the centre of texel (i, j) is at ((i + 0.5) / width, (j + 0.5) / height).
/// Outside [0, 1] the coordinates either repeat (wrap, period 1) or clamp to the edge texels.
/// Valid iff data != nullptr, width > 0, height > 0 and channels is 1, 3 or 4 (rowStride is not
/// checked).
struct TextureView
{
  const std::uint8_t* data = nullptr; ///< address of texel (0, 0), the BOTTOM-left one
  int width = 0;                      ///< number of columns
  int height = 0;                     ///< number of rows
  int channels = 4;                   ///< bytes per texel: 1 (grey), 3 (RGB) or 4 (RGBA)
  std::ptrdiff_t rowStride = 0;       ///< bytes from row j to row j+1 (may be negative)
  bool repeat = false;                ///< true: repeat (wrap); false: clamp to edge

  /// Address of the first byte of texel (i, j) (j counted from the bottom); no bounds check.
  const std::uint8_t* texel(int i, int j) const
  {
    return data + j * rowStride + channels * static_cast<std::ptrdiff_t>(i);
  }
};

/// True when the texture hides what is behind it everywhere: 1 or 3 channels, or RGBA with every
/// alpha byte 255.
bool IsOpaque(const TextureView& texture);

/// One vertex: position in pixels (pixel (0,0) is the CENTRE of the top-left pixel), colour RGBA
/// in [0, 1] (clamped), depth (smaller is nearer) and texture coordinates.
struct RasterVertex
{
  double x = 0;    ///< column coordinate, pixels
  double y = 0;    ///< row coordinate, pixels (down)
  float r = 0;     ///< red, [0, 1]
  float g = 0;     ///< green, [0, 1]
  float b = 0;     ///< blue, [0, 1]
  float a = 1;     ///< opacity, [0, 1]
  float depth = 0; ///< depth, used only with a depth buffer
  float u = 0;     ///< texture coordinate, left to right; used only with a texture
  float v = 0;     ///< texture coordinate, BOTTOM to top; used only with a texture
};

/// Outcome of rasterizeTriangle. Checks are made in this order: InvalidInput, OutsideGuardBand,
/// Degenerate, then Empty / Drawn.
enum class RasterResult
{
  Drawn,            ///< at least one pixel centre inside the clipped image area is covered
                    ///< (it may still have been rejected by the depth test)
  Empty,            ///< covers no pixel centre inside the clipped image area; nothing drawn
  Degenerate,       ///< zero area after snapping to the 1/256 grid; nothing drawn
  OutsideGuardBand, ///< a vertex lies outside +-kRasterGuardBand pixels; nothing drawn
  InvalidInput      ///< NaN/Inf in a vertex (position, colour, depth or texture
                    ///< coordinates, whether or not they are used), a target without data or
                    ///< with a non-positive size, a depth or id buffer without data or smaller
                    ///< than the target, or an invalid texture (see TextureView); nothing drawn
};

/// Name of a RasterResult value (for messages).
const char* toString(RasterResult result);

/// Samples texture bilinearly at (u, v) (see TextureView for the coordinates): the four texels
/// whose centres surround the point are weighted by the usual bilinear weights, with the texel
/// indices wrapped (repeat) or clamped to the image (clamp to edge) -- at a texel centre the
/// result is that texel, half-way between two texel centres their average. rgba receives the
/// result in [0, 1] (texel bytes / 255): grey gives r = g = b and a = 1, RGB gives a = 1.
/// Computed in float from double texel coordinates: exact at texel centres that are exact floats.
/// An invalid texture or a NaN/Inf coordinate gives rgba = (0, 0, 0, 0). Thread-safe.
void sampleTexture(const TextureView& texture, float u, float v, float rgba[4]);

/// Draws one triangle (either winding) with colours interpolated linearly in screen space
/// (Gouraud, planes through the snapped vertex positions; equal vertex colours take a
/// flat-shading fast path), composited source-over onto target (see the conventions above).
/// Coverage follows the top-left rule on the 1/256 grid.
/// depth: if non-null, the per-pixel depth (interpolated linearly in screen space from the vertex
/// depths, stored as float) is tested -- a pixel is drawn only if it is strictly less than the
/// stored value -- and written where drawn (unless depth->write is false).
/// ids: if non-null, id is written into every drawn pixel of the id buffer (see IdView).
/// clip: only pixels inside clip intersected with the image are read or written. Drawing a
/// triangle tile by tile with clip rectangles that partition the image gives exactly the same
/// result as drawing it once over the whole image.
/// texture: if non-null, the vertex texture coordinates (u, v) are interpolated linearly in screen
/// space (planes through the snapped vertex positions, like the colours), the texture is sampled
/// with sampleTexture's rule at each pixel that passes the coverage, clip and depth tests, and the
/// source colour is the interpolated (clamped) vertex colour times the texel, all four channels
/// (modulate: white opaque vertices show the texture as is); it is then composited source-over.
/// Coverage, clipping, the depth test and the depth written are exactly those of the untextured
/// drawing. Textured triangles have their own scan loops: untextured ones test nothing about
/// textures per pixel. An invalid texture (see TextureView) gives InvalidInput.
/// Without depth buffer and id buffer the scan loops test nothing about either per pixel.
/// Thread-safe for disjoint clip rectangles; allocates nothing.
RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const PixelRect& clip,
  const DepthView* depth = nullptr, const TextureView* texture = nullptr,
  const IdView* ids = nullptr, RasterId id = 0);

/// Convenience overload: clip = the whole image.
RasterResult rasterizeTriangle(const ImageView& target, const RasterVertex& v0,
  const RasterVertex& v1, const RasterVertex& v2, const DepthView* depth = nullptr,
  const TextureView* texture = nullptr, const IdView* ids = nullptr, RasterId id = 0);

// ---------------------------------------------------------------------------------------------
// Batches. rasterizeTriangle checks and snaps its three vertices on every call. A caller that
// draws many triangles sharing vertices, or draws each triangle in several clip rectangles (bands
// drawn in parallel), checks and snaps each vertex once (snapToGrid), finds the rows each triangle
// can draw (coveredPixelBounds) and draws with rasterizeSnappedTriangle: the pixels are exactly
// those rasterizeTriangle draws.

/// A pixel coordinate snapped to the 1/256 grid as rasterizeTriangle snaps vertex positions:
/// floor(256 c + 0.5) (exact halves rounded up). c must be finite with |c| <= kRasterGuardBand;
/// the result then fits in 29 bits. Inline: a batch snaps every point of its meshes.
inline std::int32_t snapToGrid(double c)
{
  const double v = c * static_cast<double>(1 << kRasterSubPixelBits) + 0.5; // exact
  const auto t = static_cast<std::int32_t>(v); // truncates towards zero
  return static_cast<double>(t) > v ? t - 1 : t;
}

/// A triangle whose vertex positions are on the 1/256 grid (snapToGrid) and whose vertices passed
/// rasterizeTriangle's checks (finite attributes, inside the guard band). Either winding.
struct SnappedTriangle
{
  std::int32_t x[3] = {}; ///< columns, 1/256 px
  std::int32_t y[3] = {}; ///< rows (down), 1/256 px
  float rgba[3][4] = {};  ///< RGBA of each vertex (clamped to [0, 1] when drawn)
  float depth[3] = {};    ///< used only with a depth buffer
  float u[3] = {};        ///< used only with a texture
  float v[3] = {};        ///< used only with a texture
};

/// The pixels inside clip that a triangle with these snapped vertex positions (either winding)
/// can draw: a rectangle holding every pixel centre it covers, empty (x0 >= x1 or y0 >= y1) when it
/// covers none of clip's. When the pixel centres of clip inside the triangle's bounding box span
/// at most 2 x 2 pixels the result is exact (the bounding box of the covered centres, found with
/// the coverage rule), so triangles about a pixel in size that fall between pixel centres are
/// recognised before any per-clip-rectangle work; otherwise it is the bounding box of those
/// centres. A degenerate triangle (zero snapped area) gives an empty rectangle.
/// clip is not intersected with any image: pass the image's rectangle (or a part of it).
/// (Inline: it is called once per triangle, most of which cover no pixel centre.)
inline PixelRect coveredPixelBounds(
  const std::int32_t x[3], const std::int32_t y[3], const PixelRect& clip)
{
  // Most calls are for triangles about a pixel in size at random places: a mispredicted branch
  // costs about as much as the whole test, so past the first test (no pixel centre in the
  // bounding box: most triangles of dense meshes, so mostly predicted) the common path has no
  // data-dependent branch (measured, bunny-like triangles: 23 -> 14 ns per call). Signed >> is
  // an arithmetic shift (floor division by 2^k) with every supported compiler, and by definition
  // since C++20.
  constexpr int kBits = kRasterSubPixelBits;
  constexpr std::int64_t kOne = std::int64_t(1) << kBits;
  const auto min3 = [](std::int32_t a, std::int32_t b, std::int32_t c) {
    const std::int32_t ab = b < a ? b : a;
    return c < ab ? c : ab;
  };
  const auto max3 = [](std::int32_t a, std::int32_t b, std::int32_t c) {
    const std::int32_t ab = b > a ? b : a;
    return c > ab ? c : ab;
  };
  const std::int64_t minX = min3(x[0], x[1], x[2]), maxX = max3(x[0], x[1], x[2]);
  const std::int64_t minY = min3(y[0], y[1], y[2]), maxY = max3(y[0], y[1], y[2]);
  const int xMin = static_cast<int>(std::max<std::int64_t>((minX + kOne - 1) >> kBits, clip.x0));
  const int yMin = static_cast<int>(std::max<std::int64_t>((minY + kOne - 1) >> kBits, clip.y0));
  const int xMax = static_cast<int>(std::min<std::int64_t>(maxX >> kBits, clip.x1 - 1LL));
  const int yMax = static_cast<int>(std::min<std::int64_t>(maxY >> kBits, clip.y1 - 1LL));
  if ((xMin > xMax) | (yMin > yMax))
  {
    return PixelRect{};
  }
  const std::int64_t ax = x[0], ay = y[0];
  const std::int64_t area = (x[1] - ax) * (y[2] - ay) - (y[1] - ay) * (x[2] - ax);
  if ((xMax - xMin > 1) | (yMax - yMin > 1))
  {
    return area == 0 ? PixelRect{} : PixelRect{ xMin, yMin, xMax + 1, yMax + 1 };
  }
  // At most 2 x 2 centres: the coverage rule (as EdgeSetup and Scan apply it, in the winding of
  // Normalise) at the centres (xMin + i, yMin + j). The winding stays a branch: a mesh's
  // triangles seen from the camera mostly share one, so it is predicted.
  const bool flip = area < 0;
  const std::int64_t bx = flip ? x[2] : x[1], by = flip ? y[2] : y[1];
  const std::int64_t cx = flip ? x[1] : x[2], cy = flip ? y[1] : y[2];
  const std::int64_t px = static_cast<std::int64_t>(xMin) * kOne;
  const std::int64_t py = static_cast<std::int64_t>(yMin) * kOne;
  const auto edge = [px, py](std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                      std::int64_t& w, std::int64_t& sx, std::int64_t& sy) {
    const std::int64_t ex = x1 - x0, ey = y1 - y0;
    const bool topLeft = (ey < 0) | ((ey == 0) & (ex > 0));
    w = ex * (py - y0) - ey * (px - x0) - (topLeft ? 0 : 1);
    sx = -ey * kOne;
    sy = ex * kOne;
  };
  std::int64_t w0, sx0, sy0, w1, sx1, sy1, w2, sx2, sy2;
  edge(bx, by, cx, cy, w0, sx0, sy0);
  edge(cx, cy, ax, ay, w1, sx1, sy1);
  edge(ax, ay, bx, by, w2, sx2, sy2);
  const bool valid = area != 0; // a degenerate triangle covers nothing
  const bool wide = xMax > xMin, tall = yMax > yMin;
  const bool c00 = valid & ((w0 | w1 | w2) >= 0);
  const bool c10 = valid & wide & (((w0 + sx0) | (w1 + sx1) | (w2 + sx2)) >= 0);
  const bool c01 = valid & tall & (((w0 + sy0) | (w1 + sy1) | (w2 + sy2)) >= 0);
  const bool c11 =
    valid & wide & tall & (((w0 + sx0 + sy0) | (w1 + sx1 + sy1) | (w2 + sx2 + sy2)) >= 0);
  const int row0 = c00 | c10, row1 = c01 | c11;
  const int col0 = c00 | c01, col1 = c10 | c11;
  const int any = row0 | row1; // all four 0 (empty) when nothing is covered
  return PixelRect{ any * (xMin + 1 - col0), any * (yMin + 1 - row0), any * (xMin + 1 + col1),
    any * (yMin + 1 + row1) };
}

/// rasterizeTriangle for a snapped triangle: draws exactly the pixels, colours, depths and ids
/// rasterizeTriangle draws for vertices that snap to t's positions and carry t's attributes.
/// Nothing is checked -- the caller guarantees finite attributes, positions snapped from inside
/// the guard band, a target with data and a positive size, depth and id buffers at least as large
/// as the target, and a valid texture -- so the result is Drawn, Empty or Degenerate.
/// Thread-safe for disjoint clip rectangles; allocates nothing.
RasterResult rasterizeSnappedTriangle(const ImageView& target, const SnappedTriangle& t,
  const PixelRect& clip, const DepthView* depth = nullptr, const TextureView* texture = nullptr,
  const IdView* ids = nullptr, RasterId id = 0);

// ---------------------------------------------------------------------------------------------
// Edge samples (anti-aliasing). Pixel (x, y) is divided into S x S sub-pixels; sample (i, j),
// i, j in [0, S), is the centre of sub-pixel (i, j): the point (x - 0.5 + (i + 0.5) / S,
// y - 0.5 + (j + 0.5) / S). On the sample grid -- coordinates f = S (c + 0.5) - 0.5 -- the samples
// are the integer points (S x + i, S y + j), so drawing a triangle on the sample grid with the
// rules above (coverage of a "pixel centre", top-left rule, attribute planes) draws it at the
// samples.

/// Most samples per pixel side.
constexpr int kMaxEdgeSamples = 4;

/// A coordinate snapped to the 1/256 pixel grid (snapToGrid), on the sample grid of `samples`
/// (1 to kMaxEdgeSamples) per side, in 1/256 sample units: S X + 128 (S - 1), exact. From inside
/// the guard band the result fits in 31 bits.
inline std::int32_t SampleGridPosition(std::int32_t snapped, int samples)
{
  return samples * snapped + (1 << (kRasterSubPixelBits - 1)) * (samples - 1);
}

/// SampleGridPosition of a triangle's three coordinates.
inline void SampleGridPositions(const std::int32_t snapped[3], int samples, std::int32_t out[3])
{
  for (int k = 0; k < 3; ++k)
  {
    out[k] = SampleGridPosition(snapped[k], samples);
  }
}

/// Draws t at the S x S samples of pixel (x, y) -- S = samples, 2 to kMaxEdgeSamples -- into
/// block, an S x S image whose pixel (i, j) is sample (i, j): the samples rasterizeSnappedTriangle
/// covers on an image S times larger in each direction with the vertices moved to the sample grid
/// (SampleGridPosition), then cut to the pixel's samples (the same coverage, exactly; colours,
/// depths and texture coordinates to the last bit of their planes). depth, if non-null, is the S x
/// S depth block (tested and written as rasterizeSnappedTriangle does). False, drawing nothing,
/// when a vertex is more than 2^18 pixels from the pixel (the rasteriser's fixed point would not
/// hold the sample grid's coordinates); the result is otherwise Drawn, Empty or Degenerate.
bool rasterizeSamples(const ImageView& block, const SnappedTriangle& t, int x, int y, int samples,
  const DepthView* depth, const TextureView* texture, RasterResult& result);

/// The samples of pixel (x, y) that t covers, as rasterizeSamples covers them: bit i + S j for
/// sample (i, j). reachable receives false (and the result is 0) when a vertex is too far, as for
/// rasterizeSamples.
std::uint32_t sampleCoverage(const SnappedTriangle& t, int x, int y, int samples, bool& reachable);
}

#endif
