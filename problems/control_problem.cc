#include "problems/control_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/finite_differences.h"
#include "problems/internal/pivot_ratio.h"
#include "problems/internal/sensitivity.h"
#include "problems/internal/singularity.h"
#include "problems/internal/step_constraints.h"
#include "problems/path.h"

namespace ccma {
namespace {

using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

// Iterations stop once the step is this far inside its tolerances: the
// forward problem then sits at its own precision floor.
constexpr double kEnergyFloor = 1e-24;

bool InRange(double value, double lo, double hi) { return value >= lo && value <= hi; }

// Largest eigenvalue of J^T J: from the eigen-decomposition when there is
// one, else by power iteration (seeded start, 30 products: a damping scale,
// a few digits suffice).
double LargestEigenvalue(const Eigen::MatrixXd& JtJ, const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>* eig) {
  if (JtJ.rows() == 0) return 0.0;
  if (eig != nullptr) return eig->eigenvalues().cwiseMax(0.0).maxCoeff();
  Eigen::VectorXd v = Eigen::VectorXd::Ones(JtJ.rows()) / std::sqrt(double(JtJ.rows()));
  double largest = 0;
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd w = JtJ * v;
    largest = v.dot(w);
    const double norm = w.norm();
    if (!(norm > 0)) break;
    v = w / norm;
  }
  return std::max(largest, 0.0);
}

// Smallest singular value of the end-effector rows of an LM Jacobian.
double SmallestSingularValueOf(const Eigen::MatrixXd& J_end_effector) {
  if (J_end_effector.rows() == 0 || J_end_effector.cols() == 0) return 0.0;
  return Eigen::JacobiSVD<Eigen::MatrixXd>(J_end_effector).singularValues().minCoeff();
}

}  // namespace

bool ControlOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(lambda > 0 && lambda < 1)) return fail("lambda must lie in (0, 1), got " + FormatG(lambda));
  if (!InRange(max_step_m, 1e-6, 1e3)) {
    return fail("max_step_m must lie in [1e-6, 1000] (m), got " + FormatG(max_step_m));
  }
  if (!InRange(max_step_rad, 1e-6, 10)) {
    return fail("max_step_rad must lie in [1e-6, 10] (rad), got " + FormatG(max_step_rad));
  }
  if (!InRange(max_iterations, 1, 100000)) {
    return fail("max_iterations must lie in [1, 100000], got " + std::to_string(max_iterations));
  }
  if (!InRange(target_tolerance, 1e-14, 1)) {
    return fail("target_tolerance must lie in [1e-14, 1] (m or rad), got " + FormatG(target_tolerance));
  }
  if (!InRange(finite_difference_step, 1e-12, 1e-1)) {
    return fail("finite_difference_step must lie in [1e-12, 0.1] (m or rad), got " +
                FormatG(finite_difference_step));
  }
  const Secondary& sec = secondary;
  if (!InRange(sec.singularity_weight, 0, 1e6)) {
    return fail("secondary.singularity_weight must lie in [0, 1e6], got " + FormatG(sec.singularity_weight));
  }
  if (!InRange(sec.singularity_threshold, 1e-6, 100)) {
    return fail("secondary.singularity_threshold must lie in [1e-6, 100] (m or rad per control unit), got " +
                FormatG(sec.singularity_threshold));
  }
  if (!InRange(sec.pivot_weight, 0, 1e6)) {
    return fail("secondary.pivot_weight must lie in [0, 1e6], got " + FormatG(sec.pivot_weight));
  }
  if (!InRange(sec.pivot_threshold, 1e-9, 1)) {
    return fail("secondary.pivot_threshold must lie in [1e-9, 1], got " + FormatG(sec.pivot_threshold));
  }
  if (!InRange(sec.spread_weight, 0, 1e6)) {
    return fail("secondary.spread_weight must lie in [0, 1e6] (1/m^2), got " + FormatG(sec.spread_weight));
  }
  if (!InRange(sec.clearance_m, 1e-3, 100)) {
    return fail("secondary.clearance_m must lie in [0.001, 100] (m), got " + FormatG(sec.clearance_m));
  }
  if (!InRange(sec.travel_weight, 0, 1e6)) {
    return fail("secondary.travel_weight must lie in [0, 1e6], got " + FormatG(sec.travel_weight));
  }
  if (!InRange(sec.iterations, 1, 100)) {
    return fail("secondary.iterations must lie in [1, 100], got " + std::to_string(sec.iterations));
  }
  if (!InRange(sec.sigma_step, 1e-8, 1e-2)) {
    return fail("secondary.sigma_step must lie in [1e-8, 0.01] (m or rad), got " + FormatG(sec.sigma_step));
  }
  std::string forward_why;
  if (!forward.IsValid(&forward_why)) return fail("forward." + forward_why);
  return true;
}

struct ControlProblem::Workspace {
  Workspace(const Model& model, const ConstraintSet& constraints, const std::vector<int>& effective)
      : error(model), step_constraints(model, effective), hessian_solver(constraints), sigma_solver(constraints),
        effective_column(static_cast<size_t>(model.num_controls()), -1) {
    for (size_t c = 0; c < effective.size(); ++c) effective_column[static_cast<size_t>(effective[c])] = static_cast<int>(c);
  }
  EndEffectorError error;
  StepConstraints step_constraints;  // differential bases and joint limits
  HessianSolver hessian_solver;  // symbolic analysis of dG/ds, done once
  EnergyDerivatives derivatives;  // reused by every linearisation
  HessianSolver sigma_solver;     // the singularity gradient's own (keeps hessian_solver's factors)
  EnergyDerivatives sigma_derivatives;
  std::vector<int> effective_column;  // control index -> column among the effective ones, or -1
};

