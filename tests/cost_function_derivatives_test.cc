// Every analytic cost function against numeric differentiation: 200 seeded
// random states each, plus hard states (relative rotation near and at pi,
// bodies pitched 90 degrees, quaternions with w = 0, degenerate geometry),
// and a proof that the checker fails on a wrong Jacobian.
#include <functional>
#include <memory>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "ccma/rotation.h"
#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/fixed_joint_cost.h"
#include "cost_functions/legged_base_motor_cost.h"
#include "cost_functions/omni_base_motor_cost.h"
#include "cost_functions/omni_base_planar_cost.h"
#include "cost_functions/prismatic_joint_cost.h"
#include "cost_functions/revolute_joint_cost.h"
#include "cost_functions/spherical_joint_cost.h"
#include "cost_functions/universal_joint_cost.h"
#include "tests/derivative_checker.h"

namespace ccma {
namespace cost_function_derivatives_test {

using testing::CompareJacobians;
using testing::ParameterBlock;

// Analytic minus numeric must stay below this (entries are O(1) m or rad).
constexpr double kTolerance = 1e-10;
constexpr int kRandomStates = 200;

Eigen::Vector3d RandomVector(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}
Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d{n(rng), n(rng), n(rng)}.normalized();
}
Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond{n(rng), n(rng), n(rng), n(rng)}.normalized();
}
ParameterBlock Pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& p) {
  ParameterBlock b;
  b.is_pose = true;
  b.values = {q.x(), q.y(), q.z(), q.w(), p.x(), p.y(), p.z()};
  return b;
}

// A random pose: the rotation drawn first, then the position (draws in one
// statement, so every compiler draws them in this order).
ParameterBlock RandomPose(std::mt19937& rng) {
  const Eigen::Quaterniond q = RandomRotation(rng);
  return Pose(q, RandomVector(rng));
}

// A cost function with random geometry, and its autodiff twin with the same
// geometry; `degenerate` asks for the joint's singular geometry (parallel
// universal axes, point at the body origin, ...).
using CostPair = std::pair<std::unique_ptr<ceres::CostFunction>, std::unique_ptr<ceres::CostFunction>>;
struct CostCase {
  std::string name;
  int pose_blocks;   // 1 or 2 (then an optional control block)
  int control_size;  // 0 (none), 1 (an actuated joint), 3 (a wheeled base) or 6 (a legged base)
  std::function<CostPair(std::mt19937&, bool degenerate)> make_pair;
  std::unique_ptr<ceres::CostFunction> make(std::mt19937& rng, bool degenerate) const {
    return make_pair(rng, degenerate).first;
  }
};

template <typename Analytic>
std::unique_ptr<ceres::CostFunction> Own(Analytic* p) { return std::unique_ptr<ceres::CostFunction>(p); }

