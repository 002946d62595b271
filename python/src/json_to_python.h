// JSON documents (nlohmann::json, as the `ccma` tool prints them) as Python
// values, and the Python result objects made from them (python/ccma/results.py).
#ifndef CCMA_PYTHON_SRC_JSON_TO_PYTHON_H_
#define CCMA_PYTHON_SRC_JSON_TO_PYTHON_H_

#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "documents/table.h"

namespace ccma::python {

// The value as the tool's JSON reads back in Python: null -> None, a
// boolean -> bool, an integer -> int, a number -> float (NaN and infinities,
// which the tool prints as null, -> None), a string -> str, an array ->
// list, an object -> dict.
pybind11::object ToPython(const nlohmann::json& j);

// ToPython's value as a result attribute shows it (ccma._records.view: an
// object as a ccma.Record, a list of numbers as a read-only NumPy array).
pybind11::object ToView(const nlohmann::json& j);

// ccma.results.<class_name>(document, tables, **extras).
pybind11::object MakeResult(const char* class_name, const nlohmann::json& document,
                            const pybind11::dict& tables = pybind11::dict(),
                            const pybind11::dict& extras = pybind11::dict());

// The path `out=` names (os.fspath), "" for None; ValueError when its folder
// does not exist, before anything is computed (as the command checks --out).
std::string OutPath(const pybind11::object& out);

// A command's table (documents/table.h) as a ccma.Table: each column as a
// read-only NumPy array of its kind (float64, bool, int64, str), text cells
// as the CSV holds them (CsvSafeText).
pybind11::object ToTable(const documents::Table& table);

// ccma.Table.from_csv(text): the columns of a CSV the tool writes.
pybind11::object TableFromCsv(const std::string& text, const std::string& source);

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_JSON_TO_PYTHON_H_
