#include "section_stress.hpp"

#include <algorithm>
#include <cmath>

namespace xshell {

SectionModuli section_moduli(const CrossSection& s) {
  SectionModuli m;
  m.shape = s.shape;
  const double w = s.width, h = s.height;
  m.c1 = 0.5 * w;
  m.c2 = 0.5 * h;
  const double a = 0.5 * std::max(w, h), b = 0.5 * std::min(w, h);
  if (s.shape == SectionShape::Rectangle) {
    m.area = w * h;
    m.i_d2 = w * w * w * h / 12.0;
    m.i_d1 = w * h * h * h / 12.0;
    const double r = b / a;
    const double roark = 1.0 + r * (0.6095 + r * (0.8865 + r * (-1.8023 + r * 0.9100)));
    m.torsion_modulus = 8.0 * a * b * b / (3.0 * roark);
  } else {
    const double p = 0.5 * w, q = 0.5 * h;  // semi-axes along d1, d2
    m.area = M_PI * p * q;
    m.i_d2 = M_PI * p * p * p * q / 4.0;
    m.i_d1 = M_PI * p * q * q * q / 4.0;
    m.torsion_modulus = 0.5 * M_PI * a * b * b;
  }
  return m;
}

SectionStresses section_stresses(const SectionModuli& m, const SectionForces& f) {
  SectionStresses s;
  s.axial = f.axial / m.area;
  s.bending1 = std::abs(f.moment1) * m.c1 / m.i_d2;
  s.bending2 = std::abs(f.moment2) * m.c2 / m.i_d1;
  s.torsional_shear = std::abs(f.torque) / m.torsion_modulus;
  const double bending = m.shape == SectionShape::Rectangle ? s.bending1 + s.bending2
                                                            : std::hypot(s.bending1, s.bending2);
  s.max_normal = std::abs(s.axial) + bending;
  return s;
}

}  // namespace xshell
