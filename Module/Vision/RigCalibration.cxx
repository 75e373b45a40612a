#include "RigCalibration.h"

#include "LensModels.h"
#include "Mirror.h"
#include "Projector.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

namespace catar
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = 180.0 / kPi;

// The mirror as a quadric of the camera frame: F(r) = r^T A r + 2 B^T r + C.
struct CameraQuadric
{
  Mat3 A = Mat3::Zero();
  Vec3 B = Vec3::Zero();
  double C = 0.0;
};

bool QuadricOf(const MirrorDescription& d, CameraQuadric& q)
{
  return MirrorQuadric(d, q.A, q.B, q.C);
}

// What is estimated of the mirror, as a vector theta (see the header).
class MirrorUnknowns
{
public:
  // Empty when the type can be calibrated; else a sentence.
  std::string Init(const MirrorDescription& start)
  {
    this->Start = start;
    const MirrorType* type = FindMirrorType(start.type, start.parameters.size());
    if (!type || !type->quadric || start.type == "quadric")
    {
      return "a mirror of type '" + start.type +
        "' cannot be calibrated (sphere, hyperboloid, paraboloid, ellipsoid, cone)";
    }
    if (type->ParameterOffset("mirror_to_camera") < 0)
    {
      // A type placed by its own numbers (the sphere's center and radius): they are estimated
      // as they are; every one but a centre is a size.
      this->Direct = true;
      this->Theta = start.parameters;
      const char* axes[3] = { "_x", "_y", "_z" };
      for (const MirrorParameter& p : type->parameters)
      {
        for (int k = 0; k < p.count; ++k)
        {
          this->Names.push_back(p.count == 1 ? p.key : p.key + axes[k % 3]);
          this->Units.push_back("m");
          this->Size.push_back(p.key != "center");
        }
      }
      return "";
    }
    this->PoseOffset = type->ParameterOffset("mirror_to_camera");
    const Mat4 H = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(
      start.parameters.data() + this->PoseOffset);
    this->R0 = H.topLeftCorner<3, 3>();
    const Vec3 t0 = H.topRightCorner<3, 1>();
    // The shape's numbers: every parameter before mirror_to_camera.
    std::vector<double> shape(
      start.parameters.begin(), start.parameters.begin() + this->PoseOffset);
    const bool ellipsoid = start.type == "ellipsoid";
    this->Tied = ellipsoid && shape.size() == 3 && shape[0] == shape[1];
    this->Rotations = ellipsoid && !this->Tied ? 3 : 2;
    const char* axes[3] = { "x", "y", "z" };
    for (int i = 0; i < this->Rotations; ++i)
    {
      this->Theta.push_back(0.0);
      this->Names.push_back(std::string("tilt_") + axes[i]);
      this->Units.push_back("deg");
      this->Size.push_back(false);
    }
    for (int i = 0; i < 3; ++i)
    {
      this->Theta.push_back(t0[i]);
      this->Names.push_back(std::string("translation_") + axes[i]);
      this->Units.push_back("m");
      this->Size.push_back(false);
    }
    const std::string key = type->parameters.front().key;
    if (this->Tied)
    {
      shape.erase(shape.begin() + 1);
      this->Names.insert(this->Names.end(), { "semi_axes_xy", "semi_axes_z" });
    }
    else if (shape.size() == 3)
    {
      this->Names.insert(this->Names.end(), { key + "_x", key + "_y", key + "_z" });
    }
    else
    {
      for (const MirrorParameter& p : type->parameters)
      {
        if (p.key == "mirror_to_camera")
        {
          break;
        }
        this->Names.push_back(p.key);
      }
    }
    for (const double v : shape)
    {
      this->Theta.push_back(v);
      const bool angle = start.type == "cone";
      this->Units.push_back(angle ? "deg" : "m");
      this->Size.push_back(!angle);
    }
    return "";
  }

  int Count() const { return static_cast<int>(this->Theta.size()); }

