// Stresses in a rod's cross-section from its internal forces (linear
// elastic beam theory, Saint-Venant torsion).
//
// Section axes as in material.hpp: width w along d1, height h along d2.
// M1 bends about the d2 axis (curvature kappa_1, towards d1), so its normal
// stress varies along d1: sigma = M1 c1 / I_d2 with c1 = w / 2; M2 bends
// about d1: sigma = M2 c2 / I_d1 with c2 = h / 2. Axial stress N / A.
// Largest combined normal stress |N|/A + max over the section boundary of
// |M1 y1 / I_d2 + M2 y2 / I_d1|: for a rectangle the corner,
// |M1| c1 / I_d2 + |M2| c2 / I_d1; for an ellipse
// sqrt((M1 c1 / I_d2)^2 + (M2 c2 / I_d1)^2).
// Torsional shear tau = T / W_t with the torsional section modulus that
// goes with the torsion constant J of material.hpp (Roark, Formulas for
// Stress and Strain, table 10.1): rectangle with half sides a >= b,
//   W_t = 8 a b^2 / (3 (1 + 0.6095 r + 0.8865 r^2 - 1.8023 r^3 + 0.91 r^4)), r = b/a,
// (the maximum, at the middle of the long sides); ellipse with semi-axes
// a >= b, W_t = pi a b^2 / 2 (exact).
// Units: forces in the force unit, moments in force x length, stresses in
// force / length^2.
#pragma once

#include "material.hpp"

namespace xshell {

struct SectionModuli {
  SectionShape shape = SectionShape::Rectangle;
  double area = 0.0;             // A
  double i_d2 = 0.0, c1 = 0.0;   // second moment about d2, largest distance along d1
  double i_d1 = 0.0, c2 = 0.0;   // second moment about d1, largest distance along d2
  double torsion_modulus = 0.0;  // W_t: tau_max = T / W_t
};
SectionModuli section_moduli(const CrossSection& section);

// Internal forces at a place of a rod.
struct SectionForces {
  double axial = 0.0;    // N, tension positive
  double moment1 = 0.0;  // M1 about d2 (bending towards d1)
  double moment2 = 0.0;  // M2 about d1
  double torque = 0.0;   // T about the tangent
};

struct SectionStresses {
  double axial = 0.0;            // N / A (signed)
  double bending1 = 0.0;         // |M1| c1 / I_d2
  double bending2 = 0.0;         // |M2| c2 / I_d1
  double torsional_shear = 0.0;  // |T| / W_t
  double max_normal = 0.0;       // largest combined |normal stress| over the section
};
SectionStresses section_stresses(const SectionModuli& section, const SectionForces& forces);

}  // namespace xshell