// ceres::GradientProblemSolver's view of O(u_eff) for the BFGS outer loop.
// Trial controls farther than this from a step's start (max-norm, m or rad)
// are refused, so the line search backtracks instead of jumping the
// mechanism onto another assembly branch. A paper step moves bases ~1 cm.
constexpr double kMaxControlChangePerStep = 0.05;

// Every evaluation starts the forward solve from the step's starting state
// plus the first-order predictor ds/du (u - u_start): O(u) is then a function
// of u alone, not of the order in which the line search visits points (a
// far trial point would otherwise drag later ones onto another branch).
class BfgsObjective final : public ceres::FirstOrderFunction {
 public:
  BfgsObjective(ControlProblem* problem, const PoseTarget& target, const Eigen::VectorXd& start)
      : problem_(problem),
        target_(target),
        start_(start),
        state_start_(problem->forward_.state()),
        ds_du_(problem->StateSensitivity()) {}
  int NumParameters() const override { return static_cast<int>(problem_->effective_.size()); }
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::VectorXd ue = Eigen::Map<const Eigen::VectorXd>(parameters, NumParameters());
    if ((ue - start_).lpNorm<Eigen::Infinity>() > kMaxControlChangePerStep) return false;
    State predicted = state_start_;
    predicted.Plus(ds_du_ * (ue - start_));
    if (!problem_->SolveAt(ue, predicted)) return false;
    Eigen::VectorXd g;
    *cost = problem_->Objective(target_, gradient != nullptr ? &g : nullptr);
    if (gradient != nullptr) Eigen::Map<Eigen::VectorXd>(gradient, NumParameters()) = g;
    return std::isfinite(*cost);
  }

 private:
  ControlProblem* problem_;
  const PoseTarget target_;
  const Eigen::VectorXd start_;
  const State state_start_;
  const Eigen::MatrixXd ds_du_;
};

// Stops BFGS once O certifies the target: sqrt(2 O) bounds every error
// component, and lambda E <= O.
class TargetReached final : public ceres::IterationCallback {
 public:
  TargetReached(double objective, std::function<void(const ceres::IterationSummary&)> report)
      : objective_(objective), report_(std::move(report)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    report_(summary);
    return summary.cost <= objective_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }

 private:
  const double objective_;
  const std::function<void(const ceres::IterationSummary&)> report_;
};

namespace {
ForwardOptions ValidatedForwardOptions(const ControlOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("ControlOptions: " + why);
  return options.forward;
}
}  // namespace

ControlProblem::ControlProblem(const Model& model, const ControlOptions& options)
    : options_(options),
      forward_(model, ValidatedForwardOptions(options)),
      effective_(model.effective_control_indices()),
      workspace_(std::make_unique<Workspace>(model, forward_.constraints(), effective_)),
      travel_origin_(forward_.controls()) {}

ControlProblem::~ControlProblem() = default;

ForwardResult ControlProblem::SetControls(const Eigen::VectorXd& u) {
  travel_origin_ = u;
  return forward_.Assemble(u);
}

PoseTarget ControlProblem::CurrentPose() const {
  const EndEffectorPose pose = forward_.end_effector();
  return {pose.position, pose.rpy};
}

