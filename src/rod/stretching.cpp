#include "stretching.hpp"

namespace xshell {

double stretching_energy(const Eigen::Vector3d& e, double rest_length, double k) {
  const double strain = e.norm() / rest_length - 1.0;
  return 0.5 * k * strain * strain * rest_length;
}

Eigen::Vector3d stretching_gradient(const Eigen::Vector3d& e, double rest_length, double k) {
  const double len = e.norm();
  return k * (len / rest_length - 1.0) * (e / len);
}

Eigen::Matrix3d stretching_hessian(const Eigen::Vector3d& e, double rest_length, double k) {
  return stretching_hessian(e, rest_length, k, axial_force(e, rest_length, k));
}

Eigen::Matrix3d stretching_hessian(const Eigen::Vector3d& e, double rest_length, double k,
                                   double force) {
  const double len = e.norm();
  const Eigen::Vector3d t = e / len;
  const Eigen::Matrix3d tt = t * t.transpose();
  return (k / rest_length) * tt + (force / len) * (Eigen::Matrix3d::Identity() - tt);
}

double axial_force(const Eigen::Vector3d& e, double rest_length, double k) {
  return k * (e.norm() / rest_length - 1.0);
}

}  // namespace xshell
