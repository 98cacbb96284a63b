// The statics problem's assembly (LinkageAssembly: fixed pattern, value
// slots, parallel, deterministic) against the plain chain rule of
// RodLinkage (dense J^T H J per segment, triplets), at random configurations
// away from a source-frame update, with supports, gravity and point loads.
#include <doctest/doctest.h>

#include <random>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "finite_differences.hpp"
#include "linkage/statics_problem.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

StaticsSetup loads(bool supported) {
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0.2, -0.1, -7.0);
  setup.forces = {{0, Eigen::Vector3d(0.1, 0.0, -0.3)}};
  // Vertex 0 is a joint in every graph used here.
  if (supported)
    setup.supports = {{0, {SupportDof::Orientation, SupportDof::OpeningAngle}},
                      {1, {SupportDof::Z}}};
  return setup;
}

// The free Hessian from RodLinkage::hessian (dense local chain rule).
Eigen::MatrixXd reference_free_hessian(const LinkageProblem& problem,
                                       const std::vector<Eigen::VectorXd>& forces) {
  const Eigen::MatrixXd full(problem.linkage().hessian(&forces));
  const std::vector<int>& free = problem.free_indices();
  Eigen::MatrixXd h(free.size(), free.size());
  for (size_t c = 0; c < free.size(); ++c)
    for (size_t r = 0; r < free.size(); ++r) h(r, c) = full(free[r], free[c]);
  return h;
}

// Gravity as the problem applies it, on the full variables of every segment.
std::vector<Eigen::VectorXd> gravity_forces(const RodLinkage& linkage,
                                            const Eigen::Vector3d& gravity) {
  std::vector<Eigen::VectorXd> f;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const ElasticRod& rod = linkage.segment(s);
    const Eigen::VectorXd mass = rod.lumped_mass();
    Eigen::VectorXd fs = Eigen::VectorXd::Zero(rod.num_dofs());
    for (int n = 0; n < rod.num_nodes(); ++n) fs.segment<3>(3 * n) = mass[3 * n] * gravity;
    f.push_back(fs);
  }
  return f;
}

}  // namespace

TEST_CASE("Assembled free gradient and Hessian equal the plain chain rule, pattern included") {
  std::mt19937 rng(17);
  int compared = 0, cases = 0;
  const LineGraph graphs[] = {single_x(), tee(), grid(3, 4, 0.4)};
  for (const LineGraph& g : graphs) {
    for (int subdivisions : {3, 5}) {
      for (bool supported : {false, true}) {
        CAPTURE(subdivisions);
        CAPTURE(supported);
        LinkageProblem problem(RodLinkage(g, test_options(RestShape::Straight, subdivisions)),
                               loads(supported));
        problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
        problem.rebase();
        // Away from the update too: the kernels are exact there.
        problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
        const StaticsSetup setup = loads(supported);
        std::vector<Eigen::VectorXd> forces = gravity_forces(problem.linkage(), setup.gravity);
        const Eigen::MatrixXd reference = reference_free_hessian(problem, forces);
        const Eigen::SparseMatrix<double>& H = problem.free_hessian();
        const Eigen::MatrixXd dense(H);
        const double scale = reference.cwiseAbs().maxCoeff();
        REQUIRE(scale > 0.0);
        CHECK((dense - reference).cwiseAbs().maxCoeff() <= 1e-12 * scale);
        CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() == 0.0);
        // Every nonzero of the reference is inside the pattern.
        int missing = 0;
        for (Eigen::Index c = 0; c < reference.cols(); ++c)
          for (Eigen::Index r = 0; r < reference.rows(); ++r)
            if (reference(r, c) != 0.0 && H.coeff(r, c) == 0.0 && dense(r, c) == 0.0) ++missing;
        CHECK(missing == 0);
        CHECK(H.nonZeros() < reference.size());

        // Gradient: the plain chain rule minus the point load (on vertex 0, a
        // joint in these graphs), restricted to the free unknowns.
        const Eigen::VectorXd g_free = problem.free_gradient();
        Eigen::VectorXd g_full = problem.linkage().gradient(&forces);
        const int joint = problem.linkage().topology().joint_of_vertex[0];
        REQUIRE(joint >= 0);
        g_full.segment<3>(problem.linkage().joint_dof_offset(joint) + kPosition) -=
            setup.forces[0].force;
        Eigen::VectorXd g_ref(problem.num_free());
        for (int i = 0; i < problem.num_free(); ++i) g_ref[i] = g_full[problem.free_indices()[i]];
        CHECK((g_free - g_ref).cwiseAbs().maxCoeff() <= 1e-12 * g_ref.cwiseAbs().maxCoeff());
        compared += static_cast<int>(reference.size() + g_ref.size());
        ++cases;
      }
    }
  }
  CHECK(cases == 12);
  CHECK(compared > 10000);
}

