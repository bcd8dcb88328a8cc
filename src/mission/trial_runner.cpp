#include "surface_nbv/mission/trial_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/eval/report_writer.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/map/integrate_kernel.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/mission/flight_csv.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/util/json_writer.h"
#include "surface_nbv/util/run_process.h"

namespace surface_nbv {

namespace {

// printf into a string.
__attribute__((format(printf, 1, 2))) std::string printfString(const char* fmt, ...) {
  va_list args, copy;
  va_start(args, fmt);
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, copy);
  va_end(copy);
  std::string text(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(text.data(), text.size() + 1, fmt, args);
  va_end(args);
  return text;
}

// The trials' config: the config file over the defaults, the scene options
// over it, then the other options, checked as nbv_mission checks them.
Status loadTrialConfig(const TrialOptions& o, MissionConfig* config, std::string* config_file) {
  *config_file = o.config_file ? *o.config_file : defaultConfigFile(o.package_dir, o.scene.value_or("plant"));
  if (!config_file->empty()) {
    if (Status s = loadMissionConfig(*config_file, config); !s) return s;
  }
  SceneConfig& scene = config->scene;
  const std::pair<bool, const char*> given[] = {
      {o.scene.has_value(), "depth_sim/scene"},           {o.up_axis.has_value(), "depth_sim/scene_up_axis"},
      {o.scale.has_value(), "depth_sim/scene_scale"},     {o.fit_size.has_value(), "depth_sim/scene_fit_size"},
      {o.offset.has_value(), "depth_sim/scene_offset"},   {o.crop_min.has_value(), "depth_sim/crop_min"},
      {o.crop_max.has_value(), "depth_sim/crop_max"}};
  for (const auto& [has, key] : given) {
    if (has) config->given_keys.insert(key);
  }
  scene.scene = o.scene.value_or(scene.scene);
  scene.transform.up_axis = o.up_axis.value_or(scene.transform.up_axis);
  scene.transform.scale = o.scale.value_or(scene.transform.scale);
  scene.transform.fit_size = o.fit_size.value_or(scene.transform.fit_size);
  scene.transform.offset = o.offset.value_or(scene.transform.offset);
  scene.transform.crop.min = o.crop_min.value_or(scene.transform.crop.min);
  scene.transform.crop.max = o.crop_max.value_or(scene.transform.crop.max);
  if (Status s = scene.validate(); !s) return s;

  config->explorer.head_lambda = o.oracle_lambda.value_or(config->explorer.head_lambda);
  config->threads = o.threads.value_or(config->threads);
  config->max_flight_time = o.max_flight_time.value_or(config->max_flight_time);
  config->max_path_length = o.max_path_length.value_or(config->max_path_length);
  config->tsdf.voxel_size = o.voxel_size.value_or(config->tsdf.voxel_size);
  if (o.trials < 1 || o.trials > 100 || o.seed < 0) return Status::Error("--trials expects 1..100 and --seed >= 0");
  if (o.coverage_every && !(*o.coverage_every >= 1.0)) {
    return Status::Error("--coverage-every expects >= 1 s of flight");
  }
  if (o.oracle_lambda && !o.oracle_gain) return Status::Error("--oracle-lambda goes with --oracle-gain");
  if (o.oracle_gain) {
    if (*o.oracle_gain < 2) return Status::Error("--oracle-gain expects N >= 2 viewpoints to rank");
    if (o.oracle_lambda && !(config->explorer.head_lambda >= 0.0)) {
      return Status::Error("--oracle-lambda expects L >= 0");
    }
    config->explorer.head_lookahead = *o.oracle_gain;
  }
  if (o.voxel_size) config->given_keys.insert("nbv/voxel_size");
  return config->scene.validate();
}

// A CSV field: in double quotes, a quote inside doubled (RFC 4180), a line
// break made a space so that every row stays one line.
std::string csvQuoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch == '\n' ? ' ' : ch);
  return out + "\"";
}

