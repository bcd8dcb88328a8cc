#include "surface_nbv/planning/tsplib_reader.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace surface_nbv {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

bool parseDouble(const std::string& token, double* out) {
  char* end = nullptr;
  *out = std::strtod(token.c_str(), &end);
  return !token.empty() && end == token.c_str() + token.size() && std::isfinite(*out);
}

}  // namespace

Status readTsplib(const std::string& path, TsplibProblem* problem) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  auto error = [&](int line, const std::string& what) {
    return Status::Error(path + ":" + std::to_string(line) + ": " + what);
  };
  TsplibProblem p;
  std::string format;
  int dimension = -1, dimension_line = 0;
  std::vector<double> numbers;  // the section's numbers, in order
  std::vector<int> number_lines;
  std::string section;
  int section_line = 0;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty()) continue;
    if (t == "EOF") break;
    const size_t colon = t.find(':');
    const std::string key = trim(colon == std::string::npos ? t : t.substr(0, colon));
    if (key == "NODE_COORD_SECTION" || key == "EDGE_WEIGHT_SECTION") {
      if (!section.empty()) return error(line_no, key + " after " + section);
      if (dimension <= 0) return error(line_no, key + " before DIMENSION");
      section = key;
      section_line = line_no;
      continue;
    }
    if (!section.empty()) {
      std::istringstream ss(t);
      std::string token;
      while (ss >> token) {
        double v;
        if (!parseDouble(token, &v)) return error(line_no, "expected a number in " + section + ", got '" + token + "'");
        numbers.push_back(v);
        number_lines.push_back(line_no);
      }
      continue;
    }
    if (colon == std::string::npos) return error(line_no, "expected 'KEY : VALUE', got '" + t + "'");
    const std::string value = trim(t.substr(colon + 1));
    if (key == "NAME") {
      p.name = value;
    } else if (key == "COMMENT" || key == "DISPLAY_DATA_TYPE") {
    } else if (key == "TYPE") {
      if (value != "TSP" && value != "ATSP") return error(line_no, "TYPE '" + value + "' is not TSP or ATSP");
      p.type = value;
    } else if (key == "DIMENSION") {
      double d;
      if (!parseDouble(value, &d) || d != std::floor(d) || d < 1 || d > 100000)
        return error(line_no, "DIMENSION '" + value + "' is not an integer in [1, 100000]");
      dimension = static_cast<int>(d);
      dimension_line = line_no;
    } else if (key == "EDGE_WEIGHT_TYPE") {
      if (value != "EXPLICIT" && value != "EUC_2D")
        return error(line_no, "EDGE_WEIGHT_TYPE '" + value + "' is not supported (EXPLICIT, EUC_2D)");
      p.edge_weight_type = value;
    } else if (key == "EDGE_WEIGHT_FORMAT") {
      if (value != "FULL_MATRIX")
        return error(line_no, "EDGE_WEIGHT_FORMAT '" + value + "' is not supported (FULL_MATRIX)");
      format = value;
    } else {
      return error(line_no, "unknown keyword '" + key + "'");
    }
  }
  const int last = line_no;
  if (p.type.empty()) return error(last, "no TYPE");
  if (dimension <= 0) return error(last, "no DIMENSION");
  if (p.edge_weight_type.empty()) return error(last, "no EDGE_WEIGHT_TYPE");
  const int n = dimension;
  // The matrix is allocated only once the section holds its numbers: a
  // DIMENSION alone must not cost n^2 doubles (up to 80 GB).
  if (p.edge_weight_type == "EXPLICIT") {
    if (format.empty()) return error(last, "EDGE_WEIGHT_TYPE EXPLICIT needs EDGE_WEIGHT_FORMAT FULL_MATRIX");
    if (section != "EDGE_WEIGHT_SECTION") return error(last, "EXPLICIT weights need an EDGE_WEIGHT_SECTION");
    const size_t want = size_t(n) * n;
    if (numbers.size() != want)
      return error(numbers.size() > want ? number_lines[want] : last,
                   "EDGE_WEIGHT_SECTION has " + std::to_string(numbers.size()) + " numbers, DIMENSION " +
                       std::to_string(n) + " (line " + std::to_string(dimension_line) + ") needs " +
                       std::to_string(want));
    p.costs = CostMatrix(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const size_t k = size_t(i) * n + j;
        if (i != j && numbers[k] < 0) return error(number_lines[k], "negative weight " + std::to_string(numbers[k]));
        p.costs.at(i, j) = i == j ? 0.0 : numbers[k];
      }
    }
    if (p.type == "TSP" && !p.costs.isSymmetric())
      return error(section_line, "TYPE TSP but the matrix is not symmetric");
  } else {
    if (section != "NODE_COORD_SECTION") return error(last, "EUC_2D needs a NODE_COORD_SECTION");
    if (p.type != "TSP") return error(last, "EUC_2D is symmetric: TYPE must be TSP");
    if (numbers.size() != size_t(n) * 3)
      return error(last, "NODE_COORD_SECTION has " + std::to_string(numbers.size()) + " numbers, expected " +
                             std::to_string(n) + " lines 'index x y'");
    std::vector<double> x(n), y(n);
    std::vector<char> seen(n, 0);
    for (int k = 0; k < n; ++k) {
      const double index = numbers[3 * k];
      if (index != std::floor(index) || index < 1 || index > n || seen[int(index) - 1])
        return error(number_lines[3 * k],
                     "node index " + std::to_string(index) + " is not a new integer in [1, DIMENSION]");
      if (number_lines[3 * k] != number_lines[3 * k + 2])
        return error(number_lines[3 * k], "expected 'index x y' on one line");
      const int i = static_cast<int>(index) - 1;
      seen[i] = 1;
      x[i] = numbers[3 * k + 1];
      y[i] = numbers[3 * k + 2];
    }
    p.costs = CostMatrix(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        if (i == j) continue;
        const double d = std::floor(std::hypot(x[i] - x[j], y[i] - y[j]) + 0.5);
        if (!(d <= CostMatrix::kMaxCost)) {
          return error(section_line, "nodes " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                                         " are farther apart than " + std::to_string(CostMatrix::kMaxCost));
        }
        p.costs.at(i, j) = d;
      }
    }
  }
  *problem = std::move(p);
  return Status::Ok();
}

}  // namespace surface_nbv