TEST_CASE(
    "Rotation joints: the geometry's derivatives by hand equal second-order AD over all six "
    "parameters") {
  std::mt19937 rng(31);
  int compared = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Vector3d n = Eigen::Vector3d(random_vector(3, rng)).normalized();
    const Eigen::Vector3d t_a = any_perpendicular(n);
    const double alpha = 0.3 + 2.5 * std::abs(random_vector(1, rng)[0]);
    const Eigen::Vector3d t_b = std::cos(alpha) * t_a + std::sin(alpha) * n.cross(t_a);
    Joint joint(random_vector(3, rng), t_a, t_b, n, 0.5 + trial * 0.1, 2.0 - trial * 0.03);
    JointParams p = joint.params();
    // Folded (w = 0, the series branch), tiny, and far from the fold.
    const double scale = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 1e-4 : 1.5;
    p.segment<3>(kOmega) = random_vector(3, rng, scale);
    joint.set_params(p);
    REQUIRE(joint.kind() == JointKind::Rotation);
    JointGeometryDerivatives fast, ad;
    joint_geometry_derivatives(joint, fast);
    joint_geometry_derivatives_by_ad(joint, ad);
    CHECK((fast.value - ad.value).cwiseAbs().maxCoeff() <= 1e-14 * ad.value.cwiseAbs().maxCoeff());
    CHECK((fast.jacobian - ad.jacobian).cwiseAbs().maxCoeff() <=
          1e-14 * ad.jacobian.cwiseAbs().maxCoeff());
    for (int k = 0; k < 9; ++k) {
      const double hscale = std::max(ad.hessians[k].cwiseAbs().maxCoeff(), 1e-3);
      CHECK((fast.hessians[k] - ad.hessians[k]).cwiseAbs().maxCoeff() <= 1e-13 * hscale);
      CHECK((fast.hessians[k] - fast.hessians[k].transpose()).cwiseAbs().maxCoeff() == 0.0);
      compared += 36;
    }
  }
  CHECK(compared == 30 * 9 * 36);
}

TEST_CASE(
    "Terminal-edge derivatives from the joint's geometry equal AD over the joint's parameters") {
  std::mt19937 rng(29);
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d n = Eigen::Vector3d(random_vector(3, rng)).normalized();
    const Eigen::Vector3d t_a = any_perpendicular(n);
    const double alpha = 0.4 + 2.0 * std::abs(random_vector(1, rng)[0]);
    const Eigen::Vector3d t_b = std::cos(alpha) * t_a + std::sin(alpha) * n.cross(t_a);
    Joint joint(random_vector(3, rng), t_a, t_b, n, 0.7, 1.3);
    JointParams p = joint.params();
    p.segment<3>(kOmega) = random_vector(3, rng, 0.4);  // away from the fold too
    joint.set_params(p);
    JointGeometryDerivatives geometry, first_order;
    joint_geometry_derivatives(joint, geometry);
    joint_geometry_jacobian(joint, first_order);
    CHECK((first_order.value - geometry.value).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((first_order.jacobian - geometry.jacobian).cwiseAbs().maxCoeff() <= 1e-14);
    for (int label = 0; label < 2; ++label)
      for (int sign : {-1, 1}) {
        const Eigen::Vector3d t = sign * joint.tangent(label);
        const Eigen::Vector3d t_hat =
            (t + 0.3 * Eigen::Vector3d(random_vector(3, rng))).normalized();
        const SourceFrame source{t_hat,
                                 Eigen::Vector3d(random_vector(3, rng)).cross(t_hat).normalized()};
        const double hint = random_vector(1, rng, 3.0)[0];
        Eigen::Matrix<double, 7, 9> j_ref, j_first;
        JointHessian h_ref[7];
        joint.terminal_edge_derivatives(label, sign, source, hint, j_ref, h_ref);
        TerminalEdgeDerivatives fast;
        terminal_edge_derivatives(geometry, label, sign, source, fast);
        const Eigen::Matrix<double, 7, 9>& j_fast = fast.jacobian;
        JointHessian h_fast[7];
        for (int k = 0; k < 7; ++k) {
          h_fast[k].setZero();
          h_fast[k].block<6, 6>(3, 3) = fast.hessians[k];
        }
        terminal_edge_jacobian(joint, label, sign, source, hint, j_first);
        Eigen::Matrix<double, 7, 9> j_geometry;
        terminal_edge_jacobian(first_order, label, sign, source, j_geometry);
        const double jscale = j_ref.cwiseAbs().maxCoeff();
        CHECK((j_fast - j_ref).cwiseAbs().maxCoeff() <= 1e-13 * jscale);
        CHECK((j_first - j_ref).cwiseAbs().maxCoeff() <= 1e-13 * jscale);
        CHECK((j_geometry - j_ref).cwiseAbs().maxCoeff() <= 1e-13 * jscale);
        for (int k = 0; k < 7; ++k) {
          const double hscale = std::max(h_ref[k].cwiseAbs().maxCoeff(), 1e-300);
          CHECK((h_fast[k] - h_ref[k]).cwiseAbs().maxCoeff() <= 1e-12 * std::max(hscale, 1e-3));
          compared += 81;
        }
        compared += 3 * 63;
      }
  }
  CHECK(compared == 20 * 4 * (7 * 81 + 3 * 63));
}

