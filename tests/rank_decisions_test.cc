// The dense rank decisions (ccma::RankRevealingDecomposition: the moved
// components of an import, branch detection's idle motions, the compliant
// equilibrium's stretched motions) on every model the project has: the
// bundled models (models/, examples/statics/), generated ones
// (formats/model_generator.h, the kinds of `ccma generate`) and the robots of
// example-parallel-robots (imported as the collection round trip does), at
// home and at seeded configurations near it.
//
// Every matrix a decision is given is captured (SetRankDecisionObserver),
// with dC/ds (the matrix the moved components' threshold is scaled by), and
// given to Eigen 3.4.0's BDCSVD, which ccma used before, with Eigen's
// assertions on (tests/eigen_bdcsvd_probe.h):
//  * where BDCSVD trips its defect (perturbCol0's index -1: an assertion),
//    or returns what is not an SVD of the matrix (V not orthonormal, or
//    |A v_i| not sigma_i: no assertion, a wrong answer), the matrix is a
//    trigger: listed on stdout, written to the test's folder, and the new
//    decision is checked against a Jacobi SVD instead (same threshold);
//  * everywhere else the new decision agrees with BDCSVD's: the same rank,
//    and null spaces spanning the same space (orthogonal projectors within
//    1e-7).
// The triggers found are recorded in tests/data/rank_decisions/README.md;
// the regression tests on the saved ones are at the end.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/configuration_difference.h"
#include "analyses/internal/sparse_rank.h"
#include "analyses/mobility.h"
#include "analyses/moved_components.h"
#include "analyses/robot_import.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_reader.h"
#include "formats/urdf_writer.h"
#include "problems/forward_problem.h"
#include "problems/internal/compliant_equilibrium.h"
#include "tests/eigen_bdcsvd_probe.h"
#include "tests/tool_run.h"

