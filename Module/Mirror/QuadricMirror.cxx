#include "QuadricMirror.h"

#include "Polynomials.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

namespace catar
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kGrazingCosine = 1e-9; // cos(incidence) below this: no usable reflection
constexpr int kNewtonSteps = 60;

using Vec4 = Eigen::Vector4d;

// The numbers every quadric type ends with: mirror_to_camera (16, row-major) and z_range (2).
constexpr int kTail = 18;

Mat4 RowMajor4(const double* v)
{
  Mat4 m;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m(r, c) = v[4 * r + c];
    }
  }
  return m;
}

void AppendRowMajor(const Mat4& m, std::vector<double>& out)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out.push_back(m(r, c));
    }
  }
}

Mat4 Translation(double x, double y, double z)
{
  Mat4 m = Mat4::Identity();
  m.topRightCorner<3, 1>() = Vec3(x, y, z);
  return m;
}

std::vector<MirrorParameter> WithTail(std::vector<MirrorParameter> shape)
{
  shape.push_back({ "mirror_to_camera", 16,
    "H_OC, rigid, row-major: x_camera = H_OC x_mirror (the mirror frame's axis z is the "
    "shape's)" });
  shape.push_back({ "z_range", 2, "zmin, zmax: the mirror is the part with zmin <= z <= zmax" });
  return shape;
}

std::vector<double> WithTail(std::vector<double> shape, const Mat4& h, double zmin, double zmax)
{
  AppendRowMajor(h, shape);
  shape.push_back(zmin);
  shape.push_back(zmax);
  return shape;
}

// Omega of each named shape from its own numbers (the description's first ones); false with a
// sentence when the numbers are out of range.
bool ShapeOmega(const std::string& type, const double* p, Mat4& omega, std::string& error)
{
  omega.setZero();
  std::ostringstream err;
  if (type == "quadric")
  {
    omega = RowMajor4(p);
    return true;
  }
  if (type == "hyperboloid")
  {
    if (!(p[0] > 0.0 && p[1] > 0.0))
    {
      err << "mirror.a and mirror.b must be positive (a=" << p[0] << ", b=" << p[1] << ")";
      error = err.str();
      return false;
    }
    omega.diagonal() = Vec4(1.0 / (p[1] * p[1]), 1.0 / (p[1] * p[1]), -1.0 / (p[0] * p[0]), 1.0);
    return true;
  }
  if (type == "paraboloid")
  {
    if (!(p[0] > 0.0))
    {
      err << "mirror.focal must be positive (" << p[0] << ")";
      error = err.str();
      return false;
    }
    // x^2 + y^2 - 4 f z - 4 f^2
    omega(0, 0) = omega(1, 1) = 1.0;
    omega(2, 3) = omega(3, 2) = -2.0 * p[0];
    omega(3, 3) = -4.0 * p[0] * p[0];
    return true;
  }
  if (type == "ellipsoid")
  {
    if (!(p[0] > 0.0 && p[1] > 0.0 && p[2] > 0.0))
    {
      err << "mirror.semi_axes must be positive (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
      error = err.str();
      return false;
    }
    omega.diagonal() = Vec4(1.0 / (p[0] * p[0]), 1.0 / (p[1] * p[1]), 1.0 / (p[2] * p[2]), -1.0);
    return true;
  }
  if (type == "sphere")
  {
    if (!(p[0] > 0.0))
    {
      err << "mirror.radius must be positive (" << p[0] << ")";
      error = err.str();
      return false;
    }
    omega = Mat4::Identity();
    omega(3, 3) = -p[0] * p[0];
    return true;
  }
  if (type == "cone")
  {
    if (!(p[0] > 0.0 && p[0] < 90.0))
    {
      err << "mirror.half_angle must be in (0, 90) degrees (" << p[0] << ")";
      error = err.str();
      return false;
    }
    const double t = std::tan(p[0] * kPi / 180.0);
    omega.diagonal() = Vec4(1.0, 1.0, -t * t, 0.0);
    return true;
  }
  error = "not a quadric mirror type: " + type;
  return false;
}

int ShapeCount(const std::string& type)
{
  if (type == "quadric")
  {
    return 16;
  }
  if (type == "hyperboloid")
  {
    return 2;
  }
  if (type == "ellipsoid")
  {
    return 3;
  }
  if (type == "paraboloid" || type == "cone" || type == "sphere")
  {
    return 1;
  }
  return -1;
}

std::shared_ptr<const detail::QuadricSurface> Build(
  const MirrorDescription& description, const QuadricGeometry& geometry);

std::string ValidateQuadric(const MirrorDescription& d)
{
  QuadricGeometry g;
  std::string error;
  if (!QuadricFromDescription(d, g, &error) || !error.empty())
  {
    return error.empty() ? "not a quadric mirror: " + d.type : error;
  }
  error = g.Validate();
  if (!error.empty())
  {
    return error;
  }
  // The camera must see some of it.
  if (!Build(d, g))
  {
    return "the camera sees no part of the mirror (check mirror_to_camera and z_range)";
  }
  return std::string();
}

// A few surfaces kept built (the table takes a fraction of a millisecond; filters make a
// projector every execution).
std::shared_ptr<const detail::QuadricSurface> Build(
  const MirrorDescription& description, const QuadricGeometry& geometry)
{
  static std::mutex mutex;
  static std::vector<std::shared_ptr<const detail::QuadricSurface>> cache;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& s : cache)
    {
      if (s->Describe() == description)
      {
        return s->Viewpoint().allFinite() ? s : nullptr;
      }
    }
  }
  auto surface = std::make_shared<const detail::QuadricSurface>(description, geometry);
  const std::lock_guard<std::mutex> lock(mutex);
  cache.insert(cache.begin(), surface);
  if (cache.size() > 8)
  {
    cache.pop_back();
  }
  return surface->Viewpoint().allFinite() ? surface : nullptr;
}

