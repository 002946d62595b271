#include "formats/internal/base_radius_fit.h"

#include <algorithm>
#include <numeric>
#include <set>

namespace ccma {
namespace internal {
namespace {

using NamePair = std::pair<std::string, std::string>;

NamePair Ordered(const std::string& a, const std::string& b) {
  return a < b ? NamePair{a, b} : NamePair{b, a};
}

}  // namespace

BaseRadiusFit FitDefaultBaseRadius(const Model& model, const std::vector<double>& given,
                                   const std::vector<std::pair<std::string, std::string>>& ignored,
                                   double gap, double cap) {
  BaseRadiusFit fit;
  fit.radius = cap;
  const int n = model.num_bases();
  std::set<NamePair> skipped;
  for (const auto& pair : ignored) skipped.insert(Ordered(pair.first, pair.second));
  for (const Joint& joint : model.joints) {
    if (joint.body_a != kWorld && joint.body_b != kWorld) {
      skipped.insert(Ordered(model.bodies[joint.body_a].name, model.bodies[joint.body_b].name));
    }
  }
  double largest_given = 0;
  for (double r : given) largest_given = std::max(largest_given, r);
  // A pair farther apart than this along x cannot bound the radius below cap.
  const double reach = cap + std::max(cap, largest_given) + gap;
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  auto x = [&](int k) { return model.mobile_bases[static_cast<size_t>(k)].home_pose.x(); };
  std::sort(order.begin(), order.end(), [&](int i, int j) { return x(i) < x(j); });
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n && x(order[j]) - x(order[i]) <= reach; ++j) {
      const int a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
      const double ra = given[static_cast<size_t>(a)], rb = given[static_cast<size_t>(b)];
      if (ra > 0 && rb > 0) continue;
      const MobileBase& base_a = model.mobile_bases[static_cast<size_t>(a)];
      const MobileBase& base_b = model.mobile_bases[static_cast<size_t>(b)];
      if (skipped.count(Ordered(base_a.name, base_b.name)) > 0) continue;
      const double d = (base_a.home_pose.head<2>() - base_b.home_pose.head<2>()).norm();
      // d - r_a - r_b >= gap, with r for each base that gives none.
      const double bound = ra > 0 ? d - gap - ra : rb > 0 ? d - gap - rb : 0.5 * (d - gap);
      if (bound < fit.radius) fit = {bound, a, b, d};
    }
  }
  return fit;
}

}  // namespace internal
}  // namespace ccma
