// Pearson's chi-squared goodness-of-fit test for the sampling tests: the
// chi-squared distribution's upper tail through the regularized incomplete gamma
// function (series below x < a + 1, Lentz's continued fraction above, both to
// double precision), cells with a low expected count pooled, and the Sidak
// per-test level for a family of tests.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace penumbra::chi2 {

// The prefactor x^a e^-x / Gamma(a) of both expansions, in logs (no overflow for
// the hundreds of degrees of freedom a 10 x 20 grid has).
inline double gammaPrefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

// P(a, x) = gamma(a, x) / Gamma(a) by its power series; converges fast for x < a + 1.
inline double gammaPSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 100000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * gammaPrefactor(a, x);
}

// Q(a, x) = Gamma(a, x) / Gamma(a) by its continued fraction (modified Lentz);
// converges fast for x >= a + 1.
inline double gammaQFraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < 1e-16) break;
  }
  return h * gammaPrefactor(a, x);
}

// The regularized lower and upper incomplete gamma functions, P + Q = 1.
inline double gammaP(double a, double x) {
  if (x <= 0.0) return 0.0;
  return x < a + 1.0 ? gammaPSeries(a, x) : 1.0 - gammaQFraction(a, x);
}
inline double gammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  return x < a + 1.0 ? 1.0 - gammaPSeries(a, x) : gammaQFraction(a, x);
}

// The chi-squared distribution with `dof` degrees of freedom: CDF and upper tail
// (the p-value of a statistic `x`), computed without 1 - CDF cancellation.
inline double cdf(double x, int dof) { return gammaP(0.5 * dof, 0.5 * x); }
inline double pValue(double x, int dof) { return gammaQ(0.5 * dof, 0.5 * x); }

// Sidak: the level each of `tests` independent tests must pass at for the family
// to reject a correct sampler with probability `alpha`.
inline double sidakLevel(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

struct Result {
  double statistic = 0.0;
  int dof = 0;
  double pValue = 1.0;
  std::string failure;  // non-empty: samples where nothing is expected
  std::string worst;    // the cells contributing most, for the failure message
};

// Pearson's statistic over cells with observed counts `observed` and expected
// counts `expected` (the same total). Cells expecting fewer than `minExpected`
// are pooled, smallest first, into one cell; cells expecting nothing must see at
// most `strayFraction` of `samples` (float rounding at a lobe's edge).
inline Result test(const std::vector<double>& observed, const std::vector<double>& expected, double samples,
                   double minExpected = 5.0, double strayFraction = 1e-5) {
  Result r;
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double pooledObs = 0.0, pooledExp = 0.0, stray = 0.0;
  std::vector<std::pair<double, size_t>> terms;
  for (size_t i : order) {
    const double e = expected[i], o = observed[i];
    if (e <= 0.0) {
      stray += o;
    } else if (e < minExpected || (pooledExp > 0.0 && pooledExp < minExpected)) {
      pooledObs += o;
      pooledExp += e;
    } else {
      r.statistic += (o - e) * (o - e) / e;
      terms.push_back({(o - e) * (o - e) / e, i});
      ++r.dof;
    }
  }
  if (stray > strayFraction * samples) {
    r.failure = std::to_string(stray) + " samples in cells where the pdf is zero";
  }
  if (pooledExp > 0.0) {
    r.statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
    ++r.dof;
  }
  r.dof -= 1;  // the counts' total is fixed; no parameter is estimated from them
  if (r.dof < 1) {
    r.failure += " (fewer than 2 cells with enough expected samples)";
    return r;
  }
  r.pValue = pValue(r.statistic, r.dof);
  std::sort(terms.rbegin(), terms.rend());
  std::ostringstream worst;
  for (size_t k = 0; k < std::min<size_t>(5, terms.size()); ++k) {
    const size_t i = terms[k].second;
    worst << " cell " << i << ": observed " << observed[i] << ", expected " << expected[i] << ";";
  }
  r.worst = worst.str();
  return r;
}

}  // namespace penumbra::chi2
