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

DesignWeights scaled_weights(const DesignWeights& unit_free, const DesignScales& scales) {
  DesignWeights w;
  w.fit = unit_free.fit / scales.fit;
  w.deployed_energy = unit_free.deployed_energy / scales.energy;
  w.flat_energy = unit_free.flat_energy / scales.energy;
  w.regularization = unit_free.regularization / scales.regularization;
  return w;
}

DesignTerms unit_free_terms(const DesignTerms& terms, const DesignScales& scales) {
  DesignTerms t;
  t.fit = terms.fit / scales.fit;
  t.deployed_energy = terms.deployed_energy / scales.energy;
  t.flat_energy = terms.flat_energy / scales.energy;
  t.regularization = terms.regularization / scales.regularization;
  return t;
}

}  // namespace xshell
