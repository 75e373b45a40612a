// CatadioptricAR Core: the lens models' formulas, as templates over the number type (double, or a
// type that carries derivatives: Eigen's AutoDiffScalar for the inverse's Newton, ceres::Jet for
// calibration), so that every user computes the one formula.
//
// Both take a camera-frame direction to distorted normalised coordinates (xd, yd); the camera
// matrix K then gives the pixel (CameraModel::DirectionToPixel):
//  - pinhole, OpenCV's full distortion vector k = (k1 k2 p1 p2 k3 k4 k5 k6 s1 s2 s3 s4 tauX tauY),
//    exactly as cv::projectPoints (x = X/Z, y = Y/Z, r^2 = x^2 + y^2):
//      radial = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//      x0 = x radial + 2 p1 x y + p2 (r^2 + 2 x^2) + s1 r^2 + s2 r^4
//      y0 = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y + s3 r^2 + s4 r^4
//    then the sensor's tilt (tauX, tauY in radians; cv::computeTiltProjectionMatrix): (x0, y0, 1)
//    through the tilt's projection matrix, divided by its third coordinate;
//  - fisheye (Kannala-Brandt, exactly as cv::fisheye::projectPoints for Z > 0, and on beyond 90
//    degrees): theta = the angle from the optical axis, theta_d = theta (1 + k1 theta^2 +
//    k2 theta^4 + k3 theta^6 + k4 theta^8), (xd, yd) = theta_d (X, Y) / sqrt(X^2 + Y^2).
#ifndef catarLensModels_h
#define catarLensModels_h

#include <cmath>

namespace catar
{
namespace lens
{
/// Number of coefficients of OpenCV's full pinhole distortion vector, and of the fisheye's.
constexpr int kPinholeCoefficients = 14;
constexpr int kFisheyeCoefficients = 4;

/// The 3x3 matrix of the sensor's tilt (row-major), as cv::computeTiltProjectionMatrix.
template<class T>
void TiltMatrix(const T& tauX, const T& tauY, T m[9])
{
  using std::cos;
  using std::sin;
  const T cX = cos(tauX), sX = sin(tauX), cY = cos(tauY), sY = sin(tauY);
  // R = RotY(tauY) * RotX(tauX)
  const T r[9] = { cY, sY * sX, -sY * cX, T(0.0), cX, sX, sY, -cY * sX, cY * cX };
  // ProjZ = [r22 0 -r02; 0 r22 -r12; 0 0 1]; tilt = ProjZ * R
  for (int c = 0; c < 3; ++c)
  {
    m[c] = r[8] * r[c] - r[2] * r[6 + c];
    m[3 + c] = r[8] * r[3 + c] - r[5] * r[6 + c];
    m[6 + c] = r[6 + c];
  }
}

/// OpenCV's pinhole distortion of normalised coordinates (x, y) = (X/Z, Y/Z); k holds the 14
/// coefficients (zeros for those a model does not use). tilted: tauX or tauY is not zero.
template<class T>
void PinholeDistort(const T* k, bool tilted, const T& x, const T& y, T& xd, T& yd)
{
  const T r2 = x * x + y * y;
  const T r4 = r2 * r2;
  const T r6 = r4 * r2;
  const T radial =
    (1.0 + k[0] * r2 + k[1] * r4 + k[4] * r6) / (1.0 + k[5] * r2 + k[6] * r4 + k[7] * r6);
  const T a1 = 2.0 * x * y;
  const T a2 = r2 + 2.0 * x * x;
  const T a3 = r2 + 2.0 * y * y;
  const T x0 = x * radial + k[2] * a1 + k[3] * a2 + k[8] * r2 + k[9] * r4;
  const T y0 = y * radial + k[2] * a3 + k[3] * a1 + k[10] * r2 + k[11] * r4;
  if (!tilted)
  {
    xd = x0;
    yd = y0;
    return;
  }
  T m[9];
  TiltMatrix(k[12], k[13], m);
  const T w = m[6] * x0 + m[7] * y0 + m[8];
  xd = (m[0] * x0 + m[1] * y0 + m[2]) / w;
  yd = (m[3] * x0 + m[4] * y0 + m[5]) / w;
}

/// The fisheye's theta_d of the angle theta from the axis; k holds k1..k4.
template<class T>
T FisheyeThetaD(const T* k, const T& theta)
{
  const T t2 = theta * theta;
  return theta * (1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
}

/// The fisheye's distorted normalised coordinates of the camera-frame direction (X, Y, Z); k holds
/// k1..k4. A direction on the axis gives (0, 0).
template<class T>
void FisheyeDistort(const T* k, const T& X, const T& Y, const T& Z, T& xd, T& yd)
{
  using std::atan2;
  using std::sqrt;
  const T rho2 = X * X + Y * Y;
  if (!(rho2 > 0.0))
  {
    xd = X / Z; // 0, with the first-order derivatives of x/z
    yd = Y / Z;
    return;
  }
  const T rho = sqrt(rho2);
  const T scale = FisheyeThetaD(k, atan2(rho, Z)) / rho;
  xd = scale * X;
  yd = scale * Y;
}
} // namespace lens
} // namespace catar

#endif
