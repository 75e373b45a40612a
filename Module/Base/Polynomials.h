// CatadioptricAR Core: real roots of polynomials of degree 2 to 4 in closed form (numerically
// stable quadratic, Cardano / trigonometric cubic, Ferrari quartic), each root polished by
// Newton's method. The mirrors' reflection equations reduce to them.
#ifndef catarPolynomials_h
#define catarPolynomials_h

namespace catar
{
namespace detail
{
/// Real roots of a x^2 + b x + c (a stable form; a tiny negative discriminant gives a double
/// root; degree reduction when a is 0). Returns the number of roots written.
int SolveQuadratic(double a, double b, double c, double roots[2]);
/// Real roots of c3 x^3 + c2 x^2 + c1 x + c0 (Cardano / trigonometric). Returns the count.
int SolveCubic(double c3, double c2, double c1, double c0, double roots[3]);
/// Real roots of c4 x^4 + c3 x^3 + c2 x^2 + c1 x + c0 (closed form: Ferrari / Cardano, with
/// degree reduction when leading coefficients vanish). Returns the number of roots written.
int SolveQuartic(double c4, double c3, double c2, double c1, double c0, double roots[4]);
} // namespace detail
} // namespace catar

#endif
