#include "integrators/deployment/average_constraint.hpp"

#include <algorithm>
#include <deque>
#include <stdexcept>

#include "linkage/joint.hpp"

namespace xshell {

AverageConstraint::AverageConstraint(Eigen::Index size, std::vector<int> members,
                                     std::vector<int> parent, int count, double fixed_sum)
    : size_(size), members_(std::move(members)), count_(count), fixed_sum_(fixed_sum), root_(-1) {
  const int m = static_cast<int>(members_.size());
  if (m == 0) throw std::invalid_argument("average constraint: no free member");
  if (static_cast<int>(parent.size()) != m)
    throw std::invalid_argument("average constraint: one parent per member");
  if (count_ < m)
    throw std::invalid_argument("average constraint: count below the number of members");
  std::vector<bool> seen(size_, false);
  for (int i : members_) {
    if (i < 0 || i >= size_ || seen[i])
      throw std::invalid_argument("average constraint: bad member index");
    seen[i] = true;
  }
  children_.assign(size_, {});
  parent_.assign(m, -1);
  for (int k = 0; k < m; ++k) {
    if (parent[k] < 0) {
      if (root_ >= 0) throw std::invalid_argument("average constraint: more than one root");
      root_ = members_[k];
      continue;
    }
    if (parent[k] >= m || parent[k] == k)
      throw std::invalid_argument("average constraint: bad parent");
    parent_[k] = members_[parent[k]];
    children_[parent_[k]].push_back(members_[k]);
  }
  if (root_ < 0) throw std::invalid_argument("average constraint: no root");
  // Parents before children; every member must hang from the root.
  std::deque<int> queue{root_};
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    member_order_.push_back(i);
    for (int c : children_[i]) queue.push_back(c);
  }
  if (static_cast<int>(member_order_.size()) != m)
    throw std::invalid_argument("average constraint: the parents do not form a tree");
  a_ = Eigen::VectorXd::Zero(size_);
  for (int i : members_) a_[i] = 1.0 / count_;
}

double AverageConstraint::value(const Eigen::VectorXd& q) const {
  double sum = fixed_sum_;
  for (int i : members_) sum += q[i];
  return sum / count_;
}

void AverageConstraint::project(Eigen::VectorXd& q, double target) const {
  const double shift = (target - value(q)) * count_ / static_cast<double>(members_.size());
  for (int i : members_) q[i] += shift;
}

double AverageConstraint::multiplier(const Eigen::VectorXd& g) const {
  double sum = 0.0;
  for (int i : members_) sum += g[i];
  // a.g / a.a = (sum / N) / (m / N^2)
  return sum * count_ / static_cast<double>(members_.size());
}

Eigen::VectorXd AverageConstraint::projected(const Eigen::VectorXd& g) const {
  return g - multiplier(g) * a_;
}

Eigen::VectorXd AverageConstraint::expand(const Eigen::VectorXd& z) const {
  Eigen::VectorXd dq(size_);
  for (Eigen::Index i = 0; i < size_; ++i)
    dq[i] = i == root_ ? 0.0 : z[z_index(static_cast<int>(i))];
  for (size_t k = 0; k < members_.size(); ++k)
    if (parent_[k] >= 0) dq[parent_[k]] -= z[z_index(members_[k])];
  return dq;
}

Eigen::VectorXd AverageConstraint::restrict(const Eigen::VectorXd& g) const {
  Eigen::VectorXd out(size_ - 1);
  for (Eigen::Index i = 0; i < size_; ++i)
    if (i != root_) out[z_index(static_cast<int>(i))] = g[i];
  for (size_t k = 0; k < members_.size(); ++k)
    if (parent_[k] >= 0) out[z_index(members_[k])] -= g[parent_[k]];
  return out;
}

Eigen::VectorXd AverageConstraint::coordinates(const Eigen::VectorXd& dq) const {
  // A member's coordinate is the sum of dq over its subtree: B z = dq gives
  // dq_k = z_k - sum of z over k's children.
  Eigen::VectorXd subtree = dq;
  Eigen::VectorXd z(size_ - 1);
  for (auto it = member_order_.rbegin(); it != member_order_.rend(); ++it)
    for (int c : children_[*it]) subtree[*it] += subtree[c];
  for (Eigen::Index i = 0; i < size_; ++i)
    if (i != root_) z[z_index(static_cast<int>(i))] = subtree[i];
  return z;
}

Eigen::SparseMatrix<double> AverageConstraint::reduce(const Eigen::SparseMatrix<double>& H) const {
  Eigen::SparseMatrix<double> out;
  reduce(H, out);
  return out;
}

void AverageConstraint::reduce(const Eigen::SparseMatrix<double>& H,
                               Eigen::SparseMatrix<double>& out) const {
  if (!H.isCompressed()) throw std::invalid_argument("AverageConstraint::reduce: H not compressed");
  if (!planned_for(H)) plan_for(H);
  const ReducePlan& p = plan_;
  if (out.nonZeros() != p.pattern.nonZeros() || out.rows() != p.pattern.rows() ||
      !std::equal(p.pattern.outerIndexPtr(), p.pattern.outerIndexPtr() + p.pattern.cols() + 1,
                  out.outerIndexPtr()) ||
      !std::equal(p.pattern.innerIndexPtr(), p.pattern.innerIndexPtr() + p.pattern.nonZeros(),
                  out.innerIndexPtr()))
    out = p.pattern;
  double* values = out.valuePtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  const double* h = H.valuePtr();
  for (Eigen::Index k = 0; k < H.nonZeros(); ++k)
    for (int j = p.start[k]; j < p.start[k + 1]; ++j) values[p.dest[j]] += p.sign[j] * h[k];
}