Status writeCsvs(const std::string& dir, const MissionResult& r) {
  if (Status s = writeFlightCsv(dir + "/path.csv", r.flown_t, r.flown); !s) return s;
  std::ofstream events(dir + "/events.csv");
  events << "t_s,path_m,ises,inside,remaining,viewpoints,clusters,tour,observed,action,reason,collision_ms,frontier_ms,graph_ms,tour_ms,path_ms,full,x_m,y_m,z_m,yaw_rad,leg_failures,message\n";
  for (const MissionEvent& e : r.events) {
    events << e.t << "," << e.path_length << "," << e.ises << "," << e.inside << "," << e.remaining << ","
           << e.viewpoints << "," << e.clusters << "," << e.tour << "," << e.observed << "," << e.action << ","
           << e.reason << "," << e.collision_ms << "," << e.frontier_ms << "," << e.graph_ms << "," << e.tour_ms << ","
           << e.path_ms << "," << (e.full_recompute ? 1 : 0) << "," << e.uav.x() << "," << e.uav.y() << ","
           << e.uav.z() << "," << e.uav.w() << "," << e.leg_failures << "," << csvQuoted(e.message) << "\n";
  }
  if (!events) return Status::Error("cannot write events.csv in " + dir);
  return Status::Ok();
}

Status writeCoverageCsv(const std::string& dir, const std::vector<CoveragePoint>& points) {
  std::ofstream out(dir + "/coverage.csv");
  out.precision(10);
  out << "t_s,path_m,coverage,rmse_m\n";
  for (const CoveragePoint& p : points) {
    out << p.t << "," << p.path_length << "," << p.coverage << "," << p.rmse << "\n";
  }
  if (!out) return Status::Error("cannot write coverage.csv in " + dir);
  return Status::Ok();
}

// coverage_every: coverage [%] by flight time, a row per checkpoint and a
// column per trial, with the path flown; the last row is each trial's end.
void writeCoverageTable(const std::vector<TrialRow>& rows, std::ostream* md) {
  size_t n = 0;
  for (const TrialRow& r : rows) n = std::max(n, r.coverage_over_time.size());
  *md << "\nCoverage over flight time (--coverage-every), per trial: coverage [%] (path [m]).\n\n| checkpoint |";
  for (const TrialRow& r : rows) *md << " trial " << r.trial << " |";
  *md << "\n|---|";
  for (size_t k = 0; k < rows.size(); ++k) *md << "---|";
  *md << "\n";
  char cell[64];
  for (size_t i = 0; i < n; ++i) {
    *md << "| " << i + 1 << " |";
    for (const TrialRow& r : rows) {
      if (i >= r.coverage_over_time.size()) {
        *md << " |";
        continue;
      }
      const CoveragePoint& c = r.coverage_over_time[i];
      std::snprintf(cell, sizeof(cell), " %.1f min: %.2f (%.0f) |", c.t / 60.0, 100.0 * c.coverage, c.path_length);
      *md << cell;
    }
    *md << "\n";
  }
}

// "65.8 % cruise, 17.2 % moving slower, ..., 704 rad of yaw": shares of the flight time.
std::string profileLine(const FlightProfile& p) {
  const double percent = p.flight_s > 0.0 ? 100.0 / p.flight_s : 0.0;
  char line[256];
  std::snprintf(line, sizeof(line), "%.1f %% cruise, %.1f %% moving slower, %.1f %% turning in place, %.1f %% stopped "
                "(vertical %.0f %%), %.0f rad of yaw", percent * p.cruise_s, percent * p.moving_s,
                percent * p.turning_in_place_s, percent * p.stopped_s, percent * p.vertical_s, p.total_yaw_rad);
  return line;
}

void meanStd(const std::vector<double>& v, double* mean, double* sd) {
  *mean = 0.0;
  *sd = 0.0;
  if (v.empty()) return;
  for (double x : v) *mean += x / v.size();
  for (double x : v) *sd += (x - *mean) * (x - *mean) / v.size();
  *sd = std::sqrt(*sd);
}

