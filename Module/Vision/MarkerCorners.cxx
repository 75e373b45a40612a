// RefineMarkerCorners (Markers.h): each marker's corners placed on its black square's edges, the
// sides' curvature taken from the exact projection of the board's marker through the mirror.
#include "MarkerGrey.h"
#include "Markers.h"
#include "Projector.h"

#include <Eigen/Dense>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace catar
{
namespace
{
constexpr double kStep = 0.25;   // spacing of the grey samples across a side, pixels
constexpr double kReach = 2.5;   // the edge is looked for this far either side of the side
constexpr double kEnds = 0.1;    // the ends of each side (this fraction) are left out
constexpr double kAlong = 1.0;   // spacing of the profiles along a side, pixels
constexpr double kMaxMove = 2.0; // a corner that would move further is left where it was
constexpr double kMinContrast = 30.0;
// A pose gives a marker's curvature when it projects the corners within this fraction of the
// marker's shorter side (kMinGate px at least) of where they were found.
constexpr double kGate = 0.1;
constexpr double kMinGate = 2.0;
constexpr int kBowSamples = 9; // points of the projected side that give its curvature
constexpr std::size_t kMinPoints = 6;

// A side of the square in the image: from `start` along the unit chord direction u for `length`
// pixels, offset along the unit outward normal n by b(t) = c0 + c1 t + c2 t^2 + c3 t^3 at t pixels
// along the chord.
struct Side
{
  Vec2 start = Vec2::Zero();
  Vec2 u = Vec2::UnitX();
  Vec2 n = Vec2::UnitY();
  double length = 0.0;
  Eigen::Vector4d c = Eigen::Vector4d::Zero();

  double Offset(double t) const { return c(0) + t * (c(1) + t * (c(2) + t * c(3))); }
  Vec2 At(double t) const { return this->start + t * this->u + this->Offset(t) * this->n; }
  Vec2 Slope(double t) const
  {
    return this->u + (c(1) + t * (2.0 * c(2) + 3.0 * t * c(3))) * this->n;
  }
};

// The chord frame from p to q, its normal pointing away from `centre`.
Side Chord(const Vec2& p, const Vec2& q, const Vec2& centre)
{
  Side s;
  s.start = p;
  s.length = (q - p).norm();
  s.u = (q - p) / s.length;
  s.n = Vec2(s.u.y(), -s.u.x());
  if (s.n.dot(0.5 * (p + q) - centre) < 0.0)
  {
    s.n = -s.n;
  }
  return s;
}

// The bow of the projected side from world point a to world point b (the marker's centre at
// `centre`), transferred to the detected chord `side`: b(t) = t (L - t / s) (beta0 + beta1 t / s)
// with L the projected chord's length and s the detected chord's over it (zero at both corners).
// False when the side does not project.
bool Bow(const Projector& projector, const Vec3& a, const Vec3& b, const Vec2& centre, Side& side)
{
  std::array<Vec2, kBowSamples> p;
  for (int k = 0; k < kBowSamples; ++k)
  {
    const double f = static_cast<double>(k) / (kBowSamples - 1);
    const ProjectedPoint q = projector.ProjectWorld(a + f * (b - a));
    if (q.status != ProjectionStatus::Valid)
    {
      return false;
    }
    p[static_cast<std::size_t>(k)] = q.pixel;
  }
  const Side chord = Chord(p.front(), p.back(), centre);
  if (!(chord.length > 1.0))
  {
    return false;
  }
  Eigen::Matrix<double, kBowSamples - 2, 2> A;
  Eigen::Matrix<double, kBowSamples - 2, 1> y;
  for (int k = 1; k + 1 < kBowSamples; ++k)
  {
    const Vec2 d = p[static_cast<std::size_t>(k)] - chord.start;
    const double t = d.dot(chord.u);
    const double w = t * (chord.length - t);
    A.row(k - 1) << w, w * t;
    y(k - 1) = d.dot(chord.n);
  }
  const Eigen::Vector2d beta = A.colPivHouseholderQr().solve(y);
  const double s = side.length / chord.length;
  side.c << 0.0, chord.length * beta(0), (chord.length * beta(1) - beta(0)) / s, -beta(1) / (s * s);
  return side.c.allFinite();
}

// Where the grey level crosses halfway from the black square to the white margin along the
// profile through `foot` in direction n (kReach either side): the offset from the foot, pixels.
// False without a clear single rise.
bool EdgeOffset(const cv::Mat& grey, const Vec2& foot, const Vec2& n, double reach, double& offset)
{
  const int samples = static_cast<int>(2.0 * reach / kStep) + 1;
  std::vector<double> profile(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k)
  {
    const double g = detail::GreyAt(grey, foot + (k * kStep - reach) * n);
    if (g < 0.0)
    {
      return false;
    }
    profile[static_cast<std::size_t>(k)] = g;
  }
  const auto at = [&](int k) { return profile[static_cast<std::size_t>(k)]; };
  const double dark = (at(0) + at(1) + at(2)) / 3.0;
  const double light = (at(samples - 1) + at(samples - 2) + at(samples - 3)) / 3.0;
  if (!(light - dark > kMinContrast))
  {
    return false;
  }
  // The steepest rise over one pixel, then the half-way crossing next to it.
  const int span = static_cast<int>(std::lround(0.5 / kStep));
  int steepest = -1;
  double rise = 0.0;
  for (int k = span; k + span < samples; ++k)
  {
    const double r = at(k + span) - at(k - span);
    if (r > rise)
    {
      rise = r;
      steepest = k;
    }
  }
  if (steepest < 0 || rise < 0.25 * (light - dark))
  {
    return false;
  }
  const double half = 0.5 * (dark + light);
  for (int d = 0; d <= 2 * span; ++d)
  {
    for (int k : { steepest - d, steepest + d - 1 })
    {
      if (k < 0 || k + 1 >= samples)
      {
        continue;
      }
      const double g0 = at(k);
      const double g1 = at(k + 1);
      if (g0 <= half && g1 > half)
      {
        offset = (k + (half - g0) / (g1 - g0)) * kStep - reach;
        return true;
      }
    }
  }
  return false;
}

// The detected side's offset from its bowed curve, c0 + c1 t, fitted to the edge's crossings
// (least squares, then again without those more than 3 spreads off, 0.2 px at least). False when
// too few crossings show.
bool FitSide(const cv::Mat& grey, Side& side)
{
  const double reach = std::min(kReach, 0.12 * side.length);
  const int count = std::max(static_cast<int>((1.0 - 2.0 * kEnds) * side.length / kAlong), 6);
  std::vector<double> ts;
  std::vector<double> offsets;
  for (int j = 0; j < count; ++j)
  {
    const double t = side.length * (kEnds + (1.0 - 2.0 * kEnds) * (j + 0.5) / count);
    double offset = 0.0;
    if (EdgeOffset(grey, side.At(t), side.n, reach, offset))
    {
      ts.push_back(t);
      offsets.push_back(offset);
    }
  }
  if (ts.size() < kMinPoints)
  {
    return false;
  }
  std::vector<bool> use(ts.size(), true);
  Eigen::Vector2d line = Eigen::Vector2d::Zero();
  for (int pass = 0; pass < 2; ++pass)
  {
    Eigen::MatrixXd A(static_cast<Eigen::Index>(ts.size()), 2);
    Eigen::VectorXd b(static_cast<Eigen::Index>(ts.size()));
    Eigen::Index rows = 0;
    for (std::size_t i = 0; i < ts.size(); ++i)
    {
      if (use[i])
      {
        A.row(rows) << 1.0, ts[i];
        b(rows) = offsets[i];
        ++rows;
      }
    }
    if (rows < static_cast<Eigen::Index>(kMinPoints))
    {
      return false;
    }
    line = A.topRows(rows).colPivHouseholderQr().solve(b.head(rows));
    std::vector<double> residuals(ts.size());
    for (std::size_t i = 0; i < ts.size(); ++i)
    {
      residuals[i] = std::abs(offsets[i] - line(0) - line(1) * ts[i]);
    }
    std::vector<double> sorted = residuals;
    std::nth_element(sorted.begin(),
      sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double limit = std::max(0.2, 3.0 * 1.4826 * sorted[sorted.size() / 2]);
    for (std::size_t i = 0; i < ts.size(); ++i)
    {
      use[i] = residuals[i] <= limit;
    }
  }
  side.c(0) += line(0);
  side.c(1) += line(1);
  return side.c.allFinite();
}

// Whether the marker's corners project within `gate` pixels of where they were found.
bool Predicts(const Projector& projector, const std::array<Vec3, 4>& world,
  const std::array<Vec2, 4>& found, double gate)
{
  for (std::size_t i = 0; i < 4; ++i)
  {
    const ProjectedPoint p = projector.ProjectWorld(world[i]);
    if (p.status != ProjectionStatus::Valid || !((p.pixel - found[i]).norm() <= gate))
    {
      return false;
    }
  }
  return true;
}

// Where the end of `first` meets the start of `second` (Newton on the two curves' parameters).
bool Meet(const Side& first, const Side& second, Vec2& corner)
{
  double a = first.length;
  double b = 0.0;
  for (int iteration = 0; iteration < 20; ++iteration)
  {
    const Vec2 gap = first.At(a) - second.At(b);
    Eigen::Matrix2d J;
    J.col(0) = first.Slope(a);
    J.col(1) = -second.Slope(b);
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-6))
    {
      return false;
    }
    const Eigen::Vector2d step = J.inverse() * gap;
    a -= step(0);
    b -= step(1);
    if (step.norm() < 1e-10)
    {
      break;
    }
  }
  corner = first.At(a);
  return (first.At(a) - second.At(b)).norm() < 1e-6 && corner.allFinite();
}
} // namespace

