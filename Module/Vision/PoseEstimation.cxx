#include "PoseEstimation.h"

#include "PoseUncertainty.h"
#include "Projector.h"

#include <ceres/ceres.h>
#include <opengv/absolute_pose/NoncentralAbsoluteAdapter.hpp>
#include <opengv/absolute_pose/methods.hpp>
#include <opengv/sac/Ransac.hpp>
#include <opengv/sac_problems/absolute_pose/AbsolutePoseSacProblem.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>

namespace catar
{
namespace
{
using SacProblem = opengv::sac_problems::absolute_pose::AbsolutePoseSacProblem;
using Inliers = std::vector<unsigned char>;

// GP3P needs 3 correspondences, and a 4th to choose among its (up to 8) solutions.
constexpr int kMinObservations = 4;
constexpr double kPi = 3.14159265358979323846;
// Rays whose directions all lie within this angle of their mean span less than ~0.1 degree: the
// points are too close together, as the mirror sees them, to fix a pose.
constexpr double kParallelHalfAngle = 0.05 * kPi / 180.0;
// World points whose second principal spread is below this fraction of the first are collinear:
// a rotation about their line is not observable.
constexpr double kCollinearRatio = 1e-4;
// The RANSAC pre-filter accepts bearing errors up to this many times the inlier threshold (in
// pixels, converted with the median angle a pixel spans): loose, because the inliers are then
// decided by the pixel error, which the angle only approximates (the angle a pixel spans grows
// fast towards the mirror's rim).
constexpr double kPreFilterFactor = 4.0;

PoseResult Fail(const std::string& error)
{
  PoseResult r;
  r.error = error;
  return r;
}

std::string CheckOptions(const PoseOptions& o)
{
  if (!(o.inlierThreshold > 0.0 && std::isfinite(o.inlierThreshold)))
  {
    return "the inlier threshold must be a positive number of pixels";
  }
  if (o.maxIterations < 1)
  {
    return "the RANSAC iteration count must be at least 1";
  }
  if (!(o.minimumPixelSigma >= 0.0 && std::isfinite(o.minimumPixelSigma)) ||
    !(o.maxPositionSigma > 0.0) || !(o.maxAngleSigmaDegrees > 0.0) ||
    !(o.minInlierFraction >= 0.0 && o.minInlierFraction <= 1.0))
  {
    return "the guards' bounds must be positive (the pixel sigma's floor at least 0, the inlier "
           "fraction from 0 to 1)";
  }
  if (!(o.confidence > 0.0 && o.confidence < 1.0))
  {
    return "the RANSAC confidence must lie strictly between 0 and 1";
  }
  return std::string();
}

std::string CheckFinite(const std::vector<PoseObservation>& observations)
{
  for (std::size_t i = 0; i < observations.size(); ++i)
  {
    if (!observations[i].pixel.allFinite() || !observations[i].world.allFinite())
    {
      return "observation " + std::to_string(i) +
        " is not finite (NaN or Inf in its pixel or world point)";
    }
  }
  return std::string();
}

// The usable observations' reflected rays, as OpenGV's non-central adapter takes them: one
// "camera" per ray, placed at the ray's mirror point (camera frame) with the identity rotation,
// and the ray's direction as its bearing.
struct Rays
{
  std::vector<int> observation; // the observation of each ray
  std::vector<int> ray;         // the ray of each observation, -1 where its pixel misses the mirror
  opengv::bearingVectors_t bearings;
  opengv::translations_t offsets;
  opengv::rotations_t rotations;
  opengv::points_t points;
  std::vector<int> cameras; // ray i is camera i
  std::vector<double> anglePerPixel;
  std::size_t Size() const { return this->observation.size(); }
};

// The angle (radians) the reflected ray turns through when its pixel moves by one (the largest
// over the four neighbours that see the mirror; NaN when none does).
double AnglePerPixel(const Projector& projector, const Vec2& pixel, const Vec3& direction)
{
  const Vec2 steps[4] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
  double angle = std::numeric_limits<double>::quiet_NaN();
  for (const Vec2& step : steps)
  {
    const BackProjectedRay n = projector.BackProjectCamera(pixel + step);
    if (HasProjection(n.status))
    {
      const double a = std::atan2(direction.cross(n.direction).norm(), direction.dot(n.direction));
      angle = std::isnan(angle) ? a : std::max(angle, a);
    }
  }
  return angle;
}

Rays BackProject(const Projector& projector, const std::vector<PoseObservation>& observations)
{
  Rays rays;
  rays.ray.assign(observations.size(), -1);
  for (std::size_t i = 0; i < observations.size(); ++i)
  {
    const BackProjectedRay b = projector.BackProjectCamera(observations[i].pixel);
    if (!HasProjection(b.status))
    {
      continue;
    }
    rays.ray[i] = static_cast<int>(rays.Size());
    rays.cameras.push_back(static_cast<int>(rays.Size()));
    rays.observation.push_back(static_cast<int>(i));
    rays.bearings.push_back(b.direction);
    rays.offsets.push_back(b.mirrorPoint);
    rays.rotations.push_back(Mat3::Identity());
    rays.points.push_back(observations[i].world);
    rays.anglePerPixel.push_back(AnglePerPixel(projector, observations[i].pixel, b.direction));
  }
  return rays;
}

bool Collinear(const Rays& rays)
{
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : rays.points)
  {
    mean += p;
  }
  mean /= static_cast<double>(rays.Size());
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& p : rays.points)
  {
    covariance += (p - mean) * (p - mean).transpose();
  }
  // Eigenvalues in increasing order: [1] is the second principal variance.
  const Vec3 variances = Eigen::SelfAdjointEigenSolver<Mat3>(covariance).eigenvalues();
  return !(variances[1] > kCollinearRatio * kCollinearRatio * variances[2]);
}

