// Derivatives of a rod's energy and gradient with respect to a uniform
// scale of its rest lengths, l_j -> lambda l_j, at lambda = 1 (the design
// parameters of docs/model.md section 3.8 and section 9.7 scale each
// segment's edges by one factor).
//
// Stretching, per edge (stretching.hpp), E = k/2 (|e|/l - 1)^2 l:
//   l dE/dl = -k/2 (|e|^2/l^2 - 1) l,   l d(dE/de)/dl = -k e / l.
// Bending and twisting at vertex i carry the rest lengths only through the
// prefactor 1/V_i, V_i = (l_{i-1} + l_i)/2, which scales with lambda, and
// nothing else (rest curvatures and twists are length-free), so
//   dE_i/dlambda = -E_i,   d(grad E_i)/dlambda = -grad E_i.
// Unknowns: the rod's full variables (elastic_rod.hpp).
#pragma once

#include <Eigen/Core>

#include "elastic_rod.hpp"

namespace xshell {

// dE/dlambda of the rod's elastic energy (energy units).
double rest_scale_energy_derivative(const ElasticRod& rod);

// d(grad E)/dlambda (num_dofs()), grad E as ElasticRod::gradient().
Eigen::VectorXd rest_scale_gradient_derivative(const ElasticRod& rod);

}  // namespace xshell