namespace ccma {
namespace rank_decisions_test {

namespace fs = std::filesystem;
using Method = RankRevealingDecomposition::Method;

// Null spaces agree when their orthogonal projectors do, entry by entry.
constexpr double kProjectorTolerance = 1e-7;

struct Captured {
  Eigen::MatrixXd A;
  RankRevealingDecomposition::Threshold threshold;
  Method method = Method::kJacobiSvd;
  std::string where;
  bool values_only_too = false;  // BDCSVD was also given it for its singular values alone
};

std::vector<Captured>* capture = nullptr;
std::string capture_where;

void Record(const Eigen::MatrixXd& A, const RankRevealingDecomposition::Threshold& threshold, Method method) {
  if (capture != nullptr) capture->push_back({A, threshold, method, capture_where, false});
}

// Captures while alive.
class Capture {
 public:
  explicit Capture(std::vector<Captured>* out) {
    capture = out;
    SetRankDecisionObserver(&Record);
  }
  ~Capture() {
    SetRankDecisionObserver(nullptr);
    capture = nullptr;
  }
};

// What BDCSVD decided: the rank (singular values above the threshold) and
// the null space (V's last columns). Not valid when it asserts, or when its
// result is not an SVD of A: V not orthonormal, or |A v_i| not sigma_i (both
// within 1e-10 of max(1, sigma_max)); `failure` says which.
struct OldDecision {
  bool valid = false;
  std::string failure;
  int rank = 0;
  Eigen::MatrixXd null_space;
};

std::string Str(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", x);
  return text;
}

// Why V and sigma are not an SVD of A, or "".
std::string NotAnSvd(const Eigen::MatrixXd& A, const Eigen::VectorXd& sigma, const Eigen::MatrixXd& V) {
  const double scale = std::max(1.0, sigma.size() > 0 ? sigma[0] : 0.0);
  const Eigen::MatrixXd gram = V.transpose() * V - Eigen::MatrixXd::Identity(V.cols(), V.cols());
  const double orthonormality = gram.size() > 0 ? gram.cwiseAbs().maxCoeff() : 0.0;
  if (!(orthonormality <= 1e-10)) return "V not orthonormal (|V^T V - I| = " + Str(orthonormality) + ")";
  const Eigen::VectorXd norms = (A * V).colwise().norm().transpose();
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(V.cols());
  expected.head(sigma.size()) = sigma;
  const double mismatch = (norms - expected).cwiseAbs().maxCoeff();
  if (!(mismatch <= 1e-10 * scale)) return "|A v_i| != sigma_i (by " + Str(mismatch) + ", sigma_max " + Str(scale) + ")";
  return "";
}

OldDecision OldBdcsvd(const Eigen::MatrixXd& A, const RankRevealingDecomposition::Threshold& threshold) {
  const std::vector<double> data(A.data(), A.data() + A.size());
  const testing::BdcsvdProbe probe =
      testing::ProbeBdcsvd(data, static_cast<int>(A.rows()), static_cast<int>(A.cols()), true);
  OldDecision out;
  if (probe.assertion_failed) {
    out.failure = "assertion " + probe.assertion;
    return out;
  }
  const Eigen::Map<const Eigen::VectorXd> sigma(probe.singular_values.data(),
                                                static_cast<Eigen::Index>(probe.singular_values.size()));
  const Eigen::Map<const Eigen::MatrixXd> V(probe.V.data(), A.cols(), A.cols());
  out.failure = NotAnSvd(A, sigma, V);
  out.valid = out.failure.empty();
  const double bound = std::max(threshold.absolute, threshold.relative * (sigma.size() > 0 ? sigma[0] : 0.0));
  while (out.rank < sigma.size() && sigma[out.rank] > bound) ++out.rank;
  out.null_space = V.rightCols(A.cols() - out.rank);
  return out;
}

double ProjectorDifference(const Eigen::MatrixXd& N1, const Eigen::MatrixXd& N2) {
  if (N1.rows() == 0) return 0.0;
  return (N1 * N1.transpose() - N2 * N2.transpose()).cwiseAbs().maxCoeff();
}

// A model and the configurations to decide at.
struct Sample {
  State s;
  Eigen::VectorXd u;
};

// Home, then `count` seeded configurations: the effective controls moved by
// up to 0.02 (rad or m) from home, shrunk fourfold until the model assembles.
std::vector<Sample> Samples(const Model& model, int count, unsigned seed) {
  std::vector<Sample> samples = {{State::Home(model), model.home_controls()}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.02, 0.02);
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(model.num_controls());
    for (const int i : model.effective_control_indices()) du[i] = offset(rng);
    for (int shrink = 0; shrink < 4; ++shrink, du /= 4) {
      ForwardProblem forward(model);
      if (forward.Assemble(model.home_controls() + du).assembled) {
        samples.push_back({forward.state(), model.home_controls() + du});
        break;
      }
    }
  }
  return samples;
}

// A body other than the end-effector's, moved: CompareConfigurations then
// finds the same end-effector pose and a state difference, and lists the
// idle motions (DenseIdleMotions).
State MovedBody(const Model& model, const State& s, std::mt19937* rng) {
  State out = s;
  std::vector<int> others;
  for (int b = 0; b < model.num_bodies(); ++b) {
    if (b != model.end_effector.body) others.push_back(b);
  }
  if (others.empty()) return out;
  const int b = others[std::uniform_int_distribution<size_t>(0, others.size() - 1)(*rng)];
  out.SetPose(b, s.q_WB(b), s.p_WB(b) + Eigen::Vector3d(1e-3, -2e-3, 1e-3));
  return out;
}

// Runs every dense rank decision of `model` at each sample, capturing the
// matrices; dC/ds is added as the moved components' first matrix (BDCSVD
// of its values set their threshold before).
void Decide(const Model& model, const std::vector<Sample>& samples, unsigned seed, std::vector<Captured>* out) {
  std::mt19937 rng(seed);
  ComponentSet all;
  all.fill(true);
  const bool dense = model.state_size() <= kDenseMobilityStateSize;
  for (size_t k = 0; k < samples.size(); ++k) {
    const Sample& x = samples[k];
    const std::string at = k == 0 ? "home" : "sample " + std::to_string(k);
    Eigen::VectorXd C;
    Eigen::MatrixXd J_s, J_u;
    ConstraintSet(model).Evaluate(x.s, x.u, &C, &J_s, &J_u);
    const double threshold = 1e-8 * std::max(1.0, LargestSingularValue(SparseMatrixCol(J_s.sparseView())));
    if (dense) out->push_back({J_s, {threshold, 0.0}, Method::kPivotedQr, at + ", dC/ds", true});
    Capture capturing(out);
    capture_where = at + ", moved components";
    if (dense) AnalyzeMovedComponents(model, x.s, x.u, all);
    capture_where = at + ", idle motions";
    CompareConfigurations(model, x.s, MovedBody(model, x.s, &rng), x.u);
    capture_where = at + ", compliant equilibrium";
    const bool springs = std::any_of(model.joints.begin(), model.joints.end(),
                                     [](const Joint& joint) { return joint.stiffness.has_springs(); });
    if (springs || !CompliantEquilibrium::CompliantControls(model).empty()) {
      CompliantEquilibrium(model, ConstraintSet(model), x.s, x.u, CompliantEquilibrium::Factorization::kIdleMotions);
    }
  }
}

// A's nonzeros as text: "rows cols", then "row col value" lines (values in
// %.17g, so that they read back exactly). The Jacobians are sparse.
void SaveNonzeros(const Eigen::MatrixXd& A, const std::string& path) {
  std::ofstream out(path);
  out << A.rows() << " " << A.cols() << "\n";
  char value[40];
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (A(i, j) == 0.0) continue;
      std::snprintf(value, sizeof(value), "%.17g", A(i, j));
      out << i << " " << j << " " << value << "\n";
    }
  }
}

