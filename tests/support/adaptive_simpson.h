// Adaptive Simpson quadrature in double for the tests' 1D reference integrals: an
// interval is halved until Richardson's estimate of its error is below its share.
#pragma once
#include <cmath>
#include <functional>

namespace penumbra::testing {

namespace detail {
inline double simpsonStep(const std::function<double(double)>& f, double a, double b, double fa, double fm,
                          double fb, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::abs(delta) <= 15.0 * tol) return left + right + delta / 15.0;
  return simpsonStep(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1) +
         simpsonStep(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
}
}  // namespace detail

// The integral of f over [a, b] to an absolute tolerance `tol`. The interval is first
// cut into `pieces` so a narrow peak cannot fall between the first samples.
inline double adaptiveSimpson(const std::function<double(double)>& f, double a, double b, double tol,
                              int pieces = 64, int depth = 40) {
  double sum = 0.0;
  for (int i = 0; i < pieces; ++i) {
    const double lo = a + (b - a) * i / pieces, hi = a + (b - a) * (i + 1) / pieces, mid = 0.5 * (lo + hi);
    const double flo = f(lo), fmid = f(mid), fhi = f(hi);
    const double whole = (hi - lo) / 6.0 * (flo + 4.0 * fmid + fhi);
    sum += detail::simpsonStep(f, lo, hi, flo, fmid, fhi, whole, tol / pieces, depth);
  }
  return sum;
}

}  // namespace penumbra::testing
