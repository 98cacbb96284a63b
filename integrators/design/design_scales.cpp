#include "integrators/design/design_scales.hpp"

#include <algorithm>
#include <cmath>

#include "rod/material.hpp"

namespace xshell {

double bending_energy_scale(const RodLinkage& linkage, double diagonal) {
  const std::vector<double> lengths = linkage.segment_rest_lengths();
  double sum = 0.0;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const RodStiffness k = stiffness(linkage.segment_material(s));
    sum += 0.5 * std::min(k.bending1, k.bending2) * lengths[s];
  }
  return sum / std::max(diagonal * diagonal, 1e-300);
}

DesignScales design_scales(int targets, double diagonal, double energy_scale, int parameters) {
  DesignScales s;
  s.fit = 0.5 * std::max(targets, 1) * std::max(diagonal * diagonal, 1e-300);
  s.energy = energy_scale > 0.0 && std::isfinite(energy_scale) ? energy_scale : 1.0;
  s.regularization = 0.5 * std::max(parameters, 1);
  return s;
}

namespace {

// Each of the four terms' fields divided by its scale (DesignWeights and
// DesignTerms share their fields' names).
template <typename T>
T divided(const T& v, const DesignScales& scales) {
  T out;
  out.fit = v.fit / scales.fit;
  out.deployed_energy = v.deployed_energy / scales.energy;
  out.flat_energy = v.flat_energy / scales.energy;
  out.regularization = v.regularization / scales.regularization;
  return out;
}

}  // namespace

DesignWeights scaled_weights(const DesignWeights& unit_free, const DesignScales& scales) {
  return divided(unit_free, scales);
}

DesignTerms unit_free_terms(const DesignTerms& terms, const DesignScales& scales) {
  return divided(terms, scales);
}

}  // namespace xshell