bool Parallel(const Rays& rays)
{
  Vec3 mean = Vec3::Zero();
  for (const Vec3& d : rays.bearings)
  {
    mean += d;
  }
  if (!(mean.norm() > 0.5 * static_cast<double>(rays.Size())))
  {
    return false; // directions spread widely enough to (nearly) cancel out
  }
  mean.normalize();
  for (const Vec3& d : rays.bearings)
  {
    if (std::atan2(d.cross(mean).norm(), d.dot(mean)) > kParallelHalfAngle)
    {
      return false;
    }
  }
  return true;
}

// OpenGV's threshold on 1 - cos(angle between the bearing and the direction to the point).
double PreFilterThreshold(const Rays& rays, double pixels)
{
  std::vector<double> angles;
  for (double a : rays.anglePerPixel)
  {
    if (std::isfinite(a))
    {
      angles.push_back(a);
    }
  }
  double perPixel = 1e-3; // f = 1000 px without a mirror, if no neighbour saw the mirror
  if (!angles.empty())
  {
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    perPixel = angles[angles.size() / 2];
  }
  const double angle = std::clamp(kPreFilterFactor * pixels * perPixel, 1e-6, 0.5);
  return 1.0 - std::cos(angle);
}

// A rotation matrix nearest to m (the solvers' rotations are orthonormal to rounding only).
Mat3 NearestRotation(const Mat3& m)
{
  const Eigen::JacobiSVD<Mat3> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 d = Mat3::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

// OpenGV's transformation is the viewpoint's orientation and position in the world
// (body-to-world R, t = position): world-to-camera is [R^T, -R^T t].
Mat4 FromOpenGV(const opengv::transformation_t& T)
{
  const Mat3 R = NearestRotation(T.topLeftCorner<3, 3>());
  Mat4 pose = Mat4::Identity();
  pose.topLeftCorner<3, 3>() = R.transpose();
  pose.topRightCorner<3, 1>() = -R.transpose() * T.col(3);
  return pose;
}

// RANSAC with GP3P; its pose and inliers (ray indices, by the pre-filter).
bool RunRansac(opengv::absolute_pose::NoncentralAbsoluteAdapter& adapter, const Rays& rays,
  const PoseOptions& options, Mat4& pose, std::vector<int>& inliers)
{
  auto problem = std::make_shared<SacProblem>(adapter, SacProblem::GP3P, false);
  // Seeded here so that one seed gives one result (OpenGV seeds with a constant or the clock).
  problem->rng_alg_.seed(options.seed);
  problem->rng_gen_ =
    std::make_shared<std::function<int()>>(std::bind(*problem->rng_dist_, problem->rng_alg_));
  opengv::sac::Ransac<SacProblem> ransac(
    options.maxIterations, PreFilterThreshold(rays, options.inlierThreshold), options.confidence);
  ransac.sac_model_ = problem;
  if (!ransac.computeModel() || !ransac.model_coefficients_.allFinite())
  {
    return false;
  }
  pose = FromOpenGV(ransac.model_coefficients_);
  inliers = ransac.inliers_;
  return true;
}

// Each observation's pixel reprojection error through the mirror under a world-to-camera pose
// (infinite where its point has no image).
std::vector<double> PixelErrors(
  const Projector& projector, const std::vector<PoseObservation>& observations, const Mat4& pose)
{
  const PoseFrames frames(pose);
  std::vector<double> errors(observations.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < observations.size(); ++i)
  {
    const ProjectedPoint q = projector.ProjectCamera(frames.ToCamera(observations[i].world));
    if (HasProjection(q.status))
    {
      errors[i] = (q.pixel - observations[i].pixel).norm();
    }
  }
  return errors;
}

Inliers SelectInliers(const std::vector<double>& errors, double threshold, int& count)
{
  Inliers inliers(errors.size(), 0);
  count = 0;
  for (std::size_t i = 0; i < errors.size(); ++i)
  {
    inliers[i] = errors[i] <= threshold ? 1 : 0;
    count += inliers[i];
  }
  return inliers;
}

double SumSquares(const std::vector<double>& errors, const Inliers& inliers)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < errors.size(); ++i)
  {
    sum += inliers[i] ? errors[i] * errors[i] : 0.0;
  }
  return sum;
}

