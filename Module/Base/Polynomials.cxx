#include "Polynomials.h"

#include "Lanes.h" // PolyEval

#include <algorithm>
#include <cmath>

namespace catar
{
namespace detail
{
int SolveQuadratic(double a, double b, double c, double roots[2])
{
  if (a == 0.0)
  {
    if (b == 0.0)
    {
      return 0;
    }
    roots[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0)
  {
    // Allow a tiny negative discriminant (rounding) to give a double root.
    if (disc > -1e-14 * b * b)
    {
      roots[0] = -b / (2.0 * a);
      return 1;
    }
    return 0;
  }
  const double sq = std::sqrt(disc);
  const double q = -0.5 * (b + std::copysign(sq, b));
  if (q == 0.0)
  {
    roots[0] = 0.0;
    roots[1] = 0.0;
    return 2;
  }
  roots[0] = q / a;
  roots[1] = c / q;
  return 2;
}

namespace
{
template<int N>
void PolishRoot(const double (&c)[N], double& x, int iterations)
{
  for (int it = 0; it < iterations; ++it)
  {
    double d = 0.0;
    const double f = PolyEval(c, x, d);
    if (d == 0.0 || !std::isfinite(f / d))
    {
      return;
    }
    const double xn = x - f / d;
    double dn = 0.0;
    // Keep the step only if it does not make things worse.
    if (std::abs(PolyEval(c, xn, dn)) <= std::abs(f))
    {
      x = xn;
    }
    else
    {
      return;
    }
  }
}
} // namespace

int SolveCubic(double c3, double c2, double c1, double c0, double roots[3])
{
  const double scale = std::max({ std::abs(c2), std::abs(c1), std::abs(c0) });
  if (std::abs(c3) <= 1e-14 * scale || c3 == 0.0)
  {
    return SolveQuadratic(c2, c1, c0, roots);
  }
  const double b = c2 / c3;
  const double c = c1 / c3;
  const double d = c0 / c3;
  // x = y - b/3: y^3 + p y + q = 0
  const double p = c - b * b / 3.0;
  const double q = 2.0 * b * b * b / 27.0 - b * c / 3.0 + d;
  const double shift = -b / 3.0;
  const double disc = 0.25 * q * q + p * p * p / 27.0;
  int n = 0;
  if (disc > 0.0)
  {
    const double u = std::cbrt(-0.5 * q - std::copysign(std::sqrt(disc), q));
    const double y = (u != 0.0) ? u - p / (3.0 * u) : 0.0;
    roots[n++] = y + shift;
  }
  else if (p == 0.0)
  {
    roots[n++] = shift; // triple root
  }
  else
  {
    const double m = 2.0 * std::sqrt(-p / 3.0);
    double arg = 3.0 * q / (p * m);
    arg = std::min(1.0, std::max(-1.0, arg));
    const double theta = std::acos(arg) / 3.0;
    constexpr double twoThirdsPi = 2.0943951023931954923;
    for (int k = 0; k < 3; ++k)
    {
      roots[n++] = m * std::cos(theta - twoThirdsPi * k) + shift;
    }
  }
  const double poly[4] = { c3, c2, c1, c0 };
  for (int i = 0; i < n; ++i)
  {
    PolishRoot(poly, roots[i], 2);
  }
  return n;
}

int SolveQuartic(double c4, double c3, double c2, double c1, double c0, double roots[4])
{
  const double scale = std::max({ std::abs(c3), std::abs(c2), std::abs(c1), std::abs(c0) });
  if (std::abs(c4) <= 1e-14 * scale || c4 == 0.0)
  {
    return SolveCubic(c3, c2, c1, c0, roots);
  }
  const double poly[5] = { c4, c3, c2, c1, c0 };
  // One root much larger than the others (small leading coefficient) would make Ferrari's shift
  // -b/4 huge and cancel every digit of the small roots: find that root by Newton from -c3/c4,
  // deflate it from the constant end (stable for a large root), and solve the cubic left.
  {
    const double cauchy =
      1.0 + std::max({ std::abs(c2 / c3), std::abs(c1 / c3), std::abs(c0 / c3) });
    double big = -c3 / c4;
    if (std::isfinite(big) && std::abs(big) > 16.0 * cauchy)
    {
      PolishRoot(poly, big, 8);
      const double d0 = -c0 / big;
      const double d1 = (d0 - c1) / big;
      const double d2 = (d1 - c2) / big;
      const double d3 = (d2 - c3) / big;
      int n = SolveCubic(d3, d2, d1, d0, roots);
      for (int i = 0; i < n; ++i)
      {
        PolishRoot(poly, roots[i], 3);
      }
      roots[n++] = big;
      return n;
    }
  }
  const double b = c3 / c4;
  const double c = c2 / c4;
  const double d = c1 / c4;
  const double e = c0 / c4;
  // x = y - b/4: y^4 + p y^2 + q y + r = 0
  const double b2 = b * b;
  const double p = c - 0.375 * b2;
  const double q = 0.125 * b2 * b - 0.5 * b * c + d;
  const double r = -3.0 / 256.0 * b2 * b2 + 0.0625 * b2 * c - 0.25 * b * d + e;
  const double shift = -0.25 * b;
  const double depressedScale = std::max({ std::abs(p) * std::abs(p), std::abs(r), 1e-300 });
  int n = 0;
  if (std::abs(q) <= 1e-14 * std::pow(depressedScale, 0.75))
  {
    // Biquadratic: z = y^2, z^2 + p z + r = 0
    double z[2];
    const int nz = SolveQuadratic(1.0, p, r, z);
    for (int i = 0; i < nz; ++i)
    {
      if (z[i] >= 0.0)
      {
        const double y = std::sqrt(z[i]);
        roots[n++] = y + shift;
        roots[n++] = -y + shift;
      }
    }
  }
  else
  {
    // Resolvent cubic 8 m^3 + 8 p m^2 + (2 p^2 - 8 r) m - q^2 = 0; take its largest root (> 0).
    double mr[3];
    const int nm = SolveCubic(8.0, 8.0 * p, 2.0 * p * p - 8.0 * r, -q * q, mr);
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < nm; ++i)
    {
      m = std::max(m, mr[i]);
    }
    if (!(m > 0.0))
    {
      return 0;
    }
    const double s = std::sqrt(2.0 * m);
    const double half = 0.5 * p + m;
    const double t = q / (2.0 * s);
    double y[2];
    int ny = SolveQuadratic(1.0, -s, half + t, y);
    for (int i = 0; i < ny; ++i)
    {
      roots[n++] = y[i] + shift;
    }
    ny = SolveQuadratic(1.0, s, half - t, y);
    for (int i = 0; i < ny; ++i)
    {
      roots[n++] = y[i] + shift;
    }
  }
  for (int i = 0; i < n; ++i)
  {
    PolishRoot(poly, roots[i], 3);
  }
  return n;
}
} // namespace detail
} // namespace catar