TrialRow trialRow(int k, unsigned seed, const MissionResult& r, const EvalResult& eval, double speed) {
  TrialRow row;
  row.trial = k;
  row.seed = seed;
  row.completed = r.completed;
  row.end_reason = r.end_reason;
  row.path_length = r.path_length;
  row.flight_min = r.flight_time / 60.0;
  row.coverage = eval.coverage.coverage();
  row.mean = eval.error_stats.mean;
  row.std_dev = eval.error_stats.std_dev;
  row.rmse = eval.error_stats.rmse;
  row.wall_s = r.wall_time;
  row.times = r.times;
  row.pose_error = r.pose_error;
  row.fused_pose_error = r.fused_pose_error;
  row.yaw_corrections = r.yaw_corrections;
  row.profile = profileFlight(r.flown, r.flown_t, speed);
  row.frames = r.frames;
  row.updates = r.frontier_updates;
  row.full = r.explorer.full_recomputes;
  row.local = r.explorer.local_updates;
  row.legs = r.explorer.legs;
  row.failures = r.explorer.leg_failures;
  row.blacklisted = r.blacklisted;
  row.roadmap_growths = r.explorer.roadmap_growths;
  row.roadmap_vertices = r.explorer.roadmap_vertices;
  row.lattice_legs = r.explorer.lattice_legs;
  row.corridor_legs = r.explorer.corridor_legs;
  row.final_inside = r.final_inside;
  row.frontier_ms_max = r.max_frontier_ms;
  row.plan_ms_max = r.max_plan_ms;
  return row;
}

// A report column over the trials: Table 2's criteria, mean and standard deviation.
struct Stat {
  const char* name;
  const char* unit;
  double scale;
  std::vector<double> values;
};

std::vector<Stat> summaryStats(const std::vector<TrialRow>& rows) {
  auto column = [&rows](auto get) {
    std::vector<double> v;
    for (const TrialRow& r : rows) v.push_back(get(r));
    return v;
  };
  return {
      {"path_length", "m", 1.0, column([](const TrialRow& r) { return r.path_length; })},
      {"completion_time", "min", 1.0, column([](const TrialRow& r) { return r.flight_min; })},
      {"coverage", "%", 100.0, column([](const TrialRow& r) { return r.coverage; })},
      {"error_mean", "cm", 100.0, column([](const TrialRow& r) { return r.mean; })},
      {"error_std", "cm", 100.0, column([](const TrialRow& r) { return r.std_dev; })},
      {"rmse", "cm", 100.0, column([](const TrialRow& r) { return r.rmse; })},
      {"wall_time", "s", 1.0, column([](const TrialRow& r) { return r.wall_s; })},
  };
}

// What the reports say besides the rows.
struct ReportHeader {
  const TrialOptions& options;
  const TrialResult& result;
  double e_max = 0.0;
  int packet_rays = 0;
  const char* voxel_loop = "";
  AlignedBox extent;
};