void ControlProblem::CheckTarget(const PoseTarget& target) const {
  for (int i = 0; i < 6; ++i) {
    const double v = i < 3 ? target.position[i] : target.rpy[i - 3];
    if (!(std::abs(v) <= kMaxMagnitude)) {
      throw std::invalid_argument(std::string("target: ") + kEndEffectorComponentNames[i] + " (" + FormatG(v) +
                                  ") must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                                  FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
}

Eigen::VectorXd ControlProblem::EffectiveControls(const Eigen::VectorXd& u) const {
  Eigen::VectorXd ue(static_cast<Eigen::Index>(effective_.size()));
  for (size_t c = 0; c < effective_.size(); ++c) ue[c] = u[effective_[c]];
  return ue;
}

bool ControlProblem::SolveAt(const Eigen::VectorXd& ue, const State& start) {
  if (!ue.allFinite() || ue.lpNorm<Eigen::Infinity>() > kMaxMagnitude) return false;
  Eigen::VectorXd u = forward_.controls();
  for (size_t c = 0; c < effective_.size(); ++c) u[effective_[c]] = ue[c];
  forward_.SetState(start);
  const ForwardResult r = forward_.Solve(u);
  ++forward_solves_;
  return std::isfinite(r.residual_energy);
}

Eigen::VectorXd ControlProblem::Residuals(const PoseTarget& target) const {
  Eigen::VectorXd e, C;
  workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
  forward_.constraints().Evaluate(forward_.state(), forward_.controls(), &C);
  Eigen::VectorXd r(e.size() + C.size());
  r << e, std::sqrt(options_.lambda) * C;
  return r;
}

struct ControlProblem::Linearization {
  Eigen::VectorXd r;      // [e; sqrt(lambda) C] (ne + m)
  Eigen::MatrixXd ds_du;  // n x k
  Eigen::MatrixXd J_e;    // de/du_eff (ne x k): the end-effector rows of dr/du
  Eigen::MatrixXd JtJ;    // (dr/du)^T dr/du (k x k)
  Eigen::VectorXd Jtr;    // (dr/du)^T r (k)
  // Once per linearisation, for every trial (up to kMaxEigenSolveSize controls).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> JtJ_eigen;
  bool has_eigen = false;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>* eigen() const { return has_eigen ? &JtJ_eigen : nullptr; }
  double rcond = 0;
  bool singular = false;
};

void ControlProblem::Linearize(const PoseTarget& target, Linearization* lin) {
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  const Sensitivity sensitivity(forward_.constraints(), s, u, effective_, &workspace_->hessian_solver,
                                &workspace_->derivatives);
  lin->rcond = sensitivity.rcond();
  lin->singular = sensitivity.singular();
  const EnergyDerivatives& d = sensitivity.derivatives();
  const bool finite_differences = options_.gradient == GradientMethod::kFiniteDifference;
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  workspace_->error.Evaluate(s, target, &e, finite_differences ? nullptr : &de_ds);
  // r = [e; sqrt(lambda) C] from these evaluations (the same numbers as
  // Residuals(target), which would evaluate both again).
  lin->r.resize(e.size() + d.C.size());
  lin->r << e, std::sqrt(options_.lambda) * d.C;
  const int ne = workspace_->error.size();
  if (finite_differences) {
    Eigen::MatrixXd J;
    LinearizeByFiniteDifferences(target, &J, &lin->ds_du);
    lin->singular = false;
    lin->J_e = J.topRows(ne);
    lin->JtJ.noalias() = J.transpose() * J;
    lin->Jtr.noalias() = J.transpose() * lin->r;
    lin->has_eigen = J.cols() <= kMaxEigenSolveSize;
    if (lin->has_eigen) lin->JtJ_eigen.compute(lin->JtJ);
    return;
  }
  // The LM model of O(u) = 1/2 |e|^2 + lambda E_r(u), E_r(u) = E(s_hat(u), u):
  //   Gauss-Newton on e:  J_e = de/ds S,  S = ds/du = -H^-1 B,  B = dG/du;
  //   exact on E_r: its Hessian is the Schur complement of the full
  //   d2E/d(s, u)2 onto the controls, J_u^T J_u + B^T S (B^T S = -B^T H^-1 B),
  //   and its gradient is S^T G + dE/du (= dE/du at a solution, G = 0).
  // (Gauss-Newton on the constraint rows, (J_s S + J_u)^T (J_s S + J_u),
  // would differ by S^T (J_s^T J_s - H) S = O(|C|): it needs S as a dense
  // n x k matrix, this does not.) Without step constraints S is never
  // formed: B^T S, de/ds S and S^T G come from sparse forward substitution
  // (Sensitivity::ImplicitProducts) and the LM trials predict with one solve.
  const double lambda = options_.lambda;
  const int k = static_cast<int>(effective_.size());
  // The step constraints read ds/du itself (joint coordinates' rates).
  const bool dense = !workspace_->step_constraints.empty();
  Sensitivity::Products products;
  lin->ds_du.resize(0, 0);
  if (dense || !sensitivity.ImplicitProducts(de_ds, d.G, &products)) {
    lin->ds_du = sensitivity.StateSensitivity();
    const Eigen::MatrixXd& S = lin->ds_du;
    products.FS.noalias() = de_ds * S;
    products.Stv.noalias() = S.transpose() * d.G;
    products.BtS.setZero(k, k);
    for (int c = 0; c < k; ++c) {
      for (SparseColMajor::InnerIterator it(d.dG_du, effective_[c]); it; ++it) {
        products.BtS.row(c) += it.value() * S.row(it.row());
      }
    }
  }
  lin->J_e = products.FS;
  // J_u^T J_u + B^T S over the effective controls (B^T S = -B^T H^-1 B is symmetric).
  Eigen::MatrixXd C_part = 0.5 * (products.BtS + products.BtS.transpose());
  const std::vector<int>& column = workspace_->effective_column;
  for (int row = 0; row < d.J_u.outerSize(); ++row) {
    for (SparseRowMajor::InnerIterator a(d.J_u, row); a; ++a) {
      if (column[a.col()] < 0) continue;
      for (SparseRowMajor::InnerIterator b(d.J_u, row); b; ++b) {
        if (column[b.col()] >= 0) C_part(column[a.col()], column[b.col()]) += a.value() * b.value();
      }
    }
  }
  lin->JtJ.noalias() = lin->J_e.transpose() * lin->J_e;
  lin->JtJ += lambda * C_part;
  lin->Jtr.noalias() = lin->J_e.transpose() * e;
  Eigen::VectorXd constraint_part = products.Stv;
  for (int c = 0; c < k; ++c) constraint_part[c] += d.dE_du[effective_[c]];
  lin->Jtr += lambda * constraint_part;
  lin->has_eigen = k <= kMaxEigenSolveSize;
  if (lin->has_eigen) lin->JtJ_eigen.compute(lin->JtJ);
}

Eigen::VectorXd ControlProblem::PredictedStateChange(const Linearization& lin, const Eigen::VectorXd& du) const {
  if (lin.ds_du.size() > 0) return lin.ds_du * du;
  // -H^-1 B du with the factorisation of the last Linearize (still in the
  // workspace: the trial solves use the forward problem's own).
  const SparseColMajor& B = workspace_->derivatives.dG_du;
  Eigen::VectorXd B_du = Eigen::VectorXd::Zero(B.rows());
  for (size_t c = 0; c < effective_.size(); ++c) {
    if (du[c] != 0) B_du += du[c] * B.col(effective_[c]);
  }
  return -workspace_->hessian_solver.Solve(B_du);
}

void ControlProblem::LinearizeByFiniteDifferences(const PoseTarget& target, Eigen::MatrixXd* J,
                                                  Eigen::MatrixXd* ds_du) {
  // Central differences of re-solved forward problems: 2k solves each.
  const State base = forward_.state();
  const Eigen::VectorXd u_base = forward_.controls();
  const double h = options_.finite_difference_step;
  *J = CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& ue) {
        SolveAt(ue, base);
        return Residuals(target);
      },
      EffectiveControls(u_base), h);
  *ds_du = CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& ue) {
        SolveAt(ue, base);
        return Eigen::VectorXd(forward_.state().Minus(base));
      },
      EffectiveControls(u_base), h);
  forward_.Restore(base, u_base);
}

