// minimize_bounded (bounded_minimizer.hpp) through IPOPT's TNLP interface.
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>
#include <stdexcept>

#include "bounded_minimizer.hpp"

namespace xshell {

namespace {

using Ipopt::Index;
using Ipopt::Number;

// The problem as IPOPT sees it: n variables with bounds, no constraints.
// f and its gradient come from one evaluation, kept for the point it was
// made at (IPOPT asks for them separately).
class BoundedTnlp : public Ipopt::TNLP {
 public:
  BoundedTnlp(const BoundedProblem& problem, const MinimizerOptions& options,
              MinimizerResult& result)
      : problem_(problem), options_(options), result_(result) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = static_cast<Index>(problem_.start.size());
    m = nnz_jac_g = nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number*, Number*) override {
    Eigen::Map<Eigen::VectorXd>(x_l, n) = problem_.lower;
    Eigen::Map<Eigen::VectorXd>(x_u, n) = problem_.upper;
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    Eigen::Map<Eigen::VectorXd>(x, n) = problem_.start;
    return true;
  }
  bool eval_f(Index n, const Number* x, bool new_x, Number& f) override {
    if (!evaluate_at(n, x, new_x)) return false;
    f = value_;
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool new_x, Number* grad) override {
    if (!evaluate_at(n, x, new_x)) return false;
    Eigen::Map<Eigen::VectorXd>(grad, n) = gradient_;
    return true;
  }
  bool eval_g(Index, const Number*, bool, Index, Number*) override { return true; }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index*, Index*, Number*) override {
    return true;
  }
  bool intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number obj_value, Number,
                             Number inf_du, Number, Number d_norm, Number, Number, Number, Index,
                             const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    result_.iterations = static_cast<int>(iter);
    if (options_.on_iteration)
      options_.on_iteration({static_cast<int>(iter), obj_value, inf_du, iter == 0 ? 0.0 : d_norm,
                             result_.evaluations});
    return !(options_.stop && options_.stop->load());
  }
  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number obj_value,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    result_.p = Eigen::Map<const Eigen::VectorXd>(x, n);
    result_.objective = obj_value;
  }

 private:
  bool evaluate_at(Index n, const Number* x, bool new_x) {
    const Eigen::Map<const Eigen::VectorXd> p(x, n);
    if (!new_x && valid_ && p == point_) return true;
    point_ = p;
    ++result_.evaluations;
    valid_ = problem_.evaluate(point_, value_, gradient_) && gradient_.size() == n;
    return valid_;
  }

  const BoundedProblem& problem_;
  const MinimizerOptions& options_;
  MinimizerResult& result_;
  Eigen::VectorXd point_, gradient_;
  double value_ = 0.0;
  bool valid_ = false;
};

void check(const BoundedProblem& problem) {
  const Eigen::Index n = problem.start.size();
  if (problem.lower.size() != n || problem.upper.size() != n)
    throw std::invalid_argument("bounded minimization: the bounds and the start differ in size");
  if (!(problem.lower.array() <= problem.upper.array()).all())
    throw std::invalid_argument("bounded minimization: a lower bound exceeds its upper bound");
  if (!(problem.lower.array() <= problem.start.array()).all() ||
      !(problem.start.array() <= problem.upper.array()).all())
    throw std::invalid_argument("bounded minimization: the start lies outside the bounds");
  if (!problem.evaluate) throw std::invalid_argument("bounded minimization: no function");
}

MinimizerStatus status_of(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      return MinimizerStatus::Converged;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded:
      return MinimizerStatus::IterationLimit;
    case Ipopt::User_Requested_Stop:
      return MinimizerStatus::Interrupted;
    default:
      return MinimizerStatus::Failed;
  }
}

const char* reason_of(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "optimal point found";
    case Ipopt::Solved_To_Acceptable_Level:
      return "acceptable point found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "iteration limit";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "time limit";
    case Ipopt::User_Requested_Stop:
      return "interrupted";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "search direction too small";
    case Ipopt::Restoration_Failed:
      return "restoration failed";
    case Ipopt::Error_In_Step_Computation:
      return "error in step computation";
    case Ipopt::Invalid_Number_Detected:
      return "invalid number (the start could not be evaluated)";
    default:
      return "optimizer failure";
  }
}

void set_options(Ipopt::IpoptApplication& app, const MinimizerOptions& options) {
  Ipopt::OptionsList& o = *app.Options();
  o.SetStringValue("sb", "yes");  // no banner on stdout
  o.SetIntegerValue("print_level", 0);
  o.SetStringValue("hessian_approximation", "limited-memory");
  o.SetIntegerValue("limited_memory_max_history", options.history);
  o.SetIntegerValue("max_iter", options.max_iterations);
  o.SetNumericValue("tol", options.tolerance);
  o.SetNumericValue("acceptable_tol", options.acceptable_tolerance);
}

}  // namespace

MinimizerResult minimize_bounded(const BoundedProblem& problem, const MinimizerOptions& options) {
  check(problem);
  MinimizerResult result;
  result.p = problem.start;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  set_options(*app, options);
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    result.reason = "the optimizer could not be set up";
    return result;
  }
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp = new BoundedTnlp(problem, options, result);
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(tnlp);
  result.status = status_of(status);
  result.reason = reason_of(status);
  return result;
}

const char* minimizer_status_name(MinimizerStatus status) {
  switch (status) {
    case MinimizerStatus::Converged:
      return "converged";
    case MinimizerStatus::IterationLimit:
      return "max_iterations";
    case MinimizerStatus::Interrupted:
      return "interrupted";
    case MinimizerStatus::Failed:
      return "failed";
  }
  return "failed";
}

}  // namespace xshell
