// Large CSV files for the tests of `ccma view`'s memory (viewer_memory_test,
// viewer_memory_large_test): written row by row, so that the test process
// itself stays small, and sized by their row and column counts.
#ifndef CCMA_TESTS_LARGE_CSV_H_
#define CCMA_TESTS_LARGE_CSV_H_

#include <cstdint>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace ccma::testing {

// A workspace map of 4dof_reduced (it controls x, y, z and yaw): `rows`
// rows of x, y, z, yaw, reachable, sigma_min and then `controls` control
// columns u0, u1, ... of "0". The points spread over a 1 m cube, every
// other one reachable. Returns the file's size [bytes].
inline std::uintmax_t WriteWideWorkspaceMap(const std::string& path, long rows, int controls) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << "x,y,z,yaw,reachable,sigma_min";
  for (int k = 0; k < controls; ++k) out << ",u" << k;
  out << "\n";
  std::string zeros;
  for (int k = 0; k < controls; ++k) zeros += ",0";
  for (long r = 0; r < rows; ++r) {
    out << (r % 97) * 0.01 << "," << (r % 89) * 0.01 << "," << 0.2 + (r % 83) * 0.01 << ",0," << (r % 2) << ","
        << 0.001 * (r % 1000) << zeros << "\n";
  }
  out.close();
  return std::filesystem::file_size(path);
}

// The data rows of a CSV (no comment, no header), and its header.
inline std::vector<std::string> CsvRows(const std::string& path, std::string* header) {
  std::ifstream in(path);
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header->empty()) {
      *header = line;
    } else {
      rows.push_back(line);
    }
  }
  return rows;
}

// A row with every number written to `digits` significant digits.
inline std::string Rounded(const std::string& line, int digits) {
  std::ostringstream out;
  out << std::setprecision(digits);
  std::size_t from = 0;
  for (std::size_t comma = 0; comma != std::string::npos; from = comma + 1) {
    comma = line.find(',', from);
    const std::string cell = line.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    if (from > 0) out << ",";
    if (!cell.empty() && *end == '\0') {
      out << v;
    } else {
      out << cell;
    }
  }
  return out.str();
}

// A trajectory of `rows` rows: the rows of the trajectory CSV `source`
// (written by `ccma trajectory`) over and over, time_s rising by 0.01 s a
// row, each with `extra` empty columns more; with `digits` > 0, every
// number to that many significant digits (shorter rows, whose controls then
// fit the mechanism less well). Returns its size [bytes].
inline std::uintmax_t WriteLongTrajectory(const std::string& path, const std::string& source, long rows, int extra,
                                          int digits = 0) {
  std::string header;
  std::vector<std::string> lines = CsvRows(source, &header);
  if (digits > 0) {
    for (std::string& line : lines) line = Rounded(line, digits);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << header;
  for (int k = 0; k < extra; ++k) out << ",extra" << k;
  out << "\n";
  const std::string empty(static_cast<std::size_t>(extra), ',');
  for (long r = 0; r < rows && !lines.empty(); ++r) {
    const std::string& line = lines[static_cast<std::size_t>(r) % lines.size()];
    out << r / 100 << "." << (r % 100 < 10 ? "0" : "") << r % 100 << line.substr(line.find(',')) << empty << "\n";
  }
  out.close();
  return std::filesystem::file_size(path);
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_LARGE_CSV_H_
