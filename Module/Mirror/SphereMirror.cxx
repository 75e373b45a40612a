#include "SphereMirror.h"

#include "Lanes.h"
#include "Polynomials.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace catar
{

namespace
{
constexpr double kOnSurfaceTolerance = 1e-12; // |P - C| / R within 1 +- this: touching the mirror
constexpr double kGrazingCosine = 1e-9;       // cos(incidence) below this: no usable reflection

// tan(x / 2) of the angle x in (-pi, pi] whose cosine and sine are c and s (+inf at x = pi).
// tan(x / 2) grows with x over (-pi, pi], so angles are compared through it without any
// inverse trigonometric function.
inline double TanHalf(double c, double s)
{
  if (c >= 0.0)
  {
    return s / (1.0 + c);
  }
  return s != 0.0 ? (1.0 - c) / s : std::numeric_limits<double>::infinity();
}

// The point (c, s) = (cos t, sin t) of the unit circle at u = tan(t / 2).
template<typename T>
inline void CircleAt(T u, T& c, T& s)
{
  const T one = lanes::Constant<T>(1.0);
  const T w = one / (one + u * u);
  c = (one - u * u) * w;
  s = lanes::Constant<T>(2.0) * u * w;
}

// Whether the camera at (a, 0) sees the circle point (c, s) at more than grazing incidence: the
// cosine of the incidence angle, an / |(an, at)|, above kGrazingCosine (no square root). A bool
// for doubles, a mask per lane for lanes.
template<typename T>
inline auto CameraSees(T a, T c, T s)
{
  const T an = a * c - lanes::Constant<T>(1.0);
  const T at = -a * s;
  return (an > lanes::Constant<T>(0.0)) &
    (an * an > lanes::Constant<T>(kGrazingCosine * kGrazingCosine) * (an * an + at * at));
}

// The coefficients of the reflection quartic of SphereMirror.h in u = tan(t / 2), highest
// degree first.
template<typename T>
inline void QuarticCoefficients(T a, T bx, T by, T (&c)[5])
{
  const T one = lanes::Constant<T>(1.0), two = lanes::Constant<T>(2.0);
  c[0] = by * (a + one);
  c[1] = two * (two * a * bx + a + bx);
  c[2] = lanes::Constant<T>(-6.0) * a * by;
  c[3] = two * (a + bx - two * a * bx);
  c[4] = by * (a - one);
}

// The reflection quartic for one point.
struct ReflectionQuartic
{
  double c[5];
  ReflectionQuartic(double a, double bx, double by) { QuarticCoefficients(a, bx, by, this->c); }
  double operator()(double u, double& derivative) const
  {
    return detail::PolyEval(this->c, u, derivative);
  }
};

// The closed-form step: the root of the quartic (Ferrari) inside [lo, hi] (allowing rounding
// slack), clamped to it; of several, the one nearest to a root by its Newton step. False if none.
bool QuarticRootInBracket(const ReflectionQuartic& q, double lo, double hi, double& u)
{
  double roots[4];
  const int n = detail::SolveQuartic(q.c[0], q.c[1], q.c[2], q.c[3], q.c[4], roots);
  const double slack = 1e-7 * (1.0 + hi - lo);
  double best = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int i = 0; i < n; ++i)
  {
    if (!(roots[i] >= lo - slack && roots[i] <= hi + slack))
    {
      continue;
    }
    const double r = std::min(hi, std::max(lo, roots[i]));
    double d = 0.0;
    const double f = q(r, d);
    const double step = d != 0.0 ? std::abs(f / d) : (f == 0.0 ? 0.0 : best);
    if (!found || step < best)
    {
      best = step;
      u = r;
      found = true;
    }
  }
  return found;
}

// Safeguarded Newton (bisection fallback) on the quartic inside [lo, hi], from u. Inside the
// bracket the quartic's only root is the physical reflection (h runs over (-pi, pi) there, and
// the quartic vanishes where h is 0 or +-pi), and the quartic has the sign of sin(h) (it is a
// positive multiple of it: both are positive at u = 0 for by > 0), so it decreases through the
// root as h does; no end needs evaluating. No trigonometric function is called.
double NewtonInBracket(const ReflectionQuartic& q, double u, double lo, double hi)
{
  double d = 0.0;
  u = std::min(hi, std::max(lo, u));
  for (int it = 0; it < 100; ++it)
  {
    const double g = q(u, d);
    if (g == 0.0)
    {
      break;
    }
    if (g > 0.0)
    {
      lo = u;
    }
    else
    {
      hi = u;
    }
    const double newton = g / d;
    if (std::abs(newton) <= 1e-9 * (1.0 + u))
    {
      // Converged: Newton's error after a step of size e is about K e^2 (K = |q''/2q'|, of
      // order one here), far below rounding; taking this last step without evaluating q again
      // saves an iteration, and a step that lands on a bracket's end must not restart
      // bisection from there.
      u = std::min(hi, std::max(lo, u - newton));
      break;
    }
    double un = u - newton;
    if (!(un > lo && un < hi))
    {
      un = 0.5 * (lo + hi);
    }
    u = un;
    if (hi - lo <= 2e-16 * (1.0 + u))
    {
      break;
    }
  }
  return u;
}
} // namespace

