// CatadioptricAR Core: the quadric mirror's ReflectNear, Newton on the Lagrange system for
// several points side by side (QuadricMirror.h).
#include "Lanes.h"
#include "QuadricMirror.h"

#include <algorithm>
#include <cmath>

namespace catar
{
namespace detail
{
namespace
{
using namespace catar::lanes;
constexpr int kPairs = QuadricSurface::kLanes / kW;
static_assert(QuadricSurface::kLanes % kW == 0, "lanes come in pairs");

// A symmetric 3x3 matrix's six entries.
struct Sym3
{
  Lanes xx, xy, xz, yy, yz, zz;
};

// The state of a pair at its current point x and multiplier lambda: the Lagrange residual G
// (stationarity g123, the surface's equation divided by L in g4), the gradient, the unit vectors,
// the distances. As QuadricSurface::Newton's State.
struct PairState
{
  Lanes x[3], ah[3], qh[3], g[3], G[3], G4, la, lq, lambda, merit;
};
} // namespace

void QuadricSurface::ReflectNear(
  int n, const Vec3* points, const Vec3* guesses, Vec3* mirrorPoints, unsigned char* settled) const
{
  // Plain Newton from each guess (no step halving): a lane settles when it reaches Newton's
  // quadratic regime within a few steps, each lowering the residual and no longer than Newton's
  // limit (half the distance to the camera or the point), with the exit of Newton (the step below
  // 1e-8 L at a residual below 1e-6, the point after it on the surface to 1e-13); then Check must
  // find it a reflection the camera sees. Those are the tests Reflect's Newton applies, so a
  // settled lane holds an answer Reflect accepts from that guess. Points Reflect answers before
  // any Newton (on the mirror, inside it) and lanes that fail any test are left to Reflect. Each
  // stage runs for every pair before the next, so that the pairs' divisions and square roots
  // overlap.
  n = std::max(0, std::min(n, kLanes));
  std::fill(settled, settled + n, static_cast<unsigned char>(0));
  if (!this->EffectiveViewpoint.allFinite() || this->TablePoints.empty() || n == 0)
  {
    return;
  }
  const int pairs = (n + kW - 1) / kW;
  const double L = this->Length;
  const Lanes zero = Splat(0.0), one = Splat(1.0), two = Splat(2.0), half = Splat(0.5);
  const Lanes iL = Splat(1.0 / L), Lv = Splat(L), tiny = Splat(1e-12 * L);
  const Sym3 A{ Splat(this->A(0, 0)), Splat(this->A(0, 1)), Splat(this->A(0, 2)),
    Splat(this->A(1, 1)), Splat(this->A(1, 2)), Splat(this->A(2, 2)) };
  const Lanes B[3] = { Splat(this->B.x()), Splat(this->B.y()), Splat(this->B.z()) };
  const Lanes C = Splat(this->C);

  Lanes P[kPairs][3];
  PairState s[kPairs];
  LaneMask ok[kPairs], done[kPairs];
  Lanes out[kPairs][3];

  // G at (x, lambda) for pair k; false lanes where x is at the camera or the point.
  auto evaluate = [&](int k) {
    PairState& t = s[k];
    const Lanes q[3] = { t.x[0] - P[k][0], t.x[1] - P[k][1], t.x[2] - P[k][2] };
    t.la = Sqrt(t.x[0] * t.x[0] + t.x[1] * t.x[1] + t.x[2] * t.x[2]);
    t.lq = Sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    const LaneMask good = (t.la > tiny) & (t.lq > tiny);
    const Lanes ia = one / t.la, iq = one / t.lq;
    const Lanes Ax[3] = { A.xx * t.x[0] + A.xy * t.x[1] + A.xz * t.x[2],
      A.xy * t.x[0] + A.yy * t.x[1] + A.yz * t.x[2],
      A.xz * t.x[0] + A.yz * t.x[1] + A.zz * t.x[2] };
    for (int c = 0; c < 3; ++c)
    {
      t.ah[c] = t.x[c] * ia;
      t.qh[c] = q[c] * iq;
      t.g[c] = two * (Ax[c] + B[c]);
      t.G[c] = t.ah[c] + t.qh[c] - t.lambda * t.g[c];
    }
    t.G4 = (t.x[0] * (Ax[0] + two * B[0]) + t.x[1] * (Ax[1] + two * B[1]) +
             t.x[2] * (Ax[2] + two * B[2]) + C) *
      iL;
    t.merit = t.G[0] * t.G[0] + t.G[1] * t.G[1] + t.G[2] * t.G[2] + t.G4 * t.G4;
    return good & Finite(t.merit);
  };

  for (int k = 0; k < pairs; ++k)
  {
    LaneMask used = zero == one;
    for (int c = 0; c < 3; ++c)
    {
      P[k][c] = zero;
      s[k].x[c] = one; // lanes past n: a harmless point
    }
    for (int l = 0; l < kW; ++l)
    {
      const int i = k * kW + l;
      if (i >= n)
      {
        continue;
      }
      const Vec3& p = points[i];
      const Vec3& r = guesses[i];
      // Reflect's answers before any Newton: a point on the mirror, or inside it.
      const double F = this->Value(p);
      const bool onMirror =
        std::abs(F) <= 1e-12 * this->Gradient(p).norm() * L && this->InPart(p, 1e-12 * L);
      if (!p.allFinite() || !r.allFinite() || onMirror || (F < 0.0 && this->InPart(p, 0.0)))
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        P[k][c][l] = p[c];
        s[k].x[c][l] = r[c];
      }
      used[l] = -1;
    }
    s[k].lambda = zero;
    ok[k] = used & evaluate(k);
    // lambda to start: the least-squares multiplier of the stationarity equation.
    const Lanes gg = s[k].g[0] * s[k].g[0] + s[k].g[1] * s[k].g[1] + s[k].g[2] * s[k].g[2];
    ok[k] &= gg > zero;
    const Lanes lambda = (s[k].G[0] * s[k].g[0] + s[k].G[1] * s[k].g[1] + s[k].G[2] * s[k].g[2]) /
      Select(ok[k], gg, one);
    s[k].lambda = Select(ok[k], lambda, zero);
    for (int c = 0; c < 3; ++c)
    {
      s[k].G[c] = s[k].G[c] - s[k].lambda * s[k].g[c];
    }
    s[k].merit =
      s[k].G[0] * s[k].G[0] + s[k].G[1] * s[k].G[1] + s[k].G[2] * s[k].G[2] + s[k].G4 * s[k].G4;
    done[k] = used & ~used;
    for (int c = 0; c < 3; ++c)
    {
      out[k][c] = zero;
    }
  }