std::vector<CostCase> AllCostCases() {
  std::vector<CostCase> cases = {
      {"revolute", 2, 0,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d r = degenerate ? Eigen::Vector3d::Zero() : RandomVector(rng);
         const Eigen::Vector3d r_B = RandomVector(rng), a = RandomUnit(rng), b = RandomUnit(rng);
         return CostPair(Own(new RevoluteJointCost(r, r_B, a, b)), Own(MakeRevoluteJointAutoDiff(r, r_B, a, b)));
       }},
      {"spherical", 2, 0,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d r = degenerate ? Eigen::Vector3d::Zero() : RandomVector(rng);
         const Eigen::Vector3d r_B = RandomVector(rng);
         return CostPair(Own(new SphericalJointCost(r, r_B)), Own(MakeSphericalJointAutoDiff(r, r_B)));
       }},
      {"universal", 2, 0,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d a = RandomUnit(rng);
         const Eigen::Vector3d b = degenerate ? a : RandomUnit(rng);  // a x b = 0
         const Eigen::Vector3d r_A = RandomVector(rng), r_B = RandomVector(rng);
         return CostPair(Own(new UniversalJointCost(r_A, r_B, a, b)),
                         Own(MakeUniversalJointAutoDiff(r_A, r_B, a, b)));
       }},
      {"prismatic", 2, 0,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d r_A = RandomVector(rng);
         // Degenerate: B's point on A's axis line, so the projection is ~0.
         const Eigen::Vector3d a = RandomUnit(rng);
         const Eigen::Vector3d r_B = degenerate ? Eigen::Vector3d(r_A + 0.3 * a) : RandomVector(rng);
         const Eigen::Vector3d d1A = RandomUnit(rng), d1B = RandomUnit(rng), d2A = RandomUnit(rng),
                               d2B = RandomUnit(rng);
         return CostPair(Own(new PrismaticJointCost(r_A, r_B, a, d1A, d1B, d2A, d2B)),
                         Own(MakePrismaticJointAutoDiff(r_A, r_B, a, d1A, d1B, d2A, d2B)));
       }},
      {"fixed", 2, 0,
       [](std::mt19937& rng, bool) {
         const Eigen::Vector3d r_A = RandomVector(rng), r_B = RandomVector(rng);
         const Eigen::Vector3d d1A = RandomUnit(rng), d1B = RandomUnit(rng), d2A = RandomUnit(rng),
                               d2B = RandomUnit(rng);
         return CostPair(Own(new FixedJointCost(r_A, r_B, d1A, d1B, d2A, d2B)),
                         Own(MakeFixedJointAutoDiff(r_A, r_B, d1A, d1B, d2A, d2B)));
       }},
      {"omni_base_planar", 1, 0,
       [](std::mt19937&, bool) {
         return CostPair(Own(new OmniBasePlanarCost()), Own(MakeOmniBasePlanarAutoDiff()));
       }},
      {"omni_base_motor", 1, 3,
       [](std::mt19937&, bool) {
         return CostPair(Own(new OmniBaseMotorCost()), Own(MakeOmniBaseMotorAutoDiff()));
       }},
      {"legged_base_motor", 1, 6,
       [](std::mt19937&, bool) {
         return CostPair(Own(new LeggedBaseMotorCost()), Own(MakeLeggedBaseMotorAutoDiff()));
       }},
      {"actuated_revolute", 2, 1,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d a = RandomUnit(rng);
         const Eigen::Vector3d e1 = (RandomUnit(rng).cross(a)).normalized(), e2 = a.cross(e1);
         // Degenerate: B's reference along the axis (q undefined there).
         const Eigen::Vector3d w = degenerate ? a : RandomUnit(rng);
         return CostPair(Own(new ActuatedRevoluteCost(e1, e2, w)), Own(MakeActuatedRevoluteAutoDiff(e1, e2, w)));
       }},
      {"actuated_prismatic", 2, 1,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d r_A = RandomVector(rng), a = RandomUnit(rng);
         const Eigen::Vector3d r_B = degenerate ? Eigen::Vector3d(r_A + 0.3 * a) : RandomVector(rng);
         return CostPair(Own(new ActuatedPrismaticCost(r_A, r_B, a)),
                         Own(MakeActuatedPrismaticAutoDiff(r_A, r_B, a)));
       }},
      // With a home value q_home (model.h): the motor compares u - q_home.
      {"actuated_revolute_q_home", 2, 1,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d a = RandomUnit(rng);
         const Eigen::Vector3d e1 = (RandomUnit(rng).cross(a)).normalized(), e2 = a.cross(e1);
         const Eigen::Vector3d w = degenerate ? a : RandomUnit(rng);
         return CostPair(Own(new ActuatedRevoluteCost(e1, e2, w, 2.7)),
                         Own(MakeActuatedRevoluteAutoDiff(e1, e2, w, 2.7)));
       }},
      {"actuated_prismatic_q_home", 2, 1,
       [](std::mt19937& rng, bool degenerate) {
         const Eigen::Vector3d r_A = RandomVector(rng), a = RandomUnit(rng);
         const Eigen::Vector3d r_B = degenerate ? Eigen::Vector3d(r_A + 0.3 * a) : RandomVector(rng);
         return CostPair(Own(new ActuatedPrismaticCost(r_A, r_B, a, -0.4)),
                         Own(MakeActuatedPrismaticAutoDiff(r_A, r_B, a, -0.4)));
       }},
  };
  return cases;
}

