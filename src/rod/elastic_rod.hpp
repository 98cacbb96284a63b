// A discrete elastic rod (Bergou et al. 2008, 2010): nodes x_0..x_n and one
// material angle theta_j per edge, measured from the edge's reference frame,
// which is parallel-transported in time from a stored source frame
// (frames.hpp).
//
// Unknowns of a rod, in this order ("full" variables, as the linkage's chain
// rule sees them):
//   [x_0 (3), x_1 (3), ..., x_n (3), theta_0, ..., theta_{n-1}],
// 3 (n + 1) + n in all.
//
// Energy = stretching (per edge, stretching.hpp) + bending and twisting (per
// interior vertex, vertex_stencil.hpp). The rest state (rest lengths, rest
// material curvatures on each side of every vertex, rest twists) is taken
// from a configuration (set_rest_state_from_current), so a rod built from a
// polyline has zero energy there, or set explicitly.
//
// Each edge's stretching stiffness carries a share factor (default 1): the
// linkage gives 1/2 to the terminal edges at joints, which two segments own.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "frames.hpp"
#include "material.hpp"
#include "vertex_stencil.hpp"

namespace xshell {

struct RodEnergy {
  double stretching = 0.0, bending = 0.0, twisting = 0.0;
  double total() const { return stretching + bending + twisting; }
  RodEnergy& operator+=(const RodEnergy& o) {
    stretching += o.stretching;
    bending += o.bending;
    twisting += o.twisting;
    return *this;
  }
};

class ElasticRod {
 public:
  // A rod through `nodes` (at least 2) with a twist-free frame: edge 0's d1
  // is `first_d1` projected orthogonal to the edge (any perpendicular when
  // null), transported along the rod; thetas 0; at rest in this state.
  ElasticRod(const std::vector<Eigen::Vector3d>& nodes, const RodStiffness& stiffness,
             const Eigen::Vector3d* first_d1 = nullptr);
  // A rod with given source frames (one per edge, each tangent equal to its
  // edge's direction) and thetas; at rest in this state.
  ElasticRod(const std::vector<Eigen::Vector3d>& nodes, std::vector<SourceFrame> source_frames,
             const std::vector<double>& thetas, const RodStiffness& stiffness);

  int num_edges() const { return static_cast<int>(thetas_.size()); }
  int num_nodes() const { return num_edges() + 1; }
  int num_dofs() const { return 3 * num_nodes() + num_edges(); }
  static int node_dof(int node) { return 3 * node; }
  int theta_dof(int edge) const { return 3 * num_nodes() + edge; }

  // Configuration.
  const std::vector<Eigen::Vector3d>& nodes() const { return nodes_; }
  const std::vector<double>& thetas() const { return thetas_; }
  void set_configuration(const std::vector<Eigen::Vector3d>& nodes,
                         const std::vector<double>& thetas);
  Eigen::VectorXd dofs() const;
  void set_dofs(const Eigen::VectorXd& dofs);

  // Frames at the current configuration.
  Eigen::Vector3d edge(int j) const { return nodes_[j + 1] - nodes_[j]; }
  Eigen::Vector3d tangent(int j) const { return edge(j).normalized(); }
  const Frame<double>& reference_frame(int j) const { return reference_[j]; }
  Frame<double> material_frame(int j) const;
  const std::vector<SourceFrame>& source_frames() const { return source_; }
  // Reference twist at interior vertex i (1 <= i <= n - 1).
  double reference_twist(int i) const { return reference_twist_[i]; }
  // Reference twists at the last source update (the branch each reference
  // twist is unwrapped towards), per node.
  const std::vector<double>& twist_hints() const { return twist_hint_; }
  // Restores a saved configuration with its source frames and twist hints.
  void restore(const std::vector<Eigen::Vector3d>& nodes, const std::vector<double>& thetas,
               const std::vector<SourceFrame>& source_frames,
               const std::vector<double>& twist_hints);
  // Moves every source frame to the current reference frame: nothing about
  // the configuration or the energy changes.
  void update_source_frames();