bool AverageConstraint::planned_for(const Eigen::SparseMatrix<double>& H) const {
  const ReducePlan& p = plan_;
  return static_cast<Eigen::Index>(p.outer.size()) == H.cols() + 1 &&
         static_cast<Eigen::Index>(p.inner.size()) == H.nonZeros() &&
         std::equal(p.outer.begin(), p.outer.end(), H.outerIndexPtr()) &&
         std::equal(p.inner.begin(), p.inner.end(), H.innerIndexPtr());
}

// The result's pattern from H's (B has at most one entry per column of a
// non-member row and one more per child), then each of H's entries' places.
void AverageConstraint::plan_for(const Eigen::SparseMatrix<double>& H) const {
  if (H.rows() != size_ || H.cols() != size_)
    throw std::invalid_argument("AverageConstraint::reduce: H does not fit the constraint");
  ReducePlan p;
  p.outer.assign(H.outerIndexPtr(), H.outerIndexPtr() + H.cols() + 1);
  p.inner.assign(H.innerIndexPtr(), H.innerIndexPtr() + H.nonZeros());
  std::vector<Eigen::Triplet<double>> triplets;
  for (int col = 0; col < H.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, col); it; ++it)
      for_row(static_cast<int>(it.row()), [&](int zr, double) {
        for_row(col, [&](int zc, double) { triplets.emplace_back(zr, zc, 1.0); });
      });
  p.pattern.resize(size_ - 1, size_ - 1);
  p.pattern.setFromTriplets(triplets.begin(), triplets.end());
  p.pattern.makeCompressed();
  p.start.assign(1, 0);
  for (int col = 0; col < H.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, col); it; ++it) {
      for_row(static_cast<int>(it.row()), [&](int zr, double br) {
        for_row(col, [&](int zc, double bc) {
          const int* first = p.pattern.innerIndexPtr() + p.pattern.outerIndexPtr()[zc];
          const int* last = p.pattern.innerIndexPtr() + p.pattern.outerIndexPtr()[zc + 1];
          p.dest.push_back(
              static_cast<int>(std::lower_bound(first, last, zr) - p.pattern.innerIndexPtr()));
          p.sign.push_back(br * bc);
        });
      });
      p.start.push_back(static_cast<int>(p.dest.size()));
    }
  plan_ = std::move(p);
}

Eigen::VectorXd AverageConstraint::reduce_diagonal(const Eigen::VectorXd& m) const {
  Eigen::VectorXd out(size_ - 1);
  for (Eigen::Index i = 0; i < size_; ++i)
    if (i != root_) out[z_index(static_cast<int>(i))] = m[i];
  for (size_t k = 0; k < members_.size(); ++k)
    if (parent_[k] >= 0) out[z_index(members_[k])] += m[parent_[k]];
  return out;
}

Eigen::VectorXd AverageConstraint::reduce_weights(const Eigen::VectorXd& w) const {
  Eigen::VectorXd out(size_ - 1);
  for (Eigen::Index i = 0; i < size_; ++i)
    if (i != root_) out[z_index(static_cast<int>(i))] = w[i];
  return out;
}

AverageConstraint average_opening_angle_constraint(const LinkageProblem& problem) {
  const RodLinkage& linkage = problem.linkage();
  const int nv = static_cast<int>(linkage.graph().vertices.size());
  std::vector<int> member_of_vertex(nv, -1);  // position in `members`
  std::vector<int> members;
  double fixed_sum = 0.0;
  int root_vertex = -1;
  for (int j = 0; j < linkage.num_joints(); ++j) {
    const int f = problem.free_position(linkage.joint_dof_offset(j) + kAlpha);
    if (f < 0) {
      fixed_sum += linkage.joint(j).opening_angle();
      continue;
    }
    const int v = linkage.topology().joints[j].vertex;
    member_of_vertex[v] = static_cast<int>(members.size());
    members.push_back(f);
    if (root_vertex < 0) root_vertex = v;
  }
  if (members.empty())
    throw std::invalid_argument(
        "every opening angle is fixed: the average opening angle cannot be actuated");

  // Breadth first through the graph from the root's vertex; a member's
  // parent is the nearest member on its path back to the root.
  std::vector<std::vector<int>> neighbours(nv);
  for (const auto& e : linkage.graph().edges) {
    neighbours[e[0]].push_back(e[1]);
    neighbours[e[1]].push_back(e[0]);
  }
  std::vector<int> parent(members.size(), -1),
      nearest(nv, -1);  // nearest member at or above a vertex
  std::vector<bool> visited(nv, false);
  std::deque<int> queue{root_vertex};
  visited[root_vertex] = true;
  nearest[root_vertex] = member_of_vertex[root_vertex];
  while (!queue.empty()) {
    const int u = queue.front();
    queue.pop_front();
    for (int v : neighbours[u]) {
      if (visited[v]) continue;
      visited[v] = true;
      if (member_of_vertex[v] >= 0) {
        parent[member_of_vertex[v]] = nearest[u];
        nearest[v] = member_of_vertex[v];
      } else {
        nearest[v] = nearest[u];
      }
      queue.push_back(v);
    }
  }
  return AverageConstraint(problem.num_free(), members, parent, linkage.num_joints(), fixed_sum);
}

double average_opening_angle(const RodLinkage& linkage) {
  if (linkage.num_joints() == 0) return 0.0;
  double sum = 0.0;
  for (int j = 0; j < linkage.num_joints(); ++j) sum += linkage.joint(j).opening_angle();
  return sum / linkage.num_joints();
}

}  // namespace xshell
