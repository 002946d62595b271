#include "formats/internal/sdformat_cost.h"

#include <map>
#include <string>

#include <sdf/Element.hh>
#include <sdf/SDFImpl.hh>
#include <sdf/parser.hh>

#include "formats/internal/sdformat_console.h"

namespace ccma {
namespace internal {
namespace {

constexpr double kKilobytesPerElement = 8;
constexpr double kKilobytesPerNode = 1.6;

// Nodes (the element, its attributes and, recursively, its child
// descriptions) of `element`; records the largest per name in *nodes.
std::size_t CountNodes(const sdf::ElementPtr& element, int depth, std::map<std::string, std::size_t>* nodes) {
  std::size_t n = 1 + element->GetAttributeCount();
  if (depth < 64) {  // the specification is a finite tree; this only guards
    for (std::size_t i = 0; i < element->GetElementDescriptionCount(); ++i) {
      n += CountNodes(element->GetElementDescription(i), depth + 1, nodes);
    }
  }
  std::size_t& largest = (*nodes)[element->GetName()];
  if (n > largest) largest = n;
  return n;
}

// Description nodes per element name, from libsdformat's own specification
// (built once).
const std::map<std::string, std::size_t>& DescriptionNodes() {
  static const std::map<std::string, std::size_t> nodes = [] {
    std::map<std::string, std::size_t> out;
    QuietSdformatConsole();  // libsdformat may log from here on: never to a file
    sdf::SDFPtr specification(new sdf::SDF());
    sdf::init(specification);
    if (specification->Root()) CountNodes(specification->Root(), 0, &out);
    return out;
  }();
  return nodes;
}

}  // namespace

double SdformatMegabytes(const std::string& name, std::size_t count) {
  const auto& nodes = DescriptionNodes();
  const auto it = nodes.find(name);
  const double kilobytes = kKilobytesPerElement + (it == nodes.end() ? 0.0 : kKilobytesPerNode * it->second);
  return static_cast<double>(count) * kilobytes / 1024;
}

double SdformatMegabytes(const RobotXmlSummary& summary) {
  double total = 0;
  for (const auto& [name, counted] : summary.names) total += SdformatMegabytes(name, counted.count);
  return total;
}

}  // namespace internal
}  // namespace ccma
