// CatadioptricAR Core: accuracy metrics between two renderings of the same scene (typically the
// fast rasterising path against the exact ray-traced reference).
//
// Images are RGBA8 (4 bytes per pixel: R, G, B, A), read through ConstImageView; "row 0" may be
// the top or the bottom row, as long as both images (and their triangle id buffers) use the same
// order. Every metric is computed on the logical pixel grid (x, y), 0 <= x < width, 0 <= y <
// height.
//
// Metrics (see ImageComparison for units):
//  - Silhouette: a pixel belongs to the object when its visible-triangle id is >= 0 (when the input
//    has an id buffer; preferred), otherwise when its colour differs from the background (a
//    background image when given, else a background colour) by more than a tolerance in some
//    channel (R, G, B or A).
//  - Silhouette IoU: |A and B| / |A or B|; 1 when both silhouettes are empty.
//  - Boundary distances: the boundary of a silhouette is the set of its pixels with a 4-neighbour
//    INSIDE the image that is not in the silhouette (pixels outside the image do not count: the
//    frame clips an object, it is not its outline). For each boundary pixel of A the Euclidean
//    distance (pixel centre to pixel centre) to the nearest boundary pixel of B, and vice versa,
//    computed with an exact Euclidean distance transform (Felzenszwalb & Huttenlocher 2012). Mean
//    over the union of both sets, and maximum (the symmetric Hausdorff distance between the two
//    boundaries). Both boundaries empty: 0 and 0; exactly one empty: +infinity and +infinity.
//  - PSNR of R, G, B with peak 255: 10 log10(255^2 / MSE), the MSE over the three channels of all
//    pixels (or of the pixels of the union of the silhouettes). +infinity when the compared pixels
//    are identical or there are none.
//  - SSIM (Wang, Bovik, Sheikh & Simoncelli 2004) on luminance Y = 0.299 R + 0.587 G + 0.114 B
//    (not rounded), with an 11x11 Gaussian window of sigma 1.5, C1 = (0.01 * 255)^2 and C2 = (0.03
//    * 255)^2. The window is centred on every pixel; near the border it is truncated to the image
//    and renormalised, so every pixel has an SSIM value and the result is their mean (images of
//    any size >= 1x1 are accepted). 1 for identical images.
//  - Visible-triangle difference (only when both inputs have an id buffer): the pixels where both
//    ids are >= 0, and those of them where the ids differ.
#ifndef catarImageMetrics_h
#define catarImageMetrics_h

