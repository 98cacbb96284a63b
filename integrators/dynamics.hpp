// Statics by damped dynamics with IDA: integrate
//   M q'' + C q' + grad E(q) = 0   (second order; C = c M)
// or the overdamped C q' + grad E(q) = 0 (first order) from rest until the
// motion has died out, with IDA's adaptive BDF steps (which grow as the
// motion decays, approaching Newton steps: pseudo-transient continuation,
// Kelley & Keyes 1998). Damped dynamics only lowers E + kinetic energy, so
// it settles in stable minima where Newton may stop at a saddle; from an
// exactly symmetric start it can still stay on a symmetric saddle.
//
// Layout and linear algebra: dynamics_system.hpp (Schur complement onto
// the n x n symmetric K = H + (c_j^2 + c c_j) M, factorized by CHOLMOD).
// Masses and the automatic damping: mass_and_damping.hpp.
//
// Stepping: IDA_ONE_STEP; after every step the objective is moved to the
// step's q and the stop criterion is tested:
//   gradient measure <= gradient_tolerance  and
//   kinetic energy <= kinetic_tolerance * max(|E_0 - E|, |E|)
// (second order; the first-order form has no kinetic energy). Every
// rebase_interval steps, objective.rebase(&v) re-expresses the unknowns and
// IDA restarts (IDAReInit) from the transformed state with consistent
// derivatives (q' = v, v' = -c v - M^-1 grad E) and the last step size;
// when the rebase changed neither q nor v, IDA simply continues (a restart
// drops IDA back to order 1).
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "dynamics_system.hpp"
#include "objective.hpp"
#include "shifted_factorization.hpp"

namespace xshell {

enum class MassModel {
  Physical,    // objective.mass()
  Fictitious,  // row sums of |H| at the start (dynamic relaxation)
};

struct DynamicsOptions {
  DynamicsForm form = DynamicsForm::SecondOrder;
  MassModel mass = MassModel::Physical;
  // c in C = c M; <= 0 selects 2 sqrt(|lambda_min|) of (H, M) at the start
  // (critical damping of the slowest mode; mass_and_damping.hpp). In the
  // first-order form c only rescales time.
  double damping = 0.0;
  int damping_iterations = 20;       // inverse iterations for lambda_min
  double gradient_tolerance = 2e-8;  // as NewtonOptions
  double kinetic_tolerance = 1e-12;  // relative to the energy scale, see above
  long max_steps = 100000;
  int rebase_interval = 20;  // steps between rebases (>= 1)
  // IDA local error control: rtol, and atol for q (atol for v is atol c/2).
  // Statics needs no accurate trajectory, only a decreasing E + K and the
  // right basin: on the test toys rtol 1e-3 takes 3-15x fewer steps than
  // 1e-6 with E + K still decreasing to round-off, while rtol 1e-2 let E + K
  // rise by 3e-4 of the total drop (extended Rosenbrock).
  double relative_tolerance = 1e-3;
  double absolute_tolerance = 1e-6;
  double initial_step = 0.0;  // 0: IDA's estimate
  ShiftOptions shift;         // for the damping estimate at an indefinite start
};

enum class DynamicsStatus {
  Converged,  // gradient and kinetic criteria met
  MaxSteps,
  LinearSolverFailed,  // IDA could not factorize K even with short steps
  IntegratorFailed,    // other IDA failures (error test, convergence, steps stagnating
                       // below 1e-12 t), or invalid configurations
  NonFinite,           // NaN/inf in the energy, gradient or Hessian
  Interrupted,
};

const char* to_string(DynamicsStatus status);

// One per accepted step, and one for the initial state (step 0).
struct DynamicsReport {
  long step = 0;
  double time = 0.0;            // simulated time
  double step_size = 0.0;       // of the last step
  double energy = 0.0;          // E(q)
  double kinetic_energy = 0.0;  // v'Mv/2 (0 in the first-order form)
  double gradient_measure = 0.0;
};

struct DynamicsCallbacks {
  std::function<void(const DynamicsReport&)> on_step;  // optional
  const std::atomic<bool>* stop = nullptr;             // optional; checked before each step
};

struct DynamicsResult {
  DynamicsStatus status = DynamicsStatus::MaxSteps;
  std::string reason;
  long steps = 0;
  double time = 0.0;
  double gradient_measure = 0.0;
  double energy = 0.0;
  double kinetic_energy = 0.0;
  bool stable = false;      // unshifted LL^T of the final Hessian succeeded
  double damping = 0.0;     // c used
  long factorizations = 0;  // numeric Cholesky factorizations (incl. estimate and check)
  long rebases = 0;
  double seconds = 0.0;
  bool converged() const { return status == DynamicsStatus::Converged; }
};

// Integrates from the objective's current configuration, at rest. On
// failure the objective is left at the last accepted step.
DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options = {},
                              const DynamicsCallbacks& callbacks = {});

}  // namespace xshell