double ControlProblem::Objective(const PoseTarget& target, Eigen::VectorXd* gradient) {
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  Eigen::VectorXd e;
  if (gradient == nullptr || options_.gradient == GradientMethod::kFiniteDifference) {
    workspace_->error.Evaluate(s, target, &e, nullptr);
    const double O = 0.5 * e.squaredNorm() + options_.lambda * forward_.Energy();
    if (gradient != nullptr) {
      const State base = s;
      const Eigen::VectorXd u_base = u;
      *gradient = CentralDifferenceGradient(
          [&](const Eigen::VectorXd& ue) {
            SolveAt(ue, base);
            return Objective(target, nullptr);
          },
          EffectiveControls(u_base), options_.finite_difference_step);
      forward_.Restore(base, u_base);
    }
    return O;
  }
  // Adjoint: dO/du = lambda dE/du - (dG/du)^T (dG/ds)^-1 (de/ds^T e + lambda G).
  Eigen::MatrixXd de_ds;
  workspace_->error.Evaluate(s, target, &e, &de_ds);
  const Sensitivity sensitivity(forward_.constraints(), s, u, effective_, &workspace_->hessian_solver,
                                &workspace_->derivatives);
  const EnergyDerivatives& d = sensitivity.derivatives();
  const Eigen::VectorXd dO_ds = de_ds.transpose() * e + options_.lambda * d.G;
  *gradient = sensitivity.TotalDerivative(dO_ds, options_.lambda * sensitivity.ResidualEnergyGradient());
  return 0.5 * e.squaredNorm() + options_.lambda * d.energy;
}

Eigen::MatrixXd ControlProblem::StateSensitivity() {
  if (options_.gradient == GradientMethod::kImplicit) {
    return Sensitivity(forward_.constraints(), forward_.state(), forward_.controls(), effective_,
                       &workspace_->hessian_solver, &workspace_->derivatives)
        .StateSensitivity();
  }
  Eigen::MatrixXd J, ds_du;
  LinearizeByFiniteDifferences(CurrentPose(), &J, &ds_du);
  return ds_du;
}

