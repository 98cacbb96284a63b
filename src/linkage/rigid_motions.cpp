#include "rigid_motions.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace xshell {

namespace {

// Singular values below this (of equations scaled to O(1)) count as zero.
constexpr double kRankTolerance = 1e-9;

// Orthonormal basis (columns) of the null space of `a` (n columns).
Eigen::MatrixXd null_space(const Eigen::MatrixXd& a, int n) {
  if (a.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  int rank = 0;
  for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i)
    if (svd.singularValues()[i] > kRankTolerance) ++rank;
  return svd.matrixV().rightCols(n - rank);
}

// Orthonormal basis (columns) of the column space of `a` (3 rows).
Eigen::MatrixXd column_space(const Eigen::MatrixXd& a) {
  if (a.cols() == 0) return Eigen::MatrixXd(3, 0);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU);
  int rank = 0;
  for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i)
    if (svd.singularValues()[i] > kRankTolerance) ++rank;
  return svd.matrixU().leftCols(rank);
}

// The same subspace as the orthonormal columns of `basis` (3 x k), spelled
// with the coordinate axes it contains first, then completed.
std::vector<Eigen::Vector3d> readable_basis(const Eigen::MatrixXd& basis) {
  std::vector<Eigen::Vector3d> out;
  auto add_if_new = [&](Eigen::Vector3d v) {
    for (const auto& u : out) v -= u.dot(v) * u;
    if (v.norm() < 1e-6) return;
    out.push_back(v.normalized());
  };
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
    if ((e - basis * (basis.transpose() * e)).norm() < 1e-6) add_if_new(e);
  }
  for (Eigen::Index c = 0; c < basis.cols() && static_cast<Eigen::Index>(out.size()) < basis.cols();
       ++c)
    add_if_new(basis.col(c));
  return out;
}

std::string direction_text(const Eigen::Vector3d& d) {
  static const char* const kAxes[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(std::abs(d[axis]) - 1.0) < 1e-9) return kAxes[axis];
  char text[96];
  std::snprintf(text, sizeof text, "[%.3g, %.3g, %.3g]", d.x(), d.y(), d.z());
  return text;
}

}  // namespace

std::vector<RigidMotion> free_rigid_motions(const std::vector<VertexSupport>& supports,
                                            const std::vector<Eigen::Vector3d>& vertex_positions) {
  // Unknowns (tau, omega): tau = t + w x c, omega = L w, with c the centroid
  // and L the size of the vertices, so that every equation is O(1).
  const int nv = static_cast<int>(vertex_positions.size());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& x : vertex_positions) c += x;
  if (nv > 0) c /= nv;
  double size = 0.0;
  for (const auto& x : vertex_positions) size = std::max(size, (x - c).norm());
  if (!(size > 0.0) || !std::isfinite(size)) size = 1.0;

  std::vector<Eigen::Matrix<double, 1, 6>> rows;
  for (const VertexSupport& s : supports) {
    if (s.vertex < 0 || s.vertex >= nv) continue;
    const Eigen::Vector3d x = (vertex_positions[s.vertex] - c) / size;
    auto hold_component = [&](int axis) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
      Eigen::Matrix<double, 1, 6> row;
      row << e.transpose(), x.cross(e).transpose();
      rows.push_back(row);
    };
    for (SupportDof dof : s.fix) switch (dof) {
        case SupportDof::Position:
          for (int axis = 0; axis < 3; ++axis) hold_component(axis);
          break;
        case SupportDof::X:
          hold_component(0);
          break;
        case SupportDof::Y:
          hold_component(1);
          break;
        case SupportDof::Z:
          hold_component(2);
          break;
        case SupportDof::Orientation:
          for (int axis = 0; axis < 3; ++axis) {
            Eigen::Matrix<double, 1, 6> row = Eigen::Matrix<double, 1, 6>::Zero();
            row(3 + axis) = 1.0;
            rows.push_back(row);
          }
          break;
        case SupportDof::OpeningAngle:
          break;
      }
  }
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), 6);
  for (std::size_t i = 0; i < rows.size(); ++i) a.row(static_cast<Eigen::Index>(i)) = rows[i];

  std::vector<RigidMotion> motions;
  // Translations: (tau, 0) with A_tau tau = 0.
  const Eigen::MatrixXd translations = null_space(a.leftCols(3), 3);
  for (const Eigen::Vector3d& d : readable_basis(translations))
    motions.push_back({RigidMotion::Kind::Translation, d, Eigen::Vector3d::Zero()});
  // Rotations: the omega parts of the null space, each with a tau that
  // completes it; the axis passes through c + L (u x tau) for unit u.
  const Eigen::MatrixXd free = null_space(a, 6);
  if (free.cols() == 0) return motions;
  const Eigen::MatrixXd omegas = free.bottomRows(3);
  const Eigen::JacobiSVD<Eigen::MatrixXd> solve(omegas, Eigen::ComputeThinU | Eigen::ComputeThinV);
  for (const Eigen::Vector3d& u : readable_basis(column_space(omegas))) {
    const Eigen::VectorXd coefficients = solve.solve(u);
    const Eigen::Vector3d tau = free.topRows(3) * coefficients;
    motions.push_back({RigidMotion::Kind::Rotation, u, c + size * u.cross(tau)});
  }
  return motions;
}

std::string describe(const std::vector<RigidMotion>& motions, const Eigen::Vector3d& origin) {
  std::string text;
  for (const RigidMotion& m : motions) {
    if (!text.empty()) text += "; ";
    if (m.kind == RigidMotion::Kind::Translation) {
      text += "translation along " + direction_text(m.direction);
    } else {
      const Eigen::Vector3d p = m.point + origin;
      char point[112];
      std::snprintf(point, sizeof point, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
      text += "rotation about " + direction_text(m.direction) + " through " + point;
    }
  }
  return text;
}

}  // namespace xshell
