#include "elastic_rod.hpp"

#include <algorithm>
#include <stdexcept>

#include "stretching.hpp"

namespace xshell {

namespace {
std::vector<SourceFrame> twist_free_frames(const std::vector<Eigen::Vector3d>& nodes,
                                           const Eigen::Vector3d* first_d1) {
  std::vector<SourceFrame> frames(nodes.size() - 1);
  for (size_t j = 0; j < frames.size(); ++j) {
    const Eigen::Vector3d t = (nodes[j + 1] - nodes[j]).normalized();
    frames[j].tangent = t;
    if (j == 0) {
      Eigen::Vector3d d1 = first_d1 ? *first_d1 : any_perpendicular(t);
      d1 -= d1.dot(t) * t;
      if (d1.norm() < 1e-12) d1 = any_perpendicular(t);
      frames[j].d1 = d1.normalized();
    } else {
      frames[j].d1 = parallel_transport(V3<double>(frames[j - 1].tangent), V3<double>(t),
                                        V3<double>(frames[j - 1].d1))
                         .values();
    }
  }
  return frames;
}
}  // namespace

ElasticRod::ElasticRod(const std::vector<Eigen::Vector3d>& nodes, const RodStiffness& stiffness,
                       const Eigen::Vector3d* first_d1)
    : ElasticRod(nodes, twist_free_frames(nodes, first_d1),
                 std::vector<double>(nodes.size() - 1, 0.0), stiffness) {}

ElasticRod::ElasticRod(const std::vector<Eigen::Vector3d>& nodes,
                       std::vector<SourceFrame> source_frames, const std::vector<double>& thetas,
                       const RodStiffness& stiffness)
    : stiffness_(stiffness), nodes_(nodes), thetas_(thetas), source_(std::move(source_frames)) {
  if (nodes_.size() < 2) throw std::invalid_argument("ElasticRod: needs at least two nodes");
  if (thetas_.size() != nodes_.size() - 1 || source_.size() != thetas_.size())
    throw std::invalid_argument("ElasticRod: one theta and one source frame per edge");
  const size_t n = thetas_.size();
  reference_.resize(n);
  reference_twist_.assign(n + 1, 0.0);
  twist_hint_.assign(n + 1, 0.0);
  rest_length_.assign(n, 0.0);
  stretching_share_.assign(n, 1.0);
  rest_kappa_.assign(n + 1, {{{0.0, 0.0}, {0.0, 0.0}}});
  rest_twist_.assign(n + 1, 0.0);
  // The given frames and thetas fix the reference twist only up to 2 pi:
  // take the branch on which the material twist theta_i - theta_{i-1} + m_ref
  // lies in (-pi, pi].
  update_reference_frames();
  for (int i = 1; i < num_edges(); ++i) {
    const double dtheta = thetas_[i] - thetas_[i - 1];
    twist_hint_[i] = std::remainder(reference_twist_[i] + dtheta, 2.0 * M_PI) - dtheta;
  }
  update_reference_frames();
  set_rest_state_from_current();
}

void ElasticRod::update_reference_frames() {
  for (int j = 0; j < num_edges(); ++j)
    reference_[j] = xshell::reference_frame(V3<double>(tangent(j)), source_[j]);
  for (int i = 1; i < num_edges(); ++i) {
    const V3<double> t0(tangent(i - 1)), t1(tangent(i));
    const double angle =
        signed_angle(parallel_transport(t0, t1, reference_[i - 1].d1), reference_[i].d1, t1);
    reference_twist_[i] = unwrap_towards(angle, twist_hint_[i]);
  }
}

void ElasticRod::set_configuration(const std::vector<Eigen::Vector3d>& nodes,
                                   const std::vector<double>& thetas) {
  if (nodes.size() != nodes_.size() || thetas.size() != thetas_.size())
    throw std::invalid_argument("ElasticRod::set_configuration: size mismatch");
  nodes_ = nodes;
  thetas_ = thetas;
  update_reference_frames();
}

Eigen::VectorXd ElasticRod::dofs() const {
  Eigen::VectorXd q(num_dofs());
  for (int k = 0; k < num_nodes(); ++k) q.segment<3>(node_dof(k)) = nodes_[k];
  for (int j = 0; j < num_edges(); ++j) q[theta_dof(j)] = thetas_[j];
  return q;
}

void ElasticRod::set_dofs(const Eigen::VectorXd& q) {
  if (q.size() != num_dofs()) throw std::invalid_argument("ElasticRod::set_dofs: size mismatch");
  for (int k = 0; k < num_nodes(); ++k) nodes_[k] = q.segment<3>(node_dof(k));
  for (int j = 0; j < num_edges(); ++j) thetas_[j] = q[theta_dof(j)];
  update_reference_frames();
}

Frame<double> ElasticRod::material_frame(int j) const {
  return xshell::material_frame(reference_[j], thetas_[j]);
}

void ElasticRod::restore(const std::vector<Eigen::Vector3d>& nodes,
                         const std::vector<double>& thetas,
                         const std::vector<SourceFrame>& source_frames,
                         const std::vector<double>& twist_hints) {
  if (nodes.size() != nodes_.size() || thetas.size() != thetas_.size() ||
      source_frames.size() != source_.size() || twist_hints.size() != twist_hint_.size())
    throw std::invalid_argument("ElasticRod::restore: size mismatch");
  nodes_ = nodes;
  thetas_ = thetas;
  source_ = source_frames;
  twist_hint_ = twist_hints;
  update_reference_frames();
}

void ElasticRod::update_source_frames() {
  for (int j = 0; j < num_edges(); ++j) {
    source_[j].tangent = tangent(j);
    source_[j].d1 = reference_[j].d1.values();
  }
  for (int i = 1; i < num_edges(); ++i) twist_hint_[i] = reference_twist_[i];
  update_reference_frames();
}

void ElasticRod::set_rest_state_from_current() {
  for (int j = 0; j < num_edges(); ++j) rest_length_[j] = edge(j).norm();
  for (int i = 1; i < num_edges(); ++i) {
    const VertexStrains<double> k = strains(i);
    for (int side = 0; side < 2; ++side)
      for (int c = 0; c < 2; ++c) rest_kappa_[i][side][c] = k.kappa[side][c];
    rest_twist_[i] = k.twist;
  }
}

void ElasticRod::set_rest_straight() {
  for (auto& k : rest_kappa_) k = {{{0.0, 0.0}, {0.0, 0.0}}};
  std::fill(rest_twist_.begin(), rest_twist_.end(), 0.0);
}

VertexStencil ElasticRod::stencil(int i) const {
  VertexStencil s;
  s.source[0] = source_[i - 1];
  s.source[1] = source_[i];
  for (int side = 0; side < 2; ++side)
    for (int c = 0; c < 2; ++c) s.rest_kappa[side][c] = rest_kappa_[i][side][c];
  s.rest_twist = rest_twist_[i];
  s.twist_hint = twist_hint_[i];
  s.voronoi_length = voronoi_length(i);
  s.bending1 = stiffness_.bending1;
  s.bending2 = stiffness_.bending2;
  s.twisting = stiffness_.twisting;
  return s;
}

VertexDofs ElasticRod::stencil_dofs(int i) const {
  VertexDofs q;
  q.segment<3>(0) = nodes_[i - 1];
  q.segment<3>(3) = nodes_[i];
  q.segment<3>(6) = nodes_[i + 1];
  q[9] = thetas_[i - 1];
  q[10] = thetas_[i];
  return q;
}

VertexStrains<double> ElasticRod::strains(int i) const {
  return vertex_strains(stencil_dofs(i), stencil(i));
}

RodEnergy ElasticRod::energy() const {
  RodEnergy e;
  for (int j = 0; j < num_edges(); ++j)
    e.stretching +=
        stretching_energy(edge(j), rest_length_[j], stiffness_.stretching * stretching_share_[j]);
  for (int i = 1; i < num_edges(); ++i) {
    const VertexEnergy<double> v = vertex_energy(stencil_dofs(i), stencil(i));
    e.bending += v.bending;
    e.twisting += v.twisting;
  }
  return e;
}

void ElasticRod::energy_per_element(std::vector<double>& stretching, std::vector<double>& bending,
                                    std::vector<double>& twisting) const {
  stretching.assign(num_edges(), 0.0);
  bending.assign(num_nodes(), 0.0);
  twisting.assign(num_nodes(), 0.0);
  for (int j = 0; j < num_edges(); ++j)
    stretching[j] =
        stretching_energy(edge(j), rest_length_[j], stiffness_.stretching * stretching_share_[j]);
  for (int i = 1; i < num_edges(); ++i) {
    const VertexEnergy<double> v = vertex_energy(stencil_dofs(i), stencil(i));
    bending[i] = v.bending;
    twisting[i] = v.twisting;
  }
}

Eigen::VectorXd ElasticRod::gradient() const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs());
  add_gradient(g);
  return g;
}