  // The mirror the solver projects through: the described one, but a quadric's part widened by
  // half its z_range either way (not across z = 0 where the surface meets itself: the
  // hyperboloid's other sheet, the cone's apex). A corner seen near the rim may fall just past it
  // while the mirror is still off; through the surface's continuation its residual stays smooth,
  // where a lost image would stop the solver.
  MirrorDescription Widened(const MirrorDescription& d) const
  {
    const MirrorType* type = FindMirrorType(d.type, d.parameters.size());
    const int offset = type ? type->ParameterOffset("z_range") : -1;
    if (this->Direct || offset < 0)
    {
      return d;
    }
    MirrorDescription w = d;
    const std::size_t z = static_cast<std::size_t>(offset);
    const double zmin = w.parameters[z];
    const double zmax = w.parameters[z + 1];
    const double margin = 0.5 * (zmax - zmin);
    const bool meets = w.type == "hyperboloid" || w.type == "cone";
    w.parameters[z] = meets && zmin >= 0.0 ? std::max(0.0, zmin - margin) : zmin - margin;
    w.parameters[z + 1] = meets && zmax <= 0.0 ? std::min(0.0, zmax + margin) : zmax + margin;
    return w;
  }

  MirrorDescription Describe(const double* theta) const
  {
    MirrorDescription d = this->Start;
    if (this->Direct)
    {
      d.parameters.assign(theta, theta + this->Theta.size());
      return d;
    }
    const Vec3 delta(theta[0], theta[1], this->Rotations == 3 ? theta[2] : 0.0);
    const double* t = theta + this->Rotations;
    Mat4 H = Mat4::Identity();
    H.topLeftCorner<3, 3>() = this->R0 * RotationFromAngleAxis(delta);
    H.topRightCorner<3, 1>() = Vec3(t[0], t[1], t[2]);
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(
      d.parameters.data() + this->PoseOffset) = H;
    const double* shape = t + 3;
    if (this->Tied)
    {
      d.parameters[0] = d.parameters[1] = shape[0];
      d.parameters[2] = shape[1];
    }
    else
    {
      std::copy(shape, shape + this->PoseOffset, d.parameters.begin());
    }
    return d;
  }

  // A step for central differences of the quadric's coefficients along theta[i]: 1e-7 m for
  // lengths, 1e-6 rad for the tilts, 1e-5 degrees for the cone's angle.
  double Step(int i) const
  {
    const std::size_t k = static_cast<std::size_t>(i);
    return !this->Direct && i < this->Rotations ? 1e-6 : this->Units[k] == "deg" ? 1e-5 : 1e-7;
  }

  // Theta's value as reported (rotations in degrees).
  double Reported(int i, double value) const
  {
    return !this->Direct && i < this->Rotations ? value * kDegrees : value;
  }

  std::vector<double> Theta;
  std::vector<std::string> Names;
  std::vector<std::string> Units;
  std::vector<bool> Size; // a size of the mirror: scales with the board

private:
  MirrorDescription Start;
  bool Direct = false; // the type's numbers are theta (no mirror_to_camera)
  bool Tied = false;
  int Rotations = 0;
  int PoseOffset = 0;
  Mat3 R0 = Mat3::Identity();
};