std::string reportJson(const ReportHeader& h, const std::vector<Stat>& stats) {
  const MissionConfig& config = h.result.config;
  const SceneDefaults& derived = h.result.derived;
  const AlignedBox& extent = h.extent;
  JsonWriter json;
  json.beginObject().value("scene", config.scene.scene).value("config", h.result.config_file);
  json.value("trials", h.options.trials);
  json.value("seed", h.options.seed).value("voxel_size_m", config.tsdf.voxel_size).value("e_max_m", h.e_max);
  json.value("threads", config.threads).value("render_packet_rays", h.packet_rays).value("voxel_loop", h.voxel_loop);
  json.value("size_class", derived.size_class).value("map_bytes_estimate", derived.map_bytes);
  json.beginArray("scene_box_m");
  for (double v : {extent.min.x(), extent.min.y(), extent.min.z(), extent.max.x(), extent.max.y(), extent.max.z()}) {
    json.value("", v);
  }
  json.endArray().value("reference_config", derived.reference_config);
  derived.writeJson(&json);  // the keys no config gave, as derived (scene_defaults.h)
  json.beginObject("summary");
  for (const Stat& s : stats) {
    double m, sd;
    meanStd(s.values, &m, &sd);
    json.beginObject(s.name).value("unit", s.unit).value("mean", m * s.scale).value("std", sd * s.scale).endObject();
  }
  json.endObject().beginArray("per_trial");
  for (const TrialRow& r : h.result.rows) {
    json.beginObject().value("trial", r.trial).value("seed", static_cast<int>(r.seed)).value("completed", r.completed);
    json.value("end_reason", r.end_reason).value("path_length_m", r.path_length).value("completion_min", r.flight_min);
    json.value("coverage", r.coverage).value("error_mean_m", r.mean).value("error_std_m", r.std_dev);
    json.value("rmse_m", r.rmse).value("wall_s", r.wall_s).value("frames", r.frames).value("frontier_updates", r.updates);
    json.value("full_recomputes", r.full).value("local_updates", r.local).value("legs", r.legs);
    json.value("leg_failures", r.failures).value("blacklisted", r.blacklisted).value("final_c_ins", r.final_inside);
    json.value("max_frontier_ms", r.frontier_ms_max).value("max_plan_ms", r.plan_ms_max);
    json.value("roadmap_growths", r.roadmap_growths).value("roadmap_vertices", r.roadmap_vertices);
    json.value("lattice_legs", r.lattice_legs).value("corridor_legs", r.corridor_legs);
    if (config.pose_error.enabled()) {  // the estimate and the fused poses against the truth (pose_error.h)
      for (const auto& [name, e] : {std::make_pair("pose_error", r.pose_error),
                                    std::make_pair("fused_pose_error", r.fused_pose_error)}) {
        json.beginObject(name).value("final_m", e.final_position).value("rms_m", e.rms_position);
        json.value("max_m", e.max_position).value("final_yaw_deg", e.final_yaw_deg);
        json.value("rms_yaw_deg", e.rms_yaw_deg).endObject();
      }
      json.value("yaw_corrections", r.yaw_corrections);
    }
    json.beginObject("stage_ms").value("render", r.times.render).value("integrate", r.times.integrate);
    json.value("collision", r.times.collision).value("frontier", r.times.frontier).value("graph", r.times.graph);
    json.value("tour", r.times.tour).value("path", r.times.path).value("tracker", r.times.tracker).endObject();
    json.beginObject("frontier_stage_ms").value("ises", r.times.frontier_ises).value("poses", r.times.frontier_poses);
    json.value("merge", r.times.frontier_merge).value("visibility", r.times.frontier_visibility);
    json.value("clusters", r.times.frontier_clusters).endObject();
    const FlightProfile& p = r.profile;
    json.beginObject("flight_profile").value("cruise_s", p.cruise_s).value("moving_s", p.moving_s);
    json.value("turning_in_place_s", p.turning_in_place_s).value("stopped_s", p.stopped_s);
    json.value("vertical_s", p.vertical_s).value("total_yaw_rad", p.total_yaw_rad).endObject();
    if (h.options.coverage_every) {
      json.beginArray("coverage_over_time");
      for (const CoveragePoint& c : r.coverage_over_time) {
        json.beginObject().value("t_s", c.t).value("path_m", c.path_length).value("coverage", c.coverage);
        json.value("rmse_m", c.rmse).endObject();
      }
      json.endArray();
    }
    json.endObject();
  }
  json.endArray().endObject();
  return json.str();
}

