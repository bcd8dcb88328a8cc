// TSDF integration speed: milliseconds per 640 x 480 depth frame of the
// built-in plant along the scripted flight, with 1 and 2 threads, at the
// paper's settings (0.3 m voxels / 8 m range, 0.15 m / 5 m) and at a stress
// setting (30 m range at 0.3, 0.2 and 0.15 m), free space carved. Where
// Open3D is installed, its ScalableTSDFVolume integrates the same frames side
// by side (it only updates the truncation band around surfaces).
// BM_DepthIndexBuild times the image preparation of each frame on its own,
// and BM_IntegrateLoop compares the scalar and the AVX2 per-block loops
// (integrate_kernel.h) on one thread, side by side in one run.
// Frames are integrated once before timing, so blocks are allocated and the
// figures are the steady state of a map that already covers the view.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>

#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/sim/scripted_flight.h"

#ifdef NBV_HAVE_OPEN3D
#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/pipelines/integration/ScalableTSDFVolume.h>
#include <omp.h>
#endif

using namespace surface_nbv;

namespace {

struct Setting {
  double voxel, range, standoff;
};
// Indexed by the benchmark's first argument.
const Setting kSettings[] = {{0.3, 8.0, 3.0}, {0.15, 5.0, 2.0}, {0.3, 30.0, 10.0}, {0.2, 30.0, 10.0}, {0.15, 30.0, 10.0},
                             {0.1, 8.0, 3.0}};  // 5: the power plant's mesh layer voxels

struct Frames {
  CameraConfig camera;
  std::vector<Transform> poses;
  std::vector<DepthImage> depths;
  AlignedBox bounds;
};

const Frames& framesFor(const Setting& s) {
  static std::map<double, std::unique_ptr<Frames>> cache;
  auto& slot = cache[s.range * 100 + s.standoff];
  if (slot) return *slot;
  slot = std::make_unique<Frames>();
  SceneConfig scene_config;
  scene_config.scene = "plant";
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  if (!loadScene(scene_config, &mesh) || !RaycastScene::create(mesh, &scene)) std::abort();
  slot->camera.max_range = s.range;
  const DepthCamera camera(slot->camera);
  const DepthRenderer renderer(*scene, camera, 2);
  const AlignedBox b = mesh.bounds();
  const ScriptedFlight flight(flightAround(b, s.standoff, 2, 0.5));
  slot->bounds = AlignedBox(b.min - Eigen::Vector3d(s.range + 2, s.range + 2, 1), b.max + Eigen::Vector3d::Constant(s.range + 2));
  size_t valid = 0;
  for (int i = 0; i < 16; ++i) {
    const Transform T = flight.poseAtDistance(flight.length() * (i + 0.5) / 16) * opticalInBody();
    DepthImage d;
    renderer.render(T, &d);
    valid += d.validCount();
    slot->poses.push_back(T);
    slot->depths.push_back(std::move(d));
  }
  std::printf("frames at %.0f m range: 16 poses, %.0f%% valid pixels\n", s.range, 100.0 * valid / (16.0 * 640 * 480));
  return *slot;
}

// Integrates the setting's frames once (the steady state), then one frame
// per iteration with `threads` and the voxel loop `isa`.
void integrateFrames(benchmark::State& state, const Setting& s, int threads, KernelIsa isa) {
  const Frames& f = framesFor(s);
  TsdfConfig config;
  config.voxel_size = s.voxel;
  config.bounds = f.bounds;
  config.threads = threads;
  config.max_blocks = 4u << 20;
  TsdfMap map(config);
  TsdfIntegrator integrator(&map);
  integrator.setKernelIsa(isa);
  const DepthCamera camera(f.camera);
  for (size_t i = 0; i < f.poses.size(); ++i) integrator.integrateDepth(camera, f.depths[i], f.poses[i]);
  size_t i = 0, voxels = 0;
  for (auto _ : state) {
    IntegrationStats stats;
    integrator.integrateDepth(camera, f.depths[i % f.poses.size()], f.poses[i % f.poses.size()], &stats);
    voxels += stats.voxels_updated;
    ++i;
  }
  state.counters["voxels_per_frame"] = static_cast<double>(voxels) / state.iterations();
  state.counters["blocks"] = static_cast<double>(map.numBlocks());
  state.counters["bytes_per_voxel"] = static_cast<double>(map.memoryBytes()) / (map.numBlocks() * kBlockVoxels);
}

// Args: {setting, threads}.
void BM_Integrate(benchmark::State& state) {
  integrateFrames(state, kSettings[state.range(0)], static_cast<int>(state.range(1)), bestKernelIsa());
}

// Args: {setting, loop: 0 scalar, 1 AVX2 (scalar without AVX2)}, one thread.
void BM_IntegrateLoop(benchmark::State& state) {
  const bool avx2 = state.range(1) == 1 && bestKernelIsa() == KernelIsa::kAvx2;
  integrateFrames(state, kSettings[state.range(0)], 1, avx2 ? KernelIsa::kAvx2 : KernelIsa::kScalar);
  state.SetLabel(avx2 ? "avx2" : "scalar");
}

// The per-frame image preparation alone (usable depths, silhouettes, the
// max-depth pyramid), part of every BM_Integrate frame. Args: {threads}.
void BM_DepthIndexBuild(benchmark::State& state) {
  const Frames& f = framesFor(kSettings[0]);
  const DepthCamera camera(f.camera);
  DepthIndex index;
  size_t i = 0, invalid = 0;
  for (auto _ : state) {
    invalid += index.build(camera, f.depths[i % f.depths.size()], 0.9f, InvalidPixelPolicy::kClearInfinite,
                           static_cast<int>(state.range(0)));
    ++i;
  }
  state.counters["invalid_per_frame"] = static_cast<double>(invalid) / state.iterations();
}

#ifdef NBV_HAVE_OPEN3D
void BM_IntegrateOpen3D(benchmark::State& state) {
  namespace o3d = open3d;
  const Setting& s = kSettings[state.range(0)];
  const Frames& f = framesFor(s);
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const DepthCamera camera(f.camera);
  Eigen::Matrix3d K;
  K << camera.fx(), 0, camera.cx(), 0, camera.fy(), camera.cy(), 0, 0, 1;
  const o3d::camera::PinholeCameraIntrinsic intrinsic(camera.width(), camera.height(), K);
  std::vector<o3d::geometry::RGBDImage> images(f.depths.size());
  for (size_t k = 0; k < f.depths.size(); ++k) {
    o3d::geometry::Image& depth = images[k].depth_;
    depth.Prepare(camera.width(), camera.height(), 1, 4);
    float* px = depth.PointerAs<float>();
    for (size_t p = 0; p < f.depths[k].data.size(); ++p) px[p] = std::isfinite(f.depths[k].data[p]) ? f.depths[k].data[p] : 0.0f;
    images[k].color_.Prepare(camera.width(), camera.height(), 1, 4);
  }
  o3d::pipelines::integration::ScalableTSDFVolume volume(s.voxel, 3 * s.voxel,
                                                         o3d::pipelines::integration::TSDFVolumeColorType::NoColor);
  for (size_t k = 0; k < images.size(); ++k) volume.Integrate(images[k], intrinsic, f.poses[k].inverse().matrix());
  size_t i = 0;
  for (auto _ : state) {
    volume.Integrate(images[i % images.size()], intrinsic, f.poses[i % images.size()].inverse().matrix());
    ++i;
  }
  state.counters["blocks"] = static_cast<double>(volume.volume_units_.size());
}
#endif

void settings(benchmark::internal::Benchmark* b) {
  b->ArgNames({"setting", "threads"});
  for (int s = 0; s < 5; ++s) {
    for (int t : {1, 2}) b->Args({s, t});
  }
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK(BM_Integrate)->Apply(settings);
BENCHMARK(BM_IntegrateLoop)
    ->ArgNames({"setting", "avx2"})
    ->ArgsProduct({{0, 5}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_DepthIndexBuild)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
#ifdef NBV_HAVE_OPEN3D
BENCHMARK(BM_IntegrateOpen3D)->Apply(settings);
#endif

BENCHMARK_MAIN();