// The lens's free numbers: fx, fy, cx, cy and the distortion coefficients the lens uses
// (pinhole: at least k1 k2 p1 p2 k3), each with its index among the 22 of the pixel's formula's
// automatic derivatives (3 of the ray, fx fy cx cy skew, the 14 coefficients).
class LensUnknowns
{
public:
  void Init(const CameraModel& m)
  {
    const Intrinsics& in = m.intrinsics;
    this->Values = { in.fx, in.fy, in.cx, in.cy };
    this->Names = { "fx", "fy", "cx", "cy" };
    this->JetIndex = { 3, 4, 5, 6 };
    const std::vector<double> c = m.distortion.Coefficients(m.lens);
    static const char* names[14] = { "k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1", "s2",
      "s3", "s4", "tauX", "tauY" };
    static const int fisheyeField[4] = { 0, 1, 4, 5 };
    static const char* fisheyeNames[4] = { "k1", "k2", "k3", "k4" };
    for (std::size_t j = 0; j < c.size(); ++j)
    {
      const bool fisheye = m.lens == LensType::Fisheye;
      this->Values.push_back(c[j]);
      this->Names.emplace_back(fisheye ? fisheyeNames[j] : names[j]);
      this->JetIndex.push_back(8 + (fisheye ? fisheyeField[j] : static_cast<int>(j)));
    }
  }
  int Count() const { return static_cast<int>(this->Values.size()); }
  void Apply(const double* v, CameraModel& m) const
  {
    m.intrinsics.fx = v[0];
    m.intrinsics.fy = v[1];
    m.intrinsics.cx = v[2];
    m.intrinsics.cy = v[3];
    m.distortion.SetCoefficients(m.lens, std::vector<double>(v + 4, v + this->Count()));
  }
  std::string Unit(int i) const { return i < 4 ? "px" : ""; }

  std::vector<double> Values;
  std::vector<std::string> Names;
  std::vector<int> JetIndex;
};

// The pixel of the camera-frame mirror point r through the lens (LensModels.h), over a number
// type with derivatives: intr = fx fy cx cy skew, k = the 14 coefficients (fisheye: k1 k2 in 0 1,
// k3 k4 in 4 5).
template<class T>
void LensPixel(LensType lens, bool tilted, const T* intr, const T* k, const T* r, T* px)
{
  T xd, yd;
  if (lens == LensType::Fisheye)
  {
    const T kk[4] = { k[0], k[1], k[4], k[5] };
    lens::FisheyeDistort(kk, r[0], r[1], r[2], xd, yd);
  }
  else
  {
    lens::PinholeDistort(k, tilted, r[0] / r[2], r[1] / r[2], xd, yd);
  }
  px[0] = intr[0] * xd + intr[4] * yd + intr[2];
  px[1] = intr[1] * yd + intr[3];
}

using LensJet = ceres::Jet<double, 22>;

// What every corner's cost reads at the solver's current point: the rig's model, its projector,
// the mirror as a quadric and the quadric's derivatives along theta. Prepared by Ceres before
// each evaluation (the parameter blocks then hold the point).
class RigState : public ceres::EvaluationCallback
{
public:
  RigState(const CameraModel& base, const MirrorUnknowns& mirror, const LensUnknowns* lens,
    double* theta, double* lensValues)
    : Base(base)
    , Mirror(mirror)
    , Lens(lens)
    , Theta(theta)
    , LensValues(lensValues)
  {
  }

  void PrepareForEvaluation(bool evaluateJacobians, bool newPoint) override
  {
    if (newPoint || !this->Current)
    {
      CameraModel m = this->Base;
      m.mirror = this->Mirror.Describe(this->Theta);
      if (this->Lens)
      {
        this->Lens->Apply(this->LensValues, m);
      }
      this->Model = m;
      m.mirror = this->Mirror.Widened(m.mirror);
      this->Current = std::make_unique<Projector>(m);
      this->Valid = this->Current->IsValid() && QuadricOf(m.mirror, this->Quadric);
      this->HaveDerivatives = false;
    }
    if (evaluateJacobians && this->Valid && !this->HaveDerivatives)
    {
      const int k = this->Mirror.Count();
      this->dQuadric.assign(static_cast<std::size_t>(k), CameraQuadric());
      std::vector<double> th(this->Theta, this->Theta + k);
      for (int i = 0; i < k; ++i)
      {
        const double h = this->Mirror.Step(i);
        CameraQuadric plus, minus;
        th[i] = this->Theta[i] + h;
        const bool a = QuadricOf(this->Mirror.Describe(th.data()), plus);
        th[i] = this->Theta[i] - h;
        const bool b = QuadricOf(this->Mirror.Describe(th.data()), minus);
        th[i] = this->Theta[i];
        CameraQuadric& d = this->dQuadric[static_cast<std::size_t>(i)];
        if (a && b)
        {
          d.A = (plus.A - minus.A) / (2.0 * h);
          d.B = (plus.B - minus.B) / (2.0 * h);
          d.C = (plus.C - minus.C) / (2.0 * h);
        }
      }
      this->HaveDerivatives = true;
    }
  }

