// Actuation of a linkage by its average opening angle: one linear equality
// on the free unknowns q (size n),
//   a . q = A   with   a_k = 1/N on the free opening angles, 0 elsewhere,
// i.e. (1/N) (sum of the free alphas + sum of the fixed ones) = A over all N
// joints. Its multiplier tau (grad E = tau a at a constrained equilibrium)
// is the actuation torque dE/dA, energy per radian, positive when the
// linkage resists further opening.
//
// Two ways to enforce it, both here:
//  - with a multiplier (constrained_newton.hpp): a = coefficients();
//  - by a change of variables q = c + B z over the constraint's null space
//    (constrained_objective.hpp). B is sparse: with the averaged unknowns
//    (members) tied into a spanning tree of the linkage graph, every member
//    k but the root has the column e_k - e_parent(k) and every other unknown
//    its unit column, so z is q without the root's entry, and a member's z
//    is its offset carried to the root. A column couples only two
//    neighbouring joints, so B^T H B is about as sparse as H (eliminating
//    one alpha instead would couple every alpha with the neighbourhood of
//    the eliminated one).
// Layout of z: q's order with the root member's entry left out.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "linkage/statics_problem.hpp"

namespace xshell {

class AverageConstraint {
 public:
  // size: n, the number of free unknowns. members: free indices of the
  // averaged unknowns (distinct, non-empty). parent: per member, the
  // position in `members` of its parent in a spanning tree, -1 for exactly
  // one root. count: N >= members.size(), the number of averaged
  // quantities. fixed_sum: the sum of those that are not free unknowns.
  // Throws std::invalid_argument for inconsistent arguments.
  AverageConstraint(Eigen::Index size, std::vector<int> members, std::vector<int> parent, int count,
                    double fixed_sum);

  Eigen::Index size() const { return size_; }
  Eigen::Index reduced_size() const { return size_ - 1; }
  const std::vector<int>& members() const { return members_; }
  int count() const { return count_; }

  // a (n): 1/N on the members.
  const Eigen::VectorXd& coefficients() const { return a_; }
  // The average a . q + fixed_sum / N of q (n).
  double value(const Eigen::VectorXd& q) const;
  // Shifts every member by the same amount so that value(q) = target.
  void project(Eigen::VectorXd& q, double target) const;
  // Least-squares multiplier a.g / a.a of a gradient g (n): the torque when
  // g = tau a, i.e. at a constrained equilibrium.
  double multiplier(const Eigen::VectorXd& g) const;
  // g - multiplier(g) a: the part of g that the constraint does not absorb.
  Eigen::VectorXd projected(const Eigen::VectorXd& g) const;

  // The null-space basis B (n x (n-1)), applied without forming it.
  Eigen::VectorXd expand(const Eigen::VectorXd& z) const;    // B z
  Eigen::VectorXd restrict(const Eigen::VectorXd& g) const;  // B^T g
  // z with B z = dq, for dq whose members sum to 0 (a . dq = 0).
  Eigen::VectorXd coordinates(const Eigen::VectorXd& dq) const;
  // B^T H B for H (n x n, both triangles); both triangles, and its pattern
  // depends only on H's pattern. The scatter from H's entries to the
  // result's is planned once per pattern and kept (so one constraint
  // serves one thread at a time); `out` keeps its storage when its pattern
  // is already the result's.
  Eigen::SparseMatrix<double> reduce(const Eigen::SparseMatrix<double>& H) const;
  void reduce(const Eigen::SparseMatrix<double>& H, Eigen::SparseMatrix<double>& out) const;
  // diag(B^T diag(m) B): a lumped mass in z.
  Eigen::VectorXd reduce_diagonal(const Eigen::VectorXd& m) const;
  // Per-entry weights (n) carried to z (n-1): each z entry keeps the weight
  // of its own q entry.
  Eigen::VectorXd reduce_weights(const Eigen::VectorXd& w) const;

 private:
  Eigen::Index size_;
  std::vector<int> members_, parent_;  // parent_: free index of the parent, -1 for the root
  int count_;
  double fixed_sum_;
  int root_;                                // free index of the root member
  std::vector<int> member_order_;           // free indices of the members, parents before children
  std::vector<std::vector<int>> children_;  // per free index (empty for non-members)
  Eigen::VectorXd a_;
  // reduce()'s plan for the last pattern of H: H's entry k adds
  // sign[j] * H_k to the result's entry dest[j], j in [start[k], start[k+1]).
  struct ReducePlan {
    std::vector<int> outer, inner;        // H's pattern
    Eigen::SparseMatrix<double> pattern;  // the result's
    std::vector<int> start, dest;
    std::vector<double> sign;
  };
  mutable ReducePlan plan_;
  int z_index(int i) const { return i < root_ ? i : i - 1; }  // i != root_
  // Calls f(z row, B entry) for the nonzeros of row i of B.
  template <class F>
  void for_row(int i, F&& f) const {
    if (i != root_) f(z_index(i), 1.0);
    for (int c : children_[i]) f(z_index(c), -1.0);
  }
  bool planned_for(const Eigen::SparseMatrix<double>& H) const;
  void plan_for(const Eigen::SparseMatrix<double>& H) const;
};

// The average opening angle over all joints of `problem`'s linkage, as a
// constraint on its free unknowns; the tree follows the linkage graph
// breadth first (a member's parent is its nearest member ancestor). Throws
// std::invalid_argument when every opening angle is fixed.
AverageConstraint average_opening_angle_constraint(const LinkageProblem& problem);

// The mean opening angle over all joints (radians).
double average_opening_angle(const RodLinkage& linkage);

}  // namespace xshell