#include "Rasterizer.h" // ImageView

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace catar
{
/// A read-only RGBA8 image (not owned), addressed as ImageView: pixel (x, y) starts at data + y *
/// rowStride + 4 x; rowStride (bytes) MAY BE NEGATIVE. Valid for the metrics iff data != nullptr,
/// width > 0, height > 0 and |rowStride| >= 4 * width.
struct ConstImageView
{
  const std::uint8_t* data = nullptr; ///< address of pixel (0, 0)
  int width = 0;                      ///< number of columns
  int height = 0;                     ///< number of rows
  std::ptrdiff_t rowStride = 0;       ///< bytes from row y to row y+1 (may be negative)

  /// Address of the first (R) byte of pixel (x, y); no bounds check.
  const std::uint8_t* pixel(int x, int y) const
  {
    return data + y * rowStride + 4 * static_cast<std::ptrdiff_t>(x);
  }
};

/// The read-only view of a rasteriser target.
inline ConstImageView AsConstView(const ImageView& view)
{
  return ConstImageView{ view.data, view.width, view.height, view.rowStride };
}

/// A read-only per-pixel visible-triangle id buffer (not owned): one int64 per pixel, < 0 (-1 by
/// convention) where no triangle is visible. rowStride is counted in ELEMENTS and may be negative.
/// Valid iff data != nullptr, width > 0, height > 0 and |rowStride| >= width.
struct TriangleIdView
{
  const RasterId* data = nullptr; ///< address of the id of pixel (0, 0)
  int width = 0;                  ///< number of columns
  int height = 0;                 ///< number of rows
  std::ptrdiff_t rowStride = 0;   ///< elements from row y to row y+1 (may be negative)

  /// Id of pixel (x, y); no bounds check.
  RasterId at(int x, int y) const { return data[y * rowStride + static_cast<std::ptrdiff_t>(x)]; }
};

/// One rendering to compare: its colours and, optionally, its visible-triangle ids.
struct ImageInput
{
  ConstImageView color;       ///< RGBA8 colours (required)
  TriangleIdView triangleIds; ///< optional (data == nullptr: none); same size as color
};

/// How CompareImages derives silhouettes and restricts the PSNR.
struct CompareOptions
{
  /// Background colour R, G, B, A (0..255), used for an input without a triangle id buffer when no
  /// backgroundImage is given.
  std::array<std::uint8_t, 4> background{ { 0, 0, 0, 255 } };
  /// Optional background image (same size as the inputs), used instead of `background`.
  ConstImageView backgroundImage;
  /// A pixel differs from the background when |pixel - background| > colorTolerance in at least
  /// one of R, G, B, A (levels, 0..255).
  int colorTolerance = 0;
  /// false: PSNR over all pixels; true: PSNR over the union of the two silhouettes.
  bool psnrOverSilhouette = false;
};

/// The result of CompareImages. When `error` is not empty the input was invalid and the numbers
/// are meaningless (zero).
struct ImageComparison
{
  double silhouetteIoU = 0;        ///< |A and B| / |A or B|, in [0, 1]; 1 when both are empty
  double meanBoundaryDistance = 0; ///< pixels; mean over both boundaries (0 / +inf, see top)
  double maxBoundaryDistance = 0;  ///< pixels; symmetric Hausdorff distance of the boundaries
  double psnr = 0;                 ///< dB, RGB, peak 255; +inf for identical compared pixels
  double ssim = 0;                 ///< dimensionless, <= 1; mean SSIM of the luminance
  std::size_t differentTrianglePixels = 0; ///< pixels where both ids are >= 0 and they differ
  std::size_t comparedTrianglePixels = 0;  ///< pixels where both ids are >= 0 (0 without ids)
  std::size_t pixels = 0;                  ///< width * height

  std::size_t silhouettePixelsA = 0; ///< pixels in the silhouette of A
  std::size_t silhouettePixelsB = 0; ///< pixels in the silhouette of B
  std::size_t boundaryPixelsA = 0;   ///< boundary pixels of A's silhouette
  std::size_t boundaryPixelsB = 0;   ///< boundary pixels of B's silhouette
  std::size_t psnrPixels = 0;        ///< pixels the PSNR was computed over
  bool trianglesCompared = false;    ///< true when both inputs had a triangle id buffer

  std::string error; ///< empty on success, otherwise why the input was rejected

  bool ok() const { return this->error.empty(); }
};

/// A binary per-pixel mask, row-major, row y of the mask = row y of the image it came from.
struct PixelMask
{
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> data; ///< width * height values, 0 or 1

  bool at(int x, int y) const
  {
    return this->data[static_cast<std::size_t>(y) * static_cast<std::size_t>(this->width) +
             static_cast<std::size_t>(x)] != 0;
  }
  /// Number of set pixels.
  std::size_t count() const;
};

/// Directed and symmetric distances between two boundaries (pixels). See the top of this file.
struct BoundaryDistances
{
  double mean = 0;        ///< mean over the boundary pixels of both sets
  double max = 0;         ///< max(maxAToB, maxBToA), the symmetric Hausdorff distance
  double meanAToB = 0;    ///< mean over A's boundary of the distance to B's boundary
  double meanBToA = 0;    ///< mean over B's boundary of the distance to A's boundary
  double maxAToB = 0;     ///< max over A's boundary of the distance to B's boundary
  double maxBToA = 0;     ///< max over B's boundary of the distance to A's boundary
  std::size_t countA = 0; ///< boundary pixels of A
  std::size_t countB = 0; ///< boundary pixels of B
};

/// Compares two renderings. Never throws; invalid input (null data, zero or mismatched sizes,
/// too small strides, a tolerance outside 0..255, running out of memory) gives a result whose
/// `error` says why.
ImageComparison CompareImages(
  const ImageInput& a, const ImageInput& b, const CompareOptions& options = CompareOptions());

/// The silhouette of one input (ids when it has them, else colour against the background). The
/// input must be valid (an empty mask is returned otherwise).
PixelMask SilhouetteMask(const ImageInput& input, const CompareOptions& options);

/// The boundary of a mask: set pixels with a 4-neighbour inside the image that is not set.
PixelMask BoundaryMask(const PixelMask& mask);

/// |A and B| / |A or B|; 1 when both are empty; NaN when the sizes differ.
double SilhouetteIoU(const PixelMask& a, const PixelMask& b);

/// Exact squared Euclidean distance transform: for each pixel the squared distance (pixel units)
/// to the nearest set pixel of `sites`, +infinity when `sites` is empty. O(width * height).
std::vector<double> SquaredDistanceTransform(const PixelMask& sites);

/// Distances between the boundary pixels of two boundary masks (already boundaries, e.g. from
/// BoundaryMask). Sizes must match (all NaN otherwise).
BoundaryDistances ComputeBoundaryDistances(const PixelMask& boundaryA, const PixelMask& boundaryB);

/// PSNR (dB) of R, G, B with peak 255 over all pixels, or over the set pixels of `region` when it
/// is not null. +infinity when the compared pixels are identical or there are none; NaN for
/// invalid or mismatched views (or region size). `comparedPixels` (optional) receives the count.
double ComputePSNR(const ConstImageView& a, const ConstImageView& b,
  const PixelMask* region = nullptr, std::size_t* comparedPixels = nullptr);

/// Mean SSIM of the luminance (see the top of this file); NaN for invalid or mismatched views.
double ComputeSSIM(const ConstImageView& a, const ConstImageView& b);

/// Counts the pixels where both ids are >= 0 (`compared`) and those of them whose ids differ
/// (`different`). Returns false (and zero counts) for invalid or mismatched buffers.
bool CountTriangleDifferences(
  const TriangleIdView& a, const TriangleIdView& b, std::size_t& different, std::size_t& compared);

/// Writes a visualisation of |a - b| into `out` (same size): R, G, B = min(255, gain * |a - b|)
/// channel by channel, A = 255. Returns an empty string on success, otherwise the error.
std::string DifferenceImage(
  const ConstImageView& a, const ConstImageView& b, const ImageView& out, int gain = 4);
} // namespace catar

#endif
