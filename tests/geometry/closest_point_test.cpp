#include "geometry/closest_point.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace xshell::test {

namespace {

// q is the projection of p onto the convex triangle abc exactly when q lies
// in the triangle and (p - q) . (v - q) <= 0 for its three vertices v.
void check_projection(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double scale = (b - a).norm() + (c - a).norm() + (p - a).norm();
  for (const Eigen::Vector3d& v : {a, b, c}) CHECK((p - q).dot(v - q) <= 1e-12 * scale * scale);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  CHECK(std::abs((q - a).dot(n)) <= 1e-12 * scale * n.norm());
  // Barycentric coordinates of q, all >= 0.
  const double area = n.squaredNorm();
  const double u = (c - b).cross(q - b).dot(n) / area, v = (a - c).cross(q - c).dot(n) / area;
  CHECK(u >= -1e-12);
  CHECK(v >= -1e-12);
  CHECK(1 - u - v >= -1e-12);
}

// A wavy height field z = f(x, y) over [0, 1]^2, n x n quads, two triangles each.
void wavy_mesh(int n, std::vector<Eigen::Vector3d>& vertices,
               std::vector<std::array<int, 3>>& triangles) {
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = double(j) / n, y = double(i) / n;
      vertices.emplace_back(x, y, 0.2 * std::sin(5 * x) * std::cos(4 * y));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * (n + 1) + j;
      triangles.push_back({v, v + 1, v + n + 2});
      triangles.push_back({v, v + n + 2, v + n + 1});
    }
}

}  // namespace

TEST_CASE("The closest point on a triangle is its projection in every region") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  auto random_point = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d a = random_point(), b = random_point(), c = random_point();
    const Eigen::Vector3d p = 2.0 * random_point();
    check_projection(p, closest_point_on_triangle(p, a, b, c), a, b, c);
  }
  // The regions by construction: inside, each edge and each vertex.
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(closest_point_on_triangle({0.2, 0.3, 5}, a, b, c).isApprox(Eigen::Vector3d(0.2, 0.3, 0)));
  CHECK(closest_point_on_triangle({0.5, -2, 1}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0, 0)));
  CHECK(closest_point_on_triangle({1, 1, -1}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  CHECK(closest_point_on_triangle({-1, -1, 0}, a, b, c) == a);
  CHECK(closest_point_on_triangle({3, -0.5, 0}, a, b, c) == b);
  CHECK(closest_point_on_triangle({-0.5, 3, 0}, a, b, c) == c);
}

TEST_CASE("The closest point on a degenerate triangle lies on its longest edge") {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(3, 0, 0);
  CHECK(closest_point_on_triangle({2, 1, 0}, a, b, c).isApprox(Eigen::Vector3d(2, 0, 0)));
  CHECK(closest_point_on_triangle({5, 1, 0}, a, b, c) == c);
  CHECK(closest_point_on_triangle({-1, 0, 1}, a, a, a) == a);
}

TEST_CASE("The triangle tree finds the same closest points as a search of every triangle") {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  wavy_mesh(24, vertices, triangles);
  const TriangleTree tree(vertices, triangles);
  CHECK(tree.num_triangles() == 2 * 24 * 24);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> box(-0.5, 1.5);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d p(box(rng), box(rng), 0.8 * box(rng) - 0.4);
    double brute = INFINITY;
    for (const auto& t : triangles)
      brute = std::min(
          brute, (closest_point_on_triangle(p, vertices[t[0]], vertices[t[1]], vertices[t[2]]) - p)
                     .norm());
    const ClosestPoint hit = tree.closest(p);
    CHECK(hit.distance == doctest::Approx(brute).epsilon(1e-14).scale(1e-14));
    CHECK((hit.point - p).norm() == doctest::Approx(hit.distance));
    const auto& t = triangles[hit.triangle];
    check_projection(p, hit.point, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
}

TEST_CASE(
    "The gradient of the squared distance to a mesh is twice the offset to the closest point") {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  wavy_mesh(10, vertices, triangles);
  const TriangleTree tree(vertices, triangles);
  const Eigen::Vector3d p(0.37, 0.61, 0.45);
  const Eigen::Vector3d g = 2.0 * (p - tree.closest(p).point);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
    const double plus = tree.closest(p + e).distance, minus = tree.closest(p - e).distance;
    CHECK((plus * plus - minus * minus) / (2 * h) == doctest::Approx(g[i]).epsilon(1e-6));
  }
}

TEST_CASE("A triangle tree refuses bad meshes") {
  const std::vector<Eigen::Vector3d> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_THROWS_AS(TriangleTree(v, {}), std::invalid_argument);
  CHECK_THROWS_WITH_AS(TriangleTree(v, {{0, 1, 3}}), "triangle mesh: triangle 0 uses vertex 3 of 3",
                       std::invalid_argument);
  CHECK_THROWS_AS(TriangleTree({{0, 0, 0}, {1, 0, NAN}, {0, 1, 0}}, {{0, 1, 2}}),
                  std::invalid_argument);
  const TriangleTree one(v, {{0, 1, 2}});
  CHECK(one.closest({0.25, 0.25, 2}).distance == doctest::Approx(2.0));
  CHECK(one.closest({0.25, 0.25, 2}).triangle == 0);
}

}  // namespace xshell::test