Eigen::MatrixXd LoadNonzeros(const std::string& path) {
  std::ifstream in(path);
  Eigen::Index rows = -1, cols = -1;
  in >> rows >> cols;
  if (!in || rows < 0 || cols < 0 || rows > 100000 || cols > 100000) {
    ADD_FAILURE() << path << ": no \"rows cols\" line";
    return Eigen::MatrixXd();
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, cols);
  Eigen::Index i = 0, j = 0;
  double value = 0.0;
  while (in >> i >> j >> value) {
    if (i < 0 || i >= rows || j < 0 || j >= cols) {
      ADD_FAILURE() << path << ": entry (" << i << ", " << j << ") outside " << rows << " x " << cols;
      return Eigen::MatrixXd();
    }
    A(i, j) = value;
  }
  return A;
}

// Every captured decision against BDCSVD's, or against a Jacobi SVD where
// BDCSVD asserts or is wrong (the matrix then written to the test's folder);
// returns the triggers' descriptions.
std::vector<std::string> Compare(const std::string& model, const std::vector<Captured>& captured) {
  std::vector<std::string> triggers;
  for (const Captured& c : captured) {
    SCOPED_TRACE(model + ", " + c.where + ", " + std::to_string(c.A.rows()) + " x " + std::to_string(c.A.cols()));
    const RankRevealingDecomposition now(c.A, c.threshold, c.method);
    OldDecision old = OldBdcsvd(c.A, c.threshold);
    if (old.valid && c.values_only_too) {
      // DenseMotions asked BDCSVD for dC/ds's singular values alone.
      const std::vector<double> data(c.A.data(), c.A.data() + c.A.size());
      const testing::BdcsvdProbe values =
          testing::ProbeBdcsvd(data, static_cast<int>(c.A.rows()), static_cast<int>(c.A.cols()), false);
      if (values.assertion_failed) old.valid = false, old.failure = "values only: assertion " + values.assertion;
    }
    if (!old.valid) {
      const std::string path = testing::ScratchPath(
          "rank_decisions", model + "_" + std::to_string(triggers.size()) + ".txt");
      SaveNonzeros(c.A, path);
      triggers.push_back(model + ", " + c.where + " (" + std::to_string(c.A.rows()) + " x " +
                         std::to_string(c.A.cols()) + "): " + old.failure + "; saved as " + path);
      const RankRevealingDecomposition jacobi(c.A, {now.threshold(), 0.0}, Method::kJacobiSvd);
      EXPECT_EQ(now.rank(), jacobi.rank());
      if (now.rank() == jacobi.rank()) {
        EXPECT_LT(ProjectorDifference(now.nullSpace(), jacobi.nullSpace()), kProjectorTolerance);
      }
      continue;
    }
    EXPECT_EQ(now.rank(), old.rank);
    if (now.rank() == old.rank) EXPECT_LT(ProjectorDifference(now.nullSpace(), old.null_space), kProjectorTolerance);
  }
  return triggers;
}

// Runs and compares; prints the triggers and the count of decisions.
void Survey(const std::string& name, const Model& model, int samples, unsigned seed,
            std::vector<Captured> captured = {}) {
  Decide(model, Samples(model, samples, seed), seed, &captured);
  ASSERT_FALSE(captured.empty());
  const std::vector<std::string> triggers = Compare(name, captured);
  std::cout << name << ": " << captured.size() << " decisions, " << triggers.size() << " BDCSVD triggers\n";
  for (const std::string& t : triggers) std::cout << "  trigger: " << t << "\n";
}

// ---------------------------------------------------------------- models ---