  // Rest state.
  void set_rest_state_from_current();
  // Zero rest curvature and twist (a straight, untwisted rod at rest), rest
  // lengths unchanged.
  void set_rest_straight();
  const std::vector<double>& rest_lengths() const { return rest_length_; }
  // Rest material curvatures at interior vertex i, [edge side][kappa1,
  // kappa2], and its rest twist.
  const std::array<std::array<double, 2>, 2>& rest_kappa(int i) const { return rest_kappa_[i]; }
  double rest_twist(int i) const { return rest_twist_[i]; }
  void set_rest_lengths(const std::vector<double>& lengths) { rest_length_ = lengths; }
  void set_stretching_share(int edge, double share) { stretching_share_[edge] = share; }
  double stretching_share(int edge) const { return stretching_share_[edge]; }
  const RodStiffness& stiffness() const { return stiffness_; }
  // Voronoi length of interior vertex i: half the sum of its edges' rest lengths.
  double voronoi_length(int i) const { return 0.5 * (rest_length_[i - 1] + rest_length_[i]); }

  // Energy, its gradient (num_dofs()) and Hessian (num_dofs() square,
  // symmetric, both triangles; triplets are appended with the rod's own
  // indices shifted by `offset`).
  RodEnergy energy() const;
  // Energy of each part, per element, for outputs: stretching per edge,
  // bending and twisting per node (0 at the two end nodes).
  void energy_per_element(std::vector<double>& stretching, std::vector<double>& bending,
                          std::vector<double>& twisting) const;
  Eigen::VectorXd gradient() const;
  void hessian_triplets(std::vector<Eigen::Triplet<double>>& triplets, int offset = 0) const;
  Eigen::SparseMatrix<double> hessian() const;
  // Adds the Hessian to a dense num_dofs() square matrix.
  void add_hessian(Eigen::MatrixXd& hessian) const;
  // Adds the gradient to g (num_dofs()); allocates nothing.
  void add_gradient(Eigen::Ref<Eigen::VectorXd> g) const;
  // Adds the gradient to g (num_dofs()) and the Hessian to h (dense,
  // num_dofs() square) in one pass over the stencils; allocates nothing.
  // With hessian_axial_forces (one per edge), the stretching Hessian's
  // geometric stiffness takes those axial forces instead of the edges' own
  // (Newton's mixed Hessian, docs/model.md section 9.8); g stays exact.
  void add_gradient_and_hessian(Eigen::Ref<Eigen::VectorXd> g, Eigen::Ref<Eigen::MatrixXd> h,
                                const Eigen::VectorXd* hessian_axial_forces = nullptr) const;
  // Edge j's axial force N_j = k_j (|e_j| / l_j - 1) (stretching.hpp).
  double axial_force(int j) const;
  // The axial forces linearized along a velocity v of the full variables
  // (num_dofs()): N_j + k_j t_j . (v_{j+1} - v_j) / l_j, one per edge.
  Eigen::VectorXd linearized_axial_forces(const Eigen::VectorXd& velocity) const;
  // max_j |v_{j+1} - v_j| / l_j: the largest change of an edge vector along
  // a velocity v of the full variables, relative to its rest length.
  double largest_edge_change(const Eigen::VectorXd& velocity) const;
  // Structure of the Hessian: true where some stencil can make an entry
  // nonzero (num_dofs() square, symmetric). Depends on num_edges() only.
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> hessian_pattern() const;

  // Lumped masses of the full variables (num_dofs()): each edge's mass
  // (mass per length x rest length x share) split between its two nodes,
  // and each theta's rotational inertia (per length x rest length x share).
  // With unit_density, the masses the rod would have at density 1.
  Eigen::VectorXd lumped_mass(bool unit_density = false) const;
  // Per node (num_nodes()), its share of the rod's rest length: half of each
  // adjacent edge's rest length x share, as lumped_mass splits the masses.
  // What a dead load per unit length acts on.
  Eigen::VectorXd lumped_rest_lengths() const;

  // Strains at interior vertex i (1 <= i <= n - 1).
  VertexStrains<double> strains(int i) const;

 private:
  VertexStencil stencil(int i) const;
  VertexDofs stencil_dofs(int i) const;
  void update_reference_frames();

  RodStiffness stiffness_;
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<double> thetas_;
  std::vector<SourceFrame> source_;
  std::vector<Frame<double>> reference_;
  std::vector<double> reference_twist_;  // per node (entries 0 and n unused)
  std::vector<double> twist_hint_;       // reference twist at the last source update

  std::vector<double> rest_length_;
  std::vector<double> stretching_share_;
  std::vector<std::array<std::array<double, 2>, 2>> rest_kappa_;  // per node, [edge side][k1, k2]
  std::vector<double> rest_twist_;                                // per node
};

}  // namespace xshell