  const CameraModel Base;
  const MirrorUnknowns& Mirror;
  const LensUnknowns* Lens;
  const double* Theta;
  const double* LensValues;
  CameraModel Model;
  std::unique_ptr<Projector> Current;
  bool Valid = false;
  CameraQuadric Quadric;
  std::vector<CameraQuadric> dQuadric;
  bool HaveDerivatives = false;
};

// One corner's pixel residual: its board point X posed by (exp(w) R0, t) into the camera frame,
// reflected by the mirror theta, imaged by the lens. Blocks: w (3), t (3), theta, [lens].
class CornerCost : public ceres::CostFunction
{
public:
  CornerCost(const RigState& state, const Mat3& R0, const PoseObservation& o)
    : State(state)
    , R0X(R0 * o.world)
    , Pixel(o.pixel)
  {
    this->set_num_residuals(2);
    this->mutable_parameter_block_sizes()->push_back(3);
    this->mutable_parameter_block_sizes()->push_back(3);
    this->mutable_parameter_block_sizes()->push_back(state.Mirror.Count());
    if (state.Lens)
    {
      this->mutable_parameter_block_sizes()->push_back(state.Lens->Count());
    }
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override
  {
    if (!this->State.Valid)
    {
      return false;
    }
    const Vec3 w(p[0][0], p[0][1], p[0][2]);
    const Vec3 t(p[1][0], p[1][1], p[1][2]);
    const Mat3 R = RotationFromAngleAxis(w);
    const Vec3 P = R * this->R0X + t;
    const ProjectedPoint q = this->State.Current->ProjectCamera(P);
    if (!HasProjection(q.status))
    {
      return false; // Ceres rejects the step
    }
    residuals[0] = q.pixel.x() - this->Pixel.x();
    residuals[1] = q.pixel.y() - this->Pixel.y();
    if (!jacobians)
    {
      return true;
    }
    // The lens: the pixel's derivatives with respect to r and the lens's numbers.
    const CameraModel& m = this->State.Model;
    LensJet rj[3], intr[5], k[14], px[2];
    for (int i = 0; i < 3; ++i)
    {
      rj[i] = LensJet(q.mirrorPoint[i], i);
    }
    const double in[5] = { m.intrinsics.fx, m.intrinsics.fy, m.intrinsics.cx, m.intrinsics.cy,
      m.intrinsics.skew };
    for (int i = 0; i < 5; ++i)
    {
      intr[i] = LensJet(in[i], 3 + i);
    }
    for (int i = 0; i < 14; ++i)
    {
      k[i] = LensJet(m.distortion.Data()[i], 8 + i);
    }
    LensPixel(m.lens, m.distortion.Tilted(), intr, k, rj, px);
    Eigen::Matrix<double, 2, 3> dPixelDr;
    for (int row = 0; row < 2; ++row)
    {
      for (int c = 0; c < 3; ++c)
      {
        dPixelDr(row, c) = px[row].v[c];
      }
    }
    // The reflection point: the implicit function theorem on the Lagrange system
    // G(r, lambda) = [r/|r| + (r - P)/|r - P| - lambda grad F(r); F(r)] = 0.
    const CameraQuadric& Q = this->State.Quadric;
    const Vec3 r = q.mirrorPoint;
    const Vec3 s = r - P;
    const double rn = r.norm();
    const double sn = s.norm();
    const Vec3 rh = r / rn;
    const Vec3 sh = s / sn;
    const Vec3 g = 2.0 * (Q.A * r + Q.B);
    const double lambda = (rh + sh).dot(g) / g.squaredNorm();
    Eigen::Matrix4d Ju = Eigen::Matrix4d::Zero();
    Ju.topLeftCorner<3, 3>() = (Mat3::Identity() - rh * rh.transpose()) / rn +
      (Mat3::Identity() - sh * sh.transpose()) / sn - 2.0 * lambda * Q.A;
    Ju.topRightCorner<3, 1>() = -g;
    Ju.bottomLeftCorner<1, 3>() = g.transpose();
    const Eigen::PartialPivLU<Eigen::Matrix4d> lu(Ju);
    Eigen::Matrix<double, 4, 3> GP = Eigen::Matrix<double, 4, 3>::Zero();
    GP.topRows<3>() = -(Mat3::Identity() - sh * sh.transpose()) / sn;
    const Mat3 drdP = (-lu.solve(GP)).topRows<3>();
    const Eigen::Matrix<double, 2, 3> dPixelDP = dPixelDr * drdP;
    if (jacobians[0]) // d P / d w = -[R R0 X]x J_l(w)
    {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> dw(jacobians[0]);
      dw = dPixelDP * (-Skew(R * this->R0X) * RotationLeftJacobian(w));
    }
    if (jacobians[1])
    {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> dt(jacobians[1]);
      dt = dPixelDP;
    }
    if (jacobians[2])
    {
      const int n = this->State.Mirror.Count();
      Eigen::MatrixXd Gt(4, n);
      for (int i = 0; i < n; ++i)
      {
        const CameraQuadric& d = this->State.dQuadric[static_cast<std::size_t>(i)];
        Gt.block<3, 1>(0, i) = -lambda * 2.0 * (d.A * r + d.B);
        Gt(3, i) = r.dot(d.A * r) + 2.0 * d.B.dot(r) + d.C;
      }
      const Eigen::MatrixXd drdTheta = (-lu.solve(Gt)).topRows(3);
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> dm(
        jacobians[2], 2, n);
      dm = dPixelDr * drdTheta;
    }
    if (this->State.Lens && jacobians[3])
    {
      const LensUnknowns& L = *this->State.Lens;
      for (int row = 0; row < 2; ++row)
      {
        for (int i = 0; i < L.Count(); ++i)
        {
          jacobians[3][row * L.Count() + i] = px[row].v[L.JetIndex[static_cast<std::size_t>(i)]];
        }
      }
    }
    return true;
  }

private:
  const RigState& State;
  const Vec3 R0X;
  const Vec2 Pixel;
};

class Progress : public ceres::IterationCallback
{
public:
  Progress(const std::function<void(int, double)>& report, int residuals)
    : Report(report)
    , Residuals(residuals)
  {
  }
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override
  {
    if (this->Report)
    {
      this->Report(s.iteration, std::sqrt(2.0 * s.cost / std::max(1, this->Residuals)));
    }
    return ceres::SOLVER_CONTINUE;
  }

private:
  std::function<void(int, double)> Report;
  int Residuals;
};

std::string Percent(double fraction)
{
  std::ostringstream s;
  s.precision(3);
  s << 100.0 * fraction << " %";
  return s.str();
}
} // namespace