std::vector<std::string> ModelFiles() {
  std::vector<std::string> files;
  for (const std::string folder : {std::string(CCMA_MODELS_DIR), std::string(CCMA_SOURCE_DIR) + "/examples/statics"}) {
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

class BundledModel : public ::testing::TestWithParam<std::string> {};

TEST_P(BundledModel, DecisionsAgreeWithBdcsvdWhereItIsValid) {
  const std::string stem = fs::path(GetParam()).stem().string();
  Survey(stem, LoadModel(GetParam()), 2, 17);
}

INSTANTIATE_TEST_SUITE_P(RankDecisions, BundledModel, ::testing::ValuesIn(ModelFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return fs::path(info.param).stem().string();
                         });

// Generated models: `ccma generate stewart|stewart-gough|legged --agents N`,
// and the Stewart one made compliant (every base and revolute joint).
struct Generated {
  std::string kind;
  int agents;
};

std::string GeneratedText(const Generated& g) {
  if (g.kind == "stewart" || g.kind == "compliant_stewart") {
    StewartOptions o;
    o.agents = g.agents;
    return GenerateStewartModel(o);
  }
  if (g.kind == "stewart_gough") {
    StewartOptions o;
    o.agents = g.agents;
    return GenerateStewartGoughModel(o);
  }
  LeggedOptions o;
  o.agents = g.agents;
  return GenerateLeggedModel(o);
}

class GeneratedModel : public ::testing::TestWithParam<Generated> {};

TEST_P(GeneratedModel, DecisionsAgreeWithBdcsvdWhereItIsValid) {
  const Generated g = GetParam();
  const std::string name = g.kind + "_" + std::to_string(g.agents);
  Model model = LoadModelFromString(GeneratedText(g), name + ".yaml");
  if (g.kind == "compliant_stewart") {  // as benchmarks/statics_benchmark.cc
    for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(2e4, 2e4, 500);
    for (Joint& joint : model.joints) {
      if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {2e3, 2e3};
    }
  }
  Survey(name, model, 2, 31 + static_cast<unsigned>(g.agents));
}

INSTANTIATE_TEST_SUITE_P(RankDecisions, GeneratedModel,
                         ::testing::Values(Generated{"stewart", 3}, Generated{"stewart", 5}, Generated{"stewart", 6},
                                           Generated{"stewart", 12}, Generated{"stewart", 24},
                                           Generated{"stewart_gough", 6}, Generated{"stewart_gough", 12},
                                           Generated{"legged", 3}, Generated{"legged", 8},
                                           Generated{"compliant_stewart", 6},
                                           Generated{"compliant_stewart", 24}),
                         [](const ::testing::TestParamInfo<Generated>& info) {
                           return info.param.kind + "_" + std::to_string(info.param.agents);
                         });

// The robots of example-parallel-robots, imported as the collection round
// trip imports them, then exported as URDF and as SDFormat and imported
// again (tests/collection_round_trip_test.cc): every import's own moved
// components captured, then the decisions at home and one seeded
// configuration of the first import. A robot that does not read or import
// is skipped (the round trip checks which those are).
std::vector<std::string> CollectionUrdfs() {
  std::vector<std::string> files;
  for (const auto& entry :
       fs::recursive_directory_iterator(std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots")) {
    if (entry.path().extension() == ".urdf") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string CollectionName(const std::string& urdf) {
  const std::string root = std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots";
  std::string name = fs::relative(fs::path(urdf).parent_path(), root).string();
  std::replace(name.begin(), name.end(), '/', '_');
  return name;
}

}  // namespace rank_decisions_test

// The end-effector the collection round trip imports with: the link deepest
// down a chain (tests/collection_round_trip_test.cc, same executable).
namespace collection_round_trip_test {
std::string DeepestLink(const RobotDescription& robot);
}  // namespace collection_round_trip_test

namespace rank_decisions_test {

// `model` written as URDF + closure file and as SDFormat, each imported
// again (their moved components captured, labelled).
void ReimportExports(const Model& model, const std::string& name, std::vector<Captured>* captured) {
  const std::string urdf = testing::ScratchPath("rank_decisions", name + ".urdf");
  const UrdfExport e = WriteUrdf(model);
  std::ofstream(urdf) << e.urdf;
  std::ofstream(ClosureFilePath(urdf)) << e.closures;
  const std::string sdf = testing::ScratchPath("rank_decisions", name + ".sdf");
  std::ofstream(sdf) << WriteSdformat(model).sdf;
  Capture capturing(captured);
  capture_where = "import of the exported URDF";
  ImportRobot(ReadUrdf(urdf, ClosureFilePath(urdf)), ImportOptions{});
  capture_where = "import of the exported SDFormat";
  ImportRobot(ReadSdformat(sdf, {}), ImportOptions{});
}

class CollectionRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(CollectionRobot, DecisionsAgreeWithBdcsvdWhereItIsValid) {
  const std::string name = CollectionName(GetParam());
  const fs::path closures = fs::path(GetParam()).parent_path() / "robot.yaml";
  std::vector<Captured> captured;
  Model model;
  try {
    const RobotDescription description = ReadUrdf(GetParam(), fs::exists(closures) ? closures.string() : "");
    ImportOptions options;
    options.end_effector_link = collection_round_trip_test::DeepestLink(description);
    Capture capturing(&captured);
    capture_where = "import";
    model = ImportRobot(description, options).model;
  } catch (const std::exception& e) {
    GTEST_SKIP() << "does not import: " << e.what();
  }
  ReimportExports(model, name, &captured);
  Survey(name, model, 1, 47, std::move(captured));
}

INSTANTIATE_TEST_SUITE_P(RankDecisions, CollectionRobot, ::testing::ValuesIn(CollectionUrdfs()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return CollectionName(info.param);
                         });

// ---------------------------------------------------- saved triggers ---
// The matrices on which Eigen 3.4.0's BDCSVD fails (tests/data/rank_decisions/,
// README.md there says where each comes from): BDCSVD still asserts on them
// or returns what is not an SVD (were Debian's Eigen fixed, this says so),
// and both decompositions decide as a Jacobi SVD does at the sites'
// threshold. ccma's old code (BDCSVD, up to 826693e) aborts on the first kind
// in a build with assertions and decides wrongly on the second.
std::vector<std::string> SavedTriggers() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(std::string(CCMA_TEST_DATA_DIR) + "/rank_decisions")) {
    if (entry.path().extension() == ".txt") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class SavedTrigger : public ::testing::TestWithParam<std::string> {};

TEST_P(SavedTrigger, BdcsvdAssertsAndTheDecisionsAgreeWithJacobi) {
  const Eigen::MatrixXd A = LoadNonzeros(GetParam());
  ASSERT_GT(A.size(), 0);
  const std::vector<double> data(A.data(), A.data() + A.size());
  const int rows = static_cast<int>(A.rows()), cols = static_cast<int>(A.cols());
  const testing::BdcsvdProbe values = testing::ProbeBdcsvd(data, rows, cols, false);
  const testing::BdcsvdProbe full = testing::ProbeBdcsvd(data, rows, cols, true);
  std::string wrong;
  if (!full.assertion_failed) {
    wrong = NotAnSvd(A, Eigen::Map<const Eigen::VectorXd>(full.singular_values.data(), A.cols() < A.rows() ? A.cols() : A.rows()),
                     Eigen::Map<const Eigen::MatrixXd>(full.V.data(), A.cols(), A.cols()));
  }
  EXPECT_TRUE(values.assertion_failed || full.assertion_failed || !wrong.empty())
      << "Eigen's BDCSVD no longer fails on this matrix: fixed in this Eigen?";
  // Power iteration: a lower bound, close enough to scale a threshold.
  const double scale = LargestSingularValue(SparseMatrixCol(A.sparseView()));
  const Eigen::VectorXd sigma = JacobiSvd(A).singularValues();
  EXPECT_LE(scale, sigma[0] * (1 + 1e-12));
  EXPECT_GT(scale, 0.99 * sigma[0]);
  // The sites' thresholds: the moved components' and idle motions', the
  // compliant equilibrium's.
  for (const double threshold : {1e-8 * std::max(1.0, scale), 1e-10 * scale}) {
    SCOPED_TRACE("threshold " + Str(threshold));
    const RankRevealingDecomposition jacobi(A, {threshold, 0.0}, Method::kJacobiSvd);
    const RankRevealingDecomposition qr(A, {threshold, 0.0}, Method::kPivotedQr);
    // A clear gap at the threshold: the decision is well defined.
    ASSERT_GT(jacobi.rank(), 0);
    EXPECT_GT(sigma[jacobi.rank() - 1], 1e3 * threshold);
    if (jacobi.rank() < sigma.size()) EXPECT_LT(sigma[jacobi.rank()], 1e-3 * threshold);
    EXPECT_EQ(qr.rank(), jacobi.rank());
    ASSERT_EQ(qr.nullSpace().cols(), cols - jacobi.rank());
    EXPECT_LT(ProjectorDifference(qr.nullSpace(), jacobi.nullSpace()), kProjectorTolerance);
    if (qr.nullSpace().cols() == 0) continue;
    EXPECT_LT((A * qr.nullSpace()).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, scale));
    const Eigen::MatrixXd gram = qr.nullSpace().transpose() * qr.nullSpace();
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(RankDecisions, SavedTrigger, ::testing::ValuesIn(SavedTriggers()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return fs::path(info.param).stem().string();
                         });

}  // namespace rank_decisions_test
}  // namespace ccma