// The quadric of the camera frame: Omega moved by mirror_to_camera (H^-T Omega H^-1).
bool CameraQuadric(const MirrorDescription& d, Mat3& A, Vec3& B, double& C)
{
  QuadricGeometry g;
  if (!QuadricFromDescription(d, g) || g.omega.isZero())
  {
    return false;
  }
  const Mat3 R = g.mirrorToCamera.topLeftCorner<3, 3>();
  const Vec3 t = g.mirrorToCamera.topRightCorner<3, 1>();
  Mat4 inverse = Mat4::Identity();
  inverse.topLeftCorner<3, 3>() = R.transpose();
  inverse.topRightCorner<3, 1>() = -R.transpose() * t;
  const Mat4 Q = inverse.transpose() * g.omega * inverse;
  A = Q.topLeftCorner<3, 3>();
  B = Q.topRightCorner<3, 1>();
  C = Q(3, 3);
  return true;
}

MirrorType MakeType(const std::string& name, const std::string& help,
  std::vector<MirrorParameter> shape, std::vector<double> defaults)
{
  MirrorType t;
  t.name = name;
  t.help = help;
  t.parameters = WithTail(std::move(shape));
  t.defaults = std::move(defaults);
  t.validate = &ValidateQuadric;
  t.make = [](const MirrorDescription& d) -> std::shared_ptr<const Mirror> {
    QuadricGeometry g;
    QuadricFromDescription(d, g);
    return Build(d, g);
  };
  t.quadric = &CameraQuadric;
  return t;
}
} // namespace