TEST_CASE("Assembly is deterministic: 1 and 2 threads give bit-identical results") {
#ifdef _OPENMP
  std::mt19937 rng(23);
  LinkageProblem problem(RodLinkage(grid(4, 4, 0.3), test_options(RestShape::Straight, 5)),
                         loads(false));
  const Eigen::VectorXd q = problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05);
  const int before = omp_get_max_threads();
  // Setting q again before each call discards the problem's cached results.
  auto evaluate = [&](int threads, Eigen::VectorXd& g, Eigen::SparseMatrix<double>& h,
                      Eigen::VectorXd& gh) {
    omp_set_num_threads(threads);
    problem.set_free_dofs(q);
    g = problem.free_gradient();
    problem.set_free_dofs(q);
    h = problem.free_hessian();
    gh = problem.free_gradient();  // from the Hessian's pass
  };
  Eigen::VectorXd g1, g2, gh1, gh2;
  Eigen::SparseMatrix<double> h1, h2;
  evaluate(1, g1, h1, gh1);
  evaluate(2, g2, h2, gh2);
  omp_set_num_threads(before);
  REQUIRE(h1.nonZeros() == h2.nonZeros());
  CHECK(g1 == g2);
  CHECK(gh1 == gh2);
  int equal = 0;
  for (Eigen::Index k = 0; k < h1.nonZeros(); ++k) equal += h1.valuePtr()[k] == h2.valuePtr()[k];
  CHECK(equal == h1.nonZeros());
  CHECK(equal > 1000);
#else
  MESSAGE("built without OpenMP: nothing to compare");
#endif
}

TEST_CASE("The Hessian pass gives the gradient too, and both are recomputed after any change") {
  std::mt19937 rng(41);
  LinkageProblem problem(RodLinkage(grid(3, 4, 0.3), test_options(RestShape::Straight, 4)),
                         loads(true));
  const Eigen::VectorXd q = problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05);
  problem.set_free_dofs(q);
  const Eigen::VectorXd g = problem.free_gradient();
  problem.set_free_dofs(q);
  const Eigen::SparseMatrix<double>& h = problem.free_hessian();
  const Eigen::SparseMatrix<double> h_copy = h;
  const Eigen::VectorXd g_from_hessian = problem.free_gradient();
  CHECK((g_from_hessian - g).cwiseAbs().maxCoeff() <= 1e-12 * g.cwiseAbs().maxCoeff());
  // Nothing changed: the same matrix, not recomputed.
  CHECK(&problem.free_hessian() == &h);

  // A move: new Hessian and gradient, equal to a fresh problem's there.
  const Eigen::VectorXd q2 = q + random_vector(problem.num_free(), rng, 0.02);
  problem.set_free_dofs(q2);
  const Eigen::SparseMatrix<double> h2 = problem.free_hessian();
  const Eigen::VectorXd g2 = problem.free_gradient();
  LinkageProblem fresh(RodLinkage(grid(3, 4, 0.3), test_options(RestShape::Straight, 4)),
                       loads(true));
  fresh.set_free_dofs(q2);
  CHECK((g2 - fresh.free_gradient()).cwiseAbs().maxCoeff() <= 1e-12 * g2.cwiseAbs().maxCoeff());
  CHECK((h2 - h_copy).norm() > 1e-6 * h_copy.norm());
  CHECK((h2 - fresh.free_hessian()).norm() <= 1e-12 * h2.norm());

  // A rebase re-expresses the unknowns (the joints' rotations fold): the
  // gradient over them changes, and is recomputed.
  problem.rebase();
  const Eigen::VectorXd g_rebased = problem.free_gradient();
  CHECK((g_rebased - g2).cwiseAbs().maxCoeff() > 1e-9 * g2.cwiseAbs().maxCoeff());
  // Setting the same unknowns again recomputes the rods' terminal edges
  // from the folded joints (equal to round-off).
  problem.set_dofs(problem.dofs());
  CHECK((g_rebased - problem.free_gradient()).cwiseAbs().maxCoeff() <=
        1e-12 * g2.cwiseAbs().maxCoeff());
}

}  // namespace xshell::test
