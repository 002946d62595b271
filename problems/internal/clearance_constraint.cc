#include "problems/internal/clearance_constraint.h"

#include <algorithm>
#include <cmath>

#include "ccma/internal/format.h"

namespace ccma {

ClearanceConstraint::ClearanceConstraint(const Model& model) : collision_(model) {}

void ClearanceConstraint::Begin(const Eigen::VectorXd& /*u0*/, const State& s0) {
  items_.clear();
  item_of_.clear();
  floors_.clear();
  for (const PairClearance& p : Near(s0, collision_.margin())) {
    if (p.distance.distance < collision_.margin()) floors_[{p.a, p.b}] = p.distance.distance;
  }
}

double ClearanceConstraint::Floor(const std::pair<int, int>& pair) const {
  const auto it = floors_.find(pair);
  return it == floors_.end() ? collision_.margin() : it->second;
}

int ClearanceConstraint::ItemOf(int a, int b) const {
  const auto [it, added] = item_of_.emplace(std::make_pair(a, b), static_cast<int>(items_.size()));
  if (added) items_.emplace_back(a, b);
  return it->second;
}

std::vector<PairClearance> ClearanceConstraint::Near(const State& s, double threshold) const {
  collision_.PlaceShapes(s, &shapes_);
  return NearClearances(collision_, shapes_, threshold);
}

double ClearanceConstraint::MaxViolation(const Eigen::VectorXd& /*u*/, const State& s) const {
  double worst = 0;
  for (const PairClearance& p : Near(s, collision_.margin())) {
    worst = std::max(worst, Floor({p.a, p.b}) - p.distance.distance);
  }
  return worst;
}

std::vector<int> ClearanceConstraint::AtOrBeyond(const Eigen::VectorXd& /*u*/, const State& s, double tolerance) const {
  std::vector<int> out;
  for (const PairClearance& p : Near(s, collision_.margin() + std::max(tolerance, 0.0))) {
    if (p.distance.distance <= Floor({p.a, p.b}) + tolerance) out.push_back(ItemOf(p.a, p.b));
  }
  return out;
}

Eigen::RowVectorXd ClearanceConstraint::ControlGradient(const State& s, const PairClearance& p,
                                                        const SensitivityView& ds_du) const {
  Eigen::Matrix<double, 1, 6> g_a, g_b;
  ClearanceGradient(collision_, s, p, &g_a, &g_b);
  Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(s.tangent_size());
  const int body_a = collision_.BodyOf(p.a), body_b = collision_.BodyOf(p.b);
  if (body_a != kWorld) g.segment<kPoseTangentSize>(kPoseTangentSize * body_a) += g_a;
  if (body_b != kWorld) g.segment<kPoseTangentSize>(kPoseTangentSize * body_b) += g_b;
  return ds_du.RowTimes(g);
}

void ClearanceConstraint::AppendInequalities(const Eigen::VectorXd& /*u*/, const State& s,
                                             const SensitivityView& ds_du, double watch,
                                             std::vector<InequalityRow>* rows) const {
  for (const PairClearance& p : Near(s, collision_.margin() + watch)) {
    const double floor = Floor({p.a, p.b});
    if (p.distance.distance <= floor + watch) rows->push_back({ControlGradient(s, p, ds_du), floor - p.distance.distance});
  }
}

void ClearanceConstraint::AppendRows(const Eigen::VectorXd& /*u*/, const State& s, const SensitivityView& ds_du,
                                     const std::vector<int>& active, int first_row, LinearConstraints* rows) const {
  collision_.PlaceShapes(s, &shapes_);
  int row = first_row;
  for (int item : active) {
    const auto [a, b] = items_[static_cast<size_t>(item)];
    const PairClearance p{a, b, Distance(shapes_[a], shapes_[b])};
    rows->A.row(row) = ControlGradient(s, p, ds_du);
    rows->b[row] = Floor({a, b}) - p.distance.distance;
    ++row;
  }
}

std::vector<int> ClearanceConstraint::WouldCross(const Eigen::VectorXd& /*u*/, const State& s, const SensitivityView& ds_du,
                                                 const Eigen::VectorXd& d, double tolerance) const {
  // How far any shape can move in this step (first order): translation plus
  // rotation times the shapes' reach; pairs farther apart cannot cross.
  const Eigen::VectorXd ds = ds_du.Times(d);
  double motion = 0;
  for (int body = 0; body < s.num_bodies(); ++body) {
    const auto block = ds.segment<kPoseTangentSize>(kPoseTangentSize * body);
    motion = std::max(motion, block.tail<3>().norm() + block.head<3>().norm() * collision_.reach());
  }
  std::vector<int> out;
  Eigen::Matrix<double, 1, 6> g_a, g_b;
  for (const PairClearance& p : Near(s, collision_.margin() + 2 * motion)) {
    ClearanceGradient(collision_, s, p, &g_a, &g_b);
    double predicted = p.distance.distance;
    const int body_a = collision_.BodyOf(p.a), body_b = collision_.BodyOf(p.b);
    if (body_a != kWorld) predicted += g_a.dot(ds.segment<kPoseTangentSize>(kPoseTangentSize * body_a));
    if (body_b != kWorld) predicted += g_b.dot(ds.segment<kPoseTangentSize>(kPoseTangentSize * body_b));
    if (predicted < Floor({p.a, p.b}) - tolerance) out.push_back(ItemOf(p.a, p.b));
  }
  return out;
}

std::string ClearanceConstraint::Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                                        ControlStepResult* result) const {
  result->max_clearance_violation = MaxViolation(u, s);
  std::string text;
  collision_.PlaceShapes(s, &shapes_);
  for (int item : active) {
    const auto [a, b] = items_[static_cast<size_t>(item)];
    const double d = Distance(shapes_[a], shapes_[b]).distance;
    const double floor = Floor({a, b});
    if (d > floor + 1e-8) continue;  // released since
    text += std::string(text.empty() ? "" : ", ") + "clearance between '" + collision_.Name(a) + "' and '" +
            collision_.Name(b) + "' at " +
            (floor < collision_.margin() ? "its value at the start " + FormatG(floor) + " m (below the margin)"
                                         : "the margin " + FormatG(floor) + " m");
  }
  return text;
}

}  // namespace ccma
