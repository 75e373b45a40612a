#include "ImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <new>

namespace catar
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t PixelCount(int width, int height)
{
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

bool IsValid(const ConstImageView& v)
{
  return v.data != nullptr && v.width > 0 && v.height > 0 &&
    std::abs(v.rowStride) >= 4 * static_cast<std::ptrdiff_t>(v.width);
}

bool IsValid(const TriangleIdView& v)
{
  return v.data != nullptr && v.width > 0 && v.height > 0 &&
    std::abs(v.rowStride) >= static_cast<std::ptrdiff_t>(v.width);
}

bool SameSize(const ConstImageView& a, const ConstImageView& b)
{
  return a.width == b.width && a.height == b.height;
}

// Why a view is invalid ("" when valid).
std::string ViewError(const ConstImageView& v, const char* what)
{
  const std::string name(what);
  if (!v.data)
  {
    return name + ": null data";
  }
  if (v.width <= 0 || v.height <= 0)
  {
    return name + ": empty size " + std::to_string(v.width) + "x" + std::to_string(v.height);
  }
  if (std::abs(v.rowStride) < 4 * static_cast<std::ptrdiff_t>(v.width))
  {
    return name + ": row stride " + std::to_string(v.rowStride) + " smaller than 4 * width";
  }
  return std::string();
}

std::string IdViewError(const TriangleIdView& v, const ConstImageView& color, const char* what)
{
  const std::string name(what);
  if (!IsValid(v))
  {
    return name + ": invalid triangle id buffer (null data, empty size or too small stride)";
  }
  if (v.width != color.width || v.height != color.height)
  {
    return name + ": triangle id buffer is " + std::to_string(v.width) + "x" +
      std::to_string(v.height) + ", colour image is " + std::to_string(color.width) + "x" +
      std::to_string(color.height);
  }
  return std::string();
}

// Felzenszwalb-Huttenlocher 1D squared distance transform of a sampled function f (values may be
// +inf: those samples carry no parabola). d[q] = min_p (q - p)^2 + f[p]; +inf when every f is inf.
// v and z are work arrays of size n and n + 1.
void DistanceTransform1D(const double* f, int n, double* d, int* v, double* z)
{
  int k = -1;
  for (int q = 0; q < n; ++q)
  {
    if (f[q] == kInf)
    {
      continue;
    }
    const double fq = f[q] + static_cast<double>(q) * q;
    if (k < 0)
    {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    // Pop the parabolas hidden by the new one (z[0] = -inf stops the loop at k = 0).
    double s = (fq - (f[v[k]] + static_cast<double>(v[k]) * v[k])) / (2.0 * (q - v[k]));
    while (s <= z[k])
    {
      --k;
      s = (fq - (f[v[k]] + static_cast<double>(v[k]) * v[k])) / (2.0 * (q - v[k]));
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (k < 0)
  {
    std::fill(d, d + n, kInf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q)
  {
    while (z[j + 1] < q)
    {
      ++j;
    }
    const double dq = static_cast<double>(q - v[j]);
    d[q] = dq * dq + f[v[j]];
  }
}

// Luminance of a view, row-major.
std::vector<double> Luminance(const ConstImageView& v)
{
  std::vector<double> y(PixelCount(v.width, v.height));
  std::size_t i = 0;
  for (int r = 0; r < v.height; ++r)
  {
    for (int c = 0; c < v.width; ++c, ++i)
    {
      const std::uint8_t* p = v.pixel(c, r);
      y[i] = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    }
  }
  return y;
}

// Gaussian window of SSIM: 11 taps, sigma 1.5.
constexpr int kSsimRadius = 5;
constexpr double kSsimSigma = 1.5;
} // namespace

std::size_t PixelMask::count() const
{
  std::size_t n = 0;
  for (std::uint8_t v : this->data)
  {
    n += v != 0 ? 1 : 0;
  }
  return n;
}

PixelMask SilhouetteMask(const ImageInput& input, const CompareOptions& options)
{
  PixelMask mask;
  const ConstImageView& c = input.color;
  if (!IsValid(c))
  {
    return mask;
  }
  const bool useIds = input.triangleIds.data != nullptr;
  if (useIds && !IdViewError(input.triangleIds, c, "").empty())
  {
    return mask;
  }
  const ConstImageView& bg = options.backgroundImage;
  const bool useBackgroundImage = bg.data != nullptr;
  if (!useIds && useBackgroundImage && (!IsValid(bg) || !SameSize(bg, c)))
  {
    return mask;
  }
  mask.width = c.width;
  mask.height = c.height;
  mask.data.assign(PixelCount(c.width, c.height), 0);
  const int tol = options.colorTolerance;
  std::size_t i = 0;
  for (int y = 0; y < c.height; ++y)
  {
    for (int x = 0; x < c.width; ++x, ++i)
    {
      bool inside = false;
      if (useIds)
      {
        inside = input.triangleIds.at(x, y) >= 0;
      }
      else
      {
        const std::uint8_t* p = c.pixel(x, y);
        const std::uint8_t* q = useBackgroundImage ? bg.pixel(x, y) : options.background.data();
        for (int ch = 0; ch < 4 && !inside; ++ch)
        {
          inside = std::abs(static_cast<int>(p[ch]) - static_cast<int>(q[ch])) > tol;
        }
      }
      mask.data[i] = inside ? 1 : 0;
    }
  }
  return mask;
}

PixelMask BoundaryMask(const PixelMask& mask)
{
  PixelMask boundary;
  boundary.width = mask.width;
  boundary.height = mask.height;
  boundary.data.assign(mask.data.size(), 0);
  if (mask.data.size() != PixelCount(mask.width, mask.height))
  {
    boundary.width = boundary.height = 0;
    boundary.data.clear();
    return boundary;
  }
  const int w = mask.width;
  const int h = mask.height;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      if (!mask.at(x, y))
      {
        continue;
      }
      const bool edge = (x > 0 && !mask.at(x - 1, y)) || (x + 1 < w && !mask.at(x + 1, y)) ||
        (y > 0 && !mask.at(x, y - 1)) || (y + 1 < h && !mask.at(x, y + 1));
      if (edge)
      {
        boundary.data[static_cast<std::size_t>(y) * w + x] = 1;
      }
    }
  }
  return boundary;
}

double SilhouetteIoU(const PixelMask& a, const PixelMask& b)
{
  if (a.width != b.width || a.height != b.height || a.data.size() != b.data.size())
  {
    return kNaN;
  }
  std::size_t both = 0;
  std::size_t either = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
  {
    const bool pa = a.data[i] != 0;
    const bool pb = b.data[i] != 0;
    both += (pa && pb) ? 1 : 0;
    either += (pa || pb) ? 1 : 0;
  }
  if (either == 0)
  {
    return 1.0;
  }
  return static_cast<double>(both) / static_cast<double>(either);
}

std::vector<double> SquaredDistanceTransform(const PixelMask& sites)
{
  const int w = sites.width;
  const int h = sites.height;
  if (w <= 0 || h <= 0 || sites.data.size() != PixelCount(w, h))
  {
    return std::vector<double>();
  }
  std::vector<double> grid(sites.data.size());
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    grid[i] = sites.data[i] ? 0.0 : kInf;
  }
  const int n = std::max(w, h);
  std::vector<double> f(n);
  std::vector<double> d(n);
  std::vector<int> v(n);
  std::vector<double> z(static_cast<std::size_t>(n) + 1);
  // Columns.
  for (int x = 0; x < w; ++x)
  {
    for (int y = 0; y < h; ++y)
    {
      f[y] = grid[static_cast<std::size_t>(y) * w + x];
    }
    DistanceTransform1D(f.data(), h, d.data(), v.data(), z.data());
    for (int y = 0; y < h; ++y)
    {
      grid[static_cast<std::size_t>(y) * w + x] = d[y];
    }
  }
  // Rows.
  for (int y = 0; y < h; ++y)
  {
    double* row = grid.data() + static_cast<std::size_t>(y) * w;
    std::copy(row, row + w, f.begin());
    DistanceTransform1D(f.data(), w, row, v.data(), z.data());
  }
  return grid;
}

BoundaryDistances ComputeBoundaryDistances(const PixelMask& boundaryA, const PixelMask& boundaryB)
{
  BoundaryDistances r;
  if (boundaryA.width != boundaryB.width || boundaryA.height != boundaryB.height ||
    boundaryA.data.size() != PixelCount(boundaryA.width, boundaryA.height) ||
    boundaryB.data.size() != boundaryA.data.size())
  {
    r.mean = r.max = r.meanAToB = r.meanBToA = r.maxAToB = r.maxBToA = kNaN;
    return r;
  }
  r.countA = boundaryA.count();
  r.countB = boundaryB.count();
  if (r.countA == 0 && r.countB == 0)
  {
    return r;
  }
  if (r.countA == 0 || r.countB == 0)
  {
    r.mean = r.max = r.meanAToB = r.meanBToA = r.maxAToB = r.maxBToA = kInf;
    return r;
  }
  // Directed distances from the set pixels of `from` to the nearest set pixel of `to`.
  auto directed = [](const PixelMask& from, const PixelMask& to, double& sum, double& maximum) {
    const std::vector<double> dt = SquaredDistanceTransform(to);
    sum = 0;
    maximum = 0;
    for (std::size_t i = 0; i < from.data.size(); ++i)
    {
      if (from.data[i])
      {
        const double dist = std::sqrt(dt[i]);
        sum += dist;
        maximum = std::max(maximum, dist);
      }
    }
  };
  double sumAB = 0;
  double sumBA = 0;
  directed(boundaryA, boundaryB, sumAB, r.maxAToB);
  directed(boundaryB, boundaryA, sumBA, r.maxBToA);
  r.meanAToB = sumAB / static_cast<double>(r.countA);
  r.meanBToA = sumBA / static_cast<double>(r.countB);
  r.mean = (sumAB + sumBA) / static_cast<double>(r.countA + r.countB);
  r.max = std::max(r.maxAToB, r.maxBToA);
  return r;
}

double ComputePSNR(const ConstImageView& a, const ConstImageView& b, const PixelMask* region,
  std::size_t* comparedPixels)
{
  if (comparedPixels)
  {
    *comparedPixels = 0;
  }
  if (!IsValid(a) || !IsValid(b) || !SameSize(a, b))
  {
    return kNaN;
  }
  if (region &&
    (region->width != a.width || region->height != a.height ||
      region->data.size() != PixelCount(a.width, a.height)))
  {
    return kNaN;
  }
  std::uint64_t sumSquares = 0;
  std::size_t count = 0;
  std::size_t i = 0;
  for (int y = 0; y < a.height; ++y)
  {
    for (int x = 0; x < a.width; ++x, ++i)
    {
      if (region && !region->data[i])
      {
        continue;
      }
      const std::uint8_t* p = a.pixel(x, y);
      const std::uint8_t* q = b.pixel(x, y);
      for (int ch = 0; ch < 3; ++ch)
      {
        const int diff = static_cast<int>(p[ch]) - static_cast<int>(q[ch]);
        sumSquares += static_cast<std::uint64_t>(diff * diff);
      }
      ++count;
    }
  }
  if (comparedPixels)
  {
    *comparedPixels = count;
  }
  if (count == 0 || sumSquares == 0)
  {
    return kInf;
  }
  // MSE = sumSquares / (3 count); PSNR = 10 log10(255^2 / MSE).
  const double ratio =
    255.0 * 255.0 * 3.0 * static_cast<double>(count) / static_cast<double>(sumSquares);
  return 10.0 * std::log10(ratio);
}

double ComputeSSIM(const ConstImageView& a, const ConstImageView& b)
{
  if (!IsValid(a) || !IsValid(b) || !SameSize(a, b))
  {
    return kNaN;
  }
  const int w = a.width;
  const int h = a.height;
  const std::vector<double> ya = Luminance(a);
  const std::vector<double> yb = Luminance(b);

  double g[2 * kSsimRadius + 1];
  for (int k = -kSsimRadius; k <= kSsimRadius; ++k)
  {
    g[k + kSsimRadius] = std::exp(-(k * k) / (2.0 * kSsimSigma * kSsimSigma));
  }

  // Horizontal pass of the five filtered quantities (truncated, renormalised window).
  const std::size_t n = PixelCount(w, h);
  std::vector<double> ha(n), hb(n), haa(n), hbb(n), hab(n);
  for (int y = 0; y < h; ++y)
  {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x)
    {
      const int k0 = std::max(-kSsimRadius, -x);
      const int k1 = std::min(kSsimRadius, w - 1 - x);
      double sw = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (int k = k0; k <= k1; ++k)
      {
        const double gk = g[k + kSsimRadius];
        const double va = ya[row + x + k];
        const double vb = yb[row + x + k];
        sw += gk;
        sa += gk * va;
        sb += gk * vb;
        saa += gk * va * va;
        sbb += gk * vb * vb;
        sab += gk * va * vb;
      }
      const std::size_t i = row + x;
      ha[i] = sa / sw;
      hb[i] = sb / sw;
      haa[i] = saa / sw;
      hbb[i] = sbb / sw;
      hab[i] = sab / sw;
    }
  }

  // Vertical pass and the SSIM map, accumulated.
  const double c1 = (0.01 * 255.0) * (0.01 * 255.0);
  const double c2 = (0.03 * 255.0) * (0.03 * 255.0);
  double total = 0;
  for (int y = 0; y < h; ++y)
  {
    const int k0 = std::max(-kSsimRadius, -y);
    const int k1 = std::min(kSsimRadius, h - 1 - y);
    double sw = 0;
    for (int k = k0; k <= k1; ++k)
    {
      sw += g[k + kSsimRadius];
    }
    double rowTotal = 0;
    for (int x = 0; x < w; ++x)
    {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (int k = k0; k <= k1; ++k)
      {
        const double gk = g[k + kSsimRadius];
        const std::size_t i = static_cast<std::size_t>(y + k) * w + x;
        sa += gk * ha[i];
        sb += gk * hb[i];
        saa += gk * haa[i];
        sbb += gk * hbb[i];
        sab += gk * hab[i];
      }
      const double mua = sa / sw;
      const double mub = sb / sw;
      const double varA = saa / sw - mua * mua;
      const double varB = sbb / sw - mub * mub;
      const double cov = sab / sw - mua * mub;
      const double num = (2.0 * mua * mub + c1) * (2.0 * cov + c2);
      const double den = (mua * mua + mub * mub + c1) * (varA + varB + c2);
      rowTotal += num / den;
    }
    total += rowTotal;
  }
  return total / static_cast<double>(n);
}