void ElasticRod::add_gradient(Eigen::Ref<Eigen::VectorXd> g) const {
  for (int j = 0; j < num_edges(); ++j) {
    const Eigen::Vector3d ge =
        stretching_gradient(edge(j), rest_length_[j], stiffness_.stretching * stretching_share_[j]);
    g.segment<3>(node_dof(j)) -= ge;
    g.segment<3>(node_dof(j + 1)) += ge;
  }
  VertexGradient gv;
  for (int i = 1; i < num_edges(); ++i) {
    vertex_energy_gradient(stencil_dofs(i), stencil(i), gv);
    g.segment<9>(node_dof(i - 1)) += gv.head<9>();
    g[theta_dof(i - 1)] += gv[9];
    g[theta_dof(i)] += gv[10];
  }
}

void ElasticRod::add_gradient_and_hessian(Eigen::Ref<Eigen::VectorXd> g,
                                          Eigen::Ref<Eigen::MatrixXd> hessian,
                                          const Eigen::VectorXd* hessian_axial_forces) const {
  for (int j = 0; j < num_edges(); ++j) {
    const double k = stiffness_.stretching * stretching_share_[j];
    const Eigen::Vector3d e = edge(j);
    const Eigen::Vector3d ge = stretching_gradient(e, rest_length_[j], k);
    g.segment<3>(node_dof(j)) -= ge;
    g.segment<3>(node_dof(j + 1)) += ge;
    const Eigen::Matrix3d h =
        hessian_axial_forces ? stretching_hessian(e, rest_length_[j], k, (*hessian_axial_forces)[j])
                             : stretching_hessian(e, rest_length_[j], k);
    const int a = node_dof(j), b = node_dof(j + 1);
    hessian.block<3, 3>(a, a) += h;
    hessian.block<3, 3>(b, b) += h;
    hessian.block<3, 3>(a, b) -= h;
    hessian.block<3, 3>(b, a) -= h;
  }
  VertexGradient gv;
  VertexHessian hv;
  for (int i = 1; i < num_edges(); ++i) {
    vertex_energy_hessian(stencil_dofs(i), stencil(i), gv, hv);
    const int x = node_dof(i - 1), t0 = theta_dof(i - 1);
    g.segment<9>(x) += gv.head<9>();
    g.segment<2>(t0) += gv.tail<2>();
    hessian.block<9, 9>(x, x) += hv.block<9, 9>(0, 0);
    hessian.block<9, 2>(x, t0) += hv.block<9, 2>(0, 9);
    hessian.block<2, 9>(t0, x) += hv.block<2, 9>(9, 0);
    hessian.block<2, 2>(t0, t0) += hv.block<2, 2>(9, 9);
  }
}

