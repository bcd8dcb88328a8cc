// Command-line options of the form `--key value` or `--flag`, plus positional
// arguments. Each tool declares its options; an unknown option, a missing
// value or an unparsable number is an error naming it.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

class CliArgs {
 public:
  // `options` take a value, `flags` do not.
  CliArgs(std::vector<std::string> options, std::vector<std::string> flags);

  Status parse(int argc, char** argv);
  // For a tool that takes options only: parse(); then, with the `help` flag,
  // writes `usage` to `out` and sets *help; else refuses positional arguments.
  Status parseCommand(int argc, char** argv, const std::string& usage, std::ostream& out, bool* help);
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  std::string get(const std::string& key, const std::string& fallback) const;
  Status getDouble(const std::string& key, double* value) const;
  Status getInt(const std::string& key, int* value) const;
  // A comma-separated list of exactly `n` numbers, e.g. "1,2,3".
  Status getDoubles(const std::string& key, size_t n, std::vector<double>* values) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::vector<std::string> options_, flags_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
};

}  // namespace surface_nbv