void writeReportMd(const ReportHeader& h, const std::vector<Stat>& stats, std::ostream& md) {
  const MissionConfig& config = h.result.config;
  const int trials = h.options.trials, seed = h.options.seed;
  md << "# Mission on `" << config.scene.scene << "` (" << trials << " trial(s), seeds " << seed << ".."
     << seed + trials - 1 << ")\n\nConfig: `" << h.result.config_file << "`, voxel " << config.tsdf.voxel_size
     << " m, e_max " << 100.0 * h.e_max << " cm. Compute: " << config.threads << " thread(s), "
     << h.packet_rays << "-ray render packets, " << h.voxel_loop << " voxel loop.\n\n"
     << "Derived from the scene (" << h.result.derived.size_class << " class): " << h.result.derived.summary()
     << ".\n\n"
     << "| trial | seed | completed | path [m] | time [min] | coverage [%] | mean [cm] | std [cm] | RMSE [cm] | "
        "wall [s] | frontier updates | full / local | legs / failures | blacklisted |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const TrialRow& r : h.result.rows) {
    std::snprintf(line, sizeof(line), "| %d | %u | %s | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.1f | %zu | %zu / %zu | %zu / %zu | %zu |\n",
                  r.trial, r.seed, r.completed ? "yes" : "no", r.path_length, r.flight_min, 100.0 * r.coverage,
                  100.0 * r.mean, 100.0 * r.std_dev, 100.0 * r.rmse, r.wall_s, r.updates, r.full, r.local, r.legs,
                  r.failures, r.blacklisted);
    md << line;
  }
  md << "\n| criterion | mean | std |\n|---|---|---|\n";
  for (const Stat& s : stats) {
    double m, sd;
    meanStd(s.values, &m, &sd);
    std::snprintf(line, sizeof(line), "| %s [%s] | %.2f | %.2f |\n", s.name, s.unit, m * s.scale, sd * s.scale);
    md << line;
  }
  md << "\nWall-clock milliseconds by stage, per trial: render / integrate / collision map / frontier / graph / "
        "tour / legs / tracker.\n\n";
  for (const TrialRow& r : h.result.rows) {
    std::snprintf(line, sizeof(line), "- trial %d: %.0f / %.0f / %.0f / %.0f / %.0f / %.0f / %.0f / %.0f (slowest "
                  "frontier update %.0f ms, slowest decision %.0f ms); end: %s\n",
                  r.trial, r.times.render, r.times.integrate, r.times.collision, r.times.frontier, r.times.graph,
                  r.times.tour, r.times.path, r.times.tracker, r.frontier_ms_max, r.plan_ms_max, r.end_reason.c_str());
    md << line;
  }
  md << "\nWhere the flight time goes, per trial: cruise at 88 % of the reference speed or more, moving slower "
        "from 0.2 m/s, turning in place below that at over 0.3 rad/s, else stopped; vertical is the part of cruise "
        "and moving that climbs or descends more than it goes sideways.\n\n";
  for (const TrialRow& r : h.result.rows) md << "- trial " << r.trial << ": " << profileLine(r.profile) << "\n";
  if (h.options.coverage_every) writeCoverageTable(h.result.rows, &md);
}

}  // namespace

bool TrialResult::allCompleted() const {
  return std::all_of(rows.begin(), rows.end(), [](const TrialRow& r) { return r.completed; });
}

TrialRunner::TrialRunner(std::ostream& out, std::ostream& err, std::string name)
    : out_(out), err_(err), name_(std::move(name)) {}

void TrialRunner::warn(const std::string& message) const {
  // As fprintf(stderr) did: a warning does not flush what `out` holds first
  // (std::cerr is tied to std::cout).
  std::ostream* tie = err_.tie(nullptr);
  err_ << name_ << ": warning: " << message << "\n" << std::flush;
  err_.tie(tie);
}

