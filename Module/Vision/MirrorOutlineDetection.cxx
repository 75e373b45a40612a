// CatadioptricAR Core: a mirror's outline in a camera frame, DetectMirrorOutline (see
// MirrorOutline.h for the method).
#include "MirrorOutline.h"

#include "ConicFit.h"
#include "MirrorRim.h"

#include <Eigen/Eigenvalues>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace catar
{
namespace
{
using detail::ConicKind;
using detail::Describe;
using detail::Ellipse;
using detail::EllipseOf;
using detail::FitConic;
using detail::RimFromProfiles;
using detail::RimReport;
using detail::RimSearch;
using detail::SampsonDistance;
using detail::Undistorter;
using detail::ValidateLens;

constexpr double kPi = 3.14159265358979323846;
// The least side of a frame searched, and the largest side searched whole (larger ones are
// reduced for the search, then the rim placed on the whole frame).
constexpr int kMinSide = 16;
constexpr double kWorkingSide = 1024.0;
// The rim's points left out at each end of the outline's arcs (its points are 2 px apart, and
// smoothed along the rim over 10 px).
constexpr std::size_t kEndTrim = 10;

// ---- Detection ------------------------------------------------------------------------------

// An edge pixel: where it is (image and undistorted pixels) and the edge's normal (unit, either
// sign).
struct EdgePoint
{
  Vec2 pixel;
  Vec2 undistorted;
  Vec2 normal;
};

// The conic's normal and the edge's agree (either sign) to within acos(minCos).
bool Aligned(const Vec2& conicNormal, const Vec2& edgeNormal, double minCos)
{
  return std::abs(conicNormal.dot(edgeNormal)) >= minCos;
}

// The colour structure tensor (sum over the channels of g g^T, g the Sobel gradient) of a float
// RGB image blurred with sigma: its larger eigenvalue's square root (the edge's strength) and,
// when asked, its eigenvector (the edge's unit normal, either sign).
void StructureTensor(
  const cv::Mat& colour, double sigma, cv::Mat& strength, cv::Mat* nx, cv::Mat* ny)
{
  cv::Mat blurred, gx, gy;
  cv::GaussianBlur(colour, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  cv::Sobel(blurred, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(blurred, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  strength.create(colour.rows, colour.cols, CV_32F);
  if (nx && ny)
  {
    nx->create(colour.rows, colour.cols, CV_32F);
    ny->create(colour.rows, colour.cols, CV_32F);
  }
  for (int y = 0; y < colour.rows; ++y)
  {
    const cv::Vec3f* rx = gx.ptr<cv::Vec3f>(y);
    const cv::Vec3f* ry = gy.ptr<cv::Vec3f>(y);
    float* s = strength.ptr<float>(y);
    for (int x = 0; x < colour.cols; ++x)
    {
      double xx = 0.0, yy = 0.0, xy = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        xx += rx[x][c] * rx[x][c];
        yy += ry[x][c] * ry[x][c];
        xy += rx[x][c] * ry[x][c];
      }
      const double half = 0.5 * (xx - yy);
      const double big = 0.5 * (xx + yy) + std::sqrt(half * half + xy * xy);
      s[x] = static_cast<float>(std::sqrt(std::max(big, 0.0)));
      if (nx && ny)
      {
        const double theta = 0.5 * std::atan2(2.0 * xy, xx - yy);
        nx->at<float>(y, x) = static_cast<float>(std::cos(theta));
        ny->at<float>(y, x) = static_cast<float>(std::sin(theta));
      }
    }
  }
}

// The support of an ellipse among edge points: how much of its perimeter (inside the image) they
// cover.
struct Support
{
  int bins = 0;      // bins of the perimeter that lie inside the image
  int covered = 0;   // of those, bins with a supporting edge point
  double length = 0; // covered perimeter length
};

constexpr int kBins = 120;

// Which of kBins equal-angle bins of the ellipse lie (as image pixels) inside the image, away
// from its border by `margin`.
std::array<bool, kBins> BinsInImage(
  const Ellipse& e, const Undistorter& undistort, int width, int height, double margin)
{
  std::array<bool, kBins> inside{};
  for (int k = 0; k < kBins; ++k)
  {
    const Vec2 p = undistort.Distorted(e.At(2.0 * kPi * (k + 0.5) / kBins));
    inside[k] = p.allFinite() && p.x() >= margin && p.y() >= margin &&
      p.x() <= width - 1 - margin && p.y() <= height - 1 - margin;
  }
  return inside;
}

Support Supported(const Ellipse& e, const std::vector<EdgePoint>& edges, std::size_t stride,
  const std::array<bool, kBins>& inside, double tolerance, double minCos)
{
  std::array<bool, kBins> hit{};
  for (std::size_t i = 0; i < edges.size(); i += stride)
  {
    const EdgePoint& p = edges[i];
    Vec2 normal;
    if (SampsonDistance(e.Q, p.undistorted, &normal) < tolerance &&
      Aligned(normal, p.normal, minCos))
    {
      double phi = e.AngleOf(p.undistorted);
      phi = phi < 0.0 ? phi + 2.0 * kPi : phi;
      const int k = static_cast<int>(std::floor(phi / (2.0 * kPi) * kBins));
      hit[static_cast<std::size_t>(std::min(std::max(k, 0), kBins - 1))] = true;
    }
  }
  Support s;
  for (int k = 0; k < kBins; ++k)
  {
    s.bins += inside[k];
    if (inside[k] && hit[k])
    {
      ++s.covered;
      s.length += (e.At(2.0 * kPi * (k + 1) / kBins) - e.At(2.0 * kPi * k / kBins)).norm();
    }
  }
  return s;
}

// The least points of a piece of edge that proposes an ellipse, its least semi-axis and its
// largest ratio of axes (a sphere's outline is far rounder; longer ones are straight edges).
constexpr std::size_t kMinPiece = 20;
constexpr double kMinSemiAxis = 5.0;
constexpr double kMaxAspect = 5.0;

// Could the ellipse be a mirror's outline in an image of that diagonal?
bool Plausible(const Ellipse& e, double diagonal)
{
  return e.b >= kMinSemiAxis && e.a <= 2.0 * diagonal && e.a <= kMaxAspect * e.b;
}

// The largest distance (undistorted pixels) of an outline point from the outline's ellipse.
constexpr double kInlierPixels = 1.0;

// A contour (a closed chain of neighbouring pixels) cut where it turns sharply (corners,
// junctions with other edges, the ends of open edges, which a contour traces there and back) into
// smooth pieces of at least kMinPiece points.
std::vector<std::vector<Vec2>> SmoothPieces(const std::vector<Vec2>& chain)
{
  std::vector<std::vector<Vec2>> pieces;
  const std::size_t n = chain.size();
  constexpr std::size_t kReach = 4;
  if (n < kMinPiece)
  {
    return pieces;
  }
  const double cosTurn = std::cos(40.0 * kPi / 180.0);
  std::vector<bool> sharp(n, false);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec2 before = chain[i] - chain[(i + n - kReach) % n];
    const Vec2 after = chain[(i + kReach) % n] - chain[i];
    const double norms = before.norm() * after.norm();
    sharp[i] = !(norms > 0.0) || before.dot(after) < cosTurn * norms;
  }
  // Start after a sharp point, so that a piece does not wrap around the chain's start.
  std::size_t first = 0;
  while (first < n && !sharp[first])
  {
    ++first;
  }
  if (first == n) // smooth all round: a closed curve
  {
    pieces.push_back(chain);
    return pieces;
  }
  std::vector<Vec2> piece;
  for (std::size_t k = 1; k <= n; ++k)
  {
    const std::size_t i = (first + k) % n;
    if (sharp[i])
    {
      if (piece.size() >= kMinPiece)
      {
        pieces.push_back(piece);
      }
      piece.clear();
    }
    else
    {
      piece.push_back(chain[i]);
    }
  }
  if (piece.size() >= kMinPiece)
  {
    pieces.push_back(piece);
  }
  return pieces;
}

// The image of a sphere's outline is that of a right circular cone from the camera centre: its
// rays' unit vectors end on a circle of the unit sphere, in a plane. So the cone nearest a set of
// rays (least squares on d . r - cos(alpha)) has the axis d of the least eigenvector of the rays'
// covariance, and cos(alpha) the mean ray's component along it. The conic of that cone in
// undistorted pixels (K the intrinsics): K^-T (d d^T - cos^2(alpha) I) K^-1. False when the
// points fix no cone (fewer than 3, or along one great circle) or its conic is no ellipse.
// The unit ray of an undistorted pixel.
Vec3 RayOf(const Intrinsics& k, const Vec2& undistorted)
{
  const double y = (undistorted.y() - k.cy) / k.fy;
  return Vec3((undistorted.x() - k.cx - k.skew * y) / k.fx, y, 1.0).normalized();
}

// The right circular cone nearest the rays (see ConeEllipse): its unit axis d and cos(alpha).
bool ConeOfRays(const std::vector<Vec3>& rays, Vec3& d, double& cosAlpha)
{
  if (rays.size() < 3)
  {
    return false;
  }
  Vec3 mean = Vec3::Zero();
  for (const Vec3& r : rays)
  {
    mean += r;
  }
  mean /= static_cast<double>(rays.size());
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& r : rays)
  {
    covariance += (r - mean) * (r - mean).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> es(covariance);
  d = es.eigenvectors().col(0);
  d = d.dot(mean) < 0.0 ? Vec3(-d) : d;
  cosAlpha = d.dot(mean);
  return cosAlpha > 0.05 && cosAlpha < 1.0 - 1e-9 && d.z() > 0.0 &&
    es.eigenvalues()(1) > 1e-6 * es.eigenvalues()(2);
}

bool ConeEllipse(const Intrinsics& k, const Vec2* undistorted, std::size_t n, Ellipse& e)
{
  std::vector<Vec3> rays(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    rays[i] = RayOf(k, undistorted[i]);
  }
  Vec3 d;
  double cosAlpha = 0.0;
  if (!ConeOfRays(rays, d, cosAlpha))
  {
    return false;
  }
  Mat3 K;
  K << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0;
  const Mat3 inverse = K.inverse();
  const Mat3 Q =
    inverse.transpose() * (d * d.transpose() - cosAlpha * cosAlpha * Mat3::Identity()) * inverse;
  return EllipseOf(Q / Q.norm(), e) == ConicKind::Ellipse;
}

// What an outline is: a sphere's limb (the image of a right circular cone of rays from the camera
// centre, fitted as in ConeEllipse) or, for a circular rim seen aslant, any ellipse (a conic
// fitted to the points).
struct OutlineModel
{
  Intrinsics k;
  bool limb = true;
  std::size_t SampleSize() const { return this->limb ? 3 : 5; }
  bool Fit(const Vec2* undistorted, std::size_t n, Ellipse& e) const
  {
    if (this->limb)
    {
      return ConeEllipse(this->k, undistorted, n, e);
    }
    Mat3 conic;
    return FitConic(undistorted, n, conic) && EllipseOf(conic, e) == ConicKind::Ellipse;
  }
};

// Is the ellipse about the size and shape of the guess (a RANSAC's model near it)?
bool Similar(const Ellipse& e, const Ellipse& guess)
{
  return e.a <= 1.5 * guess.a && e.b >= guess.b / 1.5 && e.a <= kMaxAspect * e.b;
}

// RANSAC with five-point conics among the edge points near a guessed ellipse (within a band of a
// few pixels, their edges along it), then least squares on the inliers: the ellipse and its
// inliers (within 1 pixel, their edges along it). False when too few points support one.
bool RefineByRansac(const OutlineModel& model, const Ellipse& guess,
  const std::vector<EdgePoint>& points, Ellipse& refined, std::vector<std::size_t>& bestInliers)
{
  const double band = std::max(4.0, 0.03 * std::sqrt(guess.a * guess.b));
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Vec2 normal;
    if (SampsonDistance(guess.Q, points[i].undistorted, &normal) < band &&
      Aligned(normal, points[i].normal, 0.7))
    {
      near.push_back(i);
    }
  }
  if (near.size() < kMinPiece)
  {
    return false;
  }
  const auto inliersOf = [&](const Mat3& q, std::vector<std::size_t>& inliers) {
    inliers.clear();
    for (std::size_t i : near)
    {
      Vec2 normal;
      if (SampsonDistance(q, points[i].undistorted, &normal) < kInlierPixels &&
        Aligned(normal, points[i].normal, 0.7))
      {
        inliers.push_back(i);
      }
    }
  };
  std::mt19937 random(20240607u);
  std::uniform_int_distribution<std::size_t> pick(0, near.size() - 1);
  std::vector<std::size_t> inliers;
  refined = guess;
  inliersOf(refined.Q, bestInliers);
  for (int iteration = 0; iteration < 400; ++iteration)
  {
    std::array<Vec2, 5> sample;
    std::array<std::size_t, 5> chosen{};
    const std::size_t size = model.SampleSize();
    for (std::size_t j = 0; j < size; ++j)
    {
      std::size_t i = 0;
      do
      {
        i = pick(random);
      } while (std::find(chosen.begin(), chosen.begin() + j, i) != chosen.begin() + j);
      chosen[j] = i;
      sample[j] = points[near[i]].undistorted;
    }
    Ellipse e;
    if (!model.Fit(sample.data(), size, e) || !Similar(e, guess))
    {
      continue;
    }
    inliersOf(e.Q, inliers);
    if (inliers.size() > bestInliers.size())
    {
      bestInliers.swap(inliers);
      refined = e;
    }
  }
  std::vector<Vec2> fitted;
  for (int pass = 0; pass < 3; ++pass)
  {
    fitted.clear();
    for (std::size_t i : bestInliers)
    {
      fitted.push_back(points[i].undistorted);
    }
    Ellipse e;
    if (!model.Fit(fitted.data(), fitted.size(), e) || !Similar(e, guess))
    {
      break;
    }
    inliersOf(e.Q, inliers);
    if (inliers.size() < bestInliers.size() / 2)
    {
      break;
    }
    refined = e;
    bestInliers.swap(inliers);
  }
  return bestInliers.size() >= kMinPiece;
}
// The ellipse (undistorted pixels) of the image's strong edges that they cover along the greatest
// length: the mirror's outline, or an edge of its reflection just inside it. `rgb`: 8-bit RGB of
// the camera's size.
bool StrongEdgeEllipse(
  const CameraModel& camera, bool limb, const cv::Mat& rgb, Ellipse& found, std::string& error)
{
  const int width = rgb.cols, height = rgb.rows;
  const OutlineModel model{ camera.intrinsics, limb };
  // The edges' strength and normals (Canny's thresholds, the edges' directions) on the image
  // blurred with sigma 1; the strength again with less blur for the sub-pixel positions, which the
  // reflection's own edges just inside the rim pull less.
  cv::Mat colour;
  rgb.convertTo(colour, CV_32F);
  cv::Mat strength, nx, ny;
  StructureTensor(colour, 1.0, strength, &nx, &ny);
  std::vector<float> nonFlat;
  for (int y = 0; y < height; ++y)
  {
    const float* row = strength.ptr<float>(y);
    for (int x = 0; x < width; ++x)
    {
      if (row[x] > 1.0f)
      {
        nonFlat.push_back(row[x]);
      }
    }
  }
  if (nonFlat.empty())
  {
    error = "no mirror outline found: the image has no edges";
    return false;
  }

  // Canny's thresholds from the strength of the image's edges (on the scale of the Sobel of 8-bit
  // values that Canny is given): a fraction of the 95th percentile, at least 24.
  const std::size_t rank = nonFlat.size() * 95 / 100;
  std::nth_element(
    nonFlat.begin(), nonFlat.begin() + static_cast<std::ptrdiff_t>(rank), nonFlat.end());
  double noise = 0.0;
  {
    std::vector<float> all(strength.begin<float>(), strength.end<float>());
    const std::size_t middle = all.size() / 2;
    std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(middle), all.end());
    noise = all[middle];
  }
  const double high = std::max({ 24.0, 0.3 * nonFlat[rank], 4.0 * noise });
  const double low = 0.4 * high;
  cv::Mat blurred8, dx, dy, edges;
  cv::GaussianBlur(rgb, blurred8, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REPLICATE);
  cv::Sobel(blurred8, dx, CV_16S, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(blurred8, dy, CV_16S, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Canny(dx, dy, edges, low, high, true);

  // Edge pixels away from the border, in undistorted pixels.
  const Undistorter undistort(camera);
  constexpr int kBorder = 2;
  std::vector<EdgePoint> points;
  cv::Mat index(height, width, CV_32S, cv::Scalar(-1));
  for (int y = kBorder; y < height - kBorder; ++y)
  {
    const unsigned char* row = edges.ptr<unsigned char>(y);
    for (int x = kBorder; x < width - kBorder; ++x)
    {
      EdgePoint p;
      p.pixel = Vec2(x, y);
      if (row[x] && undistort(p.pixel, p.undistorted))
      {
        p.normal = Vec2(nx.at<float>(y, x), ny.at<float>(y, x));
        index.at<int>(y, x) = static_cast<int>(points.size());
        points.push_back(p);
      }
    }
  }
  if (points.size() < 20)
  {
    error = "no mirror outline found: the image has too few edges";
    return false;
  }

  // Candidate ellipses: the conics of the edge contours, of their smooth pieces and of pairs of
  // the longest pieces (an outline that other edges cross is cut into pieces).
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(edges, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  const double diagonal = std::hypot(width, height);
  std::vector<std::vector<Vec2>> pieces;
  std::vector<Ellipse> candidates;
  const auto addCandidate = [&](const std::vector<Vec2>& group) {
    Ellipse e;
    if (group.size() < kMinPiece || !model.Fit(group.data(), group.size(), e) ||
      !Plausible(e, diagonal))
    {
      return;
    }
    std::size_t close = 0;
    for (const Vec2& p : group)
    {
      close += SampsonDistance(e.Q, p) < 1.5;
    }
    if (close >= 0.7 * static_cast<double>(group.size()))
    {
      candidates.push_back(e);
    }
  };
  for (const std::vector<cv::Point>& contour : contours)
  {
    if (contour.size() < kMinPiece)
    {
      continue;
    }
    std::vector<Vec2> whole;
    for (const cv::Point& q : contour)
    {
      const int i = index.at<int>(q.y, q.x);
      if (i >= 0)
      {
        whole.push_back(points[static_cast<std::size_t>(i)].undistorted);
      }
    }
    addCandidate(whole);
    for (std::vector<Vec2>& piece : SmoothPieces(whole))
    {
      addCandidate(piece);
      pieces.push_back(std::move(piece));
    }
  }
  std::sort(pieces.begin(), pieces.end(),
    [](const std::vector<Vec2>& a, const std::vector<Vec2>& b) { return a.size() > b.size(); });
  pieces.resize(std::min<std::size_t>(pieces.size(), 40));
  std::vector<Vec2> pair;
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    for (std::size_t j = i + 1; j < pieces.size(); ++j)
    {
      pair = pieces[i];
      pair.insert(pair.end(), pieces[j].begin(), pieces[j].end());
      addCandidate(pair);
    }
  }

  // The candidates whose perimeter the edges cover along the greatest length, each refined by a
  // RANSAC (five-point conics) among the edge points near it; the refined ellipse that the edges
  // cover along the greatest length is the outline.
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 30000);
  constexpr double kMargin = 3.0;
  // Ranked apart: those with at least half their perimeter in the image (a whole mirror) and the
  // others (a mirror cut by the frame), so that neither crowds the other out of the first few;
  // a cut one wins only when the edges cover it along a greater length.
  std::vector<std::pair<double, std::size_t>> rankedWhole, rankedCut;
  for (std::size_t k = 0; k < candidates.size(); ++k)
  {
    const Ellipse& e = candidates[k];
    const Support s =
      Supported(e, points, stride, BinsInImage(e, undistort, width, height, kMargin), 2.0, 0.8);
    if (s.bins > 0 && s.covered >= 0.3 * s.bins)
    {
      (2 * s.bins >= kBins ? rankedWhole : rankedCut).emplace_back(s.length, k);
    }
  }
  // The refined ellipse that the edges cover along the greatest length, among the first few
  // candidates that differ (near-copies come from both sides of an edge and from pairs).
  struct Found
  {
    Ellipse ellipse;
    std::vector<std::size_t> inliers;
    int inside = 0;
    double length = 0.0;
  };
  const auto search = [&](std::vector<std::pair<double, std::size_t>>& ranked, std::size_t tries) {
    std::sort(ranked.begin(), ranked.end(), std::greater<>());
    std::vector<const Ellipse*> tried;
    const auto similar = [](const Ellipse& a, const Ellipse& b) {
      return (a.centre - b.centre).norm() < 3.0 && std::abs(a.a - b.a) < 3.0 &&
        std::abs(a.b - b.b) < 3.0;
    };
    Found best;
    for (const auto& [length, k] : ranked)
    {
      (void)length;
      const Ellipse& guess = candidates[k];
      if (tried.size() >= tries || std::any_of(tried.begin(), tried.end(), [&](const Ellipse* e) {
            return similar(*e, guess);
          }))
      {
        continue;
      }
      tried.push_back(&guess);
      Found f;
      if (!RefineByRansac(model, guess, points, f.ellipse, f.inliers))
      {
        continue;
      }
      const Support s = Supported(f.ellipse, points, 1,
        BinsInImage(f.ellipse, undistort, width, height, kMargin), kInlierPixels, 0.7);
      f.inside = s.bins;
      f.length = s.length;
      if (s.bins > 0 && s.covered >= 0.35 * s.bins && s.length > best.length)
      {
        best = std::move(f);
      }
    }
    return best;
  };
  const Found whole = search(rankedWhole, 8);
  const Found cut = search(rankedCut, 4);
  if (!cut.inliers.empty() && cut.length > whole.length)
  {
    error =
      "the mirror is cut by the image frame: " + Describe(100.0 * (kBins - cut.inside) / kBins, 3) +
      "% of its outline lies on or beyond the image border";
    return false;
  }
  if (whole.inliers.size() < kMinPiece)
  {
    error = "no mirror outline found: no closed, roughly elliptical boundary among the image's "
            "edges";
    return false;
  }

  found = whole.ellipse;
  return true;
}
// The points of one outline among the rim's: the model's ellipse (a right circular cone's, or
// any) that most of them lie near, found by a RANSAC with the model through a few of them (three
// rays fix a cone, five points a conic; a dome's cut is a circle seen aslant: no right circular
// cone), then refitted to those near it (within three times their spread, from 0.6 to 1.5 px)
// three times; the last points near each end of its arcs are left out.
void OutlineConsensus(const OutlineModel& model, const std::vector<Vec2>& pixels,
  const std::vector<Vec2>& undistorted, std::vector<Vec2>& keptPixels,
  std::vector<Vec2>& keptUndistorted)
{
  keptPixels.clear();
  keptUndistorted.clear();
  std::vector<std::size_t> best, inliers;
  const auto near = [&](const Ellipse& e, double tolerance, std::vector<std::size_t>& found,
                      std::vector<double>* residuals) {
    found.clear();
    for (std::size_t i = 0; i < undistorted.size(); ++i)
    {
      const double r = SampsonDistance(e.Q, undistorted[i]);
      if (r < tolerance)
      {
        found.push_back(i);
        if (residuals)
        {
          residuals->push_back(r);
        }
      }
    }
  };
  std::mt19937 random(20261128u);
  std::uniform_int_distribution<std::size_t> pick(0, undistorted.size() - 1);
  std::vector<Vec2> sample(model.SampleSize());
  for (int iteration = 0; iteration < 500 && undistorted.size() >= 20; ++iteration)
  {
    for (Vec2& p : sample)
    {
      p = undistorted[pick(random)];
    }
    Ellipse e;
    if (!model.Fit(sample.data(), sample.size(), e))
    {
      continue;
    }
    near(e, 1.5, inliers, nullptr);
    if (inliers.size() > best.size())
    {
      best.swap(inliers);
    }
  }
  for (int pass = 0; pass < 3 && best.size() >= 20; ++pass)
  {
    std::vector<Vec2> chosen;
    chosen.reserve(best.size());
    for (std::size_t i : best)
    {
      chosen.push_back(undistorted[i]);
    }
    Ellipse e;
    std::vector<double> residuals;
    if (!model.Fit(chosen.data(), chosen.size(), e))
    {
      break;
    }
    near(e, 1e9, inliers, &residuals);
    std::vector<double> sorted = residuals;
    std::nth_element(sorted.begin(),
      sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double spread = 1.4826 * sorted[sorted.size() / 2];
    near(e, std::clamp(3.0 * spread, 0.6, 1.5), best, nullptr);
  }
  // Where the outline leaves the cone (a dome's limb meets its cut), the rim's points were
  // smoothed along the rim with those beyond: the last ones near each end are left out.
  std::vector<bool> on(undistorted.size(), false);
  for (std::size_t i : best)
  {
    on[i] = true;
  }
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(undistorted.size());
  const std::ptrdiff_t reach = static_cast<std::ptrdiff_t>(kEndTrim);
  for (std::size_t i : best)
  {
    bool inner = true;
    for (std::ptrdiff_t j = -reach; j <= reach && inner; ++j)
    {
      inner = on[static_cast<std::size_t>(
        ((static_cast<std::ptrdiff_t>(i) + j) % count + count) % count)];
    }
    if (inner || best.size() < 4 * kEndTrim)
    {
      keptPixels.push_back(pixels[i]);
      keptUndistorted.push_back(undistorted[i]);
    }
  }
}

} // namespace

bool DetectMirrorOutline(const Intrinsics& intrinsics, int width, int height,
  const std::uint8_t* rgba, std::vector<Vec2>& outlinePixels, std::string& error)
{
  CameraModel camera;
  camera.intrinsics = intrinsics;
  return DetectMirrorOutline(camera, width, height, rgba, outlinePixels, error);
}

bool DetectMirrorOutline(const CameraModel& camera, int width, int height, const std::uint8_t* rgba,
  std::vector<Vec2>& outlinePixels, std::string& error)
{
  return DetectMirrorOutline(
    camera, width, height, rgba, MirrorOutlineOptions(), outlinePixels, error);
}

bool DetectMirrorOutline(const CameraModel& camera, int width, int height, const std::uint8_t* rgba,
  const MirrorOutlineOptions& options, std::vector<Vec2>& outlinePixels, std::string& error)
{
  outlinePixels.clear();
  if (!rgba || width <= 0 || height <= 0)
  {
    error = "the image is empty";
    return false;
  }
  if (const std::string lens = ValidateLens(camera); !lens.empty())
  {
    error = "the camera is not usable: " + lens;
    return false;
  }
  if (width != camera.intrinsics.width || height != camera.intrinsics.height)
  {
    error = "the image is " + std::to_string(width) + " x " + std::to_string(height) +
      " pixels but the camera's intrinsics are for " + std::to_string(camera.intrinsics.width) +
      " x " + std::to_string(camera.intrinsics.height);
    return false;
  }
  if (width < kMinSide || height < kMinSide)
  {
    error = "the image is too small to find an outline in (at least " + std::to_string(kMinSide) +
      " x " + std::to_string(kMinSide) + " pixels)";
    return false;
  }

  const cv::Mat frame(height, width, CV_8UC4, const_cast<std::uint8_t*>(rgba));
  // Coarse to fine: the strong edges and the rim's search on the frame reduced to at most
  // kWorkingSide pixels a side (a large photograph costs no more than that), then the rim placed
  // on the whole frame in a narrow band around it.
  const double scale = std::min(1.0, kWorkingSide / std::max(width, height));
  cv::Mat rgb;
  if (scale < 1.0)
  {
    cv::Mat reduced;
    cv::resize(frame, reduced,
      cv::Size(std::max(kMinSide, static_cast<int>(std::lround(width * scale))),
        std::max(kMinSide, static_cast<int>(std::lround(height * scale)))),
      0.0, 0.0, cv::INTER_AREA);
    cv::cvtColor(reduced, rgb, cv::COLOR_RGBA2RGB);
  }
  else
  {
    cv::cvtColor(frame, rgb, cv::COLOR_RGBA2RGB);
  }
  {
    std::vector<cv::Mat> channels;
    cv::split(rgb, channels);
    double range = 0.0;
    for (const cv::Mat& channel : channels)
    {
      double lo = 0.0, hi = 0.0;
      cv::minMaxLoc(channel, &lo, &hi);
      range = std::max(range, hi - lo);
    }
    if (range < 4.0)
    {
      error = "the image is blank (a single colour): there is no mirror to outline";
      return false;
    }
  }

  // The camera of the reduced frame: pixel centres map as the area reduction maps them.
  CameraModel coarse = camera;
  {
    const double sx = static_cast<double>(rgb.cols) / width;
    const double sy = static_cast<double>(rgb.rows) / height;
    Intrinsics& k = coarse.intrinsics;
    k.fx *= sx;
    k.skew *= sx;
    k.cx = (k.cx + 0.5) * sx - 0.5;
    k.fy *= sy;
    k.cy = (k.cy + 0.5) * sy - 0.5;
    k.width = rgb.cols;
    k.height = rgb.rows;
  }
  Ellipse guess;
  if (!StrongEdgeEllipse(coarse, options.limb, rgb, guess, error))
  {
    return false;
  }

  // The rim along the normals of that ellipse: it may lie outside it, where the mirror reflects
  // the backdrop at its rim with less contrast than its reflection's own edges inside. The points
  // of one outline among the rim's (OutlineConsensus), and the rim searched again near
  // their cone, where the first search took an edge inside the rim over part of it.
  const Undistorter coarseLens(coarse);
  const Intrinsics& c = coarse.intrinsics;
  const OutlineModel coarseModel{ c, options.limb };
  const OutlineModel wholeModel{ camera.intrinsics, options.limb };
  std::vector<Vec2> rimPixels, rimUndistorted, conePixels, coneUndistorted;
  RimReport rim;
  RimSearch search;
  search.outside = std::max(6.0, 0.25 * guess.b);
  for (int pass = 0; pass < 2; ++pass)
  {
    if (!RimFromProfiles(rgb, coarseLens, guess, search, rimPixels, rimUndistorted, rim, error))
    {
      return false;
    }
    OutlineConsensus(coarseModel, rimPixels, rimUndistorted, conePixels, coneUndistorted);
    if (pass == 0 && !coarseModel.Fit(coneUndistorted.data(), coneUndistorted.size(), guess))
    {
      error = "no mirror outline found: the rim's points do not lie on a sphere's outline";
      return false;
    }
    search.outside = 6.0;
  }
  const Undistorter undistort(camera);
  if (scale < 1.0)
  {
    // On the whole frame, near the rim found: the reduced frame's undistorted pixels are the
    // whole one's through the normalised coordinates.
    const Intrinsics& f = camera.intrinsics;
    std::vector<Vec2> whole;
    for (const Vec2& u : coneUndistorted)
    {
      const double y = (u.y() - c.cy) / c.fy;
      const double x = (u.x() - c.cx - c.skew * y) / c.fx;
      whole.push_back(Vec2(f.fx * x + f.skew * y + f.cx, f.fy * y + f.cy));
    }
    Ellipse rimEllipse;
    if (whole.size() < 20 || !wholeModel.Fit(whole.data(), whole.size(), rimEllipse))
    {
      error = "no mirror outline found: the rim's points do not lie on a sphere's outline";
      return false;
    }
    RimSearch near;
    near.inside = near.outside = 2.0 + 2.0 / scale;
    near.alongSigma = search.alongSigma / scale;
    near.place = true;
    near.feet = &whole;
    if (!RimFromProfiles(frame, undistort, rimEllipse, near, rimPixels, rimUndistorted, rim, error))
    {
      return false;
    }
    OutlineConsensus(wholeModel, rimPixels, rimUndistorted, conePixels, coneUndistorted);
  }
  std::vector<Vec2>& refined = conePixels;
  std::vector<Vec2>& refinedUndistorted = coneUndistorted;
  Mat3 finalConic;
  Ellipse outline;
  if (refined.size() < 20 ||
    !FitConic(refinedUndistorted.data(), refinedUndistorted.size(), finalConic) ||
    EllipseOf(finalConic, outline) != ConicKind::Ellipse)
  {
    error = "no mirror outline found: the edge points do not lie on an ellipse";
    return false;
  }
  for (std::size_t i = 0; i < refined.size(); ++i)
  {
    if (SampsonDistance(outline.Q, refinedUndistorted[i]) < kInlierPixels)
    {
      outlinePixels.push_back(refined[i]);
    }
  }

  if (outlinePixels.size() < 20)
  {
    outlinePixels.clear();
    error = "no mirror outline found: too few edge points lie on one ellipse";
    return false;
  }
  return true;
}
} // namespace catar