// The sum of squared pixel errors over the inliers (infinite where one has no image).
double Cost(const Projector& projector, const std::vector<PoseObservation>& observations,
  const Inliers& inliers, const Mat4& pose)
{
  return pose.allFinite() ? SumSquares(PixelErrors(projector, observations, pose), inliers)
                          : std::numeric_limits<double>::infinity();
}

// OpenGV's non-linear refinement of the bearing errors of the given rays, from a world-to-camera
// pose (the pose itself where there are too few rays).
Mat4 OptimizeBearings(opengv::absolute_pose::NoncentralAbsoluteAdapter& adapter,
  const std::vector<int>& rays, const Mat4& pose)
{
  if (rays.size() < 6) // one residual per ray, six unknowns
  {
    return pose;
  }
  const Mat3 R = pose.topLeftCorner<3, 3>();
  adapter.setR(R.transpose());
  adapter.sett(-R.transpose() * pose.topRightCorner<3, 1>());
  return FromOpenGV(opengv::absolute_pose::optimize_nonlinear(adapter, rays));
}

// The rays of the inliers that have one.
std::vector<int> InlierRays(const Rays& rays, const Inliers& inliers)
{
  std::vector<int> indices;
  for (std::size_t i = 0; i < inliers.size(); ++i)
  {
    if (inliers[i] && rays.ray[i] >= 0)
    {
      indices.push_back(rays.ray[i]);
    }
  }
  return indices;
}

int CountInliers(const Projector& projector, const std::vector<PoseObservation>& observations,
  const Mat4& pose, double threshold)
{
  int count = 0;
  SelectInliers(PixelErrors(projector, observations, pose), threshold, count);
  return count;
}