std::string QuadricGeometry::Validate() const
{
  std::ostringstream err;
  const double norm = this->omega.cwiseAbs().maxCoeff();
  if (!(norm > 0.0))
  {
    return "mirror.matrix is zero";
  }
  if ((this->omega - this->omega.transpose()).cwiseAbs().maxCoeff() > 1e-12 * norm)
  {
    return "mirror.matrix is not symmetric";
  }
  const Eigen::SelfAdjointEigenSolver<Mat4> eig(this->omega / norm);
  int rank = 0;
  for (int i = 0; i < 4; ++i)
  {
    rank += std::abs(eig.eigenvalues()[i]) > 1e-12 ? 1 : 0;
  }
  if (rank < 3 || !(this->omega.topLeftCorner<3, 3>().cwiseAbs().maxCoeff() > 1e-12 * norm))
  {
    err << "mirror.matrix is degenerate (rank " << rank << "): a plane, a pair of planes or a line";
    return err.str();
  }
  const Mat3 R = this->mirrorToCamera.topLeftCorner<3, 3>();
  const double orth = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (orth > 1e-9 || R.determinant() < 0.0 ||
    (this->mirrorToCamera.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-12)
  {
    err << "mirror.mirror_to_camera is not a rigid transform (|R^T R - I| = " << orth
        << ", det = " << R.determinant() << ", last row must be 0 0 0 1)";
    return err.str();
  }
  if (!(this->zmin < this->zmax))
  {
    err << "mirror.z_range is empty (zmin = " << this->zmin << ", zmax = " << this->zmax << ")";
    return err.str();
  }
  // The camera centre in the mirror frame.
  const Vec3 t = this->mirrorToCamera.topRightCorner<3, 1>();
  const Vec3 camera = -(R.transpose() * t);
  const Vec4 X(camera.x(), camera.y(), camera.z(), 1.0);
  const double F = X.dot(this->omega * X) / norm;
  const Vec4 gradient = 2.0 * this->omega * X / norm;
  const double scale = std::max(1.0, camera.norm());
  const bool inRange = camera.z() >= this->zmin && camera.z() <= this->zmax;
  if (std::abs(F) <= 1e-12 * std::max(gradient.head<3>().norm() * scale, 1e-300) && inRange)
  {
    return "the camera centre is on the mirror surface";
  }
  if (F < 0.0 && inRange)
  {
    return "the camera centre is inside the mirror (the quadric is negative there, within "
           "z_range)";
  }
  return std::string();
}

bool QuadricFromDescription(
  const MirrorDescription& description, QuadricGeometry& g, std::string* shapeError)
{
  const int shape = ShapeCount(description.type);
  if (shape < 0 || static_cast<int>(description.parameters.size()) != shape + kTail)
  {
    return false;
  }
  const double* p = description.parameters.data();
  std::string error;
  if (!ShapeOmega(description.type, p, g.omega, error))
  {
    g.omega.setZero();
    if (shapeError)
    {
      *shapeError = error;
    }
  }
  g.mirrorToCamera = RowMajor4(p + shape);
  g.zmin = p[shape + 16];
  g.zmax = p[shape + 17];
  return true;
}

std::vector<MirrorType> QuadricMirrorTypes()
{
  std::vector<MirrorType> types;
  // The defaults: each a mirror 10 to 20 cm in front of the camera, axis along the camera's.
  {
    // A sphere of radius 5 cm given as a quadric: x^2 + y^2 + z^2 - r^2.
    Mat4 omega = Mat4::Identity();
    omega(3, 3) = -0.05 * 0.05;
    std::vector<double> shape;
    AppendRowMajor(omega, shape);
    MirrorType t = MakeType("quadric",
      "any quadric X^T Omega X = 0 (mirror frame, negative inside), placed by mirror_to_camera",
      { { "matrix", 16, "Omega, symmetric, row-major" } },
      WithTail(shape, Translation(0, 0, 0.2), -0.05, 0.05));
    types.push_back(t);
  }
  {
    // a = 2 cm, b = 3 cm; the camera at the outer focus (0, 0, -c): central.
    const double c = std::sqrt(0.02 * 0.02 + 0.03 * 0.03);
    MirrorType t = MakeType("hyperboloid",
      "a sheet of (x^2 + y^2) / b^2 - z^2 / a^2 + 1 = 0 (foci at z = +-sqrt(a^2 + b^2))",
      { { "a", 1, "semi-axis along z (vertices at z = +-a)" }, { "b", 1, "semi-axis across z" } },
      WithTail({ 0.02, 0.03 }, Translation(0, 0, c), 0.02, 0.05));
    types.push_back(t);
  }
  {
    MirrorType t = MakeType("paraboloid",
      "x^2 + y^2 = 4 focal (z + focal): focus at the origin, vertex at z = -focal",
      { { "focal", 1, "the focal distance" } },
      WithTail({ 0.01 }, Translation(0, 0, 0.1), -0.01, 0.02));
    types.push_back(t);
  }
  {
    MirrorType t = MakeType("ellipsoid", "x^2 / ax^2 + y^2 / ay^2 + z^2 / az^2 = 1",
      { { "semi_axes", 3, "ax, ay, az" } },
      WithTail({ 0.03, 0.03, 0.02 }, Translation(0, 0, 0.15), -0.02, 0.02));
    types.push_back(t);
  }
  {
    // The sphere cut by z_range (the closed-form type of the same name takes center and radius).
    MirrorType t = MakeType("sphere", "x^2 + y^2 + z^2 = radius^2, cut by z_range",
      { { "radius", 1, "the sphere's radius" } },
      WithTail({ 0.05 }, Translation(0, 0, 0.2), -0.05, 0.0));
    types.push_back(t);
  }
  {
    MirrorType t = MakeType("cone", "x^2 + y^2 = tan(half_angle)^2 z^2: apex at the origin",
      { { "half_angle", 1, "degrees, in (0, 90)" } },
      WithTail({ 30.0 }, Translation(0, 0, 0.1), 0.0, 0.04));
    types.push_back(t);
  }
  return types;
}

namespace detail
{
QuadricSurface::QuadricSurface(const MirrorDescription& description, const QuadricGeometry& g)
  : Description(description)
{
  this->EffectiveViewpoint = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  // The quadric in the camera frame: Q = H^-T Omega H^-1, scaled to |A| = 1.
  const Mat3 R = g.mirrorToCamera.topLeftCorner<3, 3>();
  const Vec3 t = g.mirrorToCamera.topRightCorner<3, 1>();
  Mat4 inverse = Mat4::Identity();
  inverse.topLeftCorner<3, 3>() = R.transpose();
  inverse.topRightCorner<3, 1>() = -(R.transpose() * t);
  Mat4 Q = inverse.transpose() * g.omega * inverse;
  Q = 0.5 * (Q + Q.transpose());
  const double norm = Q.topLeftCorner<3, 3>().cwiseAbs().maxCoeff();
  if (!(norm > 0.0) || !std::isfinite(norm))
  {
    return;
  }
  Q /= norm;
  this->A = Q.topLeftCorner<3, 3>();
  this->B = Q.topRightCorner<3, 1>();
  this->C = Q(3, 3);
  this->W = inverse.row(2).head<3>().transpose();
  this->W0 = inverse(2, 3);
  this->Zmin = g.zmin;
  this->Zmax = g.zmax;
  this->Length = std::max(t.norm(), 1e-300);
  this->CameraToMirror = inverse;
  this->MirrorToCameraFrame = g.mirrorToCamera;
  {
    // A surface of revolution about z (no cross terms with x or y, equal x and y terms) and the
    // camera on that axis.
    const Mat4& O = g.omega;
    const double scale = O.cwiseAbs().maxCoeff();
    const Vec3 camera = inverse.topRightCorner<3, 1>();
    const double tol = 1e-12 * scale;
    if (std::abs(O(0, 0) - O(1, 1)) <= tol && std::abs(O(0, 1)) <= tol &&
      std::abs(O(0, 2)) <= tol && std::abs(O(1, 2)) <= tol && std::abs(O(0, 3)) <= tol &&
      std::abs(O(1, 3)) <= tol && std::hypot(camera.x(), camera.y()) <= 1e-12 * this->Length &&
      O(0, 0) != 0.0)
    {
      this->Axial = true;
      this->Alpha = O(0, 0) / scale;
      this->Beta = O(2, 2) / scale;
      this->Gamma = O(2, 3) / scale;
      this->Delta = O(3, 3) / scale;
      this->AxialCamera = camera.z();
    }
  }

  // Which directions meet the mirror: a scan of the whole sphere of directions, then a finer grid
  // about the cone that holds the hits.
  std::vector<Vec3> hits;
  const int rows = 64, cols = 128;
  for (int i = 0; i < rows; ++i)
  {
    const double theta = kPi * (i + 0.5) / rows;
    for (int j = 0; j < cols; ++j)
    {
      const double phi = 2.0 * kPi * (j + 0.5) / cols;
      const Vec3 d(
        std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      if (this->FirstHit(Vec3::Zero(), d, 0.0) > 0.0)
      {
        hits.push_back(d);
      }
    }
  }
  // Also the directions to the points of the axis within z_range (a small mirror far away may
  // fall between the scan's rays).
  for (int k = 0; k <= 8; ++k)
  {
    const double z = g.zmin + (g.zmax - g.zmin) * k / 8.0;
    const Vec3 p = R * Vec3(0, 0, z) + t;
    if (p.norm() > 0.0 && this->FirstHit(Vec3::Zero(), p.normalized(), 0.0) > 0.0)
    {
      hits.push_back(p.normalized());
    }
  }
  if (hits.empty())
  {
    return;
  }
  Vec3 axis = Vec3::Zero();
  for (const Vec3& d : hits)
  {
    axis += d;
  }
  axis = axis.norm() > 0.0 ? Vec3(axis.normalized()) : hits.front();
  double cosMin = 1.0; // the cosine of the largest angle from the axis
  for (const Vec3& d : hits)
  {
    cosMin = std::min(cosMin, d.dot(axis));
  }
  // That angle and one scan step more, below a right angle (the grid is on a tangent plane).
  const double spread =
    std::min(std::acos(std::max(-1.0, std::min(1.0, cosMin))) + 2.0 * kPi / cols, 0.49 * kPi);
  const Vec3 e1 = axis.unitOrthogonal();
  const Vec3 e2 = axis.cross(e1);
  const int n = 64;
  const double extent = std::tan(spread);
  Vec3 sumPoint = Vec3::Zero();
  Mat3 normal = Mat3::Zero();
  Vec3 rhs = Vec3::Zero();
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      const double u = extent * (2.0 * (i + 0.5) / n - 1.0);
      const double v = extent * (2.0 * (j + 0.5) / n - 1.0);
      const Vec3 d = (axis + u * e1 + v * e2).normalized();
      Vec3 r, nn;
      if (!this->Intersect(d, r, nn))
      {
        continue;
      }
      Vec3 e = d - 2.0 * d.dot(nn) * nn;
      e.normalize();
      this->TablePoints.push_back(r);
      this->TableDirections.push_back(e);
      sumPoint += r;
      const Mat3 P = Mat3::Identity() - e * e.transpose();
      normal += P;
      rhs += P * r;
    }
  }
  if (this->TablePoints.empty())
  {
    return;
  }
  const Vec3 mean = sumPoint / static_cast<double>(this->TablePoints.size());
  // The point nearest all the reflected rays; the mean mirror point where that is ill-posed.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(normal);
  Vec3 viewpoint = mean;
  const Vec3& values = eig.eigenvalues(); // ascending
  if (eig.info() == Eigen::Success && values[0] > 1e-6 * values[2])
  {
    const Mat3& V = eig.eigenvectors();
    viewpoint = V * (V.transpose() * rhs).cwiseQuotient(values);
  }
  if (!viewpoint.allFinite() || (viewpoint - mean).norm() > 10.0 * this->Length)
  {
    viewpoint = mean;
  }
  this->EffectiveViewpoint = viewpoint;
  if (this->Axial)
  {
    // The widest elevation of a ray that meets the mirror, from the table, one scan step wider.
    double widest = 0.0;
    for (const Vec3& r : this->TablePoints)
    {
      const Vec3 m = (this->CameraToMirror * Eigen::Vector4d(r.x(), r.y(), r.z(), 1.0)).head<3>();
      widest = std::max(widest, std::atan2(std::hypot(m.x(), m.y()), m.z() - this->AxialCamera));
    }
    this->ThetaMax = std::min(kPi, widest + 2.0 * extent / n);
    // The intervals of elevations whose rays meet the mirror, in the plane of any point (the
    // residual's point does not matter for whether a ray hits): a scan, then each end refined
    // to the rim by bisection.
    auto hits = [&](double theta) {
      double residual = 0.0, rho = 0.0, z = 0.0;
      return this->AxialResidual(theta, 1.0, 0.0, residual, rho, z);
    };
    auto edge = [&](double inside, double outside) {
      for (int k = 0; k < 64; ++k)
      {
        const double mid = 0.5 * (inside + outside);
        (hits(mid) ? inside : outside) = mid;
      }
      return inside;
    };
    constexpr int kScan = 2000;
    double start = 0.0;
    bool inside = false;
    double previous = -this->ThetaMax;
    for (int i = 0; i <= kScan; ++i)
    {
      const double theta = this->ThetaMax * (2.0 * i / kScan - 1.0);
      const bool hit = hits(theta);
      if (hit && !inside)
      {
        start = i == 0 ? theta : edge(theta, previous);
        inside = true;
      }
      else if (!hit && inside)
      {
        this->AxialIntervals.emplace_back(start, edge(previous, theta));
        inside = false;
      }
      previous = theta;
    }
    if (inside)
    {
      this->AxialIntervals.emplace_back(start, this->ThetaMax);
    }
  }
  this->Length = std::max(mean.norm(), 1e-300);
  // The map: each cell keeps the first of the table's rays whose direction falls in it; empty
  // cells next to filled ones (on the same face) take a neighbour's, a few rings deep.
  this->Map.assign(6 * kMapSide * kMapSide, -1);
  for (std::size_t i = 0; i < this->TableDirections.size(); ++i)
  {
    int& cell = this->Map[this->MapCell(this->TableDirections[i])];
    if (cell < 0)
    {
      cell = static_cast<int>(i);
    }
  }
  for (int ring = 0; ring < 4; ++ring)
  {
    std::vector<int> next = this->Map;
    for (int face = 0; face < 6; ++face)
    {
      for (int j = 0; j < kMapSide; ++j)
      {
        for (int i = 0; i < kMapSide; ++i)
        {
          const int cell = (face * kMapSide + j) * kMapSide + i;
          if (this->Map[cell] >= 0)
          {
            continue;
          }
          const int di[4] = { -1, 1, 0, 0 }, dj[4] = { 0, 0, -1, 1 };
          for (int k = 0; k < 4 && next[cell] < 0; ++k)
          {
            const int ni = i + di[k], nj = j + dj[k];
            if (ni >= 0 && ni < kMapSide && nj >= 0 && nj < kMapSide)
            {
              next[cell] = this->Map[(face * kMapSide + nj) * kMapSide + ni];
            }
          }
        }
      }
    }
    this->Map.swap(next);
  }
}

int QuadricSurface::MapCell(const Vec3& d) const
{
  const Vec3 a = d.cwiseAbs();
  int face;
  double u, v, m;
  if (a.x() >= a.y() && a.x() >= a.z())
  {
    face = d.x() > 0 ? 0 : 1;
    m = a.x();
    u = d.y();
    v = d.z();
  }
  else if (a.y() >= a.z())
  {
    face = d.y() > 0 ? 2 : 3;
    m = a.y();
    u = d.x();
    v = d.z();
  }
  else
  {
    face = d.z() > 0 ? 4 : 5;
    m = a.z();
    u = d.x();
    v = d.y();
  }
  if (!(m > 0.0))
  {
    return 0;
  }
  const int i =
    std::min(kMapSide - 1, std::max(0, static_cast<int>((u / m + 1.0) * 0.5 * kMapSide)));
  const int j =
    std::min(kMapSide - 1, std::max(0, static_cast<int>((v / m + 1.0) * 0.5 * kMapSide)));
  return (face * kMapSide + j) * kMapSide + i;
}

bool QuadricSurface::InPart(const Vec3& r, double tolerance) const
{
  const double z = this->MirrorZ(r);
  return z >= this->Zmin - tolerance && z <= this->Zmax + tolerance;
}

double QuadricSurface::FirstHit(const Vec3& o, const Vec3& d, double tmin) const
{
  const double a = d.dot(this->A * d);
  const double b = d.dot(this->A * o + this->B);
  const double c = this->Value(o);
  double t[2];
  int count = 0;
  const double scaleA = d.squaredNorm();
  if (std::abs(a) <= 1e-14 * scaleA)
  {
    if (b != 0.0)
    {
      t[count++] = -c / (2.0 * b);
    }
  }
  else
  {
    const double disc = b * b - a * c;
    if (disc < 0.0)
    {
      return -1.0;
    }
    const double s = std::sqrt(disc);
    const double q = -(b + (b >= 0.0 ? s : -s));
    if (q != 0.0)
    {
      t[count++] = q / a;
      t[count++] = c / q;
    }
    else
    {
      t[count++] = 0.0;
    }
  }
  if (count == 2 && t[1] < t[0])
  {
    std::swap(t[0], t[1]);
  }
  const double tolerance = 1e-9 * this->Length;
  for (int k = 0; k < count; ++k)
  {
    if (t[k] > tmin && std::isfinite(t[k]) && this->InPart(o + t[k] * d, tolerance))
    {
      return t[k];
    }
  }
  return -1.0;
}

bool QuadricSurface::Intersect(const Vec3& d, Vec3& point, Vec3& normal) const
{
  const double t = this->FirstHit(Vec3::Zero(), d, 0.0);
  if (!(t > 0.0))
  {
    return false;
  }
  point = t * d;
  normal = this->Gradient(point);
  const double len = normal.norm();
  if (!(len > 0.0))
  {
    return false;
  }
  normal /= len;
  if (normal.dot(d) > 0.0)
  {
    normal = -normal; // the side facing the camera
  }
  return true;
}

bool QuadricSurface::Newton(const Vec3& P, Vec3& r) const
{
  const double L = this->Length;
  // The Lagrange system at a point: unit vectors to the camera and from the point, the
  // gradient, and the residual G (stationarity, dimensionless; the surface's equation divided by
  // L to weigh alike in the merit |G|^2).
  struct State
  {
    Vec3 x, ah, qh, g;
    double la = 0.0, lq = 0.0;
    Vec4 G;
  };
  auto evaluate = [&](const Vec3& x, double lambda, State& s) {
    s.x = x;
    s.la = x.norm();
    const Vec3 q = x - P;
    s.lq = q.norm();
    if (!(s.la > 1e-12 * L) || !(s.lq > 1e-12 * L) || !x.allFinite())
    {
      return false;
    }
    s.ah = x / s.la;
    s.qh = q / s.lq;
    const Vec3 Ax = this->A * x;
    s.g = 2.0 * (Ax + this->B);
    s.G.head<3>() = s.ah + s.qh - lambda * s.g;
    s.G[3] = (x.dot(Ax) + 2.0 * this->B.dot(x) + this->C) / L;
    return s.G.allFinite();
  };
  // lambda to start: the least-squares multiplier of the stationarity equation at r.
  State s, trial;
  if (!evaluate(r, 0.0, s))
  {
    return false;
  }
  const double gg = s.g.squaredNorm();
  double lambda = gg > 0.0 ? s.G.head<3>().dot(s.g) / gg : 0.0;
  s.G.head<3>() -= lambda * s.g;
  double merit = s.G.squaredNorm();
  for (int it = 0; it < kNewtonSteps && merit > 0.0; ++it)
  {
    // The Newton step of [M, -g; g^T / L, 0] (dr, dlambda) = -G, M symmetric, by its Schur
    // complement: dr = M^-1 (g dlambda - G1), g^T dr = -L G4.
    const Mat3 M = (Mat3::Identity() - s.ah * s.ah.transpose()) / s.la +
      (Mat3::Identity() - s.qh * s.qh.transpose()) / s.lq - 2.0 * lambda * this->A;
    bool invertible = false;
    Mat3 Minv;
    double det = 0.0;
    M.computeInverseAndDetWithCheck(Minv, det, invertible, 0.0);
    Vec4 step;
    const Vec3 Mg = invertible ? Vec3(Minv * s.g) : Vec3::Zero();
    const double gMg = s.g.dot(Mg);
    if (invertible && std::isfinite(det) && gMg != 0.0)
    {
      const Vec3 MG1 = Minv * s.G.head<3>();
      const double dlambda = (s.g.dot(MG1) - L * s.G[3]) / gMg;
      step.head<3>() = dlambda * Mg - MG1;
      step[3] = dlambda;
    }
    else
    {
      Mat4 J;
      J.topLeftCorner<3, 3>() = M;
      J.topRightCorner<3, 1>() = -s.g;
      J.bottomLeftCorner<1, 3>() = s.g.transpose() / L;
      J(3, 3) = 0.0;
      step = J.partialPivLu().solve(-s.G);
    }
    if (!step.allFinite())
    {
      return false;
    }
    if (step.head<3>().norm() <= 1e-8 * L && merit <= 1e-12)
    {
      // In Newton's quadratic regime (residual below 1e-6, a step below 1e-8 L) the point after
      // this step is within about 1e-14 L of the answer: taken without another residual
      // (the surface's equation confirms it).
      const Vec3 x = s.x + step.head<3>();
      const double F = this->Value(x);
      if (std::abs(F) <= 1e-13 * s.g.norm() * L)
      {
        r = x;
        return true;
      }
    }
    // Steps no longer than half the distance to the camera or the point, halved while they
    // do not lower the residual.
    const double limit = 0.5 * std::min(s.la, s.lq);
    const double length = step.head<3>().norm();
    if (length > limit)
    {
      step *= limit / length;
    }
    bool better = false;
    for (int half = 0; half < 12; ++half)
    {
      if (evaluate(s.x + step.head<3>(), lambda + step[3], trial) && trial.G.squaredNorm() < merit)
      {
        better = true;
        break;
      }
      step *= 0.5;
    }
    if (!better)
    {
      break; // at the rounding floor (or stuck): judged below
    }
    lambda += step[3];
    std::swap(s, trial);
    merit = s.G.squaredNorm();
    if (step.head<3>().norm() <= 1e-7 * L && s.G.head<3>().norm() <= 1e-12 &&
      std::abs(s.G[3]) <= 1e-15 * s.g.norm())
    {
      // Newton converges quadratically: after a step this short the point is at the rounding
      // floor, as the residual confirms.
      break;
    }
  }
  // Converged: the reflection law holds and the point is on the surface, to rounding.
  r = s.x;
  return s.G.head<3>().norm() <= 1e-11 && std::abs(s.G[3]) <= 1e-13 * s.g.norm();
}

ProjectionStatus QuadricSurface::Check(const Vec3& P, const Vec3& r) const
{
  if (!this->InPart(r, 1e-9 * this->Length) || !(r.z() > 0.0))
  {
    return ProjectionStatus::NoReflection;
  }
  Vec3 n = this->Gradient(r);
  n.normalize();
  const Vec3 u1 = -r.normalized();
  const Vec3 u2 = (P - r).normalized();
  const double c1 = n.dot(u1);
  const double c2 = n.dot(u2);
  if (!(c1 * c2 > 0.0) || std::abs(c1) < kGrazingCosine || std::abs(c2) < kGrazingCosine)
  {
    return ProjectionStatus::NoReflection;
  }
  // The camera ray must meet the mirror first at r: its line meets the quadric at |r| and at
  // the other root of the quadratic (their product is C / (d^T A d)), which must not be a point
  // of the mirror before r.
  const double lr = r.norm();
  const Vec3 d = -u1;
  const double a = d.dot(this->A * d);
  const double tolerance = 1e-9 * this->Length;
  if (a != 0.0)
  {
    const double other = this->C / (a * lr);
    if (other > tolerance && other < lr - tolerance && this->InPart(other * d, tolerance))
    {
      return ProjectionStatus::HiddenByMirror;
    }
  }
  // Nor may the reflected segment from r to P meet it: r + t u2 meets the quadric at t = 0 and
  // at t = -2 u2^T (A r + B) / (u2^T A u2).
  const double a2 = u2.dot(this->A * u2);
  if (a2 != 0.0)
  {
    const double other = -u2.dot(this->Gradient(r)) / a2;
    if (other > tolerance && other < (P - r).norm() - tolerance &&
      this->InPart(r + other * u2, tolerance))
    {
      return ProjectionStatus::HiddenByMirror;
    }
  }
  return ProjectionStatus::Valid;
}

bool QuadricSurface::AxialResidual(
  double theta, double rhoP, double zP, double& residual, double& rho, double& z) const
{
  // The ray (rho, z) = (sin theta, cos theta) t from the camera (0, zc) meets
  // alpha rho^2 + beta z^2 + 2 gamma z + delta = 0 where a t^2 + 2 b t + c = 0.
  const double s = std::sin(theta), c = std::cos(theta), zc = this->AxialCamera;
  const double a = this->Alpha * s * s + this->Beta * c * c;
  const double b = this->Beta * zc * c + this->Gamma * c;
  const double cc = this->Beta * zc * zc + 2.0 * this->Gamma * zc + this->Delta;
  double t[2];
  const int count = detail::SolveQuadratic(a, 2.0 * b, cc, t);
  if (count == 2 && t[1] < t[0])
  {
    std::swap(t[0], t[1]);
  }
  const double tolerance = 1e-9 * this->Length;
  for (int k = 0; k < count; ++k)
  {
    const double zk = zc + c * t[k];
    if (!(t[k] > 0.0) || zk < this->Zmin - tolerance || zk > this->Zmax + tolerance)
    {
      continue;
    }
    rho = s * t[k];
    z = zk;
    // The normal (alpha rho, beta z + gamma), the camera ray d = (s, c), its reflection
    // d - 2 (d.n) n / |n|^2, and the residual: the sine of the angle between the reflection and
    // the direction to the point.
    const double nr = this->Alpha * rho, nz = this->Beta * z + this->Gamma;
    const double nn = nr * nr + nz * nz;
    if (!(nn > 0.0))
    {
      return false;
    }
    const double dn = s * nr + c * nz;
    const double er = s - 2.0 * dn * nr / nn, ez = c - 2.0 * dn * nz / nn;
    const double wr = rhoP - rho, wz = zP - z;
    const double w = std::hypot(wr, wz);
    if (!(w > 0.0))
    {
      return false;
    }
    // Continuous through the root; it also vanishes where the reflection points straight away
    // from the point, which Check tells apart.
    residual = (er * wz - ez * wr) / w;
    return true;
  }
  return false;
}

bool QuadricSurface::AxialReflect(const Vec3& P, Vec3& mirrorPoint, ProjectionStatus& status) const
{
  const Vec3 m = (this->CameraToMirror * Eigen::Vector4d(P.x(), P.y(), P.z(), 1.0)).head<3>();
  const double rhoP = std::hypot(m.x(), m.y());
  if (!(rhoP > 1e-9 * this->Length))
  {
    return false; // on the axis: a circle of solutions or the vertex; the general solver decides
  }
  const Vec3 er(m.x() / rhoP, m.y() / rhoP, 0.0); // the plane's radial direction
  const double zP = m.z();
  // The elevations whose rays meet the mirror, sampled interval by interval (their ends are on
  // the rim, so a reflection next to the rim is bracketed too); sign changes of the residual
  // between neighbouring samples bracket the reflections.
  constexpr int kSamples = 24; // a sample interval
  double best = std::numeric_limits<double>::infinity();
  bool any = false;
  // A root bracketed by [t0, t1] (residuals f0, f1 of opposite signs): regula falsi with the
  // Illinois rule down to the rounding floor, then the checks of any reflection.
  auto consider = [&](double lo, double flo, double hi, double fhi) {
    if (!std::isfinite(flo) || !std::isfinite(fhi) || (flo < 0.0) == (fhi < 0.0))
    {
      return;
    }
    double rhoR = 0.0, zR = 0.0;
    int side = 0;
    for (int k = 0; k < 100 && hi - lo > 1e-15 * std::max(1.0, std::abs(lo)); ++k)
    {
      double mid = (lo * fhi - hi * flo) / (fhi - flo);
      if (!(mid > lo && mid < hi))
      {
        mid = 0.5 * (lo + hi);
      }
      double fm = 0.0;
      if (!this->AxialResidual(mid, rhoP, zP, fm, rhoR, zR) || !std::isfinite(fm))
      {
        return;
      }
      if (fm == 0.0)
      {
        lo = hi = mid;
        break;
      }
      if ((fm < 0.0) == (flo < 0.0))
      {
        lo = mid;
        flo = fm;
        fhi *= side == -1 ? 0.5 : 1.0;
        side = -1;
      }
      else
      {
        hi = mid;
        fhi = fm;
        flo *= side == 1 ? 0.5 : 1.0;
        side = 1;
      }
    }
    // A sign change across a jump of the residual (the ray passing from one part of the mirror
    // to another) is no root: the residual must vanish there.
    double froot = 0.0;
    if (!this->AxialResidual(0.5 * (lo + hi), rhoP, zP, froot, rhoR, zR) ||
      !(std::abs(froot) <= 1e-9))
    {
      return;
    }
    const Vec3 rm = rhoR * er + Vec3(0.0, 0.0, zR);
    const Vec3 r =
      (this->MirrorToCameraFrame * Eigen::Vector4d(rm.x(), rm.y(), rm.z(), 1.0)).head<3>();
    // Check tells a reflection that points away from the point (the residual's other zero):
    // both rays must leave on the side of the normal they meet.
    const ProjectionStatus s = this->Check(P, r);
    if (s == ProjectionStatus::Valid)
    {
      const double path = r.norm() + (P - r).norm();
      if (path < best)
      {
        best = path;
        mirrorPoint = r;
        any = true;
      }
    }
    else if (s == ProjectionStatus::HiddenByMirror && !any)
    {
      status = s;
    }
  };
  auto residualAt = [&](double theta) {
    double residual = 0.0, rho = 0.0, z = 0.0;
    return this->AxialResidual(theta, rhoP, zP, residual, rho, z)
      ? residual
      : std::numeric_limits<double>::quiet_NaN();
  };
  constexpr int kCloser = 14; // down to 1e-14 of a sample step from an end on the axis
  std::array<double, kSamples + 1 + 2 * kCloser> thetas{};
  for (const std::pair<double, double>& interval : this->AxialIntervals)
  {
    // Uniform samples; where an interval ends on the axis (a ray along the axis meets the vertex,
    // which for a cone is the apex, where the normal and so the residual jump), samples closing
    // in on that end geometrically, so that a reflection next to it (1e-4 of the interval away
    // and closer) is bracketed by samples off the apex. In increasing order.
    const double width = interval.second - interval.first;
    const double step = width / kSamples;
    const double onAxis = 1e-9 * this->ThetaMax;
    std::size_t count = 0;
    thetas[count++] = interval.first;
    if (std::abs(interval.first) <= onAxis)
    {
      for (int k = kCloser; k >= 1; --k)
      {
        thetas[count++] = interval.first + step * std::pow(10.0, -k);
      }
    }
    for (int i = 1; i < kSamples; ++i)
    {
      thetas[count++] = interval.first + width * i / static_cast<double>(kSamples);
    }
    if (std::abs(interval.second) <= onAxis)
    {
      for (int k = 1; k <= kCloser; ++k)
      {
        thetas[count++] = interval.second - step * std::pow(10.0, -k);
      }
    }
    thetas[count++] = interval.second;
    double previousTheta = 0.0, previousResidual = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 0; i < count; ++i)
    {
      const double residual = residualAt(thetas[i]);
      if (i > 0)
      {
        consider(previousTheta, previousResidual, thetas[i], residual);
      }
      previousTheta = thetas[i];
      previousResidual = residual;
    }
  }
  if (any)
  {
    status = ProjectionStatus::Valid;
    return true;
  }
  mirrorPoint.setZero();
  return status == ProjectionStatus::HiddenByMirror;
}

