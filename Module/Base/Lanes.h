// CatadioptricAR Core (private): two doubles side by side, the lanes of the solvers that work on
// several points at once (the Mirror::ReflectNear implementations).
#ifndef catarLanes_h
#define catarLanes_h

#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h> // _mm_sqrt_pd
#endif

namespace catar
{
namespace lanes
{
// Lanes: a double per lane; LaneMask: a mask per lane (all bits set: true). GCC and Clang make one
// SSE2 instruction of each operation on such a pair (the same IEEE operation per lane as one lane
// at a time); other compilers get the operations lane by lane (as GCC and Clang do with
// CATAR_LANES_LOOP defined: both give the same results).
constexpr int kW = 2;
#if (defined(__GNUC__) || defined(__clang__)) && !defined(CATAR_LANES_LOOP)
typedef double Lanes __attribute__((vector_size(8 * kW)));
typedef long long LaneMask __attribute__((vector_size(8 * kW)));
inline Lanes AsLanes(LaneMask m)
{
  return reinterpret_cast<Lanes>(m);
}
inline LaneMask AsMask(Lanes v)
{
  return reinterpret_cast<LaneMask>(v);
}
#else
template<typename T>
struct LaneArray
{
  T v[kW];
  T& operator[](int l) { return this->v[l]; }
  T operator[](int l) const { return this->v[l]; }
};
using Lanes = LaneArray<double>;
using LaneMask = LaneArray<long long>;
#define CATAR_LANEWISE(T, op)                                                                      \
  inline T operator op(const T& x, const T& y)                                                     \
  {                                                                                                \
    T r;                                                                                           \
    for (int l = 0; l < kW; ++l)                                                                   \
    {                                                                                              \
      r[l] = x[l] op y[l];                                                                         \
    }                                                                                              \
    return r;                                                                                      \
  }
#define CATAR_LANES_COMPARE(op)                                                                    \
  inline LaneMask operator op(const Lanes& x, const Lanes& y)                                      \
  {                                                                                                \
    LaneMask r;                                                                                    \
    for (int l = 0; l < kW; ++l)                                                                   \
    {                                                                                              \
      r[l] = (x[l] op y[l]) ? -1 : 0;                                                              \
    }                                                                                              \
    return r;                                                                                      \
  }
CATAR_LANEWISE(Lanes, +)
CATAR_LANEWISE(Lanes, -)
CATAR_LANEWISE(Lanes, *)
CATAR_LANEWISE(Lanes, /)
CATAR_LANEWISE(LaneMask, &)
CATAR_LANEWISE(LaneMask, |)
CATAR_LANES_COMPARE(<)
CATAR_LANES_COMPARE(<=)
CATAR_LANES_COMPARE(>)
CATAR_LANES_COMPARE(>=)
CATAR_LANES_COMPARE(==)
#undef CATAR_LANEWISE
#undef CATAR_LANES_COMPARE
inline Lanes operator-(const Lanes& x)
{
  Lanes r;
  for (int l = 0; l < kW; ++l)
  {
    r[l] = -x[l];
  }
  return r;
}
inline LaneMask operator~(const LaneMask& m)
{
  LaneMask r;
  for (int l = 0; l < kW; ++l)
  {
    r[l] = ~m[l];
  }
  return r;
}
inline LaneMask& operator&=(LaneMask& m, const LaneMask& o)
{
  return m = m & o;
}
inline LaneMask& operator|=(LaneMask& m, const LaneMask& o)
{
  return m = m | o;
}
inline Lanes AsLanes(const LaneMask& m)
{
  Lanes r;
  std::memcpy(r.v, m.v, sizeof r.v);
  return r;
}
inline LaneMask AsMask(const Lanes& v)
{
  LaneMask r;
  std::memcpy(r.v, v.v, sizeof r.v);
  return r;
}
#endif

inline Lanes Splat(double x)
{
  Lanes v;
  for (int l = 0; l < kW; ++l)
  {
    v[l] = x;
  }
  return v;
}

// x as a T: a double, or the same value in every lane, so that one template serves both one
// point and a pair of lanes with the same operations.
template<typename T>
T Constant(double x);
template<>
inline double Constant<double>(double x)
{
  return x;
}
template<>
inline Lanes Constant<Lanes>(double x)
{
  return Splat(x);
}

// a where m, else b.
inline Lanes Select(LaneMask m, Lanes a, Lanes b)
{
  return AsLanes((m & AsMask(a)) | (~m & AsMask(b)));
}

inline Lanes Sqrt(Lanes x)
{
#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2__) && !defined(CATAR_LANES_LOOP)
  return reinterpret_cast<Lanes>(_mm_sqrt_pd(reinterpret_cast<__m128d>(x)));
#else
  for (int l = 0; l < kW; ++l)
  {
    x[l] = std::sqrt(x[l]);
  }
  return x;
#endif
}

inline Lanes Abs(Lanes x)
{
  for (int l = 0; l < kW; ++l)
  {
    x[l] = std::abs(x[l]);
  }
  return x;
}

// Finite lanes (x - x is 0 for them, NaN for infinities and NaN).
inline LaneMask Finite(Lanes x)
{
  return (x - x) == Splat(0.0);
}

inline bool Any(LaneMask m)
{
  long long any = 0;
  for (int l = 0; l < kW; ++l)
  {
    any |= m[l];
  }
  return any != 0;
}
} // namespace lanes

namespace detail
{
// Horner: the value of the polynomial c[0] x^(N-1) + ... + c[N-1] and its derivative, for
// doubles and for lanes.
template<int N, typename T>
T PolyEval(const T (&c)[N], T x, T& derivative)
{
  T p = c[0];
  T dp = lanes::Constant<T>(0.0);
  for (int i = 1; i < N; ++i)
  {
    dp = dp * x + p;
    p = p * x + c[i];
  }
  derivative = dp;
  return p;
}
} // namespace detail
} // namespace catar

#endif