bool CountTriangleDifferences(
  const TriangleIdView& a, const TriangleIdView& b, std::size_t& different, std::size_t& compared)
{
  different = 0;
  compared = 0;
  if (!IsValid(a) || !IsValid(b) || a.width != b.width || a.height != b.height)
  {
    return false;
  }
  for (int y = 0; y < a.height; ++y)
  {
    for (int x = 0; x < a.width; ++x)
    {
      const RasterId ia = a.at(x, y);
      const RasterId ib = b.at(x, y);
      if (ia >= 0 && ib >= 0)
      {
        ++compared;
        different += ia != ib ? 1 : 0;
      }
    }
  }
  return true;
}

std::string DifferenceImage(
  const ConstImageView& a, const ConstImageView& b, const ImageView& out, int gain)
{
  std::string error = ViewError(a, "image A");
  if (error.empty())
  {
    error = ViewError(b, "image B");
  }
  if (error.empty())
  {
    error = ViewError(AsConstView(out), "output image");
  }
  if (!error.empty())
  {
    return error;
  }
  if (!SameSize(a, b) || out.width != a.width || out.height != a.height)
  {
    return "image sizes differ";
  }
  for (int y = 0; y < a.height; ++y)
  {
    for (int x = 0; x < a.width; ++x)
    {
      const std::uint8_t* p = a.pixel(x, y);
      const std::uint8_t* q = b.pixel(x, y);
      std::uint8_t* o = out.pixel(x, y);
      for (int ch = 0; ch < 3; ++ch)
      {
        const long diff = std::abs(static_cast<long>(p[ch]) - static_cast<long>(q[ch]));
        o[ch] = static_cast<std::uint8_t>(std::clamp(diff * gain, 0L, 255L));
      }
      o[3] = 255;
    }
  }
  return std::string();
}

