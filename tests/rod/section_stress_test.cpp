#include "rod/section_stress.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

namespace xshell::test {

TEST_CASE("Section moduli agree with the stiffnesses and textbook torsion formulas") {
  int checked = 0;
  for (SectionShape shape : {SectionShape::Rectangle, SectionShape::Ellipse})
    for (const std::pair<double, double>& size :
         {std::pair{0.02, 0.007}, std::pair{0.007, 0.02}, std::pair{0.01, 0.01}}) {
      const double w = size.first, h = size.second;
      Material m;
      m.young_modulus = 3.0e9;
      m.section = {shape, w, h};
      const RodStiffness k = stiffness(m);
      const SectionModuli s = section_moduli(m.section);
      CHECK(m.young_modulus * s.area == doctest::Approx(k.stretching));
      CHECK(m.young_modulus * s.i_d2 == doctest::Approx(k.bending1));
      CHECK(m.young_modulus * s.i_d1 == doctest::Approx(k.bending2));
      CHECK(s.c1 == doctest::Approx(0.5 * w));
      CHECK(s.c2 == doctest::Approx(0.5 * h));
      ++checked;
    }
  CHECK(checked == 6);
  // Circle: tau = 2 T / (pi r^3). Square 2a x 2a: tau = 0.6010 T / a^3 (Roark).
  const SectionModuli circle = section_moduli({SectionShape::Ellipse, 0.02, 0.02});
  CHECK(1.0 / circle.torsion_modulus == doctest::Approx(2.0 / (M_PI * 1e-6)));
  const SectionModuli square = section_moduli({SectionShape::Rectangle, 0.02, 0.02});
  CHECK(1.0 / square.torsion_modulus == doctest::Approx(0.6010 / 1e-6).epsilon(2e-3));
  // Thin strip b x t: tau -> 3 T / (b t^2).
  const SectionModuli strip = section_moduli({SectionShape::Rectangle, 1.0, 0.001});
  CHECK(1.0 / strip.torsion_modulus == doctest::Approx(3.0 / 1e-6).epsilon(1e-3));
}

TEST_CASE("Combined normal stress: corners of a rectangle, the boundary of an ellipse") {
  const SectionForces f{-50.0, 2.0, -3.0, 0.7};
  const SectionModuli r = section_moduli({SectionShape::Rectangle, 0.04, 0.03});
  const SectionStresses sr = section_stresses(r, f);
  CHECK(sr.axial == doctest::Approx(-50.0 / (0.04 * 0.03)));
  CHECK(sr.bending1 == doctest::Approx(2.0 * 0.02 / (0.04 * 0.04 * 0.04 * 0.03 / 12.0)));
  CHECK(sr.bending2 == doctest::Approx(3.0 * 0.015 / (0.04 * 0.03 * 0.03 * 0.03 / 12.0)));
  // The corner where the three add up, found by brute force over the boundary.
  auto brute = [](const SectionModuli& m, const SectionForces& f, bool ellipse) {
    double best = 0.0;
    for (int k = 0; k < 20000; ++k) {
      const double a = 2.0 * M_PI * k / 20000.0;
      double y1 = m.c1 * std::cos(a), y2 = m.c2 * std::sin(a);
      if (!ellipse) {  // the rectangle's boundary by a square-to-circle map
        const double s = std::max(std::abs(std::cos(a)), std::abs(std::sin(a)));
        y1 = m.c1 * std::cos(a) / s;
        y2 = m.c2 * std::sin(a) / s;
      }
      best = std::max(
          best, std::abs(f.axial / m.area + f.moment1 * y1 / m.i_d2 + f.moment2 * y2 / m.i_d1));
    }
    return best;
  };
  CHECK(sr.max_normal == doctest::Approx(brute(r, f, false)).epsilon(1e-6));
  const SectionModuli e = section_moduli({SectionShape::Ellipse, 0.04, 0.03});
  const SectionForces bending{0.0, f.moment1, f.moment2, 0.0};
  CHECK(section_stresses(e, bending).max_normal ==
        doctest::Approx(brute(e, bending, true)).epsilon(1e-6));
  CHECK(sr.torsional_shear == doctest::Approx(0.7 / r.torsion_modulus));
}

}  // namespace xshell::test