double ElasticRod::axial_force(int j) const {
  return xshell::axial_force(edge(j), rest_length_[j],
                             stiffness_.stretching * stretching_share_[j]);
}

Eigen::VectorXd ElasticRod::linearized_axial_forces(const Eigen::VectorXd& velocity) const {
  Eigen::VectorXd out(num_edges());
  for (int j = 0; j < num_edges(); ++j) {
    const Eigen::Vector3d de =
        velocity.segment<3>(node_dof(j + 1)) - velocity.segment<3>(node_dof(j));
    const double k = stiffness_.stretching * stretching_share_[j];
    out[j] =
        xshell::axial_force(edge(j), rest_length_[j], k) + k * tangent(j).dot(de) / rest_length_[j];
  }
  return out;
}

double ElasticRod::largest_edge_change(const Eigen::VectorXd& velocity) const {
  double out = 0.0;
  for (int j = 0; j < num_edges(); ++j)
    out = std::max(
        out, (velocity.segment<3>(node_dof(j + 1)) - velocity.segment<3>(node_dof(j))).norm() /
                 rest_length_[j]);
  return out;
}

Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> ElasticRod::hessian_pattern() const {
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> p =
      Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Constant(num_dofs(), num_dofs(), false);
  for (int j = 0; j < num_edges(); ++j) p.block<6, 6>(node_dof(j), node_dof(j)).setConstant(true);
  for (int i = 1; i < num_edges(); ++i) {
    const int x = node_dof(i - 1), t0 = theta_dof(i - 1);
    p.block<9, 9>(x, x).setConstant(true);
    p.block<9, 2>(x, t0).setConstant(true);
    p.block<2, 9>(t0, x).setConstant(true);
    p.block<2, 2>(t0, t0).setConstant(true);
  }
  return p;
}