// One observation's pixel residual for the pose R = exp(w) R0, t (world to camera), x = (w, t).
// Derivatives by the chain rule: the pixel's derivative with respect to the point in the camera
// frame (Projector::PixelDerivative: three directions, half the projections of differencing the
// six pose parameters; one-sided near the mirror's rim, so that an inlier there never stops
// Ceres) times the point's derivative with respect to the pose in closed form.
class PixelCost : public ceres::SizedCostFunction<2, 3, 3>
{
public:
  PixelCost(const Projector& projector, const Mat3& R0, const PoseObservation& o)
    : ProjectorRef(projector)
    , R0World(R0 * o.world)
    , Pixel(o.pixel)
  {
  }

  bool Evaluate(
    double const* const* parameters, double* residuals, double** jacobians) const override
  {
    const Vec3 w(parameters[0][0], parameters[0][1], parameters[0][2]);
    const Vec3 t(parameters[1][0], parameters[1][1], parameters[1][2]);
    const Mat3 R = RotationFromAngleAxis(w);
    const Vec3 p = R * this->R0World + t;
    const ProjectedPoint q = this->ProjectorRef.ProjectCamera(p);
    if (!HasProjection(q.status))
    {
      return false; // Ceres rejects the step
    }
    const Vec2 r = q.pixel - this->Pixel;
    residuals[0] = r.x();
    residuals[1] = r.y();
    if (!jacobians || (!jacobians[0] && !jacobians[1]))
    {
      return true;
    }
    Eigen::Matrix<double, 2, 3> dPixel; // d pixel / d p
    this->ProjectorRef.PixelDerivative(p, q, dPixel);
    if (jacobians[1]) // d p / d t = I
    {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> dt(jacobians[1]);
      dt = dPixel;
    }
    if (jacobians[0]) // d p / d w = -[R R0 X]x J_l(w), J_l the left Jacobian of SO(3)
    {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> dw(jacobians[0]);
      dw = dPixel * (-Skew(R * this->R0World) * RotationLeftJacobian(w));
    }
    return true;
  }

private:
  const Projector& ProjectorRef;
  const Vec3 R0World; // R0 X: the world point turned by the start's rotation
  const Vec2 Pixel;
};

// Ceres: least squares of the inliers' pixel errors through the mirror, over a rotation update
// (angle-axis, applied on the left of the start's rotation, so that it starts at zero, far from
// angle-axis's singularity at 180 degrees) and the translation.
Mat4 RefinePixels(const Projector& projector, const std::vector<PoseObservation>& observations,
  const Inliers& inliers, const Mat4& pose)
{
  const Mat3 R0 = pose.topLeftCorner<3, 3>();
  double w[3] = { 0.0, 0.0, 0.0 };
  double t[3] = { pose(0, 3), pose(1, 3), pose(2, 3) };
  ceres::Problem problem;
  // Only inliers with an image at the start: Ceres stops if its first evaluation fails.
  const std::vector<double> errors = PixelErrors(projector, observations, pose);
  for (std::size_t i = 0; i < observations.size(); ++i)
  {
    if (inliers[i] && std::isfinite(errors[i]))
    {
      problem.AddResidualBlock(new PixelCost(projector, R0, observations[i]), nullptr, w, t);
    }
  }
  if (problem.NumResidualBlocks() < 3) // 2 residuals each, six unknowns
  {
    return pose;
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  // A relative step of 1e-10 is below a nanometre and a nanoradian at these scales.
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable())
  {
    return pose;
  }
  Mat4 refined = Mat4::Identity();
  refined.topLeftCorner<3, 3>() = RotationFromAngleAxis(Vec3(w[0], w[1], w[2])) * R0;
  refined.topRightCorner<3, 1>() = Vec3(t[0], t[1], t[2]);
  return refined;
}

