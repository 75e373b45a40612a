// RecoverMarkers (Markers.h): the board's undecoded markers read again where a pose puts them.
#include "MarkerGrey.h"
#include "Markers.h"
#include "Projector.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace catar
{
namespace
{
// Markers whose predicted image is smaller than this on its shorter side (pixels) are not
// looked for: too few pixels a cell to read their bits.
constexpr double kMinSearchSide = 10.0;

// The candidate's corners in the order (and direction) closest to `predicted`; the largest
// distance of a corner from its predicted place.
double Match(const std::array<Vec2, 4>& candidate, const std::array<Vec2, 4>& predicted,
  std::array<Vec2, 4>& ordered)
{
  double best = std::numeric_limits<double>::infinity();
  for (int direction : { 1, -1 })
  {
    for (int shift = 0; shift < 4; ++shift)
    {
      std::array<Vec2, 4> o = predicted;
      double worst = 0.0;
      for (int c = 0; c < 4; ++c)
      {
        o[c] = candidate[static_cast<std::size_t>((shift + direction * c + 8) % 4)];
        worst = std::max(worst, (o[c] - predicted[c]).norm());
      }
      if (worst < best)
      {
        best = worst;
        ordered = o;
      }
    }
  }
  return best;
}

// Whether the marker's cells, sampled at their projected centres, read its border and bits.
bool ReadsAs(const cv::Mat& grey, const Projector& projector, const BoardMarker& marker,
  const std::vector<std::uint8_t>& expected, int cells)
{
  const std::array<Vec3, 4> w = marker.Corners(); // top-left, top-right, bottom-right, bottom-left
  std::vector<double> samples;
  for (int r = 0; r < cells; ++r)
  {
    for (int c = 0; c < cells; ++c)
    {
      const double u = (c + 0.5) / cells;
      const double v = (r + 0.5) / cells;
      const Vec3 world = w[0] + u * (w[1] - w[0]) + v * (w[3] - w[0]);
      const ProjectedPoint p = projector.ProjectWorld(world);
      const double g = p.status == ProjectionStatus::Valid ? detail::GreyAt(grey, p.pixel) : -1.0;
      if (g < 0.0)
      {
        return false;
      }
      samples.push_back(g);
    }
  }
  std::vector<double> sorted = samples;
  std::sort(sorted.begin(), sorted.end());
  const double dark = sorted[sorted.size() / 10];
  const double light = sorted[sorted.size() * 9 / 10];
  if (light - dark < 40.0) // no contrast: nothing printed there
  {
    return false;
  }
  const double threshold = 0.5 * (dark + light);
  int borderWrong = 0;
  int bitsWrong = 0;
  std::size_t k = 0; // row by row, as MarkerImage's pixels
  for (int r = 0; r < cells; ++r)
  {
    for (int c = 0; c < cells; ++c, ++k)
    {
      const bool white = samples[k] > threshold;
      const bool expectWhite = expected[k] > 127;
      const bool border = r == 0 || c == 0 || r == cells - 1 || c == cells - 1;
      (border ? borderWrong : bitsWrong) += white != expectWhite ? 1 : 0;
    }
  }
  return borderWrong <= 2 && bitsWrong <= 1;
}

// The markers and undecoded quadrilaterals DetectMarkers finds in the frame's region around a
// predicted marker (its box and half its longer side more, 6 px at least), enlarged to about
// 60 px a side for a small marker (OpenCV's contours need some pixels per cell), mapped back to
// the frame's pixels.
void SearchAround(const cv::Mat& grey, const std::array<Vec2, 4>& predicted,
  const std::string& dictionary, std::vector<MarkerDetection>& found,
  std::vector<std::array<Vec2, 4>>& quads)
{
  found.clear();
  quads.clear();
  Vec2 low = predicted[0];
  Vec2 high = predicted[0];
  double longer = 0.0;
  for (std::size_t c = 0; c < 4; ++c)
  {
    low = low.cwiseMin(predicted[c]);
    high = high.cwiseMax(predicted[c]);
    longer = std::max(longer, (predicted[c] - predicted[(c + 1) % 4]).norm());
  }
  const double margin = std::max(6.0, 0.5 * longer);
  const int x0 = std::max(0, static_cast<int>(std::floor(low.x() - margin)));
  const int y0 = std::max(0, static_cast<int>(std::floor(low.y() - margin)));
  const int x1 = std::min(grey.cols, static_cast<int>(std::ceil(high.x() + margin)) + 1);
  const int y1 = std::min(grey.rows, static_cast<int>(std::ceil(high.y() + margin)) + 1);
  if (x1 - x0 < 8 || y1 - y0 < 8 || longer > 400.0)
  {
    return;
  }
  const double scale = std::clamp(60.0 / longer, 1.0, 4.0);
  cv::Mat region;
  cv::resize(grey(cv::Rect(x0, y0, x1 - x0, y1 - y0)), region, cv::Size(), scale, scale,
    scale > 1.0 ? cv::INTER_CUBIC : cv::INTER_LINEAR);
  cv::Mat rgba;
  cv::cvtColor(region, rgba, cv::COLOR_GRAY2RGBA);
  std::string error;
  std::vector<std::array<Vec2, 4>> undecoded;
  if (!DetectMarkers(rgba.cols, rgba.rows, rgba.data, dictionary, true, found, error, &undecoded))
  {
    found.clear();
    return;
  }
  // Pixel centres at integers: a region pixel's centre x lies at (x + 0.5) / scale - 0.5 of
  // the region's first pixel.
  const auto back = [&](const Vec2& p) {
    return Vec2(x0 + (p.x() + 0.5) / scale - 0.5, y0 + (p.y() + 0.5) / scale - 0.5);
  };
  for (MarkerDetection& d : found)
  {
    for (Vec2& c : d.corners)
    {
      c = back(c);
    }
  }
  for (std::array<Vec2, 4>& q : undecoded)
  {
    for (Vec2& c : q)
    {
      c = back(c);
    }
    quads.push_back(q);
  }
}
} // namespace

namespace detail
{
cv::Mat GreyOf(int width, int height, const std::uint8_t* rgba)
{
  const cv::Mat frame(height, width, CV_8UC4, const_cast<std::uint8_t*>(rgba));
  cv::Mat grey;
  cv::cvtColor(frame, grey, cv::COLOR_RGBA2GRAY);
  return grey;
}

double GreyAt(const cv::Mat& grey, const Vec2& p)
{
  const double x = p.x();
  const double y = p.y();
  if (!(x >= 0.0 && y >= 0.0 && x <= grey.cols - 1.0 && y <= grey.rows - 1.0))
  {
    return -1.0;
  }
  const int x0 = std::min(static_cast<int>(x), std::max(0, grey.cols - 2));
  const int y0 = std::min(static_cast<int>(y), std::max(0, grey.rows - 2));
  const int x1 = std::min(x0 + 1, grey.cols - 1);
  const int y1 = std::min(y0 + 1, grey.rows - 1);
  const double fx = x - x0;
  const double fy = y - y0;
  const auto at = [&](int u, int v) { return static_cast<double>(grey.at<std::uint8_t>(v, u)); };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
    fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
}

int RecoverMarkers(const cv::Mat& grey, const CameraModel& camera, const MarkerBoard& board,
  const std::vector<std::array<Vec2, 4>>& candidates, std::vector<MarkerDetection>& detections)
{
  const int cells = MarkerCells(board.dictionary);
  if (cells <= 0 || grey.cols <= 1 || grey.rows <= 1)
  {
    return 0;
  }
  const Projector projector(camera);
  std::vector<bool> used(candidates.size(), false);
  int added = 0;
  for (const BoardMarker& marker : board.markers)
  {
    const bool found = std::any_of(detections.begin(), detections.end(),
      [&](const MarkerDetection& d) { return d.id == marker.id; });
    if (found)
    {
      continue;
    }
    std::array<Vec2, 4> predicted;
    bool seen = true;
    const std::array<Vec3, 4> corners = marker.Corners();
    for (int c = 0; c < 4 && seen; ++c)
    {
      const ProjectedPoint p = projector.ProjectWorld(corners[static_cast<std::size_t>(c)]);
      seen = p.status == ProjectionStatus::Valid;
      predicted[static_cast<std::size_t>(c)] = p.pixel;
    }
    if (!seen)
    {
      continue;
    }
    double shorter = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 4; ++c)
    {
      shorter = std::min(shorter,
        (predicted[static_cast<std::size_t>(c)] - predicted[static_cast<std::size_t>((c + 1) % 4)])
          .norm());
    }
    if (!(shorter >= kMinSearchSide))
    {
      continue;
    }
    const double tolerance = std::max(3.0, 0.25 * shorter);
    // The closest of `quads` to the prediction within the tolerance (not one already taken).
    const auto closest = [&](const std::vector<std::array<Vec2, 4>>& quads,
                           const std::vector<bool>& taken, std::array<Vec2, 4>& ordered) {
      std::size_t best = quads.size();
      double bestDistance = tolerance;
      for (std::size_t k = 0; k < quads.size(); ++k)
      {
        std::array<Vec2, 4> o = predicted;
        const double distance =
          k < taken.size() && taken[k] ? tolerance : Match(quads[k], predicted, o);
        if (distance < bestDistance)
        {
          bestDistance = distance;
          best = k;
          ordered = o;
        }
      }
      return best;
    };
    std::vector<std::uint8_t> expected;
    std::string error;
    if (!MarkerImage(board.dictionary, marker.id, cells, 0, expected, error))
    {
      continue;
    }
    MarkerDetection d;
    d.id = marker.id;
    const std::size_t k = closest(candidates, used, d.corners);
    if (k < candidates.size())
    {
      if (!ReadsAs(grey, projector, marker, expected, cells))
      {
        continue;
      }
      used[k] = true;
    }
    else
    {
      // No quadrilateral there in the whole frame's search: the region where the marker must
      // be, searched again enlarged (a small marker's contours break up in a noisy frame).
      std::vector<MarkerDetection> here;
      std::vector<std::array<Vec2, 4>> quads;
      SearchAround(grey, predicted, board.dictionary, here, quads);
      for (const MarkerDetection& h : here)
      {
        if (h.id == marker.id)
        {
          quads.insert(quads.begin(), h.corners);
        }
      }
      if (closest(quads, {}, d.corners) == quads.size() ||
        !ReadsAs(grey, projector, marker, expected, cells))
      {
        continue;
      }
    }
    // The candidate's corners come from a polygon fitted to a thresholded contour (whole
    // pixels): refined on the image's gradients in a window of about a tenth of the marker's
    // shorter side (3 px a side for a 35 px marker). On POV-Ray's frames this took the worst pose
    // with the recovered markers from 4.2 to 2.0 mm clean and 6.1 to 3.8 mm noisy; unrefined,
    // they made it worse than leaving the markers out.
    std::vector<cv::Point2f> points;
    for (const Vec2& c : d.corners)
    {
      points.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
    }
    const int window = std::clamp(static_cast<int>(shorter / 10.0), 2, 5);
    cv::cornerSubPix(grey, points, cv::Size(window, window), cv::Size(-1, -1),
      cv::TermCriteria(cv::TermCriteria::MAX_ITER | cv::TermCriteria::EPS, 30, 0.01));
    for (std::size_t c = 0; c < 4; ++c)
    {
      d.corners[c] = Vec2(points[c].x, points[c].y);
    }
    detections.push_back(d);
    ++added;
  }
  return added;
}
} // namespace detail

int RecoverMarkers(int width, int height, const std::uint8_t* rgba, const CameraModel& camera,
  const MarkerBoard& board, const std::vector<std::array<Vec2, 4>>& candidates,
  std::vector<MarkerDetection>& detections)
{
  if (!rgba || width <= 1 || height <= 1)
  {
    return 0;
  }
  return detail::RecoverMarkers(
    detail::GreyOf(width, height, rgba), camera, board, candidates, detections);
}
} // namespace catar