  constexpr int kSteps = 5;
  for (int it = 0; it < kSteps; ++it)
  {
    bool moving = false;
    for (int k = 0; k < pairs; ++k)
    {
      const LaneMask active = ok[k] & ~done[k];
      if (!Any(active))
      {
        continue;
      }
      PairState& t = s[k];
      // M = (I - ah ah^T) / la + (I - qh qh^T) / lq - 2 lambda A, and the Newton step of
      // [M, -g; g^T / L, 0] (dr, dlambda) = -G by its Schur complement with M's adjugate:
      // dlambda = (g^T adj G1 - det L G4) / (g^T adj g), dr = (dlambda adj g - adj G1) / det.
      const Lanes ia = one / t.la, iq = one / t.lq, l2 = two * t.lambda;
      const Lanes d = ia + iq;
      Sym3 M;
      M.xx = d - t.ah[0] * t.ah[0] * ia - t.qh[0] * t.qh[0] * iq - l2 * A.xx;
      M.yy = d - t.ah[1] * t.ah[1] * ia - t.qh[1] * t.qh[1] * iq - l2 * A.yy;
      M.zz = d - t.ah[2] * t.ah[2] * ia - t.qh[2] * t.qh[2] * iq - l2 * A.zz;
      M.xy = zero - t.ah[0] * t.ah[1] * ia - t.qh[0] * t.qh[1] * iq - l2 * A.xy;
      M.xz = zero - t.ah[0] * t.ah[2] * ia - t.qh[0] * t.qh[2] * iq - l2 * A.xz;
      M.yz = zero - t.ah[1] * t.ah[2] * ia - t.qh[1] * t.qh[2] * iq - l2 * A.yz;
      Sym3 J; // adj(M)
      J.xx = M.yy * M.zz - M.yz * M.yz;
      J.xy = M.xz * M.yz - M.xy * M.zz;
      J.xz = M.xy * M.yz - M.xz * M.yy;
      J.yy = M.xx * M.zz - M.xz * M.xz;
      J.yz = M.xy * M.xz - M.xx * M.yz;
      J.zz = M.xx * M.yy - M.xy * M.xy;
      const Lanes det = M.xx * J.xx + M.xy * J.xy + M.xz * J.xz;
      auto apply = [&J](const Lanes(&v)[3], Lanes(&o)[3]) {
        o[0] = J.xx * v[0] + J.xy * v[1] + J.xz * v[2];
        o[1] = J.xy * v[0] + J.yy * v[1] + J.yz * v[2];
        o[2] = J.xz * v[0] + J.yz * v[1] + J.zz * v[2];
      };
      Lanes Jg[3], JG[3];
      apply(t.g, Jg);
      apply(t.G, JG);
      const Lanes gJg = t.g[0] * Jg[0] + t.g[1] * Jg[1] + t.g[2] * Jg[2];
      const Lanes gJG = t.g[0] * JG[0] + t.g[1] * JG[1] + t.g[2] * JG[2];
      const Lanes dlambda = (gJG - det * Lv * t.G4) / gJg;
      const Lanes idet = one / det;
      Lanes dr[3];
      for (int c = 0; c < 3; ++c)
      {
        dr[c] = (dlambda * Jg[c] - JG[c]) * idet;
      }
      const Lanes length = Sqrt(dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2]);
      // A singular M or a step past Newton's limit: Reflect's Newton decides.
      ok[k] &= ~active |
        (Finite(length) & Finite(dlambda) & (length <= half * (Select(t.la < t.lq, t.la, t.lq))));
      // The quadratic regime's exit: the point after this step, on the surface to 1e-13.
      const LaneMask exiting =
        ok[k] & active & (length <= Splat(1e-8) * Lv) & (t.merit <= Splat(1e-12));
      if (Any(exiting))
      {
        Lanes y[3];
        for (int c = 0; c < 3; ++c)
        {
          y[c] = t.x[c] + dr[c];
        }
        const Lanes Ay[3] = { A.xx * y[0] + A.xy * y[1] + A.xz * y[2],
          A.xy * y[0] + A.yy * y[1] + A.yz * y[2], A.xz * y[0] + A.yz * y[1] + A.zz * y[2] };
        const Lanes F = y[0] * (Ay[0] + two * B[0]) + y[1] * (Ay[1] + two * B[1]) +
          y[2] * (Ay[2] + two * B[2]) + C;
        const Lanes gn = Sqrt(t.g[0] * t.g[0] + t.g[1] * t.g[1] + t.g[2] * t.g[2]);
        const LaneMask onSurface = exiting & (Abs(F) <= Splat(1e-13) * gn * Lv);
        for (int c = 0; c < 3; ++c)
        {
          out[k][c] = Select(onSurface, y[c], out[k][c]);
        }
        done[k] |= onSurface;
      }
      // The others step on and must lower the residual.
      const LaneMask stepping = ok[k] & active & ~done[k];
      const Lanes before = t.merit;
      for (int c = 0; c < 3; ++c)
      {
        t.x[c] = Select(stepping, t.x[c] + dr[c], t.x[c]);
      }
      t.lambda = Select(stepping, t.lambda + dlambda, t.lambda);
      const LaneMask evaluated = evaluate(k);
      ok[k] &= ~stepping | (evaluated & (t.merit < before));
      moving = moving || Any(ok[k] & ~done[k]);
    }
    if (!moving)
    {
      break;
    }
  }

  for (int k = 0; k < pairs; ++k)
  {
    for (int l = 0; l < kW; ++l)
    {
      const int i = k * kW + l;
      if (i >= n || !ok[k][l] || !done[k][l])
      {
        continue;
      }
      const Vec3 r(out[k][0][l], out[k][1][l], out[k][2][l]);
      if (this->Check(points[i], r) == ProjectionStatus::Valid)
      {
        mirrorPoints[i] = r;
        settled[i] = 1;
      }
    }
  }
}
} // namespace detail
} // namespace catar