namespace detail
{
bool QuarticReflectionAngle(double a, double bx, double by, double lo, double hi, double& theta)
{
  double u = 0.0;
  if (!QuarticRootInBracket(
        ReflectionQuartic(a, bx, by), std::tan(0.5 * lo), std::tan(0.5 * hi), u))
  {
    return false;
  }
  theta = 2.0 * std::atan(u);
  return true;
}

SphereSurface::SphereSurface(const Vec3& centre, double radius)
  : Description(SphereMirror{ centre, radius })
  , Centre(centre)
  , Radius(radius)
{
  if (!centre.allFinite() || !std::isfinite(radius) || !(radius > 0.0))
  {
    return;
  }
  this->InvRadius = 1.0 / radius;
  const Vec3 A = -centre * this->InvRadius; // camera, sphere-centred, unit radius
  this->A = A.norm();
  if (!(this->A > 1.0) || !std::isfinite(this->A))
  {
    return;
  }
  this->E1 = A / this->A;
  // alpha_A = acos(1 / a): the camera sees the arc |t| < alpha_A.
  this->TanHalfAlphaA =
    TanHalf(1.0 / this->A, std::sqrt((this->A - 1.0) * (this->A + 1.0)) / this->A);
  this->Valid = true;
}

ProjectionStatus SphereSurface::Reflect(
  const Vec3& point, SolverType solver, Vec3& mirrorPoint, const Vec3* guess) const
{
  if (guess)
  {
    // Started next to the answer: the plain Newton of ReflectNear, whose answer, when it settles,
    // is the physical reflection; otherwise the cases and the safeguarded search below decide.
    unsigned char settled = 0;
    this->ReflectNear(1, &point, guess, &mirrorPoint, &settled);
    if (settled)
    {
      return ProjectionStatus::Valid;
    }
  }
  mirrorPoint.setZero();
  if (!this->Valid || !point.allFinite())
  {
    return ProjectionStatus::InvalidInput;
  }
  const Vec3 B = (point - this->Centre) * this->InvRadius;
  const double b = B.norm();
  if (!std::isfinite(b))
  {
    return ProjectionStatus::InvalidInput;
  }
  if (b < 1.0 - kOnSurfaceTolerance)
  {
    return ProjectionStatus::InsideMirror;
  }
  if (b <= 1.0 + kOnSurfaceTolerance)
  {
    // Touching the mirror: the point is its own reflection when the camera sees it.
    if (this->A * this->E1.dot(B / b) > 1.0)
    {
      mirrorPoint = this->Centre + this->Radius * (B / b);
      return ProjectionStatus::Valid;
    }
    return ProjectionStatus::HiddenByMirror;
  }
  const double a = this->A;
  const double bx = B.dot(this->E1);
  Vec3 perp = B - bx * this->E1;
  double by = perp.norm();
  Vec3 e2;
  if (by > 1e-300 && by > 1e-15 * b)
  {
    e2 = perp / by;
  }
  else
  {
    // On the camera-mirror axis: any plane through the axis will do.
    by = 0.0;
    const Vec3& e1 = this->E1;
    e2 = (std::abs(e1.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(e1).normalized();
  }
  const ReflectionQuartic q(a, bx, by);
  double c = 0.0, s = 0.0;
  // The bracket [lo, hi] = [max(beta - alpha_B, 0), min(alpha_A, beta)] with beta the angle of B
  // and alpha_B = acos(1 / b), in u = tan(t / 2): cosines and sines instead of angles. The point
  // is hidden by the mirror when beta - alpha_B >= alpha_A (no arc seen by both).
  const double cosBeta = bx / b;
  const double sinBeta = by / b;
  const double cosAlphaB = 1.0 / b;
  const double sinAlphaB = std::sqrt((b - 1.0) * (b + 1.0)) / b;
  const double uGap = TanHalf(cosBeta * cosAlphaB + sinBeta * sinAlphaB,
    sinBeta * cosAlphaB - cosBeta * sinAlphaB); // tan((beta - alpha_B) / 2)
  if (!(uGap < this->TanHalfAlphaA))
  {
    return ProjectionStatus::HiddenByMirror;
  }
  const double uBeta = TanHalf(cosBeta, sinBeta);
  const double lo = std::max(uGap, 0.0);
  const double hi = std::min(this->TanHalfAlphaA, uBeta);
  // Far-field guess t = beta / 2: tan(beta / 4) from tan(beta / 2).
  double start = std::isfinite(uBeta) ? uBeta / (1.0 + std::sqrt(1.0 + uBeta * uBeta)) : 1.0;
  if (solver == SolverType::Quartic && !guess) // Automatic: Iterative, the same root
  {
    // The closed-form root, polished by the same safeguarded Newton (which converges in one or
    // two steps from it). Should rounding in Ferrari's method leave no root in the bracket, the
    // polish starts from the far-field guess instead.
    double root = 0.0;
    if (QuarticRootInBracket(q, lo, hi, root))
    {
      start = root;
    }
  }
  const double u = NewtonInBracket(q, start, lo, hi);
  if (!std::isfinite(u))
  {
    return ProjectionStatus::NoReflection;
  }
  CircleAt(u, c, s);
  if (!CameraSees(a, c, s))
  {
    return ProjectionStatus::NoReflection;
  }
  mirrorPoint = this->Centre + this->Radius * (c * this->E1 + s * e2);
  return ProjectionStatus::Valid;
}

namespace
{
using namespace catar::lanes;
constexpr int kPairs = SphereSurface::kLanes / kW;
static_assert(SphereSurface::kLanes % kW == 0, "lanes come in pairs");
} // namespace

void SphereSurface::ReflectNear(
  int n, const Vec3* points, const Vec3* guesses, Vec3* mirrorPoints, unsigned char* settled) const
{
  // Plain Newton from the guess, accepted when it converges within a few steps to a point that
  // both the camera and B see (an > 0, bn > 0) with 0 <= t <= beta (bt >= 0): that arc is
  // Reflect's bracket, where the root is unique, so this is the physical reflection. The lanes
  // run in pairs (Lanes: one instruction for both), and each stage runs for every pair before
  // the next stage, so that the pairs' divisions and square roots overlap instead of waiting on
  // each other. The second lane of a last pair past n computes on zeros and is not used.
  n = std::max(0, std::min(n, kLanes));
  const int pairs = (n + kW - 1) / kW; // the pairs that hold a lane below n
  const Lanes zero = Splat(0.0), one = Splat(1.0);
  const Lanes cx = Splat(this->Centre.x()), cy = Splat(this->Centre.y()),
              cz = Splat(this->Centre.z());
  const Lanes e1x = Splat(this->E1.x()), e1y = Splat(this->E1.y()), e1z = Splat(this->E1.z());
  const Lanes a = Splat(this->A);
  Lanes bx[kPairs], by[kPairs], fx[kPairs], fy[kPairs], fz[kPairs], u[kPairs];
  Lanes q[kPairs][5];
  LaneMask ok[kPairs], converged[kPairs];
  for (int g = 0; g < pairs; ++g)
  {
    Lanes px = zero, py = zero, pz = zero, gx = zero, gy = zero, gz = zero;
    LaneMask used = zero == one;
    for (int k = 0; k < kW; ++k)
    {
      const int l = g * kW + k;
      if (l < n)
      {
        px[k] = points[l].x();
        py[k] = points[l].y();
        pz[k] = points[l].z();
        gx[k] = guesses[l].x();
        gy[k] = guesses[l].y();
        gz[k] = guesses[l].z();
        used[k] = -1;
      }
    }
    // B = (p - centre) / R; bx along E1, by across it (e2 = f, the plane's second axis).
    const Lanes ir = Splat(this->InvRadius);
    const Lanes Bx = (px - cx) * ir, By = (py - cy) * ir, Bz = (pz - cz) * ir;
    const Lanes b = Sqrt(Bx * Bx + By * By + Bz * Bz);
    bx[g] = Bx * e1x + By * e1y + Bz * e1z;
    const Lanes qx = Bx - bx[g] * e1x, qy = By - bx[g] * e1y, qz = Bz - bx[g] * e1z;
    by[g] = Sqrt(qx * qx + qy * qy + qz * qz);
    // Outside the mirror by more than the touching tolerance, off the axis (Reflect's cases).
    ok[g] = used & Finite(b) & (b > Splat(1.0 + kOnSurfaceTolerance)) & (by[g] > Splat(1e-300)) &
      (by[g] > Splat(1e-15) * b);
    if (!this->Valid)
    {
      ok[g] = used & ~used;
    }
    fx[g] = qx / by[g];
    fy[g] = qy / by[g];
    fz[g] = qz / by[g];
    // The guess in the plane: u = tan(t / 2) of its angle t from E1.
    const Lanes dx = gx - cx, dy = gy - cy, dz = gz - cz;
    const Lanes gc = dx * e1x + dy * e1y + dz * e1z;
    const Lanes gs = dx * fx[g] + dy * fy[g] + dz * fz[g];
    const Lanes gn = Sqrt(gc * gc + gs * gs);
    ok[g] &= (gn > zero) & (gc > Splat(-0.5) * gn) & Finite(gn);
    u[g] = gs / (gn + gc);
    QuarticCoefficients(a, bx[g], by[g], q[g]);
    converged[g] = used & ~used;
  }

  // Plain Newton, as Reflect: a lane stops at its first step below the tolerance (that step
  // taken); lanes still moving after four steps are not settled.
  for (int it = 0; it < 4; ++it)
  {
    bool moving = false;
    for (int g = 0; g < pairs; ++g)
    {
      const LaneMask active = ok[g] & ~converged[g];
      if (!Any(active))
      {
        continue;
      }
      Lanes dp;
      const Lanes step = PolyEval(q[g], u[g], dp) / dp;
      u[g] = Select(active, u[g] - step, u[g]);
      converged[g] |= active & (Abs(step) <= Splat(1e-9) * (one + Abs(u[g])));
      moving = moving || Any(ok[g] & ~converged[g]);
    }
    if (!moving)
    {
      break;
    }
  }

  // On the arc both the camera and B see (CircleAt, CameraSees).
  const Lanes r = Splat(this->Radius);
  for (int g = 0; g < pairs; ++g)
  {
    Lanes c, sn;
    CircleAt(u[g], c, sn);
    const Lanes bn = bx[g] * c + by[g] * sn - one;
    const Lanes bt = by[g] * c - bx[g] * sn;
    const LaneMask good =
      ok[g] & converged[g] & (u[g] >= zero) & CameraSees(a, c, sn) & (bn > zero) & (bt >= zero);
    const Lanes mx = cx + r * (c * e1x + sn * fx[g]);
    const Lanes my = cy + r * (c * e1y + sn * fy[g]);
    const Lanes mz = cz + r * (c * e1z + sn * fz[g]);
    for (int k = 0; k < kW; ++k)
    {
      const int l = g * kW + k;
      if (l < n)
      {
        settled[l] = good[k] ? 1 : 0;
        if (good[k])
        {
          mirrorPoints[l] = Vec3(mx[k], my[k], mz[k]);
        }
      }
    }
  }
}
} // namespace detail

ProjectionStatus SphereReflectionPoint(
  const Vec3& centre, double radius, const Vec3& point, SolverType solver, Vec3& mirrorPoint)
{
  return detail::SphereSurface(centre, radius).Reflect(point, solver, mirrorPoint);
}

namespace
{
// The nearer intersection of the ray from the origin along the unit vector d with the sphere.
inline bool IntersectSphere(const Vec3& c, double radius, const Vec3& d, Vec3& point, Vec3& normal)
{
  const double dc = d.dot(c);
  const double c2r2 = c.squaredNorm() - radius * radius;
  // disc = R^2 - (distance from the centre to the ray)^2, without the cancellation of
  // (d.c)^2 - |c|^2 + R^2, which would cost digits at every pixel.
  const double lateral = c.cross(d).norm();
  const double disc = (radius - lateral) * (radius + lateral);
  if (!(dc > 0.0) || !(disc >= 0.0))
  {
    return false;
  }
  // Nearer intersection, in the cancellation-free form s = (|c|^2 - R^2) / (d.c + sqrt(disc)).
  const double s = c2r2 / (dc + std::sqrt(disc));
  point = s * d;
  normal = (point - c) / radius;
  return true;
}
} // namespace

bool detail::SphereSurface::Intersect(const Vec3& d, Vec3& point, Vec3& normal) const
{
  return this->Valid && IntersectSphere(this->Centre, this->Radius, d, point, normal);
}

void detail::SphereSurface::Intersect(
  int n, const Vec3* directions, Vec3* points, Vec3* normals, unsigned char* hits) const
{
  const Vec3 c = this->Centre;
  const double radius = this->Radius;
  for (int i = 0; i < n; ++i)
  {
    hits[i] = this->Valid && IntersectSphere(c, radius, directions[i], points[i], normals[i]);
  }
}

SphereMirror::operator MirrorDescription() const
{
  return MirrorDescription(
    "sphere", { this->center.x(), this->center.y(), this->center.z(), this->radius });
}

bool SphereMirror::From(const MirrorDescription& description, SphereMirror& sphere)
{
  if (description.type != "sphere" || description.parameters.size() != 4)
  {
    return false;
  }
  const std::vector<double>& p = description.parameters;
  sphere.center = Vec3(p[0], p[1], p[2]);
  sphere.radius = p[3];
  return true;
}

namespace
{
std::string ValidateSphere(const MirrorDescription& description)
{
  const std::vector<double>& p = description.parameters;
  const SphereMirror s{ Vec3(p[0], p[1], p[2]), p[3] };
  std::ostringstream err;
  if (!(s.radius > 0.0))
  {
    err << "mirror radius must be positive (" << s.radius << ")";
  }
  else if (s.center.norm() <= s.radius * (1.0 + 1e-9))
  {
    err << "the camera centre is inside the mirror sphere (|centre|=" << s.center.norm()
        << ", radius=" << s.radius << ")";
  }
  return err.str();
}

std::shared_ptr<const Mirror> MakeSphere(const MirrorDescription& description)
{
  SphereMirror s;
  SphereMirror::From(description, s);
  return std::make_shared<detail::SphereSurface>(s.center, s.radius);
}
} // namespace

MirrorType SphereMirrorType()
{
  MirrorType t;
  t.name = "sphere";
  t.help = "a spherical mirror (closed-form reflection)";
  t.parameters = { { "center", 3, "the sphere's centre, camera frame" },
    { "radius", 1, "the sphere's radius" } };
  const SphereMirror defaults;
  t.defaults = static_cast<MirrorDescription>(defaults).parameters;
  t.validate = &ValidateSphere;
  t.make = &MakeSphere;
  t.quadric = [](const MirrorDescription& d, Mat3& A, Vec3& B, double& C) {
    SphereMirror s;
    if (!SphereMirror::From(d, s))
    {
      return false;
    }
    A = Mat3::Identity();
    B = -s.center;
    C = s.center.squaredNorm() - s.radius * s.radius;
    return true;
  };
  return t;
}
} // namespace catar