ImageComparison CompareImages(
  const ImageInput& a, const ImageInput& b, const CompareOptions& options)
{
  ImageComparison result;
  try
  {
    result.error = ViewError(a.color, "image A");
    if (result.error.empty())
    {
      result.error = ViewError(b.color, "image B");
    }
    if (result.error.empty() && !SameSize(a.color, b.color))
    {
      result.error = "image sizes differ: " + std::to_string(a.color.width) + "x" +
        std::to_string(a.color.height) + " and " + std::to_string(b.color.width) + "x" +
        std::to_string(b.color.height);
    }
    if (result.error.empty() && a.triangleIds.data)
    {
      result.error = IdViewError(a.triangleIds, a.color, "image A");
    }
    if (result.error.empty() && b.triangleIds.data)
    {
      result.error = IdViewError(b.triangleIds, b.color, "image B");
    }
    if (result.error.empty() && (options.colorTolerance < 0 || options.colorTolerance > 255))
    {
      result.error =
        "colour tolerance " + std::to_string(options.colorTolerance) + " outside 0..255";
    }
    const bool needBackground = !a.triangleIds.data || !b.triangleIds.data;
    if (result.error.empty() && needBackground && options.backgroundImage.data)
    {
      result.error = ViewError(options.backgroundImage, "background image");
      if (result.error.empty() && !SameSize(options.backgroundImage, a.color))
      {
        result.error = "background image size differs from the images";
      }
    }
    if (!result.error.empty())
    {
      return result;
    }

    result.pixels = PixelCount(a.color.width, a.color.height);

    const PixelMask maskA = SilhouetteMask(a, options);
    const PixelMask maskB = SilhouetteMask(b, options);
    result.silhouettePixelsA = maskA.count();
    result.silhouettePixelsB = maskB.count();
    result.silhouetteIoU = SilhouetteIoU(maskA, maskB);

    const BoundaryDistances bd = ComputeBoundaryDistances(BoundaryMask(maskA), BoundaryMask(maskB));
    result.meanBoundaryDistance = bd.mean;
    result.maxBoundaryDistance = bd.max;
    result.boundaryPixelsA = bd.countA;
    result.boundaryPixelsB = bd.countB;

    if (options.psnrOverSilhouette)
    {
      PixelMask both = maskA;
      for (std::size_t i = 0; i < both.data.size(); ++i)
      {
        both.data[i] = (maskA.data[i] || maskB.data[i]) ? 1 : 0;
      }
      result.psnr = ComputePSNR(a.color, b.color, &both, &result.psnrPixels);
    }
    else
    {
      result.psnr = ComputePSNR(a.color, b.color, nullptr, &result.psnrPixels);
    }
    result.ssim = ComputeSSIM(a.color, b.color);

    if (a.triangleIds.data && b.triangleIds.data)
    {
      result.trianglesCompared = CountTriangleDifferences(a.triangleIds, b.triangleIds,
        result.differentTrianglePixels, result.comparedTrianglePixels);
    }
  }
  catch (const std::bad_alloc&)
  {
    result = ImageComparison();
    result.error = "out of memory";
  }
  catch (const std::exception& e)
  {
    result = ImageComparison();
    result.error = std::string("unexpected error: ") + e.what();
  }
  catch (...)
  {
    result = ImageComparison();
    result.error = "unexpected error";
  }
  return result;
}
} // namespace catar