namespace detail
{
int RefineMarkerCorners(const cv::Mat& grey, const CameraModel& camera, const MarkerBoard& board,
  std::vector<MarkerDetection>& detections)
{
  if (grey.cols <= 1 || grey.rows <= 1 || detections.empty())
  {
    return 0;
  }
  const Projector projector(camera);
  int moved = 0;
  for (MarkerDetection& d : detections)
  {
    const auto marker = std::find_if(board.markers.begin(), board.markers.end(),
      [&](const BoardMarker& m) { return m.id == d.id; });
    if (marker == board.markers.end())
    {
      continue;
    }
    const std::array<Vec3, 4> world = marker->Corners();
    Vec2 centre = Vec2::Zero();
    double shorter = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < 4; ++i)
    {
      centre += 0.25 * d.corners[i];
      shorter = std::min(shorter, (d.corners[(i + 1) % 4] - d.corners[i]).norm());
    }
    // The sides' curvature comes from the pose only where it puts the marker where it was found
    // (not, e.g., a pose from two markers side by side, far off).
    if (!Predicts(projector, world, d.corners, std::max(kMinGate, kGate * shorter)))
    {
      continue;
    }
    std::array<Side, 4> sides;
    std::array<bool, 4> fitted{};
    for (std::size_t i = 0; i < 4; ++i)
    {
      const std::size_t j = (i + 1) % 4;
      sides[i] = Chord(d.corners[i], d.corners[j], centre);
      fitted[i] = sides[i].length > 6.0 && Bow(projector, world[i], world[j], centre, sides[i]) &&
        FitSide(grey, sides[i]);
    }
    std::array<Vec2, 4> corners = d.corners;
    for (std::size_t i = 0; i < 4; ++i)
    {
      // Corner i ends side i - 1 and starts side i.
      const std::size_t before = (i + 3) % 4;
      Vec2 corner;
      if (fitted[before] && fitted[i] && Meet(sides[before], sides[i], corner) &&
        (corner - d.corners[i]).norm() <= kMaxMove)
      {
        corners[i] = corner;
        ++moved;
      }
    }
    d.corners = corners;
  }
  return moved;
}
} // namespace detail

int RefineMarkerCorners(int width, int height, const std::uint8_t* rgba, const CameraModel& camera,
  const MarkerBoard& board, std::vector<MarkerDetection>& detections)
{
  if (!rgba || width <= 1 || height <= 1 || detections.empty())
  {
    return 0;
  }
  return detail::RefineMarkerCorners(
    detail::GreyOf(width, height, rgba), camera, board, detections);
}
} // namespace catar