ProjectionStatus QuadricSurface::Reflect(
  const Vec3& P, SolverType solver, Vec3& mirrorPoint, const Vec3* guess) const
{
  mirrorPoint.setZero();
  if (!P.allFinite() || !this->EffectiveViewpoint.allFinite() || this->TablePoints.empty())
  {
    return ProjectionStatus::InvalidInput;
  }
  const double L = this->Length;
  const Vec3 grad = this->Gradient(P);
  const double F = this->Value(P);
  if (std::abs(F) <= 1e-12 * grad.norm() * L && this->InPart(P, 1e-12 * L))
  {
    // On the mirror: its own reflection when the camera sees it.
    const double t = P.norm() > 0.0 ? this->FirstHit(Vec3::Zero(), P.normalized(), 0.0) : -1.0;
    if (t > 0.0 && std::abs(t - P.norm()) <= 1e-8 * L)
    {
      mirrorPoint = P;
      return ProjectionStatus::Valid;
    }
    return ProjectionStatus::HiddenByMirror;
  }
  if (F < 0.0 && this->InPart(P, 0.0))
  {
    return ProjectionStatus::InsideMirror;
  }
  ProjectionStatus found = ProjectionStatus::NoReflection;
  auto attempt = [&](Vec3 r) {
    if (!this->Newton(P, r))
    {
      return false;
    }
    const ProjectionStatus s = this->Check(P, r);
    if (s == ProjectionStatus::Valid)
    {
      mirrorPoint = r;
      return true;
    }
    if (s == ProjectionStatus::HiddenByMirror)
    {
      found = s;
    }
    return false;
  };
  if (guess && guess->allFinite())
  {
    // Started next to the answer: the plain Newton of ReflectNear first (so that a point gets the
    // same answer alone as in a batch), then the safeguarded one.
    unsigned char settled = 0;
    this->ReflectNear(1, &P, guess, &mirrorPoint, &settled);
    if (settled || attempt(*guess))
    {
      return ProjectionStatus::Valid;
    }
  }
  if (this->Axial && this->Resolve(solver) == SolverType::Quartic && !guess)
  {
    ProjectionStatus status = ProjectionStatus::NoReflection;
    if (this->AxialReflect(P, mirrorPoint, status))
    {
      return status;
    }
  }
  const Vec3 toPoint = P - this->EffectiveViewpoint;
  if (toPoint.norm() > 0.0)
  {
    const int start = this->Map[this->MapCell(toPoint.normalized())];
    if (start >= 0 && attempt(this->TablePoints[start]))
    {
      return ProjectionStatus::Valid;
    }
  }
  // The table's rays that pass nearest the point, best first.
  std::vector<std::pair<double, int>> order;
  order.reserve(this->TablePoints.size());
  for (std::size_t i = 0; i < this->TablePoints.size(); ++i)
  {
    const Vec3 q = P - this->TablePoints[i];
    const double lq = q.norm();
    order.emplace_back(
      lq > 0.0 ? (q / lq - this->TableDirections[i]).squaredNorm() : 4.0, static_cast<int>(i));
  }
  const std::size_t tries = std::min<std::size_t>(6, order.size());
  std::partial_sort(order.begin(), order.begin() + tries, order.end());
  for (std::size_t k = 0; k < tries; ++k)
  {
    if (attempt(this->TablePoints[order[k].second]))
    {
      return ProjectionStatus::Valid;
    }
  }
  // Newton found nothing from any start; an axial placement has the exhaustive search left (a
  // reflection next to a cone's apex, where the normal turns too fast for Newton's steps).
  if (this->Axial && found == ProjectionStatus::NoReflection &&
    !(this->Resolve(solver) == SolverType::Quartic && !guess))
  {
    ProjectionStatus status = ProjectionStatus::NoReflection;
    if (this->AxialReflect(P, mirrorPoint, status))
    {
      return status;
    }
  }
  mirrorPoint.setZero();
  return found;
}
} // namespace detail
} // namespace catar
