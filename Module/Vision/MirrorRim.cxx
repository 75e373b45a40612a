// CatadioptricAR Core: the mirror's rim along the normals of a first ellipse (MirrorRim.h).
#include "MirrorRim.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace catar
{
namespace detail
{
bool Undistorter::operator()(const Vec2& pixel, Vec2& undistorted) const
{
  Vec2 xy;
  if (!this->Camera.PixelToNormalized(pixel, xy))
  {
    return false;
  }
  const Intrinsics& k = this->Camera.intrinsics;
  undistorted = Vec2(k.fx * xy.x() + k.skew * xy.y() + k.cx, k.fy * xy.y() + k.cy);
  return undistorted.allFinite();
}

Vec2 Undistorter::Distorted(const Vec2& undistorted) const
{
  const Intrinsics& k = this->Camera.intrinsics;
  const double y = (undistorted.y() - k.cy) / k.fy;
  const double x = (undistorted.x() - k.cx - k.skew * y) / k.fx;
  return this->Camera.DirectionToPixel(Vec3(x, y, 1.0));
}

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kStep = 0.5;        // spacing of the samples along a normal, pixels
constexpr double kFineSigma = 1.0;   // smoothing across the rim to place it, pixels
constexpr double kPeakSigmas = 5.0;  // an edge: the derivative beyond this many noise sigmas
constexpr double kMinPeak = 0.5;     // and at least this (grey levels per pixel)
constexpr double kMinCovered = 0.35; // a rim: edges on at least this fraction of the normals
constexpr double kMinLayer = 0.2;    // a closed edge: on at least this fraction
constexpr int kGap = 4;              // samples between one closed edge and the next outside it

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// The mean of the first three channels of an 8-bit RGB or RGBA image at a pixel (bilinear); NaN
// outside.
template<int Channels>
float Grey(const cv::Mat& image, const Vec2& p)
{
  const double x = p.x(), y = p.y();
  if (!(x >= 0.0 && y >= 0.0 && x <= image.cols - 1 && y <= image.rows - 1))
  {
    return kNaN;
  }
  const int x0 = std::min(static_cast<int>(x), image.cols - 2);
  const int y0 = std::min(static_cast<int>(y), image.rows - 2);
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int xx, int yy) {
    const std::uint8_t* v = image.ptr<std::uint8_t>(yy) + Channels * xx;
    return (static_cast<double>(v[0]) + v[1] + v[2]) / 3.0;
  };
  return static_cast<float>((1.0 - fy) * ((1.0 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
    fy * ((1.0 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1)));
}

// A Gaussian kernel of that sigma (samples), radius 3 sigma.
std::vector<double> Kernel(double sigma)
{
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> k(static_cast<std::size_t>(2 * radius + 1));
  for (int i = 0; i <= 2 * radius; ++i)
  {
    const double x = i - radius;
    k[static_cast<std::size_t>(i)] = std::exp(-0.5 * x * x / (sigma * sigma));
  }
  return k;
}

// Rows x columns of floats, NaN where nothing was sampled.
struct Grid
{
  int rows = 0, cols = 0;
  std::vector<float> v;
  Grid(int r, int c, float fill)
    : rows(r)
    , cols(c)
    , v(static_cast<std::size_t>(r) * static_cast<std::size_t>(c), fill)
  {
  }
  float& operator()(int r, int c) { return v[static_cast<std::size_t>(r) * cols + c]; }
  float operator()(int r, int c) const { return v[static_cast<std::size_t>(r) * cols + c]; }
};

// Normalised convolution (NaN samples weigh nothing) along the columns (across) and then along
// the rows, circularly (along the closed rim).
Grid Smoothed(const Grid& g, double acrossSigma, double alongSigma)
{
  const std::vector<double> across = Kernel(acrossSigma), along = Kernel(alongSigma);
  const int ra = static_cast<int>(across.size() / 2), rl = static_cast<int>(along.size() / 2);
  Grid sum(g.rows, g.cols, 0.0f), weight(g.rows, g.cols, 0.0f);
  for (int i = 0; i < g.rows; ++i)
  {
    for (int k = 0; k < g.cols; ++k)
    {
      double s = 0.0, w = 0.0;
      for (std::size_t j = 0; j < across.size(); ++j)
      {
        const int kk = k + static_cast<int>(j) - ra;
        if (kk >= 0 && kk < g.cols && !std::isnan(g(i, kk)))
        {
          const double c = across[j];
          s += c * g(i, kk);
          w += c;
        }
      }
      sum(i, k) = static_cast<float>(s);
      weight(i, k) = static_cast<float>(w);
    }
  }
  Grid out(g.rows, g.cols, kNaN);
  for (int i = 0; i < g.rows; ++i)
  {
    for (int k = 0; k < g.cols; ++k)
    {
      if (std::isnan(g(i, k)))
      {
        continue;
      }
      double s = 0.0, w = 0.0;
      for (std::size_t j = 0; j < along.size(); ++j)
      {
        const int ii = ((i + static_cast<int>(j) - rl) % g.rows + g.rows) % g.rows;
        const double c = along[j];
        s += c * sum(ii, k);
        w += c * weight(ii, k);
      }
      out(i, k) = w > 0.0 ? static_cast<float>(s / w) : kNaN;
    }
  }
  return out;
}

// The path through the columns, one per row (normal), moving at most one column from one row to
// the next, at or beyond `lowest` on each row, that collects the most score: the strongest
// closed edge that lies wholly outside the last one.
std::vector<int> StrongestPath(const Grid& score, const std::vector<int>& lowest)
{
  const int n = score.rows, m = score.cols;
  const float kOff = -std::numeric_limits<float>::infinity();
  Grid total(n, m, kOff);
  std::vector<int> from(static_cast<std::size_t>(n) * static_cast<std::size_t>(m), -1);
  for (int k = lowest[0]; k < m; ++k)
  {
    total(0, k) = score(0, k);
  }
  for (int i = 1; i < n; ++i)
  {
    for (int k = lowest[static_cast<std::size_t>(i)]; k < m; ++k)
    {
      float best = kOff;
      int arg = -1;
      for (int d = -1; d <= 1; ++d)
      {
        const int kk = k + d;
        if (kk >= 0 && kk < m && total(i - 1, kk) > best)
        {
          best = total(i - 1, kk);
          arg = kk;
        }
      }
      if (arg >= 0)
      {
        total(i, k) = best + score(i, k);
        from[static_cast<std::size_t>(i) * m + k] = arg;
      }
    }
  }
  std::vector<int> path(static_cast<std::size_t>(n), -1);
  int k = -1;
  float best = kOff;
  for (int kk = 0; kk < m; ++kk)
  {
    if (total(n - 1, kk) > best)
    {
      best = total(n - 1, kk);
      k = kk;
    }
  }
  for (int i = n - 1; i >= 0 && k >= 0; --i)
  {
    path[static_cast<std::size_t>(i)] = k;
    k = i > 0 ? from[static_cast<std::size_t>(i) * m + k] : -1;
  }
  return path;
}
} // namespace

bool RimFromProfiles(const cv::Mat& image, const Undistorter& lens, const Ellipse& guess,
  const RimSearch& search, std::vector<Vec2>& pixels, std::vector<Vec2>& undistorted,
  RimReport& report, std::string& error)
{
  if (image.type() != CV_8UC3 && image.type() != CV_8UC4)
  {
    error = "the rim's search needs an 8-bit RGB or RGBA image";
    return false;
  }
  const auto grey = image.type() == CV_8UC3 ? Grey<3> : Grey<4>;
  pixels.clear();
  undistorted.clear();
  report = RimReport{};
  double perimeter = 2.0 * kPi * std::sqrt(0.5 * (guess.a * guess.a + guess.b * guess.b));
  int n = std::clamp(static_cast<int>(perimeter / 2.0), 180, 4096);
  if (search.feet)
  {
    // Normals at given points along the rim: the arc between them is their mean spacing.
    n = static_cast<int>(search.feet->size());
    perimeter = 0.0;
    for (int i = 1; i < n; ++i)
    {
      perimeter += ((*search.feet)[static_cast<std::size_t>(i)] -
        (*search.feet)[static_cast<std::size_t>(i - 1)])
                     .norm();
    }
    perimeter *= n > 1 ? static_cast<double>(n) / (n - 1) : 1.0;
    if (n < 20 || !(perimeter > 0.0))
    {
      error = "no mirror rim found: too few points to place it from";
      return false;
    }
  }
  const double inside = std::min(search.inside, 0.5 * guess.b);
  const int m = static_cast<int>((inside + search.outside) / kStep) + 1;
  std::vector<Vec2> foot(static_cast<std::size_t>(n)), normal(static_cast<std::size_t>(n));
  Grid profile(n, m, kNaN);
  std::vector<bool> usable(static_cast<std::size_t>(n), false);
  for (int i = 0; i < n; ++i)
  {
    const Vec2 p =
      search.feet ? (*search.feet)[static_cast<std::size_t>(i)] : guess.At(2.0 * kPi * i / n);
    Vec2 g;
    SampsonDistance(guess.Q, p, &g);
    if ((p - guess.centre).dot(g) < 0.0)
    {
      g = -g;
    }
    foot[static_cast<std::size_t>(i)] = p;
    normal[static_cast<std::size_t>(i)] = g;
    int valid = 0;
    for (int k = 0; k < m; ++k)
    {
      const Vec2 q = lens.Distorted(p + (k * kStep - inside) * g);
      profile(i, k) = q.allFinite() ? grey(image, q) : kNaN;
      valid += !std::isnan(profile(i, k));
    }
    // A normal whose search reaches out of the image over much of its length tells nothing.
    usable[static_cast<std::size_t>(i)] = valid >= 0.8 * m;
    report.angles += usable[static_cast<std::size_t>(i)];
  }
  if (report.angles < 20)
  {
    error = "the mirror's rim lies outside the image";
    return false;
  }
  const double along = search.alongSigma / (perimeter / n);
  const Grid smooth = Smoothed(profile, search.acrossSigma / kStep, along);
  Grid slope(n, m, kNaN);
  std::vector<float> magnitudes;
  for (int i = 0; i < n; ++i)
  {
    for (int k = 1; k + 1 < m; ++k)
    {
      const float d = (smooth(i, k + 1) - smooth(i, k - 1)) / static_cast<float>(2.0 * kStep);
      slope(i, k) = d;
      // The noise from the outer quarter of each normal: the backdrop, beyond the rim.
      if (!std::isnan(d) && usable[static_cast<std::size_t>(i)] && 4 * k >= 3 * m)
      {
        magnitudes.push_back(std::abs(d));
      }
    }
  }
  if (magnitudes.empty())
  {
    error = "the mirror's rim lies outside the image";
    return false;
  }
  // The noise: the median absolute derivative there (most samples lie off edges), as a sigma.
  const std::size_t half = magnitudes.size() / 2;
  std::nth_element(
    magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(half), magnitudes.end());
  report.noise = 1.4826 * magnitudes[half];
  // Placing a rim known to lie in the band: every peak counts, the strongest is the rim.
  const double threshold = search.place ? 0.0 : std::max(kPeakSigmas * report.noise, kMinPeak);

  // Edges: the derivative's peaks (across the rim) above the threshold.
  Grid peak(n, m, 0.0f), score(n, m, -0.3f);
  for (int i = 0; i < n; ++i)
  {
    if (!usable[static_cast<std::size_t>(i)])
    {
      for (int k = 0; k < m; ++k)
      {
        score(i, k) = 0.0f;
      }
      continue;
    }
    for (int k = 2; k + 2 < m; ++k)
    {
      const float a = std::abs(slope(i, k - 1)), b = std::abs(slope(i, k)),
                  c = std::abs(slope(i, k + 1));
      if (b >= threshold && b >= a && b > c && slope(i, k - 1) * slope(i, k) > 0.0f &&
        slope(i, k + 1) * slope(i, k) > 0.0f)
      {
        peak(i, k) = b;
        const float s = static_cast<float>(std::min(b / threshold, 3.0));
        for (int kk = k - 1; kk <= k + 1; ++kk)
        {
          score(i, kk) = std::max(score(i, kk), kk == k ? s : 0.5f * s);
        }
      }
    }
  }

  // Closed edges from the inside out: the strongest, then the strongest wholly outside it, and so
  // on while one is found on enough normals; the last is the rim.
  const auto peakNear = [&](int i, int k) {
    int best = -1;
    for (int kk = std::max(k - 1, 0); kk <= std::min(k + 1, m - 1); ++kk)
    {
      if (peak(i, kk) > 0.0f && (best < 0 || peak(i, kk) > peak(i, best)))
      {
        best = kk;
      }
    }
    return best;
  };
  std::vector<int> lowest(static_cast<std::size_t>(n), 0), rim;
  int rimCovered = 0;
  if (search.place)
  {
    rim.assign(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < n; ++i)
    {
      for (int k = 0; k < m; ++k)
      {
        int& best = rim[static_cast<std::size_t>(i)];
        if (peak(i, k) > 0.0f && (best < 0 || peak(i, k) > peak(i, best)))
        {
          best = k;
        }
      }
      rimCovered += usable[static_cast<std::size_t>(i)] && rim[static_cast<std::size_t>(i)] >= 0;
    }
    if (rimCovered < kMinCovered * report.angles)
    {
      rim.clear();
    }
  }
  // Closed edges from the inside out (each wholly outside the last) while one shows on at least
  // kMinLayer of the normals; on each normal the rim is the outermost of them that shows there
  // (a dome's limb runs round only part of the first ellipse; its cut, elsewhere, is no cone and
  // the outline's fit leaves it out).
  int layers = 0;
  for (int layer = 0; layer < 8 && !search.place; ++layer)
  {
    const std::vector<int> path = StrongestPath(score, lowest);
    if (path[0] < 0)
    {
      break;
    }
    int covered = 0;
    std::vector<int> found(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < n; ++i)
    {
      const std::size_t ii = static_cast<std::size_t>(i);
      found[ii] = usable[ii] ? peakNear(i, path[ii]) : -1;
      covered += found[ii] >= 0;
    }
    if (covered < kMinLayer * report.angles)
    {
      break;
    }
    ++layers;
    rim.resize(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < n; ++i)
    {
      const std::size_t ii = static_cast<std::size_t>(i);
      rim[ii] = found[ii] >= 0 ? found[ii] : rim[ii];
      lowest[ii] = std::min(path[ii] + kGap, m - 1);
    }
  }
  if (!search.place)
  {
    rimCovered =
      static_cast<int>(std::count_if(rim.begin(), rim.end(), [](int k) { return k >= 0; }));
    if (layers == 0 || rimCovered < kMinCovered * report.angles)
    {
      rim.clear();
    }
  }
  if (rim.empty())
  {
    error = "no mirror rim found: edges run round less than " +
      std::to_string(static_cast<int>(100.0 * kMinCovered)) + " % of the outline";
    return false;
  }
  report.covered = rimCovered;

  // The rim's points: on each normal, the peak of the derivative with less smoothing across
  // within a pixel and a half of the rim's, between samples by a parabola.
  const Grid fine = Smoothed(profile, kFineSigma / kStep, along);
  const auto fineSlope = [&](int i, int k) {
    return k >= 1 && k + 1 < m ? (fine(i, k + 1) - fine(i, k - 1)) / static_cast<float>(2.0 * kStep)
                               : kNaN;
  };
  double shift = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const int k = usable[static_cast<std::size_t>(i)] && rim[static_cast<std::size_t>(i)] >= 0
      ? peakNear(i, rim[static_cast<std::size_t>(i)])
      : -1;
    if (k < 0)
    {
      continue;
    }
    const float sign = slope(i, k) > 0.0f ? 1.0f : -1.0f;
    int top = k;
    for (int kk = std::max(k - 3, 2); kk <= std::min(k + 3, m - 3); ++kk)
    {
      top = sign * fineSlope(i, kk) > sign * fineSlope(i, top) ? kk : top;
    }
    const double a = sign * fineSlope(i, top - 1), b = sign * fineSlope(i, top),
                 c = sign * fineSlope(i, top + 1);
    if (!(b > 0.0) || a > b || c > b)
    {
      continue;
    }
    const double curvature = a - 2.0 * b + c;
    const double offset = curvature < 0.0 ? std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5) : 0.0;
    const double t = (top + offset) * kStep - inside;
    const Vec2 u = foot[static_cast<std::size_t>(i)] + t * normal[static_cast<std::size_t>(i)];
    const Vec2 q = lens.Distorted(u);
    if (q.allFinite())
    {
      undistorted.push_back(u);
      pixels.push_back(q);
      shift += t;
    }
  }
  report.shift = undistorted.empty() ? 0.0 : shift / static_cast<double>(undistorted.size());
  return true;
}
} // namespace detail
} // namespace catar