Status TrialRunner::run(const TrialOptions& options, TrialResult* result) const {
  *result = TrialResult();
  MissionConfig& config = result->config;
  if (Status s = loadTrialConfig(options, &config, &result->config_file); !s) return s;
  const std::string& config_file = result->config_file;
  const std::string scene_name = std::filesystem::path(config.scene.scene).stem().string();
  result->out_dir = options.out_dir.value_or("output/mission_" + scene_name);
  const std::string& out_dir = result->out_dir;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) return Status::Error("cannot create '" + out_dir + "': " + ec.message());

  TriangleMesh mesh;
  if (Status s = loadScene(config.scene, &mesh); !s) return s;
  SceneDefaults& derived = result->derived;
  SceneDefaultsOptions derive_options;
  derive_options.config_file = !config_file.empty();
  if (Status s = deriveSceneDefaults(mesh, options.package_dir, &config, &derived, derive_options); !s) {
    return Status::Error("scene '" + config.scene.scene + "': " + s.message());
  }
  if (Status s = config.validate(); !s) return Status::Error((config_file.empty() ? "" : config_file + ": ") + s.message());
  std::unique_ptr<RaycastScene> scene;
  if (Status s = RaycastScene::create(mesh, &scene); !s) return s;
  const AlignedBox extent = mesh.bounds();
  out_ << printfString("scene '%s': %zu triangles, %.0f m^2, [%.1f %.1f %.1f] - [%.1f %.1f %.1f] m; config %s; voxel "
                 "%.2f m; %d trial(s) from seed %d\n",
                 config.scene.scene.c_str(), mesh.numTriangles(), mesh.area(), extent.min.x(), extent.min.y(),
                 extent.min.z(), extent.max.x(), extent.max.y(), extent.max.z(),
                 config_file.empty() ? "(none)" : config_file.c_str(), config.tsdf.voxel_size, options.trials,
                 options.seed);
  out_ << printfString("derived from the scene (%s class, %.1f m footprint): %s\n", derived.size_class.c_str(),
                 std::max(extent.size().x(), extent.size().y()), derived.summary().c_str());
  for (const std::string& w : derived.warnings) warn(w);
  const double slack = 0.5 * config.tsdf.voxel_size;  // a ground at z = -1e-6 is inside
  if ((extent.min.array() < config.tsdf.bounds.min.array() - slack).any() ||
      (extent.max.array() > config.tsdf.bounds.max.array() + slack).any()) {
    warn("the scene reaches outside the map's bounds (nbv/bounds_min/max): what lies outside is never mapped");
  }
  // What the wall times depend on besides the host: they differ with these.
  const int packet_rays = scene->nativePacketWidth();
  const char* voxel_loop = bestKernelIsa() == KernelIsa::kAvx2 ? "avx2" : "scalar";
  out_ << printfString("compute: %d thread(s), %d-ray render packets, %s voxel loop\n", config.threads, packet_rays,
                 voxel_loop);
  // Probe points for the running coverage: 0.5 m apart on the true surface.
  SurfaceCloud probe_cloud;
  SurfaceSampler(0.5, 7, config.threads).sample(mesh, 2000000, &probe_cloud);
  std::vector<Eigen::Vector3d> probe;
  for (const Eigen::Vector3f& p : probe_cloud.points) probe.push_back(p.cast<double>());

  const Evaluator evaluator(missionEvalConfig(config));
  // The ground-truth side of the evaluation (sampling, visibility pruning),
  // once for every trial and checkpoint; each scoring replaces the rest.
  EvalResult eval;
  if (Status s = evaluator.prepareGroundTruth(mesh, &eval); !s) return s;
  const double coverage_every = options.coverage_every.value_or(0.0);
  for (int k = 0; k < options.trials; ++k) {
    MissionConfig trial_config = config;
    trial_config.seed = static_cast<unsigned>(options.seed + k);
    const std::string dir = out_dir + "/trial_" + std::to_string(k);
    std::filesystem::create_directories(dir, ec);
    out_ << printfString("trial %d (seed %u)\n", k, trial_config.seed) << std::flush;
    MissionRunner runner(trial_config, *scene);
    runner.setProbePoints(probe);
    runner.setOracleGain(options.oracle_gain.value_or(0) > 0);
    runner.setProgress([this](const MissionEvent& e) {
      out_ << printfString("  t %6.0f s  path %6.1f m  ISEs %6zu (C_ins %6zu)  clusters %4zu  tour %4zu  observed %5.1f %%"
                           "  roadmap %6zu\n",
                           e.t, e.path_length, e.ises, e.inside, e.clusters, e.tour, 100.0 * e.observed, e.roadmap)
           << std::flush;
    });
    std::vector<CoveragePoint> coverage_over_time;
    Status checkpoint_status;
    TriangleMesh checkpoint_mesh;  // of the last checkpoint, which `eval` holds the scoring of
    if (coverage_every > 0.0) {
      runner.setCheckpoints(coverage_every, [&](double t, double path_length, const TsdfMap& mesh_map) {
        MeshExtractor checkpoint_mesher;
        checkpoint_mesher.update(mesh_map);
        checkpoint_mesh = checkpoint_mesher.mesh();
        Status s = evaluator.scoreReconstruction(checkpoint_mesh, &eval);
        if (!s) {
          if (checkpoint_status) checkpoint_status = s;
          return;
        }
        coverage_over_time.push_back({t, path_length, eval.coverage.coverage(), eval.error_stats.rmse});
        out_ << printfString("  coverage at %5.1f min, %6.1f m of path: %.2f %%\n", t / 60.0, path_length,
                       100.0 * coverage_over_time.back().coverage)
             << std::flush;
      });
    }
    const MissionResult r = runner.run();
    if (!checkpoint_status) {
      return Status::Error("trial " + std::to_string(k) + ": coverage checkpoint: " + checkpoint_status.message());
    }
    if (!r.status) return Status::Error("trial " + std::to_string(k) + ": " + r.status.message());
    // The checkpoint at the end (coverage_every) already meshed and scored the reconstruction.
    const bool scored = !coverage_over_time.empty() && coverage_over_time.back().t == r.flight_time;
    TriangleMesh reconstruction;
    if (scored) {
      reconstruction = std::move(checkpoint_mesh);
    } else {
      MeshExtractor mesher;
      mesher.update(runner.meshMap());
      reconstruction = mesher.mesh();
    }
    if (!reconstruction.empty()) {
      if (Status s = saveMesh(reconstruction, dir + "/reconstruction.ply"); !s) return s;
    }
    if (Status s = saveMap(runner.map(), dir + "/map.tsdf"); !s) return s;
    if (Status s = writeCsvs(dir, r); !s) return s;
    if (coverage_every > 0.0) {
      if (Status s = writeCoverageCsv(dir, coverage_over_time); !s) return s;
    }
    if (!scored) {
      if (Status s = evaluator.scoreReconstruction(reconstruction, &eval); !s) return s;
    }
    if (Status s = ReportWriter(eval, {dir + "/reconstruction.ply", config.scene.scene}).write(dir + "/eval"); !s) {
      return s;
    }
    result->rows.push_back(trialRow(k, trial_config.seed, r, eval, trial_config.speed));
    TrialRow& row = result->rows.back();
    row.coverage_over_time = coverage_over_time;
    out_ << printfString("  %s after %.1f min of flight, %.1f m: coverage %.2f %%, error mean %.2f cm, std %.2f cm, "
                   "RMSE %.2f cm; wall %.1f s (%.0fx faster than flight)\n  end: %s\n",
                   r.completed ? "completed" : "stopped", row.flight_min, row.path_length, 100.0 * row.coverage,
                   100.0 * row.mean, 100.0 * row.std_dev, 100.0 * row.rmse, row.wall_s,
                   r.flight_time / std::max(row.wall_s, 1e-9), r.end_reason.c_str());
    out_ << "  flight: " << profileLine(row.profile) << "\n";
    if (config.pose_error.enabled()) {
      for (const auto& [name, e] : {std::make_pair("odometry", r.pose_error), std::make_pair("fused", r.fused_pose_error)}) {
        out_ << printfString("  %s pose error: %.3f m at the end (RMS %.3f m, max %.3f m), yaw %.2f deg (RMS %.2f deg)\n",
                       name, e.final_position, e.rms_position, e.max_position, e.final_yaw_deg, e.rms_yaw_deg);
      }
      if (config.manhattan_yaw.enabled) {
        out_ << printfString("  heading corrected from the walls in %zu frames\n", r.yaw_corrections);
      }
    }
    out_ << std::flush;
    if (options.plots) {
      const std::string script = options.package_dir + "/scripts/plot_mission.py";
      if (runProcess({"/usr/bin/python3", "-c", "import matplotlib"}, true) != 0) {
        out_ << "  plots skipped: python3-matplotlib is not installed\n";
      } else if (runProcess({"/usr/bin/python3", script, dir}, false) != 0) {
        out_ << "  plotting failed: /usr/bin/python3 " << script << " " << dir << "\n";
      }
    }
  }

  // Summary over trials: Table 2 columns, mean and standard deviation.
  const std::vector<Stat> stats = summaryStats(result->rows);
  const ReportHeader header{options, *result, eval.config.eMax(), packet_rays, voxel_loop, extent};
  std::ofstream(out_dir + "/report.json") << reportJson(header, stats);
  std::ofstream md(out_dir + "/report.md");
  writeReportMd(header, stats, md);
  out_ << printfString("summary over %d trial(s):\n", options.trials);
  for (const Stat& s : stats) {
    double m, sd;
    meanStd(s.values, &m, &sd);
    out_ << printfString("  %-16s %10.2f +- %.2f %s\n", s.name, m * s.scale, sd * s.scale, s.unit);
  }
  out_ << printfString("wrote %s/report.json and report.md (per trial: trial_K/)\n", out_dir.c_str());
  return Status::Ok();
}

}  // namespace surface_nbv