// Parameter blocks: the given pose(s), then a control block if needed.
std::vector<ParameterBlock> Blocks(const CostCase& c, const ParameterBlock& A,
                                   const ParameterBlock& B, const Eigen::Vector3d& u) {
  std::vector<ParameterBlock> blocks = {A};
  if (c.pose_blocks == 2) blocks.push_back(B);
  if (c.control_size == 3) blocks.push_back({{u.x(), u.y(), u.z()}, false});
  // A legged base: x, y, heading from u; height, roll and pitch derived from
  // it (roll and pitch up to 1.5 rad, near the z-y-x angles' singularity).
  if (c.control_size == 6) {
    blocks.push_back({{u.x(), u.y(), 3 * u.z(), 0.4 + 0.1 * u.x(), 1.5 * std::sin(3 * u.y()), 1.5 * std::cos(5 * u.z())},
                      false});
  }
  if (c.control_size == 1) blocks.push_back({{u.z()}, false});
  return blocks;
}

class CostFunctionDerivatives : public ::testing::TestWithParam<CostCase> {
 protected:
  void ExpectMatches(const ceres::CostFunction& cost, const std::vector<ParameterBlock>& blocks,
                     const std::string& what) {
    const auto cmp = CompareJacobians(cost, blocks);
    EXPECT_LT(cmp.max_abs_error, kTolerance) << GetParam().name << ", " << what;
    EXPECT_FALSE(cmp.lifted_column_nonzero) << GetParam().name << ", " << what;
  }
};

TEST_P(CostFunctionDerivatives, RandomStates) {
  const CostCase& c = GetParam();
  for (int seed = 0; seed < kRandomStates; ++seed) {
    std::mt19937 rng(seed);
    const auto cost = c.make(rng, false);
    const auto A = RandomPose(rng);
    const auto B = RandomPose(rng);
    ExpectMatches(*cost, Blocks(c, A, B, RandomVector(rng, 4.0)), "seed " + std::to_string(seed));
  }
}

TEST_P(CostFunctionDerivatives, HardStates) {
  const CostCase& c = GetParam();
  for (int seed = 0; seed < 20; ++seed) {
    for (bool degenerate : {false, true}) {
      std::mt19937 rng(1000 + seed);
      const auto cost = c.make(rng, degenerate);
      const Eigen::Quaterniond q_A = RandomRotation(rng);
      const Eigen::Vector3d p = RandomVector(rng);
      const Eigen::Vector3d axis = RandomUnit(rng);
      const Eigen::Quaterniond pitched(RotationFromRpy({0.3, M_PI / 2, -1.1}));
      const Eigen::Quaterniond pitched_down(RotationFromRpy({-2.0, -M_PI / 2, 0.4}));
      const Eigen::Quaterniond w_zero(0.0, axis.x(), axis.y(), axis.z());  // angle pi
      const std::vector<std::pair<std::string, std::pair<Eigen::Quaterniond, Eigen::Quaterniond>>>
          hard = {
              {"relative angle pi - 1e-7", {q_A, QuaternionExp(axis * (M_PI - 1e-7)) * q_A}},
              {"relative angle exactly pi", {q_A, w_zero * q_A}},
              {"both pitched +90 deg", {pitched, pitched}},
              {"pitched +90 and -90 deg", {pitched, pitched_down}},
              {"quaternion w = 0", {w_zero, q_A}},
              {"coincident frames", {q_A, q_A}},
          };
      const std::vector<Eigen::Vector3d> controls = {
          {0.1, -0.2, M_PI - 1e-9}, {0.0, 0.0, -M_PI}, {1.0, 2.0, M_PI / 2}};
      for (const auto& [what, qs] : hard) {
        for (const Eigen::Vector3d& u : controls) {
          ExpectMatches(*cost, Blocks(c, Pose(qs.first, p), Pose(qs.second, p), u),
                        what + (degenerate ? " (degenerate geometry)" : "") + ", seed " +
                            std::to_string(seed));
        }
      }
    }
  }
}

