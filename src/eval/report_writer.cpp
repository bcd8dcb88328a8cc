#include "surface_nbv/eval/report_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "surface_nbv/util/json_writer.h"

namespace surface_nbv {
namespace {

constexpr Rgb kCovered{40, 170, 70}, kMissed{220, 40, 40}, kVisible{200, 200, 200}, kHidden{190, 60, 190};

void vectorValue(JsonWriter* json, const std::string& key, const Eigen::Vector3d& v) {
  json->beginArray(key).value("", v.x()).value("", v.y()).value("", v.z()).endArray();
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

Status writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  return out ? Status::Ok() : Status::Error("cannot write '" + path + "'");
}

}  // namespace

double ReportWriter::colourRange() const {
  const double r = result_.error_stats.abs_p95;
  return std::isfinite(r) ? std::max(r, 1e-3) : 1e-3;
}

Rgb ReportWriter::errorColour(double error, double range) {
  const double s = std::clamp(error / range, -1.0, 1.0);
  const Eigen::Vector3d mid(221, 221, 221), low(59, 76, 192), high(180, 4, 38);
  const Eigen::Vector3d c = s < 0.0 ? mid + (-s) * (low - mid) : mid + s * (high - mid);
  return {static_cast<uint8_t>(std::lround(c.x())), static_cast<uint8_t>(std::lround(c.y())),
          static_cast<uint8_t>(std::lround(c.z()))};
}

std::string ReportWriter::json() const {
  const EvalResult& r = result_;
  const EvalConfig& c = r.config;
  const ErrorStats& e = r.error_stats;
  JsonWriter json;
  json.beginObject().beginObject("inputs");
  json.value("reconstruction", inputs_.reconstruction).value("ground_truth", inputs_.ground_truth);
  json.value("reconstruction_triangles", r.reconstruction_triangles)
      .value("reconstruction_area_m2", r.reconstruction_area);
  json.value("ground_truth_triangles", r.ground_truth_triangles).value("ground_truth_area_m2", r.ground_truth_area);
  json.endObject().beginObject("settings");
  json.value("voxel_size_m", c.voxel_size).value("e_max_m", c.eMax()).value("point_spacing_m", c.spacing());
  json.value("seed", static_cast<long long>(c.seed)).value("threads", c.threads).value("prune_hidden", c.prune_hidden);
  vectorValue(&json, "sensor_bounds_min", r.sensor_bounds.min);
  vectorValue(&json, "sensor_bounds_max", r.sensor_bounds.max);
  json.value("min_range_m", c.min_range).value("max_range_m", c.max_range);
  json.value("collision_radius_m", c.collision_radius).value("free_space_cell_m", c.free_space_cell);
  json.value("max_incidence_deg", c.max_incidence_deg).value("visibility_rays", c.visibility_rays);
  json.value("projection_radius_m", c.projectionRadius()).value("max_depth_m", c.maxDepth());
  json.value("normal_radius_m", c.normal_radius).value("normal_agreement_deg", c.normal_agreement_deg);
  json.value("min_neighbours", c.min_neighbours);
  json.endObject().beginObject("samples");
  json.value("ground_truth", r.ground_truth.size()).value("visible", r.numVisible()).value("hidden", r.numHidden());
  json.value("reconstruction", r.reconstruction.size()).value("covered", r.coverage.num_covered);
  json.value("matched", r.matched).value("free_space_cells", r.free_space_cells);
  json.value("reachable_cells", r.reachable_cells);
  json.endObject();
  json.value("coverage", r.coverage.coverage()).value("coverage_percent", 100.0 * r.coverage.coverage());
  json.beginObject("error_m");
  json.value("count", e.count).value("mean", e.mean).value("std_dev", e.std_dev).value("rmse", e.rmse);
  json.value("mean_abs", e.mean_abs).value("max_abs", e.max_abs).value("p5", e.p5).value("p25", e.p25);
  json.value("p50", e.p50).value("p75", e.p75).value("p95", e.p95).value("abs_p95", e.abs_p95);
  json.endObject().value("error_colour_range_m", colourRange()).beginObject("timings_s");
  json.value("sample", r.timings.sample_s).value("free_space", r.timings.free_space_s);
  json.value("visibility", r.timings.visibility_s).value("coverage", r.timings.coverage_s);
  json.value("m3c2", r.timings.m3c2_s).value("total", r.timings.total_s);
  json.endObject().endObject();
  return json.str();
}

std::string ReportWriter::markdown() const {
  const EvalResult& r = result_;
  const EvalConfig& c = r.config;
  const ErrorStats& e = r.error_stats;
  const auto cm = [](double m) { return fixed(100.0 * m, 2) + " cm"; };
  std::ostringstream md;
  md << "# Evaluation of `" << inputs_.reconstruction << "`\n\n"
     << "Ground truth: `" << inputs_.ground_truth << "`. Voxel size rho_v = " << c.voxel_size
     << " m, so e_max = rho_v sqrt(3) / 2 = " << cm(c.eMax()) << ".\n\n"
     << "| figure | value |\n|---|---|\n"
     << "| surface coverage | " << fixed(100.0 * r.coverage.coverage(), 2) << " % (" << r.coverage.num_covered << " of "
     << r.numVisible() << " visible samples) |\n"
     << "| M3C2 mean error | " << cm(e.mean) << " |\n"
     << "| M3C2 std. dev. | " << cm(e.std_dev) << " |\n"
     << "| RMSE | " << cm(e.rmse) << " |\n"
     << "| mean absolute error | " << cm(e.mean_abs) << " |\n"
     << "| error percentiles 5 / 25 / 50 / 75 / 95 | " << cm(e.p5) << " / " << cm(e.p25) << " / " << cm(e.p50) << " / "
     << cm(e.p75) << " / " << cm(e.p95) << " |\n"
     << "| largest absolute error | " << cm(e.max_abs) << " |\n"
     << "| matched samples (covered, with a distance) | " << r.matched << " |\n\n"
     << "| input | triangles | area | samples |\n|---|---|---|---|\n"
     << "| reconstruction | " << r.reconstruction_triangles << " | " << fixed(r.reconstruction_area, 1) << " m^2 | "
     << r.reconstruction.size() << " |\n"
     << "| ground truth | " << r.ground_truth_triangles << " | " << fixed(r.ground_truth_area, 1) << " m^2 | "
     << r.ground_truth.size() << " (" << r.numVisible() << " visible, " << r.numHidden() << " hidden) |\n\n"
     << "Samples every " << fixed(c.spacing(), 3) << " m (seed " << c.seed << "). Hidden ground truth: no line of "
     << "sight to a position at least " << c.collision_radius << " m from the surface, reachable from outside, at "
     << c.min_range << " to " << c.max_range << " m, within " << c.max_incidence_deg << " deg of the normal"
     << (c.prune_hidden ? "" : " (pruning disabled)") << ". M3C2 cylinder: radius " << cm(c.projectionRadius())
     << ", half length " << cm(c.maxDepth()) << ". Time: " << fixed(r.timings.total_s, 2) << " s on " << c.threads
     << " thread(s).\n";
  return md.str();
}

Status ReportWriter::writeClouds(const std::string& directory) const {
  const EvalResult& r = result_;
  const SurfaceCloud& gt = r.ground_truth;
  PlyCloud visible, hidden, coverage, error;
  coverage.scalar_name = "nearest_distance";
  error.scalar_name = "error";
  const double range = colourRange();
  for (size_t i = 0; i < gt.size(); ++i) {
    PlyCloud& pruned = r.visible[i] != 0 ? visible : hidden;
    pruned.points.push_back(gt.points[i]);
    pruned.normals.push_back(gt.normals[i]);
    pruned.colors.push_back(r.visible[i] != 0 ? kVisible : kHidden);
    if (r.visible[i] == 0) continue;
    coverage.points.push_back(gt.points[i]);
    coverage.colors.push_back(r.coverage.covered[i] != 0 ? kCovered : kMissed);
    coverage.scalars.push_back(r.coverage.nearest[i]);
    if (!std::isfinite(r.error[i])) continue;
    error.points.push_back(gt.points[i]);
    error.colors.push_back(errorColour(r.error[i], range));
    error.scalars.push_back(r.error[i]);
  }
  const std::pair<const char*, const PlyCloud*> files[] = {{"ground_truth_visible.ply", &visible},
                                                           {"ground_truth_hidden.ply", &hidden},
                                                           {"coverage.ply", &coverage},
                                                           {"error.ply", &error}};
  for (const auto& [name, cloud] : files) {
    if (Status s = writePlyCloud(directory + "/" + name, *cloud); !s) return s;
  }
  return Status::Ok();
}

Status ReportWriter::write(const std::string& directory) const {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) return Status::Error("cannot create output directory '" + directory + "': " + ec.message());
  if (Status s = writeText(directory + "/report.json", json()); !s) return s;
  if (Status s = writeText(directory + "/report.md", markdown()); !s) return s;
  return writeClouds(directory);
}

}  // namespace surface_nbv
