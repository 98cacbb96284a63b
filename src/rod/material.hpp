// Material and cross-section of a rod, and the stiffnesses they give.
//
// The cross-section lies in the plane of the material frame (d1, d2):
// `width` is measured along d1 and `height` along d2. In a linkage d2 is the
// joint normal, so `width` lies in the plane of the joints. Units: lengths in
// the input's length unit, the modulus in force per area, the density in
// mass per volume; the stiffnesses follow (EA a force, EI and GJ a force
// times an area).
//
// Bending convention (Bergou et al.): kappa_1 = kb . d2 is the curvature of
// the centerline towards d1, i.e. bending about the d2 axis, so its stiffness
// B1 uses the second moment about d2: E w^3 h / 12 for a w x h rectangle.
// kappa_2 = -kb . d1 bends about d1 with B2 = E w h^3 / 12.
#pragma once

namespace xshell {

enum class SectionShape { Rectangle, Ellipse };

struct CrossSection {
  SectionShape shape = SectionShape::Rectangle;
  double width = 0.01;   // along d1
  double height = 0.01;  // along d2
};

struct Material {
  double young_modulus = 1.0;  // E
  double poisson_ratio = 0.3;  // nu, in (-1, 0.5)
  double density = 0.0;        // mass per volume
  CrossSection section;
  double strength = 0.0;  // allowable stress for utilisation reports; 0: none
};

struct RodStiffness {
  double stretching = 0.0;                     // EA
  double bending1 = 0.0;                       // B1: E I about the d2 axis (for kappa_1)
  double bending2 = 0.0;                       // B2: E I about the d1 axis (for kappa_2)
  double twisting = 0.0;                       // GJ, G = E / (2 (1 + nu))
  double area = 0.0;                           // A
  double mass_per_length = 0.0;                // density * A
  double rotational_inertia_per_length = 0.0;  // density * (I_d1 + I_d2)
  double polar_moment = 0.0;                   // I_d1 + I_d2 (length^4)
};

// Section properties:
//   rectangle w x h: A = w h, I_d2 = w^3 h / 12, I_d1 = w h^3 / 12,
//     J = a b^3 (1/3 - 0.21 (b/a)(1 - b^4 / (12 a^4))) with a = max, b = min
//     (Roark's approximation, within 0.5% for all aspect ratios);
//   ellipse with semi-axes a = w/2, b = h/2: A = pi a b, I_d2 = pi a^3 b / 4,
//     I_d1 = pi a b^3 / 4, J = pi a^3 b^3 / (a^2 + b^2).
RodStiffness stiffness(const Material& material);

}  // namespace xshell
