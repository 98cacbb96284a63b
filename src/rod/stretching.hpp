// Stretching energy of one rod edge e = x_{j+1} - x_j with rest length l:
//   E = 1/2 k (|e| / l - 1)^2 l,   k = EA (times a share factor, see ElasticRod)
//   dE/de   = k (|e|/l - 1) t
//   d2E/de2 = (k / l) t t^T + k (|e|/l - 1) / |e| (I - t t^T),   t = e / |e|.
// N = k (|e|/l - 1) is the edge's axial force (dE/de = N t); the Hessian's
// second term, N / |e| (I - t t^T), is its geometric stiffness.
// Derivatives with respect to the nodes follow from de/dx_j = -I,
// de/dx_{j+1} = I.
#pragma once

#include <Eigen/Core>

namespace xshell {

double stretching_energy(const Eigen::Vector3d& e, double rest_length, double k);
Eigen::Vector3d stretching_gradient(const Eigen::Vector3d& e, double rest_length, double k);
Eigen::Matrix3d stretching_hessian(const Eigen::Vector3d& e, double rest_length, double k);
// The same with the geometric stiffness of a given axial force N instead of
// the edge's own (Newton's mixed Hessian, docs/model.md section 9.8).
Eigen::Matrix3d stretching_hessian(const Eigen::Vector3d& e, double rest_length, double k,
                                   double force);
// N = k (|e|/l - 1).
double axial_force(const Eigen::Vector3d& e, double rest_length, double k);

}  // namespace xshell
