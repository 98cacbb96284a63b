// Internal forces of a discrete elastic rod, from the derivatives of its
// energy with respect to its strains (elastic_rod.hpp, vertex_stencil.hpp):
//   axial force per edge j   N_j = EA (|e_j| / l_j - 1)         (tension > 0)
//   bending moments at interior vertex i, averaged over the material
//   frames of its two edges (the energy does the same):
//     M1_i = B1 / V_i * 1/2 sum_j (kappa1^j - kappa1_rest^j)    about d2
//     M2_i = B2 / V_i * 1/2 sum_j (kappa2^j - kappa2_rest^j)    about d1
//   torque at interior vertex i  T_i = GJ (m_i - m_rest_i) / V_i
// where kappa are the integrated curvatures (2 tan(phi/2) for a turning
// angle phi), so M = B x pointwise curvature change. N is the full edge's
// force whatever share of its stiffness the rod owns (a terminal edge at a
// joint is shared by two segments, each with half the stiffness and the
// same strain). In the small-load limit these are the moments of beam
// theory: for a cantilever, M at a vertex is the tip load times its lever.
//
// Per edge, the moments and torque are the mean of the two vertices that
// bound it; at the first and last edge of a rod only one of them is
// interior, and its value is used.
// Units: N in the force unit, M and T in force x length.
#pragma once

#include <vector>

#include "elastic_rod.hpp"
#include "section_stress.hpp"

namespace xshell {

// Moments and torque at interior vertex i (1 <= i <= num_edges() - 1).
SectionForces vertex_moments(const ElasticRod& rod, int i);

// Per edge (num_edges() entries): N, and the moments as described above.
std::vector<SectionForces> edge_forces(const ElasticRod& rod);

}  // namespace xshell