// Refines the pose on the inliers: Ceres on the pixels (options.refine), else OpenGV on the
// bearings. A step is kept only when it lowers the inliers' pixel cost. (Both, OpenGV's first,
// gave the same poses to the micrometre on POV-Ray's frames and took 3-5 times as long: OpenGV's
// step alone took about 1 ms for 30 rays.)
Mat4 Refine(const Projector& projector, const std::vector<PoseObservation>& observations,
  opengv::absolute_pose::NoncentralAbsoluteAdapter& adapter, const Rays& rays,
  const Inliers& inliers, const Mat4& pose, bool refine)
{
  Mat4 best = pose;
  double bestCost = Cost(projector, observations, inliers, pose);
  const auto keepIfBetter = [&](const Mat4& candidate) {
    const double c = Cost(projector, observations, inliers, candidate);
    if (c < bestCost) // never an infinite cost: every inlier keeps its image
    {
      best = candidate;
      bestCost = c;
    }
  };
  keepIfBetter(refine ? RefinePixels(projector, observations, inliers, pose)
                      : OptimizeBearings(adapter, InlierRays(rays, inliers), pose));
  return best;
}

// The pose of RANSAC's minimal sample carries the noise of its 4 points, which can put most
// inliers past the pixel threshold: it is first refined on RANSAC's inliers (the pre-filter's,
// those with an image), and that pose is kept when it has at least as many pixel inliers.
Mat4 Polish(const Projector& projector, const std::vector<PoseObservation>& observations,
  opengv::absolute_pose::NoncentralAbsoluteAdapter& adapter, const Rays& rays,
  const std::vector<int>& rayInliers, const Mat4& pose, const PoseOptions& options,
  Inliers& refinedOn)
{
  const std::vector<double> errors = PixelErrors(projector, observations, pose);
  Inliers preFiltered(observations.size(), 0);
  for (int r : rayInliers)
  {
    const int i = rays.observation[static_cast<std::size_t>(r)];
    preFiltered[static_cast<std::size_t>(i)] = std::isfinite(errors[static_cast<std::size_t>(i)]);
  }
  const Mat4 polished =
    Refine(projector, observations, adapter, rays, preFiltered, pose, options.refine);
  const double threshold = options.inlierThreshold;
  const bool better = CountInliers(projector, observations, polished, threshold) >=
    CountInliers(projector, observations, pose, threshold);
  refinedOn = better ? preFiltered : Inliers();
  return better ? polished : pose;
}

// Decides the inliers by their pixel error and refines the pose on them, until the set no longer
// changes; `refinedOn`: the set the pose was last refined on (Polish's), not refined on again.
Mat4 RefineOnInliers(const Projector& projector, const std::vector<PoseObservation>& observations,
  opengv::absolute_pose::NoncentralAbsoluteAdapter& adapter, const Rays& rays, const Mat4& start,
  const PoseOptions& options, Inliers refinedOn)
{
  Mat4 pose = start;
  for (int round = 0; round < 5; ++round)
  {
    int count = 0;
    const Inliers inliers =
      SelectInliers(PixelErrors(projector, observations, pose), options.inlierThreshold, count);
    if (count < kMinObservations || inliers == refinedOn)
    {
      break;
    }
    pose = Refine(projector, observations, adapter, rays, inliers, pose, options.refine);
    refinedOn = inliers;
  }
  return pose;
}

std::string TooFewUsable(std::size_t usable, std::size_t total)
{
  std::ostringstream s;
  s << "needs at least " << kMinObservations
    << " observations whose pixels see the mirror (3 for the minimal solver and one more to "
       "choose among its solutions), but "
    << usable << " of " << total << " do (" << (total - usable) << " pixels' rays miss the mirror)";
  return s.str();
}

// The checks before RANSAC: an empty string, or the sentence that refuses the input.
std::string CheckInput(const CameraModel& camera, const std::vector<PoseObservation>& observations,
  const PoseOptions& options)
{
  std::string error = CheckOptions(options);
  if (!error.empty())
  {
    return error;
  }
  error = camera.Validate();
  if (!error.empty())
  {
    return "invalid camera: " + error;
  }
  error = CheckFinite(observations);
  if (!error.empty())
  {
    return error;
  }
  if (observations.size() < static_cast<std::size_t>(kMinObservations))
  {
    return "needs at least " + std::to_string(kMinObservations) +
      " observations (3 for the minimal solver and one more to choose among its solutions), got " +
      std::to_string(observations.size());
  }
  return std::string();
}