void ElasticRod::hessian_triplets(std::vector<Eigen::Triplet<double>>& triplets, int offset) const {
  for (int j = 0; j < num_edges(); ++j) {
    const Eigen::Matrix3d h =
        stretching_hessian(edge(j), rest_length_[j], stiffness_.stretching * stretching_share_[j]);
    const int a = offset + node_dof(j), b = offset + node_dof(j + 1);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        triplets.emplace_back(a + r, a + c, h(r, c));
        triplets.emplace_back(b + r, b + c, h(r, c));
        triplets.emplace_back(a + r, b + c, -h(r, c));
        triplets.emplace_back(b + r, a + c, -h(r, c));
      }
  }
  VertexGradient gv;
  VertexHessian hv;
  for (int i = 1; i < num_edges(); ++i) {
    vertex_energy_hessian(stencil_dofs(i), stencil(i), gv, hv);
    int index[11];
    for (int k = 0; k < 9; ++k) index[k] = offset + node_dof(i - 1) + k;
    index[9] = offset + theta_dof(i - 1);
    index[10] = offset + theta_dof(i);
    for (int r = 0; r < 11; ++r)
      for (int c = 0; c < 11; ++c) triplets.emplace_back(index[r], index[c], hv(r, c));
  }
}

void ElasticRod::add_hessian(Eigen::MatrixXd& hessian) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs());
  add_gradient_and_hessian(g, hessian);
}

Eigen::VectorXd ElasticRod::lumped_mass(bool unit_density) const {
  const double mass_per_length = unit_density ? stiffness_.area : stiffness_.mass_per_length;
  const double inertia_per_length =
      unit_density ? stiffness_.polar_moment : stiffness_.rotational_inertia_per_length;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(num_dofs());
  for (int j = 0; j < num_edges(); ++j) {
    const double length = rest_length_[j] * stretching_share_[j];
    const double half = 0.5 * mass_per_length * length;
    m.segment<3>(node_dof(j)).array() += half;
    m.segment<3>(node_dof(j + 1)).array() += half;
    m[theta_dof(j)] = inertia_per_length * length;
  }
  return m;
}

Eigen::VectorXd ElasticRod::lumped_rest_lengths() const {
  Eigen::VectorXd lengths = Eigen::VectorXd::Zero(num_nodes());
  for (int j = 0; j < num_edges(); ++j) {
    const double half = 0.5 * rest_length_[j] * stretching_share_[j];
    lengths[j] += half;
    lengths[j + 1] += half;
  }
  return lengths;
}

Eigen::SparseMatrix<double> ElasticRod::hessian() const {
  std::vector<Eigen::Triplet<double>> triplets;
  hessian_triplets(triplets);
  Eigen::SparseMatrix<double> h(num_dofs(), num_dofs());
  h.setFromTriplets(triplets.begin(), triplets.end());
  return h;
}

}  // namespace xshell
