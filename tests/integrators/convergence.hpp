// Convergence-order measurements from a sequence of errors (for example
// gradient measures e_k after k Newton iterations).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace xshell::test {

struct ObservedOrders {
  int pairs = 0;                        // pairs (e_k, e_{k+1}) in the local regime
  double max_quadratic_constant = 0.0;  // max e_{k+1} / e_k^2 over them
  double min_log_ratio = INFINITY;      // min log(e_{k+1}) / log(e_k) over them
};

// Pairs with e_k < local (the local regime) and e_{k+1} > floor (above the
// round-off level of the gradient). Quadratic convergence: the constant
// stays bounded; linear convergence with rate r makes it r / e_k, which
// blows up as e_k -> 0.
inline ObservedOrders observed_orders(const std::vector<double>& errors, double local = 1e-2,
                                      double floor = 1e-12) {
  ObservedOrders result;
  for (size_t k = 0; k + 1 < errors.size(); ++k) {
    const double a = errors[k], b = errors[k + 1];
    if (!(a < local) || !(b > floor)) continue;
    ++result.pairs;
    result.max_quadratic_constant = std::max(result.max_quadratic_constant, b / (a * a));
    result.min_log_ratio = std::min(result.min_log_ratio, std::log(b) / std::log(a));
  }
  return result;
}

}  // namespace xshell::test
