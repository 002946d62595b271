#include "python/src/json_to_python.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include <pybind11/numpy.h>

#include "ccma/internal/format.h"

namespace py = pybind11;

namespace ccma::python {

py::object ToPython(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: {
      const double v = j.get<double>();
      return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const nlohmann::json& e : j) list.append(ToPython(e));
      return std::move(list);
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = j.begin(); it != j.end(); ++it) dict[py::str(it.key())] = ToPython(it.value());
      return std::move(dict);
    }
    default:
      return py::none();
  }
}

py::object ToView(const nlohmann::json& j) {
  return py::module_::import("ccma._records").attr("view")(ToPython(j));
}

py::object MakeResult(const char* class_name, const nlohmann::json& document, const py::dict& tables,
                      const py::dict& extras) {
  const py::object cls = py::module_::import("ccma.results").attr(class_name);
  return cls(ToPython(document), tables, **extras);
}

std::string OutPath(const py::object& out) {
  if (out.is_none()) return "";
  const std::string path = py::module_::import("os").attr("fspath")(out).cast<std::string>();
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (path.empty() || !std::filesystem::is_directory(folder, ec)) {
    throw py::value_error("out: " + Quote(path) + ": its folder does not exist");
  }
  return path;
}

py::object ToTable(const documents::Table& table) {
  py::dict columns;
  for (const documents::Column& c : table.columns) {
    const auto n = static_cast<py::ssize_t>(c.size());
    switch (c.kind) {
      case documents::ColumnKind::kNumber: {  // NaN where the CSV leaves the cell empty
        py::array_t<double> a(n);
        for (py::ssize_t i = 0; i < n; ++i) {
          const double v = c.values[static_cast<std::size_t>(i)];
          a.mutable_at(i) = std::isfinite(v) ? v : std::numeric_limits<double>::quiet_NaN();
        }
        columns[c.name.c_str()] = a;
        break;
      }
      case documents::ColumnKind::kFlag: {
        py::array_t<bool> a(n);
        for (py::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = c.values[static_cast<std::size_t>(i)] != 0;
        columns[c.name.c_str()] = a;
        break;
      }
      case documents::ColumnKind::kCount: {
        py::array_t<std::int64_t> a(n);
        for (py::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = static_cast<std::int64_t>(c.values[static_cast<std::size_t>(i)]);
        columns[c.name.c_str()] = a;
        break;
      }
      case documents::ColumnKind::kText: {
        py::list texts;
        for (const std::string& t : c.texts) texts.append(py::str(documents::CsvSafeText(t)));
        columns[c.name.c_str()] = texts;
        break;
      }
    }
  }
  return py::module_::import("ccma._tables").attr("Table").attr("from_arrays")(columns);
}

py::object TableFromCsv(const std::string& text, const std::string& source) {
  return py::module_::import("ccma._tables").attr("Table").attr("from_csv")(text, source);
}

}  // namespace ccma::python
