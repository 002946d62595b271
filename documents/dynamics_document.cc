#include "documents/dynamics_document.h"

#include <cmath>
#include <limits>

#include "ccma/internal/format.h"
#include "viewer/view_frames.h"

namespace ccma::documents {

Table DynamicsTable(const Model& model, const DynamicsReport& report) {
  Table table;
  Column& time = table.Add("time_s");
  for (const DynamicsRow& row : report.rows) time.values.push_back(row.time);
  const std::vector<std::string> names = viewer::EffortColumns(model);
  for (size_t i = 0; i < names.size(); ++i) {
    Column& c = table.Add(names[i]);
    for (const DynamicsRow& row : report.rows) {
      c.values.push_back(row.assembled ? row.efforts[static_cast<Eigen::Index>(i)]
                                       : std::numeric_limits<double>::quiet_NaN());
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Column& kinetic = table.Add("kinetic_J");
  Column& potential = table.Add("potential_J");
  Column& power = table.Add("power_W");
  for (const DynamicsRow& row : report.rows) {
    kinetic.values.push_back(row.assembled ? row.kinetic : nan);
    potential.values.push_back(row.assembled ? row.potential : nan);
    power.values.push_back(row.assembled ? row.power : nan);
  }
  return table;
}

namespace {

nlohmann::json ActuatorJson(const ActuatorSummary& a) {
  nlohmann::json j = {{"name", a.name}, {"kind", a.kind}, {"peak_effort", a.peak_effort},
                      {"peak_time_s", a.peak_time}, {"rms_effort", a.rms_effort},
                      {"within_limits", a.within_limits}};
  j["limit"] = a.limit ? nlohmann::json::array({a.limit->first, a.limit->second}) : nlohmann::json(nullptr);
  j["peak_rate"] = a.peak_rate;
  j["rate_limit"] = a.rate_limit ? nlohmann::json(*a.rate_limit) : nlohmann::json(nullptr);
  return j;
}

std::string Warnings(const DynamicsReport& report) {
  std::string warning;
  if (report.not_assembled_rows > 0) {
    JoinWarning(std::to_string(report.not_assembled_rows) + " of " + std::to_string(report.rows.size()) +
                    " rows did not assemble (their efforts are empty in the CSV and left out of the summary)",
                &warning);
  }
  if (!report.within_limits) {
    JoinWarning("beyond the effort or rate limits of " + std::to_string(report.limiting.size()) +
                    " actuator(s) (limiting)",
                &warning);
  }
  if (report.max_rate_inconsistency > 1e-6) {
    JoinWarning("the spline's control rates are not rates the mechanism admits (by up to " +
                    FormatG(report.max_rate_inconsistency) +
                    " per constraint row: an over-actuated model between rows); efforts are for the nearest motion",
                &warning);
  }
  return warning;
}

}  // namespace

Document DynamicsDocument(const DynamicsReport& report) {
  Document d;
  nlohmann::json& j = d.json;
  j["rows"] = report.rows.size();
  j["duration_s"] = report.duration;
  j["assembled"] = report.assembled;
  j["not_assembled_rows"] = report.not_assembled_rows;
  j["actuators"] = nlohmann::json::array();
  for (const ActuatorSummary& a : report.actuators) j["actuators"].push_back(ActuatorJson(a));
  j["within_limits"] = report.within_limits;
  j["limiting"] = report.limiting;
  j["energy_J"] = report.energy;
  j["max_power_W"] = report.max_power;
  j["max_rate_inconsistency"] = report.max_rate_inconsistency;
  d.Warn(Warnings(report));
  return d;
}

}  // namespace ccma::documents