double ControlProblem::SmallestSingularValue(const PoseTarget& target, Eigen::VectorXd* gradient) {
  const SmallestSingularValueResult r = SmallestSingularValueOfdXdu(
      forward_.constraints(), workspace_->error, target, forward_.state(), forward_.controls(), effective_,
      gradient != nullptr, options_.secondary.sigma_step, &workspace_->sigma_solver, &workspace_->sigma_derivatives);
  if (!r.valid) {
    if (gradient != nullptr) gradient->setConstant(static_cast<Eigen::Index>(effective_.size()),
                                                    std::numeric_limits<double>::quiet_NaN());
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (gradient != nullptr) *gradient = r.gradient;
  return r.sigma;
}

double ControlProblem::PivotRatio(Eigen::VectorXd* gradient) {
  const PivotRatioResult r =
      PivotRatioOfdGds(forward_.constraints(), forward_.state(), forward_.controls(), effective_, gradient != nullptr,
                       options_.secondary.sigma_step, &workspace_->sigma_solver, &workspace_->sigma_derivatives);
  if (!r.valid) {
    if (gradient != nullptr) gradient->setConstant(static_cast<Eigen::Index>(effective_.size()),
                                                    std::numeric_limits<double>::quiet_NaN());
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (gradient != nullptr) *gradient = r.gradient;
  return r.rho;
}

void ControlProblem::SecondaryResiduals(const PoseTarget& target, Eigen::VectorXd* r2, Eigen::MatrixXd* J2) {
  const ControlOptions::Secondary& sec = options_.secondary;
  const Model& model = forward_.model();
  const Eigen::VectorXd& u = forward_.controls();
  const int k = static_cast<int>(effective_.size());
  const std::vector<int>& column = workspace_->effective_column;
  std::vector<double> values;
  std::vector<Eigen::VectorXd> rows;
  if (sec.singularity_weight > 0) {
    // Barrier sqrt(w) (sigma_0 / sigma - 1) below sigma_0: C1 at sigma_0
    // (value and slope 0), infinite at sigma = 0.
    Eigen::VectorXd g;
    const double sigma = SmallestSingularValue(target, J2 != nullptr ? &g : nullptr);
    const double sigma_0 = sec.singularity_threshold;
    if (std::isfinite(sigma) && sigma < sigma_0) {
      const double root = std::sqrt(sec.singularity_weight);
      values.push_back(root * (sigma_0 / std::max(sigma, 1e-300) - 1));
      if (J2 != nullptr) rows.push_back(-root * sigma_0 / (sigma * sigma) * g);
    } else if (!std::isfinite(sigma)) {
      values.push_back(std::numeric_limits<double>::infinity());  // singular dG/ds: never accepted
      if (J2 != nullptr) rows.push_back(Eigen::VectorXd::Zero(k));
    }
  }
  if (sec.pivot_weight > 0) {
    // The same barrier on every pivot ratio of dG/ds below rho_0, not only
    // the smallest: where the smallest pivot changes index, a barrier on rho
    // alone would push up the pivot that is smallest now while another one
    // falls to zero. A non-positive ratio (an indefinite or singular Hessian:
    // the assembly is no strict minimum of E there) is never accepted.
    const PivotRatioResult p =
        PivotRatioOfdGds(forward_.constraints(), forward_.state(), u, effective_, J2 != nullptr,
                         sec.sigma_step, &workspace_->sigma_solver, &workspace_->sigma_derivatives);
    const double rho_0 = sec.pivot_threshold;
    const double root = std::sqrt(sec.pivot_weight);
    if (!p.valid || !(p.rho > 0)) {
      values.push_back(std::numeric_limits<double>::infinity());
      if (J2 != nullptr) rows.push_back(Eigen::VectorXd::Zero(k));
    } else {
      for (Eigen::Index i = 0; i < p.ratios.size(); ++i) {
        const double rho_i = p.ratios[i];
        if (rho_i >= rho_0) continue;
        values.push_back(root * (rho_0 / rho_i - 1));
        if (J2 != nullptr) rows.push_back(-root * rho_0 / (rho_i * rho_i) * p.ratio_gradients.row(i).transpose());
      }
    }
  }
  if (sec.spread_weight > 0) {
    const double root = std::sqrt(sec.spread_weight);
    for (int i = 0; i < model.num_bases(); ++i) {
      for (int j = i + 1; j < model.num_bases(); ++j) {
        const int a = kBaseControlSize * i, b = kBaseControlSize * j;
        const Eigen::Vector2d d_ij(u[a] - u[b], u[a + 1] - u[b + 1]);
        const double distance = d_ij.norm();
        if (distance >= sec.clearance_m) continue;
        values.push_back(root * (sec.clearance_m - distance));
        if (J2 == nullptr) continue;
        Eigen::VectorXd row = Eigen::VectorXd::Zero(k);
        // d|d_ij|/d(p_i) = d_ij / |d_ij| (0 for coincident bases: no direction to push).
        const Eigen::Vector2d n = distance > 0 ? Eigen::Vector2d(d_ij / distance) : Eigen::Vector2d::Zero();
        for (int c = 0; c < 2; ++c) {
          if (column[a + c] >= 0) row[column[a + c]] -= root * n[c];
          if (column[b + c] >= 0) row[column[b + c]] += root * n[c];
        }
        rows.push_back(row);
      }
    }
  }
  if (sec.travel_weight > 0) {
    const double root = std::sqrt(sec.travel_weight);
    for (int c = 0; c < k; ++c) {
      values.push_back(root * (u[effective_[c]] - travel_origin_[effective_[c]]));
      if (J2 != nullptr) rows.push_back(root * Eigen::VectorXd::Unit(k, c));
    }
  }
  r2->resize(static_cast<Eigen::Index>(values.size()));
  for (size_t i = 0; i < values.size(); ++i) (*r2)[static_cast<Eigen::Index>(i)] = values[i];
  if (J2 != nullptr) {
    J2->resize(static_cast<Eigen::Index>(rows.size()), k);
    for (size_t i = 0; i < rows.size(); ++i) J2->row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  }
}

double ControlProblem::SecondaryObjective(const PoseTarget& target, Eigen::VectorXd* gradient) {
  Eigen::VectorXd r2;
  Eigen::MatrixXd J2;
  SecondaryResiduals(target, &r2, gradient != nullptr ? &J2 : nullptr);
  if (gradient != nullptr) *gradient = J2.transpose() * r2;
  return 0.5 * r2.squaredNorm();
}

bool ControlProblem::NullSpaceIteration(const PoseTarget& target, ControlStepResult* result) {
  Eigen::VectorXd r2;
  Eigen::MatrixXd J2;
  SecondaryResiduals(target, &r2, &J2);
  const double phi = 0.5 * r2.squaredNorm();
  if (!(phi > 0) || !std::isfinite(phi)) return false;
  // Null space of the task's Gauss-Newton model J^T J = J_e^T J_e + lambda
  // d2E_r/du2: control changes that move neither the end-effector nor the
  // residual energy to first order (an over-constrained loop also has
  // control directions that keep the end-effector but pull the loop apart).
  Linearization lin;
  Linearize(target, &lin);
  const int k = static_cast<int>(effective_.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(lin.JtJ);
  const Eigen::VectorXd& ev = eig.eigenvalues();  // increasing
  int nullity = 0;
  while (nullity < k && ev[nullity] <= 1e-9 * std::max(ev[k - 1], 1e-300)) ++nullity;
  if (nullity == 0) return false;  // no redundancy here
  const Eigen::MatrixXd N = eig.eigenvectors().leftCols(nullity);
  const Eigen::MatrixXd JN = J2 * N;
  const Eigen::MatrixXd JtJ = JN.transpose() * JN;
  const Eigen::VectorXd Jtr = JN.transpose() * r2;
  const State base = forward_.state();
  const Eigen::VectorXd u_base = forward_.controls();
  const Eigen::VectorXd ue = EffectiveControls(u_base);
  double mu = 1e-6 * std::max(JtJ.trace(), 1e-30);
  double radius = options_.max_step_m;  // trust region [m or rad, max-norm]
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z =
        -(JtJ + mu * Eigen::MatrixXd::Identity(JtJ.rows(), JtJ.cols())).ldlt().solve(Jtr);
    Eigen::VectorXd du = N * z;
    // No farther than one path step per iteration (and a quarter of that
    // after each refusal): the re-converged task stays on the branch and
    // the first-order prediction stays good.
    const double largest = du.lpNorm<Eigen::Infinity>();
    if (!(largest > 1e-14)) return false;
    if (largest > radius) du *= radius / largest;
    State predicted = base;
    predicted.Plus(PredictedStateChange(lin, du));
    ControlStepResult inner;
    if (SolveAt(ue + du, predicted) && ConvergeTask(target, &inner, /*report_iterations=*/false)) {
      Eigen::VectorXd e;
      workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
      const bool reached = (e.size() == 0 || e.lpNorm<Eigen::Infinity>() <= options_.target_tolerance) &&
                           forward_.Energy() < forward_.options().assembly_tolerance;
      // Another assembly branch: the state moved far more than a control
      // change of this size moves it (the same test as Assemble's, with a
      // factor 10 for the task's re-convergence).
      const double jump = forward_.state().Minus(base).lpNorm<Eigen::Infinity>();
      const bool jumped = jump > forward_.options().branch_jump_relative * 10 * du.lpNorm<Eigen::Infinity>() +
                                     forward_.options().branch_jump_absolute;
      Eigen::VectorXd r2_new;
      SecondaryResiduals(target, &r2_new, nullptr);
      const double phi_new = 0.5 * r2_new.squaredNorm();
      result->iterations += inner.iterations;
      result->branch_jumps_rejected += inner.branch_jumps_rejected + jumped;
      if (reached && !jumped && phi_new < phi) {
        result->rcond = inner.rcond;
        result->singular |= inner.singular;
        result->min_singular_value_dX_du = inner.min_singular_value_dX_du;
        return true;
      }
    }
    forward_.Restore(base, u_base);
    mu = mu * 10 + 1e-30;
    radius = 0.25 * std::min(radius, largest);
  }
  return false;
}

ControlStepResult ControlProblem::SolveStep(const PoseTarget& target) {
  CheckTarget(target);
  return options_.method == ControlMethod::kBfgs ? SolveStepBfgs(target) : SolveStepLm(target);
}

Eigen::VectorXd ControlProblem::LmStep(const Linearization& lin, double mu, std::vector<int>* active) const {
  const StepConstraints& constraints = workspace_->step_constraints;
  if (constraints.empty()) return ConstrainedLmStep(lin.JtJ, lin.Jtr, mu, LinearConstraints{}, lin.eigen());
  // Active set: hold every joint that the step would push past a bound at
  // that bound, until no other joint would cross (at most one pass per joint).
  active->clear();
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  Eigen::VectorXd step;
  for (size_t pass = 0; pass <= forward_.model().joints.size(); ++pass) {
    step = ConstrainedLmStep(lin.JtJ, lin.Jtr, mu, constraints.Linearize(u, s, lin.ds_du, *active), lin.eigen());
    bool grew = false;
    for (int j : constraints.WouldCross(s, lin.ds_du, step, 1e-12)) {
      if (std::find(active->begin(), active->end(), j) == active->end()) {
        active->push_back(j);
        grew = true;
      }
    }
    if (!grew) break;
  }
  return step;
}

void ControlProblem::ProjectOntoStepConstraints(ControlStepResult* result) {
  const StepConstraints& constraints = workspace_->step_constraints;
  if (constraints.empty()) return;
  for (int it = 0; it < 8; ++it) {
    const double lateral = constraints.MaxLateral(forward_.controls());
    const double violation = constraints.MaxLimitViolation(forward_.state());
    if (lateral <= 1e-10 && violation <= 1e-10) break;
    const Eigen::MatrixXd ds_du = StateSensitivity();
    std::vector<int> beyond = constraints.JointsAtOrBeyond(forward_.state(), -1e-12);
    for (int j : active_) {
      if (std::find(beyond.begin(), beyond.end(), j) == beyond.end()) beyond.push_back(j);
    }
    const LinearConstraints rows = constraints.Linearize(forward_.controls(), forward_.state(), ds_du, beyond);
    const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(ds_du.cols(), ds_du.cols());
    const Eigen::VectorXd d = ConstrainedLmStep(none, Eigen::VectorXd::Zero(ds_du.cols()), 1.0, rows);
    State predicted = forward_.state();
    predicted.Plus(ds_du * d);
    SolveAt(EffectiveControls(forward_.controls()) + d, predicted);
    ++result->iterations;
  }
}

bool ControlProblem::TurnDifferentialBases(const PoseTarget& target, ControlStepResult* turn) {
  // Heading change [rad] above which a base turns on the spot first.
  constexpr double kMaxArcTurn = 0.05;
  const Model& model = forward_.model();
  std::vector<int> differential;
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[k].type == BaseType::kDifferential) differential.push_back(k);
  }
  if (differential.empty()) return false;
  const auto start = Clock::now();
  // Where would the bases go if they could slide? (a Gauss-Newton step)
  Linearization lin;
  Linearize(target, &lin);
  const Eigen::VectorXd d =
      ConstrainedLmStep(lin.JtJ, lin.Jtr, 1e-12 * std::max(lin.JtJ.trace(), 1e-30), LinearConstraints{}, lin.eigen());
  Eigen::VectorXd u = forward_.controls();
  std::vector<int> column(static_cast<size_t>(model.num_controls()), -1);
  for (size_t c = 0; c < effective_.size(); ++c) column[static_cast<size_t>(effective_[c])] = static_cast<int>(c);
  bool turned = false;
  for (int k : differential) {
    const int i = kBaseControlSize * k;
    if (column[i] < 0 || column[i + 1] < 0) continue;
    const double dx = d[column[i]], dy = d[column[i + 1]];
    if (std::hypot(dx, dy) < 1e-9) continue;
    // Face the motion, forwards or backwards, whichever is the smaller turn.
    double change = WrapAngle(std::atan2(dy, dx) - u[i + 2]);
    if (change > M_PI / 2) change -= M_PI;
    if (change < -M_PI / 2) change += M_PI;
    if (std::abs(change) <= kMaxArcTurn) continue;
    u[i + 2] += change;
    turned = true;
  }
  if (!turned) return false;
  const PoseTarget before = CurrentPose();
  const State state_before = forward_.state();
  const Eigen::VectorXd u_before = forward_.controls();
  workspace_->step_constraints.Begin(forward_.controls());  // a turn on the spot: no lateral motion
  const ForwardResult assembled = forward_.Assemble(u);
  ++forward_solves_;
  *turn = ControlStepResult();
  Finish(before, turn);  // the end-effector must not have moved
  turn->assembled = assembled.assembled;
  turn->reached = turn->reached && assembled.assembled && !assembled.branch_jump;
  if (!turn->reached) {
    // The headings are not free in this chain (turning moves the
    // end-effector): no turn; the step must manage under its constraints.
    forward_.Restore(state_before, u_before);
    return false;
  }
  turn->iterations = 1;
  turn->forward_solves = assembled.substeps;
  turn->time_ms = Milliseconds(start);
  return true;
}

