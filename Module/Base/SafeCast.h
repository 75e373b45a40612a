// CatadioptricAR Core: conversions of doubles to integers that are defined for every input. A
// cast of NaN, Inf or a value beyond the integer's range is undefined behaviour in C++; these
// give NaN a stated value and clamp the rest.
#ifndef catarSafeCast_h
#define catarSafeCast_h

#include <cmath>

namespace catar
{
/// floor(v) as a long long: NaN gives `nan`, values beyond +-2^62 are clamped to +-2^62.
inline long long FloorToInteger(double v, long long nan = 0)
{
  constexpr double kLimit = 4611686018427387904.0; // 2^62
  if (!(v == v))
  {
    return nan;
  }
  return static_cast<long long>(std::floor(v < -kLimit ? -kLimit : (v > kLimit ? kLimit : v)));
}
} // namespace catar

#endif