// The second-order terms (exact Hessian of E) against numeric second
// differences, at random and hard states, with random weights.
constexpr double kHessianTolerance = 1e-7;

TEST_P(CostFunctionDerivatives, SecondOrderTermsMatchNumericHessian) {
  const CostCase& c = GetParam();
  for (int seed = 0; seed < 100; ++seed) {
    std::mt19937 rng(5000 + seed);
    const bool degenerate = seed % 5 == 4;
    const auto cost = c.make(rng, degenerate);
    const auto* second_order = dynamic_cast<const FramedCost*>(cost.get());
    ASSERT_NE(second_order, nullptr) << c.name << " has no second-order terms";
    Eigen::Quaterniond q_A = RandomRotation(rng), q_B = RandomRotation(rng);
    if (seed % 10 == 1) q_A = Eigen::Quaterniond(RotationFromRpy({0.2, M_PI / 2, 0.5}));  // pitched 90
    if (seed % 10 == 2) q_B = QuaternionExp(RandomUnit(rng) * (M_PI - 1e-7)) * q_A;  // near pi
    const Eigen::Vector3d p_A = RandomVector(rng), p_B = RandomVector(rng);
    const auto blocks = Blocks(c, Pose(q_A, p_A), Pose(q_B, p_B), RandomVector(rng, 4.0));
    Eigen::VectorXd w(cost->num_residuals());
    for (int i = 0; i < w.size(); ++i) w[i] = std::uniform_real_distribution<double>(-1, 1)(rng);
    const int n = 6 * c.pose_blocks;
    Eigen::MatrixXd analytic = Eigen::MatrixXd::Zero(n, n);
    std::vector<const double*> params;
    for (const auto& b : blocks) params.push_back(b.values.data());
    second_order->AddWeightedHessian(params.data(), w.data(), analytic);
    const Eigen::MatrixXd numeric = testing::NumericWeightedHessian(*cost, blocks, w);
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), kHessianTolerance)
        << c.name << " seed " << seed << "\nanalytic\n" << analytic << "\nnumeric\n" << numeric;
    EXPECT_LT((analytic - analytic.transpose()).cwiseAbs().maxCoeff(), 1e-14);
  }
}

// d^2 (w . C) / ds du at seeded states and weights, by central differences.
void ExpectNoStateControlCoupling(const ceres::CostFunction& motor, const std::vector<double>& u0, int seed) {
  std::mt19937 rng(seed);
  const int rows = motor.num_residuals(), n = static_cast<int>(u0.size());
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> u = u0;
    u[2] = 2.0 * trial / 20 * M_PI;
    const std::vector<ParameterBlock> blocks = {RandomPose(rng), {u, false}};
    Eigen::VectorXd w(rows);
    for (int i = 0; i < rows; ++i) w[i] = std::uniform_real_distribution<double>(-1, 1)(rng);
    const double h = 1e-4;
    for (int i = 0; i < 6; ++i) {
      for (int k = 0; k < n; ++k) {
        auto f = [&](double si, double sk) {
          Eigen::VectorXd d = Eigen::VectorXd::Zero(6), du = Eigen::VectorXd::Zero(n);
          d[i] = si * h;
          du[k] = sk * h;
          return testing::WeightedResidual(motor, blocks, w, d, du);
        };
        const double mixed = (f(1, 1) - f(1, -1) - f(-1, 1) + f(-1, -1)) / (4 * h * h);
        EXPECT_NEAR(mixed, 0.0, 1e-7) << "tangent " << i << ", control " << k;
      }
    }
  }
}

