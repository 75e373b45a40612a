/**
 * @class   catar::EdgeSamples
 * @brief   the compositor's anti-aliasing: edge pixels redrawn from S x S samples
 *
 * CatadioptricAR Core (Raster). After vtkCatadioptricCompositor has drawn a frame at pixel
 * centres from catar::TriangleBins, Draw() finds the edge pixels and gives each the mean of S x S
 * samples:
 *  - a pixel is an edge pixel when one of its eight neighbours shows another triangle (the id
 *    buffer) and either of the two shows no triangle, or their colours differ by more than
 *    ContrastThreshold levels in a channel: silhouettes against the frame, and edges where one
 *    surface passes in front of another; neighbouring triangles of one smooth surface are left
 *    alone; and a pixel whose centre shows no triangle but one of whose samples a triangle covers
 *    (the tip of a corner, a sliver between pixel centres);
 *  - every sample (catar::rasterizeSamples: the centres of the pixel's S x S sub-pixels) starts as
 *    the background pixel and receives the band's triangles in the drawing order, with the
 *    compositor's rules (coverage, "over" compositing, textures, and with a depth buffer a depth
 *    per sample). In painter order, when the band's triangles that meet edge pixels are opaque,
 *    the same result is found nearest first: each sample is drawn once, by the nearest triangle
 *    that covers it, and the triangles it hides cost only a coverage test;
 *  - the pixel's colour becomes the mean of its samples (each channel rounded to nearest).
 * Interior pixels keep the centre-sampled colour (opaque interiors cost nothing more). The id
 * buffer keeps the centre's triangle. The triangles must have been binned with
 * Options::Samples = S, so that the bins hold every triangle that covers a sample, also those
 * that cover no pixel centre. Not found: a tip or sliver of one surface that reaches over another
 * surface without covering a pixel centre.
 * A vertex more than 2^18 pixels from an edge pixel (catar::rasterizeSamples) leaves that pixel
 * as drawn at its centre.
 */
#ifndef catarEdgeSamples_h
#define catarEdgeSamples_h

#include "Rasterizer.h" // for catar views

#include <cstdint>    // for std::uint8_t
#include <functional> // for std::function
#include <vector>     // for std::vector

namespace catar
{
class TriangleBins;

class EdgeSamples
{
public:
  /// Colour difference (0-255 levels, any of R, G, B) above which two neighbouring pixels that
  /// show different triangles make an edge.
  static constexpr int ContrastThreshold = 8;

  /// Writes the background pixel (x, y) (y down) as RGBA into rgba.
  using Background = std::function<void(int x, int y, std::uint8_t rgba[4])>;

  /// Redraws the edge pixels of view (drawn at pixel centres from bins, ids written into ids).
  /// opaqueTextures: per texture, whether every texel's alpha is 255. depth: with a depth buffer
  /// (opaque triangles write depth per sample, the others test it). threads: the loops' threads
  /// (Parallel.h; < 1: the default).
  void Draw(const catar::ImageView& view, const catar::IdView& ids, const TriangleBins& bins,
    const std::vector<catar::TextureView>& textures, const std::vector<char>& opaqueTextures,
    const Background& background, bool depth, int threads);

  /// Edge pixels of the last Draw(), and those left as drawn at their centres (a vertex too far).
  std::int64_t GetNumberOfEdgePixels() const { return this->NumberOfEdgePixels; }
  std::int64_t GetNumberOfUnsampledPixels() const { return this->NumberOfUnsampled; }

private:
  // One band's edge pixels: columns, row by row (Rows[r] .. Rows[r + 1] for row y0 + r).
  struct Band
  {
    std::vector<int> Columns;
    std::vector<int> Rows;
    std::vector<std::uint8_t> Samples; // RGBA, S x S per edge pixel
    std::vector<float> Depths;         // S x S per edge pixel (depth buffer)
    std::vector<std::uint8_t> Skip;    // 1: leave the pixel as drawn (a vertex too far)
    std::vector<std::uint8_t> Mask;    // 1 per edge pixel of the band's rows (finding them)
    std::vector<std::uint32_t> Done;   // per edge pixel, the samples drawn (front to back)
  };
  struct Context;
  static void DrawInOrder(const Context& c, int b, Band& band, bool depth);
  static bool DrawFrontToBack(const Context& c, int b, Band& band);
  std::vector<Band> Bands;
  std::int64_t NumberOfEdgePixels = 0;
  std::int64_t NumberOfUnsampled = 0;
};

} // namespace catar

#endif