CalibrationResult CalibrateRig(const CameraModel& initial,
  const std::vector<CalibrationView>& views, const CalibrationOptions& options)
{
  CalibrationResult out;
  CameraModel base = initial;
  base.worldToCamera = Mat4::Identity();
  if (const std::string why = base.Validate(); !why.empty())
  {
    out.error = "the starting calibration is not usable: " + why;
    return out;
  }
  MirrorUnknowns mirror;
  if (const std::string why = mirror.Init(base.mirror); !why.empty())
  {
    out.error = why;
    return out;
  }
  LensUnknowns lens;
  lens.Init(base);

  // Each view's board pose from the starting rig (loose inliers: the start is off).
  struct Posed
  {
    int view = 0;
    Mat3 R0;
    double w[3] = { 0.0, 0.0, 0.0 };
    double t[3] = { 0.0, 0.0, 0.0 };
    std::vector<PoseObservation> used;
  };
  std::vector<Posed> posed;
  const Projector start(base);
  for (std::size_t v = 0; v < views.size(); ++v)
  {
    const CalibrationView& view = views[v];
    const std::string name = view.name.empty() ? "view " + std::to_string(v + 1) : view.name;
    if (view.observations.size() < 4)
    {
      out.skipped.push_back(name + ": " +
        (view.observations.empty() ? std::string("no marker of the board found")
                                   : "fewer than 4 corners of the board found"));
      continue;
    }
    PoseOptions po;
    po.inlierThreshold = 10.0;
    const PoseResult pose = EstimatePose(base, view.observations, po);
    if (!pose.ok)
    {
      out.skipped.push_back(name + ": no board pose (" + pose.error + ")");
      continue;
    }
    Posed p;
    p.view = static_cast<int>(v);
    p.R0 = pose.worldToCamera.topLeftCorner<3, 3>();
    for (int i = 0; i < 3; ++i)
    {
      p.t[i] = pose.worldToCamera(i, 3);
    }
    for (std::size_t i = 0; i < view.observations.size(); ++i)
    {
      const PoseObservation& o = view.observations[i];
      const ProjectedPoint q = start.ProjectCamera(p.R0 * o.world + Vec3(p.t[0], p.t[1], p.t[2]));
      if (pose.inliers[i] && HasProjection(q.status))
      {
        p.used.push_back(o);
      }
    }
    if (p.used.size() < 4)
    {
      out.skipped.push_back(name + ": fewer than 4 corners fit the board's pose");
      continue;
    }
    posed.push_back(std::move(p));
  }
  if (static_cast<int>(posed.size()) < options.minViews)
  {
    std::ostringstream s;
    s << "too few views: " << posed.size() << " of " << views.size()
      << " have a board pose, at least " << options.minViews << " are needed";
    if (!out.skipped.empty())
    {
      s << " (" << out.skipped.front() << (out.skipped.size() > 1 ? "; ..." : "") << ")";
    }
    out.error = s.str();
    return out;
  }

  std::vector<double> theta = mirror.Theta;
  std::vector<double> lensValues = lens.Values;
  RigState state(base, mirror, options.freeLens ? &lens : nullptr, theta.data(), lensValues.data());
  ceres::Problem::Options problemOptions;
  problemOptions.evaluation_callback = &state;
  ceres::Problem problem(problemOptions);
  int corners = 0;
  std::vector<std::vector<ceres::ResidualBlockId>> ids(posed.size());
  for (std::size_t v = 0; v < posed.size(); ++v)
  {
    Posed& p = posed[v];
    for (const PoseObservation& o : p.used)
    {
      std::vector<double*> blocks = { p.w, p.t, theta.data() };
      if (options.freeLens)
      {
        blocks.push_back(lensValues.data());
      }
      ids[v].push_back(problem.AddResidualBlock(
        new CornerCost(state, p.R0, o), new ceres::HuberLoss(options.robustScale), blocks));
      ++corners;
    }
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.max_num_iterations = options.maxIterations;
  solver.function_tolerance = 1e-12;
  solver.gradient_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  solver.logging_type = ceres::SILENT;
  Progress progress(options.progress, 2 * corners);
  solver.callbacks.push_back(&progress);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out.iterations = static_cast<int>(summary.iterations.size());
  if (!summary.IsSolutionUsable())
  {
    out.error = "the calibration did not converge: " + summary.message;
    return out;
  }
  // Corners that do not fit (a marker misread, a corner OpenCV put off a bent side): those whose
  // residual exceeds four times the median's (and options.outlierPixels) are left out, and the
  // rest solved again.
  {
    std::vector<double> norms;
    std::vector<std::vector<double>> byView(posed.size());
    for (std::size_t v = 0; v < posed.size(); ++v)
    {
      for (const ceres::ResidualBlockId id : ids[v])
      {
        double r[2] = { 0.0, 0.0 };
        double cost = 0.0;
        const bool ok = problem.EvaluateResidualBlock(id, false, &cost, r, nullptr);
        const double n = ok ? std::hypot(r[0], r[1]) : 1e30;
        byView[v].push_back(n);
        norms.push_back(n);
      }
    }
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = std::max(options.outlierPixels, 4.0 * sorted[sorted.size() / 2]);
    for (std::size_t v = 0; v < posed.size(); ++v)
    {
      std::vector<PoseObservation> kept;
      std::vector<ceres::ResidualBlockId> keptIds;
      for (std::size_t i = 0; i < ids[v].size(); ++i)
      {
        if (byView[v][i] > limit)
        {
          problem.RemoveResidualBlock(ids[v][i]);
          --corners;
          ++out.outliers;
        }
        else
        {
          kept.push_back(posed[v].used[i]);
          keptIds.push_back(ids[v][i]);
        }
      }
      posed[v].used = kept;
      ids[v] = keptIds;
    }
    // A view left with fewer than 4 corners goes (its pose would be free).
    for (std::size_t v = posed.size(); v-- > 0;)
    {
      if (posed[v].used.size() >= 4)
      {
        continue;
      }
      for (const ceres::ResidualBlockId id : ids[v])
      {
        problem.RemoveResidualBlock(id);
        --corners;
        ++out.outliers;
      }
      problem.RemoveParameterBlock(posed[v].w);
      problem.RemoveParameterBlock(posed[v].t);
      out.skipped.push_back((views[static_cast<std::size_t>(posed[v].view)].name.empty()
                                ? "view " + std::to_string(posed[v].view + 1)
                                : views[static_cast<std::size_t>(posed[v].view)].name) +
        ": fewer than 4 corners fit the calibrated rig");
      posed.erase(posed.begin() + static_cast<std::ptrdiff_t>(v));
      ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(v));
    }
    if (static_cast<int>(posed.size()) < options.minViews)
    {
      out.error = "too few views: " + std::to_string(posed.size()) +
        " have corners that fit the calibrated rig, at least " + std::to_string(options.minViews) +
        " are needed";
      return out;
    }
    if (out.outliers > 0)
    {
      ceres::Solve(solver, &problem, &summary);
      out.iterations += static_cast<int>(summary.iterations.size());
      if (!summary.IsSolutionUsable())
      {
        out.error = "the calibration did not converge: " + summary.message;
        return out;
      }
    }
  }

  // The residuals and their Jacobian at the solution (without the robust loss).
  state.PrepareForEvaluation(true, true);
  ceres::Problem::EvaluateOptions eval;
  eval.apply_loss_function = false;
  eval.parameter_blocks = { theta.data() };
  if (options.freeLens)
  {
    eval.parameter_blocks.push_back(lensValues.data());
  }
  for (Posed& p : posed)
  {
    eval.parameter_blocks.push_back(p.w);
    eval.parameter_blocks.push_back(p.t);
  }
  double cost = 0.0;
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  if (!problem.Evaluate(eval, &cost, &residuals, nullptr, &crs))
  {
    out.error = "the calibrated rig does not image every corner";
    return out;
  }
  const int rows = crs.num_rows;
  const int cols = crs.num_cols;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, cols);
  for (int row = 0; row < rows; ++row)
  {
    for (int i = crs.rows[row]; i < crs.rows[row + 1]; ++i)
    {
      J(row, crs.cols[i]) = crs.values[i];
    }
  }
  double ssr = 0.0;
  for (const double r : residuals)
  {
    ssr += r * r;
  }
  out.rmsPixels = std::sqrt(ssr / std::max(1, corners));
  std::size_t at = 0;
  for (const Posed& p : posed)
  {
    double viewSsr = 0.0;
    std::vector<std::pair<Vec2, Vec2>> list;
    for (const PoseObservation& o : p.used)
    {
      const Vec2 r(residuals[at], residuals[at + 1]);
      at += 2;
      viewSsr += r.squaredNorm();
      list.emplace_back(o.pixel, r);
    }
    out.viewRmsPixels.push_back(std::sqrt(viewSsr / static_cast<double>(p.used.size())));
    out.residuals.push_back(std::move(list));
    out.usedViews.push_back(p.view);
    Mat4 pose = Mat4::Identity();
    pose.topLeftCorner<3, 3>() = RotationFromAngleAxis(Vec3(p.w[0], p.w[1], p.w[2])) * p.R0;
    pose.topRightCorner<3, 1>() = Vec3(p.t[0], p.t[1], p.t[2]);
    out.boardToCamera.push_back(pose);
  }
  out.imagesUsed = static_cast<int>(posed.size());

  // Which numbers the views fix: J^T J with its columns scaled to unit length; a direction of
  // (relative) eigenvalue below 1e-12 is not fixed, and the mirror's and lens's numbers that make
  // it up are named.
  const int nMirror = mirror.Count();
  const int nLens = options.freeLens ? lens.Count() : 0;
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  for (int c = 0; c < cols; ++c)
  {
    scale[c] = scale[c] > 0.0 ? 1.0 / scale[c] : 1.0;
  }
  const Eigen::MatrixXd Js = J * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Js.transpose() * Js);
  const double largest = eig.eigenvalues().maxCoeff();
  if (!(eig.eigenvalues().minCoeff() > 1e-12 * largest))
  {
    const Eigen::VectorXd null = eig.eigenvectors().col(0);
    std::string names;
    for (int c = 0; c < nMirror + nLens; ++c)
    {
      if (std::abs(null[c]) > 0.3)
      {
        names += (names.empty() ? "" : ", ") +
          (c < nMirror ? "the mirror's " + mirror.Names[static_cast<std::size_t>(c)]
                       : "the lens's " + lens.Names[static_cast<std::size_t>(c - nMirror)]);
      }
    }
    out.error = "these views do not fix " + (names.empty() ? "the boards' poses" : names) +
      ": add views of the board at other distances and angles";
    return out;
  }
  const int dof = std::max(1, rows - cols);
  const double variance = ssr / dof;
  const Eigen::MatrixXd covariance =
    scale.asDiagonal() * (Js.transpose() * Js).inverse() * scale.asDiagonal() * variance;
  for (int i = 0; i < nMirror; ++i)
  {
    CalibratedNumber n;
    n.name = mirror.Names[static_cast<std::size_t>(i)];
    n.unit = mirror.Units[static_cast<std::size_t>(i)];
    n.value = mirror.Reported(i, theta[static_cast<std::size_t>(i)]);
    n.sigma = mirror.Reported(i, std::sqrt(covariance(i, i)));
    out.mirror.push_back(n);
  }
  for (int i = 0; i < nLens; ++i)
  {
    CalibratedNumber n;
    n.name = lens.Names[static_cast<std::size_t>(i)];
    n.unit = lens.Unit(i);
    n.value = lensValues[static_cast<std::size_t>(i)];
    n.sigma = std::sqrt(covariance(nMirror + i, nMirror + i));
    out.lens.push_back(n);
  }
  out.camera = state.Model;

  // A board that does not fit: residuals too large, or the mirror's size moved by the board's
  // scale.
  if (out.rmsPixels > options.maxRmsPixels)
  {
    std::ostringstream s;
    s.precision(3);
    s << "the board does not fit these views: the calibrated rig leaves an RMS of " << out.rmsPixels
      << " px (at most " << options.maxRmsPixels
      << "); check the board file and the starting mirror";
    out.error = s.str();
    return out;
  }
  for (int i = 0; i < nMirror; ++i)
  {
    const double before = mirror.Theta[static_cast<std::size_t>(i)];
    const double after = theta[static_cast<std::size_t>(i)];
    if (mirror.Size[static_cast<std::size_t>(i)] &&
      std::abs(after / before - 1.0) > options.maxSizeChange)
    {
      out.error = "the board does not fit these views: the mirror's " +
        mirror.Names[static_cast<std::size_t>(i)] + " came out " + Percent(after / before - 1.0) +
        " from the start's (at most " + Percent(options.maxSizeChange) +
        "); a board printed at another size than its file says scales the whole rig";
      return out;
    }
  }
  out.ok = true;
  return out;
}
} // namespace catar
