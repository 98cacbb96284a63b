#include "material.hpp"

#include <algorithm>
#include <cmath>

namespace xshell {

RodStiffness stiffness(const Material& m) {
  const double w = m.section.width, h = m.section.height;
  double area = 0.0, i_d2 = 0.0, i_d1 = 0.0, torsion = 0.0;
  if (m.section.shape == SectionShape::Rectangle) {
    area = w * h;
    i_d2 = w * w * w * h / 12.0;
    i_d1 = w * h * h * h / 12.0;
    const double a = std::max(w, h), b = std::min(w, h);
    const double r = b / a;
    torsion = a * b * b * b * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0));
  } else {
    const double a = 0.5 * w, b = 0.5 * h;
    area = M_PI * a * b;
    i_d2 = M_PI * a * a * a * b / 4.0;
    i_d1 = M_PI * a * b * b * b / 4.0;
    torsion = M_PI * std::pow(a, 3) * std::pow(b, 3) / (a * a + b * b);
  }
  const double shear_modulus = m.young_modulus / (2.0 * (1.0 + m.poisson_ratio));
  RodStiffness k;
  k.stretching = m.young_modulus * area;
  k.bending1 = m.young_modulus * i_d2;
  k.bending2 = m.young_modulus * i_d1;
  k.twisting = shear_modulus * torsion;
  k.area = area;
  k.mass_per_length = m.density * area;
  k.rotational_inertia_per_length = m.density * (i_d1 + i_d2);
  k.polar_moment = i_d1 + i_d2;
  return k;
}

}  // namespace xshell
