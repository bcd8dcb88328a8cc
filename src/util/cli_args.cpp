#include "surface_nbv/util/cli_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace surface_nbv {
namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

bool parseNumber(const std::string& text, double* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || std::isnan(v)) return false;
  *out = v;
  return true;
}

}  // namespace

CliArgs::CliArgs(std::vector<std::string> options, std::vector<std::string> flags)
    : options_(std::move(options)), flags_(std::move(flags)) {}

Status CliArgs::parse(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      positional_.push_back(arg);
      continue;
    }
    std::string key = arg.substr(2), value;
    const size_t eq = key.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) {
      value = key.substr(eq + 1);
      key = key.substr(0, eq);
    }
    if (contains(flags_, key) && !inline_value) {
      values_[key] = "true";
    } else if (contains(options_, key)) {
      if (!inline_value) {
        if (i + 1 >= argc) return Status::Error("option --" + key + " expects a value");
        value = argv[++i];
      }
      values_[key] = value;
    } else {
      return Status::Error("unknown option --" + key);
    }
  }
  return Status::Ok();
}

Status CliArgs::parseCommand(int argc, char** argv, const std::string& usage, std::ostream& out, bool* help) {
  *help = false;
  if (Status s = parse(argc, argv); !s) return s;
  if (has("help")) {
    out << usage;
    *help = true;
    return Status::Ok();
  }
  if (!positional_.empty()) return Status::Error("unexpected argument '" + positional_[0] + "'");
  return Status::Ok();
}

std::string CliArgs::get(const std::string& key, const std::string& fallback) const {
  const auto it = values_.find(key);
  return it == values_.end() ? fallback : it->second;
}

Status CliArgs::getDouble(const std::string& key, double* value) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return Status::Ok();
  if (!parseNumber(it->second, value)) return Status::Error("--" + key + " expects a number, got '" + it->second + "'");
  return Status::Ok();
}

Status CliArgs::getInt(const std::string& key, int* value) const {
  double d = *value;
  if (Status s = getDouble(key, &d); !s) return s;
  if (d != std::floor(d) || std::abs(d) > 1e9) return Status::Error("--" + key + " expects an integer");
  *value = static_cast<int>(d);
  return Status::Ok();
}

Status CliArgs::getDoubles(const std::string& key, size_t n, std::vector<double>* values) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return Status::Ok();
  std::vector<double> out;
  std::stringstream ss(it->second);
  std::string item;
  while (std::getline(ss, item, ',')) {
    double d;
    if (!parseNumber(item, &d)) return Status::Error("--" + key + " expects numbers, got '" + it->second + "'");
    out.push_back(d);
  }
  if (out.size() != n) return Status::Error("--" + key + " expects " + std::to_string(n) + " comma-separated numbers");
  *values = out;
  return Status::Ok();
}

}  // namespace surface_nbv