bool ControlProblem::LmIteration(const PoseTarget& target, const Linearization& lin, double* O, double* mu,
                                 Eigen::VectorXd* r, ControlStepResult* result) {
  // Damped least squares (least norm among equivalent steps: the bases move
  // as little as possible), under the step constraints when there are any.
  if (*mu < 0) *mu = 1e-12 * std::max(LargestEigenvalue(lin.JtJ, lin.eigen()), 1e-30);
  const State base = forward_.state();
  const Eigen::VectorXd u_base = forward_.controls();
  const Eigen::VectorXd ue = EffectiveControls(u_base);
  const ForwardOptions& fo = forward_.options();
  const StepConstraints& step_constraints = workspace_->step_constraints;
  for (int trial = 0; trial < 16; ++trial) {
    std::vector<int> active;
    const Eigen::VectorXd step = LmStep(lin, *mu, &active);
    if (step.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + ue.lpNorm<Eigen::Infinity>())) return false;
    // First-order predictor: start the forward solve at s + ds/du * step.
    const Eigen::VectorXd ds_predicted = PredictedStateChange(lin, step);
    State predicted = base;
    predicted.Plus(ds_predicted);
    if (SolveAt(ue + step, predicted)) {
      const double deviation = forward_.state().Minus(predicted).lpNorm<Eigen::Infinity>();
      const bool jumped = deviation > fo.branch_jump_relative * ds_predicted.lpNorm<Eigen::Infinity>() +
                                          fo.branch_jump_absolute;
      const Eigen::VectorXd r_new = Residuals(target);
      const double O_new = 0.5 * r_new.squaredNorm();
      result->branch_jumps_rejected += jumped;
      // Limits hold to first order; allow the second-order slack, removed by
      // the next iterations (Newton on the active bounds).
      const bool within = step_constraints.empty() || step_constraints.MaxLimitViolation(forward_.state()) <= 1e-6;
      if (!jumped && within && O_new < *O) {
        *O = O_new;
        *r = r_new;
        *mu = std::max(*mu * 0.1, 1e-30);
        active_ = active;
        return true;
      }
    }
    forward_.Restore(base, u_base);
    *mu = *mu * 10 + 1e-30;
  }
  return false;
}

