#include "apps/json_output.h"

#include <algorithm>
#include <iostream>

#include "apps/cli.h"

namespace ccma::cli {

void AddClearance(const Model& model, const State& s, const std::string& command, nlohmann::json* out) {
  std::vector<std::string> warnings;
  documents::AddClearance(model, s, out, &warnings);
  for (const std::string& w : warnings) std::cerr << "ccma " << command << ": warning: " << w << "\n";
}

namespace {

Eigen::VectorXd Numbers(const nlohmann::json& j, size_t count, const std::string& where) {
  if (!j.is_array() || j.size() != count) {
    throw UsageError(where + ": must be a list of " + std::to_string(count) + " numbers");
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(count));
  for (size_t i = 0; i < count; ++i) {
    if (!j[i].is_number() || !(std::abs(j[i].get<double>()) <= kMaxMagnitude)) {
      throw UsageError(where + ": entry " + std::to_string(i) + " must be a finite number of magnitude <= 1e4");
    }
    v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
  }
  return v;
}

}  // namespace

State StateFromJson(const Model& model, const nlohmann::json& document, const std::string& source) {
  if (!document.is_object() || !document.contains("bodies") || !document["bodies"].is_array()) {
    throw UsageError(source + ": bodies: missing (a JSON document printed by ccma simulate or ccma control)");
  }
  State s = State::Home(model);
  std::vector<bool> seen(static_cast<size_t>(model.num_bodies()), false);
  for (size_t k = 0; k < document["bodies"].size(); ++k) {
    const nlohmann::json& body = document["bodies"][k];
    const std::string where = source + ": bodies[" + std::to_string(k) + "]";
    if (!body.is_object() || !body.contains("name") || !body["name"].is_string()) {
      throw UsageError(where + ".name: missing");
    }
    const int index = model.FindBody(body["name"].get<std::string>());
    if (index < 0) throw UsageError(where + ".name: the model has no body of that name");
    if (!body.contains("position")) throw UsageError(where + ".position: missing");
    const Eigen::Vector3d p = Numbers(body["position"], 3, where + ".position");
    Eigen::Quaterniond q;
    if (body.contains("quaternion")) {
      const Eigen::VectorXd wxyz = Numbers(body["quaternion"], 4, where + ".quaternion");
      if (!(wxyz.norm() > 0.5 && wxyz.norm() < 2)) throw UsageError(where + ".quaternion: not a unit quaternion");
      q = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    } else if (body.contains("rpy")) {
      q = Eigen::Quaterniond(RotationFromRpy(Numbers(body["rpy"], 3, where + ".rpy")));
    } else {
      throw UsageError(where + ": needs quaternion or rpy");
    }
    s.SetPose(index, q, p);
    seen[static_cast<size_t>(index)] = true;
  }
  for (int i = 0; i < model.num_bodies(); ++i) {
    if (!seen[static_cast<size_t>(i)]) {
      throw UsageError(source + ": bodies: no entry for body '" + model.bodies[i].name + "'");
    }
  }
  return s;
}

namespace {

// Objects one key per line; arrays of scalars (vectors, matrix rows) inline.
void Write(const nlohmann::json& j, int indent, std::ostream& os) {
  const std::string pad(indent, ' '), inner(indent + 2, ' ');
  auto all_scalars = [](const nlohmann::json& a) {
    for (const auto& e : a) {
      if (e.is_structured() && !(e.is_array() && std::none_of(e.begin(), e.end(), [](const auto& x) {
                                   return x.is_structured();
                                 }))) {
        return false;
      }
    }
    return true;
  };
  if (j.is_object()) {
    os << "{";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      os << (first ? "\n" : ",\n") << inner << nlohmann::json(it.key()).dump() << ": ";
      Write(it.value(), indent + 2, os);
      first = false;
    }
    os << (first ? "}" : "\n" + pad + "}");
  } else if (j.is_array() && !all_scalars(j)) {
    os << "[";
    bool first = true;
    for (const auto& e : j) {
      os << (first ? "\n" : ",\n") << inner;
      Write(e, indent + 2, os);
      first = false;
    }
    os << (first ? "]" : "\n" + pad + "]");
  } else {
    os << j.dump();
  }
}

}  // namespace

void PrintJson(const nlohmann::json& document) {
  Write(document, 0, std::cout);
  std::cout << std::endl;
}

void PrintWarnings(const documents::Document& document, const std::string& command) {
  for (const std::string& w : document.warnings) std::cerr << "ccma " << command << ": warning: " << w << "\n";
  for (const std::string& n : document.notes) std::cerr << "ccma " << command << ": note: " << n << "\n";
}

void PrintDocument(const documents::Document& document, const std::string& command) {
  PrintWarnings(document, command);
  PrintJson(document.json);
}

}  // namespace ccma::cli