std::string CheckRays(const Rays& rays, std::size_t total)
{
  if (rays.Size() < static_cast<std::size_t>(kMinObservations))
  {
    return TooFewUsable(rays.Size(), total);
  }
  if (Collinear(rays))
  {
    return "the world points are (nearly) collinear: the rotation about their line is unknown";
  }
  if (Parallel(rays))
  {
    return "the reflected rays are nearly parallel (they span less than 0.1 degree): the points "
           "are too close together as the mirror sees them";
  }
  return std::string();
}
// "" when a pose found passes the guards, else why not, with the numbers.
std::string PoseWarning(const PoseResult& r, std::size_t observations, const PoseOptions& options)
{
  std::ostringstream s;
  const PoseUncertainty& u = r.uncertainty;
  if (static_cast<double>(r.inlierCount) <
    options.minInlierFraction * static_cast<double>(observations))
  {
    s << "only " << r.inlierCount << " of " << observations
      << " observations fit the pose (fewer than " << 100.0 * options.minInlierFraction
      << "%): the points do not match their world positions";
  }
  else if (!u.known)
  {
    s << "the pixels do not fix the pose (the pose's Jacobian is singular)";
  }
  else if (u.positionSigma > options.maxPositionSigma ||
    u.angleSigmaDegrees > options.maxAngleSigmaDegrees)
  {
    s.precision(2);
    s << "the pose is uncertain: one sigma " << 1000.0 * u.positionSigma << " mm and "
      << u.angleSigmaDegrees << " degrees (bounds " << 1000.0 * options.maxPositionSigma << " mm, "
      << options.maxAngleSigmaDegrees << " degrees; pixel noise " << u.pixelSigma << " px)";
  }
  return s.str();
}
} // namespace

PoseResult EstimatePose(const CameraModel& camera, const std::vector<PoseObservation>& observations,
  const PoseOptions& options)
{
  CameraModel model = camera;
  model.worldToCamera = Mat4::Identity(); // the pose is what is sought
  std::string error = CheckInput(model, observations, options);
  if (!error.empty())
  {
    return Fail(error);
  }
  const Projector projector(model);
  const Rays rays = BackProject(projector, observations);
  error = CheckRays(rays, observations.size());
  if (!error.empty())
  {
    return Fail(error);
  }
  opengv::absolute_pose::NoncentralAbsoluteAdapter adapter(
    rays.bearings, rays.cameras, rays.points, rays.offsets, rays.rotations);
  Mat4 pose = Mat4::Identity();
  std::vector<int> rayInliers;
  PoseResult result;
  std::vector<double> errors;
  if (RunRansac(adapter, rays, options, pose, rayInliers))
  {
    Inliers polishedOn;
    pose = Polish(projector, observations, adapter, rays, rayInliers, pose, options, polishedOn);
    pose = RefineOnInliers(projector, observations, adapter, rays, pose, options, polishedOn);
    errors = PixelErrors(projector, observations, pose);
    result.inliers = SelectInliers(errors, options.inlierThreshold, result.inlierCount);
  }
  if (result.inlierCount < kMinObservations)
  {
    std::ostringstream s;
    s << "RANSAC found no pose with at least " << kMinObservations << " inliers within "
      << options.inlierThreshold << " px (best: " << result.inlierCount << " of "
      << observations.size() << ")";
    return Fail(s.str());
  }
  result.ok = true;
  result.worldToCamera = pose;
  result.rmsPixels = std::sqrt(SumSquares(errors, result.inliers) / result.inlierCount);
  result.uncertainty = EstimatePoseUncertainty(
    projector, observations, result.inliers, pose, options.minimumPixelSigma);
  result.warning = PoseWarning(result, observations.size(), options);
  result.reliable = result.warning.empty();
  return result;
}
} // namespace catar