ControlStepResult ControlProblem::SolveStepLm(const PoseTarget& target) {
  const auto start = Clock::now();
  const int solves_before = forward_solves_;
  ControlStepResult result;
  const StepConstraints& step_constraints = workspace_->step_constraints;
  step_constraints.empty() ? void() : workspace_->step_constraints.Begin(forward_.controls());
  active_.clear();
  const bool reached = ConvergeTask(target, &result, /*report_iterations=*/true);
  const bool constraints_hold = step_constraints.empty() || (step_constraints.MaxLateral(forward_.controls()) <= 1e-10 &&
                                                             step_constraints.MaxLimitViolation(forward_.state()) <= 1e-10);
  if (!constraints_hold) ProjectOntoStepConstraints(&result);
  // Redundancy resolution once the task holds (see ControlOptions::Secondary).
  if (options_.secondary.enabled() && reached && step_constraints.empty()) {
    for (int it = 0; it < options_.secondary.iterations; ++it) {
      if (!NullSpaceIteration(target, &result)) break;
      ++result.null_space_steps;
    }
  }
  if (options_.secondary.enabled()) result.secondary_objective = SecondaryObjective(target);
  result.forward_solves = forward_solves_ - solves_before;
  Finish(target, &result);
  result.time_ms = Milliseconds(start);
  return result;
}

bool ControlProblem::ConvergeTask(const PoseTarget& target, ControlStepResult* result, bool report_iterations) {
  const auto start = Clock::now();
  const int ne = workspace_->error.size();
  Linearization lin;
  Linearize(target, &lin);
  Eigen::VectorXd r = lin.r;
  result->rcond = lin.rcond;
  result->singular |= lin.singular;
  result->min_singular_value_dX_du = SmallestSingularValueOf(lin.J_e);
  double O = 0.5 * r.squaredNorm();
  auto error_of = [&] { return ne > 0 ? r.head(ne).lpNorm<Eigen::Infinity>() : 0.0; };
  const StepConstraints& step_constraints = workspace_->step_constraints;
  auto constraints_hold = [&] {
    return step_constraints.empty() || (step_constraints.MaxLateral(forward_.controls()) <= 1e-10 &&
                                        step_constraints.MaxLimitViolation(forward_.state()) <= 1e-10);
  };
  auto done = [&] {
    return error_of() <= 0.1 * options_.target_tolerance && forward_.Energy() <= kEnergyFloor && constraints_hold();
  };
  auto report = [&](int iteration) {
    if (options_.on_iteration && report_iterations) options_.on_iteration(iteration, Milliseconds(start), O, error_of());
  };
  report(0);
  double mu = -1;
  for (int it = 0; it < options_.max_iterations && !done(); ++it) {
    const bool accepted = LmIteration(target, lin, &O, &mu, &r, result);
    ++result->iterations;
    if (!accepted) break;
    report(result->iterations);
    // Converged on the new residual? Then no new linearisation is needed
    // (rcond stays that of the last one, a step of ~1e-8 away).
    if (done()) break;
    Linearize(target, &lin);
    r = lin.r;
    result->rcond = lin.rcond;
    result->singular |= lin.singular;
    result->min_singular_value_dX_du = SmallestSingularValueOf(lin.J_e);
  }
  return error_of() <= options_.target_tolerance;
}

