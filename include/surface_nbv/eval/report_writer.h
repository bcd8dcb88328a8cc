// Writes an evaluation to a directory: report.json and report.md (inputs'
// sizes, settings, coverage, signed error figures, timings) and PLY clouds:
// ground_truth_visible.ply / ground_truth_hidden.ply (the pruning, for
// inspection), coverage.ply (visible samples, green covered / red missed) and
// error.ply (matched samples coloured by signed error, blue below the ground
// truth, red above, with an `error` property in metres).
#pragma once

#include <string>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/eval/ply_cloud_writer.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct EvalInputs {
  std::string reconstruction;  // what the meshes were loaded from, for the report
  std::string ground_truth;
};

class ReportWriter {
 public:
  ReportWriter(const EvalResult& result, const EvalInputs& inputs) : result_(result), inputs_(inputs) {}

  // Creates `directory` if needed and writes every file into it.
  Status write(const std::string& directory) const;

  std::string json() const;
  std::string markdown() const;
  // Half-width of the error colour ramp: the 95th percentile of |error|, at least 1 mm.
  double colourRange() const;
  // Blue (-range) to light grey (0) to red (+range), clamped.
  static Rgb errorColour(double error, double range);

 private:
  Status writeClouds(const std::string& directory) const;

  const EvalResult& result_;
  EvalInputs inputs_;
};

}  // namespace surface_nbv