TEST(SecondOrder, NoConstraintCouplesStateAndControlsAtSecondOrder) {
  // d^2 (w . C) / ds du = 0 for the motor constraints, so dG/du = J_s^T J_u.
  ExpectNoStateControlCoupling(OmniBaseMotorCost(), {0.3, -0.2, 0.0}, 77);
  ExpectNoStateControlCoupling(LeggedBaseMotorCost(), {0.3, -0.2, 0.0, 0.45, 0.2, -0.3}, 78);
}

TEST(DerivativeChecker, RejectsAWrongHessian) {
  // Dropping the universal joint's cross term is caught.
  std::mt19937 rng(21);
  const UniversalJointCost cost{RandomVector(rng), RandomVector(rng), RandomUnit(rng), RandomUnit(rng)};
  const std::vector<ParameterBlock> blocks = {RandomPose(rng),
                                              RandomPose(rng)};
  const Eigen::VectorXd w = Eigen::Vector4d(0, 0, 0, 1.0);
  Eigen::MatrixXd analytic = Eigen::MatrixXd::Zero(12, 12);
  std::vector<const double*> params = {blocks[0].values.data(), blocks[1].values.data()};
  cost.AddWeightedHessian(params.data(), w.data(), analytic);
  analytic.block<3, 3>(0, 6).setZero();  // the bug
  analytic.block<3, 3>(6, 0).setZero();
  const Eigen::MatrixXd numeric = testing::NumericWeightedHessian(cost, blocks, w);
  EXPECT_GT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-2);
}

// d(x (+) delta)/d delta at 0 for a pose block (7 x 6): the true
// PlusJacobian of the left quaternion increment, to project the twins'
// ambient Jacobians onto the tangent.
Eigen::Matrix<double, 7, 6> TruePlusJacobian(const std::vector<double>& x) {
  const Eigen::Vector3d v(x[0], x[1], x[2]);
  const double w = x[3];
  Eigen::Matrix<double, 7, 6> P = Eigen::Matrix<double, 7, 6>::Zero();
  P.block<3, 3>(0, 0) = 0.5 * (w * Eigen::Matrix3d::Identity() - Skew(v));
  P.block<1, 3>(3, 0) = -0.5 * v.transpose();
  P.block<3, 3>(4, 3).setIdentity();
  return P;
}

