// Unit-free weights of the inverse design's objective (design_objective.hpp):
// the user weighs terms of different units (length^2, energy, none), so each
// is divided by a natural scale of the design before its weight applies:
//   fit F:            by N d^2 / 2 (N targets, d the bounding-box diagonal of
//                     the deployed start), so that 1 means a mean distance of d;
//   energies E:       by E_b = sum_s B_s L_s / (2 d^2), B_s the segment's
//                     smaller bending stiffness and L_s its rest length: the
//                     energy of bending every lath to a radius d (not the
//                     start's energy, which is 0 for a flat mechanism);
//   regularization R: by P / 2 (P rest lengths), so that 1 means a mean
//                     squared relative change of 1.
#pragma once

#include "integrators/design/design_objective.hpp"

namespace xshell {

struct DesignScales {
  double fit = 1.0, energy = 1.0, regularization = 1.0;  // the divisors above
};

// E_b of `linkage` at its rest lengths for the length d = diagonal.
double bending_energy_scale(const RodLinkage& linkage, double diagonal);

DesignScales design_scales(int targets, double diagonal, double energy_scale, int parameters);

// The model's weights (DesignWeights) of unit-free user weights.
DesignWeights scaled_weights(const DesignWeights& unit_free, const DesignScales& scales);

// The terms of J made unit-free (each divided by its scale).
DesignTerms unit_free_terms(const DesignTerms& terms, const DesignScales& scales);

}  // namespace xshell
