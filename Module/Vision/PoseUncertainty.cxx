#include "PoseUncertainty.h"

#include "Projector.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{
namespace
{
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
constexpr double kPi = 3.14159265358979323846;
// J^T J is taken as singular when its smallest eigenvalue is below this fraction of its largest
// (after the columns are scaled to one pixel per unit step, radians and metres alike).
constexpr double kSingular = 1e-14;

// The camera's pose moved by x = (rotation about world axes through the centre, centre shift):
// camera-to-world rotation exp(x.head) * Rcw, centre c + x.tail; returned world to camera.
struct CameraInWorld
{
  Mat3 rotation; // camera to world
  Vec3 centre;

  explicit CameraInWorld(const PoseFrames& frames)
    : rotation(frames.rotationT)
    , centre(frames.centre)
  {
  }

  // The world point p in the camera frame of the pose moved by x.
  Vec3 ToCamera(const Vector6& x, const Vec3& p) const
  {
    const Vec3 w = x.head<3>();
    const double angle = w.norm();
    const Mat3 turn =
      angle > 0.0 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() : Mat3::Identity();
    const Mat3 cameraToWorld = turn * this->rotation;
    return cameraToWorld.transpose() * (p - (this->centre + x.tail<3>()));
  }
};

PoseUncertainty Unknown(double pixelSigma)
{
  PoseUncertainty u;
  u.pixelSigma = pixelSigma;
  u.positionSigma = std::numeric_limits<double>::infinity();
  u.angleSigmaDegrees = std::numeric_limits<double>::infinity();
  u.covariance.setConstant(std::numeric_limits<double>::infinity());
  return u;
}

double LargestEigenvalue(const Mat3& m)
{
  return Eigen::SelfAdjointEigenSolver<Mat3>(m, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}
}

PoseUncertainty EstimatePoseUncertainty(const Projector& projector,
  const std::vector<PoseObservation>& observations, const std::vector<unsigned char>& inliers,
  const Mat4& worldToCamera, double minimumPixelSigma)
{
  const CameraInWorld camera{ PoseFrames(worldToCamera) };
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < observations.size(); ++i)
  {
    if (inliers.empty() || (i < inliers.size() && inliers[i]))
    {
      used.push_back(i);
    }
  }
  const double floor = std::max(0.0, minimumPixelSigma);
  const std::size_t rows = 2 * used.size();
  if (rows <= 6)
  {
    return Unknown(floor);
  }
  Eigen::MatrixXd jacobian(rows, 6);
  double squares = 0.0;
  const Vector6 zero = Vector6::Zero();
  // The point in the camera frame moves with the pose's x = (turn w, centre shift) as
  // d p / d w = R [X - c]x and d p / d shift = -R (R world to camera, at x = 0); the pixel's
  // derivative with respect to p from Projector::PixelDerivative.
  const Mat3 toCamera = camera.rotation.transpose();
  for (std::size_t k = 0; k < used.size(); ++k)
  {
    const PoseObservation& o = observations[used[k]];
    const Vec3 p = camera.ToCamera(zero, o.world);
    const ProjectedPoint at = projector.ProjectCamera(p);
    if (!HasProjection(at.status))
    {
      return Unknown(floor);
    }
    squares += (at.pixel - o.pixel).squaredNorm();
    Eigen::Matrix<double, 2, 3> dPixel;
    if (!projector.PixelDerivative(p, at, dPixel))
    {
      return Unknown(floor);
    }
    const Mat3 cross = Skew(o.world - camera.centre);
    const auto row = static_cast<Eigen::Index>(2 * k);
    jacobian.block<2, 3>(row, 0) = dPixel * (toCamera * cross);
    jacobian.block<2, 3>(row, 3) = -dPixel * toCamera;
  }
  const double estimated = std::sqrt(squares / static_cast<double>(rows - 6));
  const double sigma = std::max(floor, estimated);
  const Matrix6 information = jacobian.transpose() * jacobian;
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(information);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (!(largest > 0.0) || !(eigen.eigenvalues().minCoeff() > kSingular * largest))
  {
    return Unknown(sigma);
  }
  PoseUncertainty u;
  u.known = true;
  u.pixelSigma = sigma;
  u.covariance = sigma * sigma *
    (eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
      eigen.eigenvectors().transpose());
  u.angleSigmaDegrees =
    std::sqrt(LargestEigenvalue(u.covariance.topLeftCorner<3, 3>())) * 180.0 / kPi;
  u.positionSigma = std::sqrt(LargestEigenvalue(u.covariance.bottomRightCorner<3, 3>()));
  return u;
}
} // namespace catar