ControlStepResult ControlProblem::SolveStepBfgs(const PoseTarget& target) {
  const auto start = Clock::now();
  const int solves_before = forward_solves_;
  ControlStepResult result;
  Eigen::VectorXd ue = EffectiveControls(forward_.controls());

  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::BFGS;
  options.max_num_iterations = options_.max_iterations;
  options.function_tolerance = 1e-30;
  options.gradient_tolerance = 1e-30;
  options.parameter_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  const double tolerance = 0.1 * options_.target_tolerance;
  TargetReached reached(std::min(0.5 * tolerance * tolerance, options_.lambda * kEnergyFloor),
                        [&](const ceres::IterationSummary& summary) {
                          if (!options_.on_iteration) return;
                          Eigen::VectorXd e;  // the error at the last evaluated (accepted) point
                          workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
                          options_.on_iteration(summary.iteration, Milliseconds(start), summary.cost,
                                                e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0);
                        });
  options.callbacks.push_back(&reached);
  ceres::GradientProblem problem(new BfgsObjective(this, target, ue));
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, ue.data(), &summary);
  // The solver's last evaluation may be a rejected line-search point:
  // re-assemble at the returned controls from where we are.
  const State here = forward_.state();
  SolveAt(ue, here);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.forward_solves = forward_solves_ - solves_before;
  {
    Linearization lin;
    Linearize(target, &lin);
    result.rcond = lin.rcond;
    result.singular = lin.singular;
    result.min_singular_value_dX_du = SmallestSingularValueOf(lin.J_e);
  }
  Finish(target, &result);
  result.time_ms = Milliseconds(start);
  return result;
}

void ControlProblem::Finish(const PoseTarget& target, ControlStepResult* result) {
  Eigen::VectorXd e;
  workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
  result->residual_energy = forward_.Energy();
  result->error = e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0;
  result->objective = 0.5 * e.squaredNorm() + options_.lambda * result->residual_energy;
  result->assembled = result->residual_energy < forward_.options().assembly_tolerance;
  const StepConstraints& constraints = workspace_->step_constraints;
  if (!constraints.empty()) {
    result->max_limit_violation = std::max(0.0, constraints.MaxLimitViolation(forward_.state()));
    result->max_lateral_displacement = constraints.MaxLateral(forward_.controls());
    std::vector<int> at_limit;
    for (int j : active_) {
      if (!constraints.JointsAtOrBeyond(forward_.state(), 1e-8).empty()) at_limit.push_back(j);
    }
    result->limited_by = constraints.Describe(forward_.state(), at_limit);
  }
  result->reached = result->assembled && result->error <= options_.target_tolerance &&
                    result->max_limit_violation <= 1e-9 && result->max_lateral_displacement <= 1e-9;
}

ControlResult ControlProblem::MoveTo(
    const PoseTarget& target,
    const std::function<void(const PoseTarget&, const ControlStepResult&)>& on_step) {
  const auto start = Clock::now();
  CheckTarget(target);
  const PosePath path(forward_.model(), CurrentPose(), target, options_.max_step_m, options_.max_step_rad);

  ControlResult result;
  result.min_rcond = std::numeric_limits<double>::infinity();
  result.min_singular_value_dX_du_on_path = std::numeric_limits<double>::infinity();
  travel_origin_ = forward_.controls();
  ControlStepResult last;
  auto account = [&](const PoseTarget& step_target, const ControlStepResult& step, bool turn_on_the_spot = false) {
    ++result.steps;
    result.iterations += step.iterations;
    result.forward_solves += step.forward_solves;
    result.branch_jumps_rejected += step.branch_jumps_rejected;
    result.max_step_residual_energy = std::max(result.max_step_residual_energy, step.residual_energy);
    result.max_limit_violation = std::max(result.max_limit_violation, step.max_limit_violation);
    result.max_lateral_displacement = std::max(result.max_lateral_displacement, step.max_lateral_displacement);
    result.limited_by = step.limited_by;
    result.min_rcond = std::min(result.min_rcond, step.rcond);
    if (!turn_on_the_spot) {  // (a turn does not linearise)
      result.min_singular_value_dX_du_on_path =
          std::min(result.min_singular_value_dX_du_on_path, step.min_singular_value_dX_du);
    }
    result.null_space_steps += step.null_space_steps;
    if (on_step) on_step(step_target, step);
    last = step;
  };
  for (int i = 1; i <= path.steps(); ++i) {
    const PoseTarget step_target = path.At(i);
    ControlStepResult turn;
    if (TurnDifferentialBases(step_target, &turn)) account(CurrentPose(), turn, true);
    const ControlStepResult step = SolveStep(step_target);
    account(step_target, step);
    if (!step.reached) {
      result.warning = "path step " + std::to_string(i) + " of " + std::to_string(path.steps()) +
                       " not reached (error " + FormatG(step.error) + ", residual energy " +
                       FormatG(step.residual_energy) + (step.singular ? ", dG/ds singular" : "") +
                       (step.branch_jumps_rejected > 0 ? ", trial steps landed on another assembly branch" : "") +
                       (step.limited_by.empty() ? "" : ", stopped by " + step.limited_by) +
                       (step.limited_by.empty() ? "): the target may be outside the workspace or past a singularity"
                                                : "): the target would need a joint beyond its limits");
      if (i < path.steps()) account(target, SolveStep(target));  // best controls for the real target
      break;
    }
  }
  result.converged = last.reached && result.warning.empty();
  result.assembled = last.assembled;
  result.objective = last.objective;
  result.error = last.error;
  result.residual_energy = last.residual_energy;
  result.rcond = last.rcond;
  result.min_singular_value_dX_du = last.min_singular_value_dX_du;
  if (!std::isfinite(result.min_singular_value_dX_du_on_path)) result.min_singular_value_dX_du_on_path = 0;
  result.secondary_objective = last.secondary_objective;
  result.solve_time_ms = Milliseconds(start);
  return result;
}

}  // namespace ccma