TEST_P(CostFunctionDerivatives, AutodiffTwinAgrees) {
  const CostCase& c = GetParam();
  for (int seed = 0; seed < kRandomStates; ++seed) {
    std::mt19937 rng(9000 + seed);
    const auto [analytic, twin] = c.make_pair(rng, seed % 7 == 3);
    Eigen::Quaterniond q_B = RandomRotation(rng);
    const Eigen::Quaterniond q_A =
        seed % 10 == 1 ? Eigen::Quaterniond(RotationFromRpy({0.2, M_PI / 2, 0.5})) : RandomRotation(rng);
    if (seed % 10 == 2) q_B = QuaternionExp(RandomUnit(rng) * (M_PI - 1e-7)) * q_A;
    const Eigen::Vector3d p_A = RandomVector(rng), p_B = RandomVector(rng);
    const auto blocks = Blocks(c, Pose(q_A, p_A), Pose(q_B, p_B), RandomVector(rng, 4.0));
    const int rows = analytic->num_residuals();
    std::vector<const double*> params;
    std::vector<std::vector<double>> Ja, Jt;
    std::vector<double*> pa, pt;
    for (const auto& b : blocks) {
      params.push_back(b.values.data());
      Ja.emplace_back(rows * b.values.size());
      Jt.emplace_back(rows * b.values.size());
    }
    for (size_t i = 0; i < blocks.size(); ++i) {
      pa.push_back(Ja[i].data());
      pt.push_back(Jt[i].data());
    }
    Eigen::VectorXd ra(rows), rt(rows);
    analytic->Evaluate(params.data(), ra.data(), pa.data());
    twin->Evaluate(params.data(), rt.data(), pt.data());
    EXPECT_LT((ra - rt).cwiseAbs().maxCoeff(), 1e-14) << c.name;
    for (size_t i = 0; i < blocks.size(); ++i) {
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      const int cols = static_cast<int>(blocks[i].values.size());
      const Eigen::Map<const RowMajor> A(Ja[i].data(), rows, cols), T(Jt[i].data(), rows, cols);
      const Eigen::MatrixXd twin_tangent =
          blocks[i].is_pose ? Eigen::MatrixXd(T * TruePlusJacobian(blocks[i].values)) : Eigen::MatrixXd(T);
      const Eigen::MatrixXd analytic_tangent = blocks[i].is_pose ? Eigen::MatrixXd(A.leftCols(6)) : Eigen::MatrixXd(A);
      EXPECT_LT((analytic_tangent - twin_tangent).cwiseAbs().maxCoeff(), 1e-12) << c.name << " seed " << seed;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllCostFunctions, CostFunctionDerivatives,
                         ::testing::ValuesIn(AllCostCases()),
                         [](const auto& info) { return info.param.name; });

// A revolute joint whose Jacobian forgets the lever-arm term: what a typical
// sign or term slip looks like. The checker must reject it.
class WrongRevoluteCost final : public ceres::SizedCostFunction<6, 7, 7> {
 public:
  WrongRevoluteCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                    const Eigen::Vector3d& a)
      : right_(r_A, r_B, a, a) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    right_.Evaluate(parameters, residuals, jacobians);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      PoseJacobian<6>(jacobians[0]).block<3, 3>(0, 0).setZero();  // the bug
    }
    return true;
  }

 private:
  RevoluteJointCost right_;
};

TEST(DerivativeChecker, RejectsAWrongJacobian) {
  std::mt19937 rng(7);
  const WrongRevoluteCost wrong{RandomVector(rng), RandomVector(rng), RandomUnit(rng)};
  const auto A = RandomPose(rng);
  const auto B = RandomPose(rng);
  const auto cmp = CompareJacobians(wrong, {A, B});
  EXPECT_GT(cmp.max_abs_error, 1e-2);  // far above kTolerance: caught
}

TEST(DerivativeChecker, RejectsASmallSignSlip) {
  // A 1e-5 error in one entry is still caught at the tolerance used above.
  std::mt19937 rng(8);
  const Eigen::Vector3d r_A = RandomVector(rng), r_B = RandomVector(rng);
  class Slipped final : public ceres::SizedCostFunction<3, 7, 7> {
   public:
    Slipped(const Eigen::Vector3d& a, const Eigen::Vector3d& b) : right_(a, b) {}
    bool Evaluate(double const* const* p, double* r, double** J) const override {
      right_.Evaluate(p, r, J);
      if (J != nullptr && J[1] != nullptr) J[1][3] += 1e-5;
      return true;
    }
    SphericalJointCost right_;
  } slipped(r_A, r_B);
  const auto cmp = CompareJacobians(
      slipped, {RandomPose(rng), RandomPose(rng)});
  EXPECT_GT(cmp.max_abs_error, kTolerance);
}

TEST(DerivativeChecker, RejectsANonZeroLiftedColumn) {
  class Lifted final : public ceres::SizedCostFunction<3, 7, 7> {
   public:
    bool Evaluate(double const* const* p, double* r, double** J) const override {
      right_.Evaluate(p, r, J);
      if (J != nullptr && J[0] != nullptr) J[0][6] = 1.0;
      return true;
    }
    SphericalJointCost right_{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  } lifted;
  std::mt19937 rng(9);
  const auto cmp = CompareJacobians(
      lifted, {RandomPose(rng), RandomPose(rng)});
  EXPECT_TRUE(cmp.lifted_column_nonzero);
}

}  // namespace
}  // namespace ccma
