// `bench --suite city`: hierarchical occlusion culling on the city (GPU Gems 3 ch. 11 §11.3.3).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_suite.h"
#include "cli.h"
#include "plot.h"
#include "scene/city.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

struct CityPath {
  const char* name;
  CityView view;
};
constexpr CityPath kPaths[] = {{"street", CityView::street}, {"above", CityView::above}};
struct CityMethod {
  const char* name;
  Occlusion occlusion;
  glm::vec3 color;  // in --plot
};
const CityMethod kMethods[] = {{"none", Occlusion::none, {0.45f, 0.45f, 0.45f}},
                               {"culled", Occlusion::both, {0.10f, 0.60f, 0.25f}}};
// The goals: on the street path of the largest city, the shadow volumes' fill and time reduced
// kGoalReduction times by culling; and the culled street frame with kGoalBuildingsFactor times the
// buildings no more than kGoalTimeFactor times as long.
constexpr double kGoalReduction = 10.0, kGoalBuildingsFactor = 10.0, kGoalTimeFactor = 2.0;

// One size, path and method: a value per frame.
struct CitySeries {
  std::vector<std::uint64_t> fill;
  std::vector<double> frame_ms, volumes_ms, depth_ms, shade_ms, occlusion_ms;
  std::vector<int> objects_drawn, volumes_drawn;

  // The shadow volumes' time is building and counting them and, culled, their queries; the
  // frame's is the wall-clock time of the whole frame (its plan included), less measuring.
  void add(const FrameStats& s, double wall_ms) {
    fill.push_back(s.fill);
    volumes_ms.push_back(s.ms_volumes + s.ms_counts + s.ms_occlusion);
    depth_ms.push_back(s.ms_depth);
    shade_ms.push_back(s.ms_shade);
    occlusion_ms.push_back(s.ms_occlusion + s.ms_bvh);
    frame_ms.push_back(wall_ms - s.ms_measuring);
    objects_drawn.push_back(s.objects_drawn);
    volumes_drawn.push_back(s.volumes_drawn);
  }
  double mean_frame_ms() const { return total(frame_ms) / double(frame_ms.size()); }
};

std::size_t triangles_of(const Scene& scene) {
  std::size_t n = 0;
  for (const SceneObject& o : scene.objects) n += o.mesh->triangle_count();
  return n;
}

// Mean wall-clock ms of frames 1 .. frames of `scene` after one warm-up, measuring taken off.
double mean_frame_ms(Renderer& renderer, const Scene& scene, const RenderOptions& options,
                     int frames) {
  Frame frame;
  renderer.render(scene, options, frame);
  double sum = 0.0;
  for (int f = 0; f < frames; ++f) {
    const Scene at = scene_at_frame(scene, f + 1);
    const auto start = std::chrono::steady_clock::now();
    renderer.render(at, options, frame);
    sum += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
               .count() -
           frame.stats.ms_measuring;
  }
  return sum / frames;
}

}  // namespace

int run_city_suite(const CitySuiteOptions& options) {
  if (options.frames < 1) {
    std::cerr << "shadowvol: error: --frames: " << options.frames << " is not a positive count\n";
    return 1;
  }
  RenderOptions base{options.width, options.height, options.method};
  base.count_fill = true;
  auto make = [&] { return suite_renderer(options.backend, options.gl, base); };
  std::unique_ptr<Renderer> probe = make();
  if (!probe) return 1;
  const std::string backend(probe->backend().name());
  probe.reset();
  nlohmann::json json{{"suite", "city"},
                      {"width", options.width},
                      {"height", options.height},
                      {"frames", options.frames},
                      {"backend", backend},
                      {"method", std::string(to_string(options.method))},
                      {"culled", "occlusion both"},
                      {"goal",
                       {{"path", "street"},
                        {"fill_reduction", kGoalReduction},
                        {"time_reduction", kGoalReduction},
                        {"buildings_factor", kGoalBuildingsFactor},
                        {"frame_time_factor", kGoalTimeFactor}}},
                      {"sizes", nlohmann::json::array()}};
  std::string csv =
      "buildings,path,method,frame,fill,ms_frame,ms_volumes_drawn,ms_depth,ms_occlusion,"
      "objects_drawn,volumes_drawn\n";
  std::FILE* table = options.json == "-" ? stderr : stdout;
  cli::StatusLine status;
  std::fprintf(table,
               "%d frame%s a path after one warm-up, %dx%d, %s, %s; culled: --occlusion both\n",
               options.frames, options.frames == 1 ? "" : "s", options.width, options.height,
               backend.c_str(), std::string(to_string(options.method)).c_str());
  std::fprintf(table, "%9s %9s %-6s %-6s %13s %10s %10s %10s %9s %9s\n", "buildings", "triangles",
               "path", "", "fill", "frame ms", "volumes ms", "depth ms", "objects", "volumes");
  // [path][method]: the mean frame time per size, for the scaling plot.
  std::vector<double> scaling[2][2];
  double street_fill = 0, street_time = 0;
  for (const int buildings : options.sizes) {
    nlohmann::json size_json{{"buildings", buildings}, {"paths", nlohmann::json::object()}};
    for (std::size_t p = 0; p < std::size(kPaths); ++p) {
      const Scene city = make_city(buildings, kPaths[p].view);
      size_json["triangles"] = triangles_of(city);
      nlohmann::json path_json{{"methods", nlohmann::json::object()}};
      std::vector<CitySeries> series(std::size(kMethods));
      for (std::size_t m = 0; m < std::size(kMethods); ++m) {
        std::unique_ptr<Renderer> renderer = make();
        if (!renderer) return 1;
        RenderOptions o = base;
        o.occlusion = kMethods[m].occlusion;
        Frame frame;
        renderer->render(city, o, frame);  // warm-up: the first frame builds every volume, the BVH
        for (int f = 0; f < options.frames; ++f) {
          status.show(city.name + ", " + kMethods[m].name + ": frame " + std::to_string(f + 1) +
                      " of " + std::to_string(options.frames));
          const Scene at = scene_at_frame(city, f + 1);
          const auto start = std::chrono::steady_clock::now();
          renderer->render(at, o, frame);
          series[m].add(frame.stats, std::chrono::duration<double, std::milli>(
                                         std::chrono::steady_clock::now() - start)
                                         .count());
        }
      }
      status.clear();
      const CitySeries& none = series[0];
      for (std::size_t m = 0; m < std::size(kMethods); ++m) {
        const CitySeries& s = series[m];
        const char* name = kMethods[m].name;
        for (std::size_t f = 0; f < s.fill.size(); ++f)
          csv += std::to_string(buildings) + "," + kPaths[p].name + "," + name + "," +
                 std::to_string(f) + "," + std::to_string(s.fill[f]) + "," +
                 std::to_string(s.frame_ms[f]) + "," + std::to_string(s.volumes_ms[f]) + "," +
                 std::to_string(s.depth_ms[f]) + "," + std::to_string(s.occlusion_ms[f]) + "," +
                 std::to_string(s.objects_drawn[f]) + "," + std::to_string(s.volumes_drawn[f]) +
                 "\n";
        const double fill_ratio =
            double(total(none.fill)) / double(std::max<std::uint64_t>(total(s.fill), 1));
        const double time_ratio = total(none.volumes_ms) / std::max(total(s.volumes_ms), 1e-9);
        path_json["methods"][name] = {
            {"fill", total(s.fill)},
            {"ms_frame", total(s.frame_ms)},
            {"ms_volumes_drawn", total(s.volumes_ms)},
            {"ms_depth", total(s.depth_ms)},
            {"ms_shade", total(s.shade_ms)},
            {"ms_occlusion", total(s.occlusion_ms)},
            {"objects_drawn", total(s.objects_drawn)},
            {"volumes_drawn", total(s.volumes_drawn)},
            {"none_over_this", {{"fill", fill_ratio}, {"ms_volumes_drawn", time_ratio}}},
            {"per_frame",
             {{"fill", s.fill},
              {"ms_frame", s.frame_ms},
              {"ms_volumes_drawn", s.volumes_ms},
              {"objects_drawn", s.objects_drawn},
              {"volumes_drawn", s.volumes_drawn}}}};
        const int n = options.frames;
        std::fprintf(table, "%9d %9zu %-6s %-6s %13.0f %10.1f %10.1f %10.1f %9.0f %9.0f", buildings,
                     triangles_of(city), kPaths[p].name, name, double(total(s.fill)) / n,
                     total(s.frame_ms) / n, total(s.volumes_ms) / n, total(s.depth_ms) / n,
                     double(total(s.objects_drawn)) / n, double(total(s.volumes_drawn)) / n);
        if (m == 0)
          std::fprintf(table, "\n");
        else
          std::fprintf(table, "   none / culled: fill %.1fx, volumes %.1fx\n", fill_ratio,
                       time_ratio);
        scaling[p][m].push_back(s.mean_frame_ms());
        if (p == 0 && m == 1 && buildings == options.sizes.back())
          street_fill = fill_ratio, street_time = time_ratio;
      }
      size_json["paths"][kPaths[p].name] = path_json;
    }
    json["sizes"].push_back(size_json);
  }
  // Scaling: the culled street frame of the largest city against the smallest one's.
  const double buildings_factor = double(options.sizes.back()) / options.sizes.front();
  const double time_factor = scaling[0][1].back() / std::max(scaling[0][1].front(), 1e-9);
  const bool reduction_met = street_fill >= kGoalReduction && street_time >= kGoalReduction;
  const bool scaling_met =
      buildings_factor >= kGoalBuildingsFactor && time_factor <= kGoalTimeFactor;
  std::fprintf(table,
               "goal (street, %d buildings, none / culled): fill >= %.0fx: %.1fx, shadow-volume "
               "time >= %.0fx: %.1fx: %s\n",
               options.sizes.back(), kGoalReduction, street_fill, kGoalReduction, street_time,
               reduction_met ? "met" : "NOT MET");
  std::fprintf(table,
               "goal (street, culled): %.0fx the buildings (%d -> %d) in <= %.0fx the frame time: "
               "%.2fx: %s\n",
               buildings_factor, options.sizes.front(), options.sizes.back(), kGoalTimeFactor,
               time_factor, scaling_met ? "met" : "NOT MET");
  json["scaling"] = {{"buildings_factor", buildings_factor},
                     {"street_culled_frame_factor", time_factor}};
  json["goal_met"] = {{"reduction", reduction_met}, {"scaling", scaling_met}};

  // Batches: the smallest city drawn as its objects and with its buildings merged into one mesh,
  // on the street path without culling: many objects should cost what one mesh of them costs.
  {
    const Scene city = make_city(options.sizes.front(), CityView::street);
    const Scene merged = with_buildings_merged(city);
    status.show("batches: " + city.name + " as objects and as one mesh");
    RenderOptions o = base;
    o.count_fill = false;
    std::unique_ptr<Renderer> a = make(), b = make();
    if (!a || !b) return 1;
    const double objects_ms = mean_frame_ms(*a, city, o, options.frames);
    const double mesh_ms = mean_frame_ms(*b, merged, o, options.frames);
    status.clear();
    std::fprintf(table,
                 "batches (street, %d buildings, no culling): %zu objects %.1f ms a frame, the "
                 "buildings as one mesh %.1f ms: %.2fx\n",
                 options.sizes.front(), city.objects.size(), objects_ms, mesh_ms,
                 objects_ms / std::max(mesh_ms, 1e-9));
    json["batches"] = {{"buildings", options.sizes.front()},
                       {"objects", city.objects.size()},
                       {"ms_frame_objects", objects_ms},
                       {"ms_frame_one_mesh", mesh_ms},
                       {"objects_over_one_mesh", objects_ms / std::max(mesh_ms, 1e-9)}};
  }

  std::vector<std::string> sizes;  // the x axis's labels
  for (const int b : options.sizes) sizes.push_back(std::to_string(b));
  Chart chart{"City (" + std::to_string(options.width) + "x" + std::to_string(options.height) +
                  ", " + backend + "): mean ms a frame by city size",
              "buildings",
              2,
              {}};
  for (std::size_t p = 0; p < std::size(kPaths); ++p) {
    PlotPanel panel{std::string(kPaths[p].name) + " path", {}, {}, sizes};
    for (std::size_t m = 0; m < std::size(kMethods); ++m)
      panel.series.push_back({kMethods[m].name, kMethods[m].color, scaling[p][m]});
    chart.panels.push_back(std::move(panel));
  }
  return write_suite_outputs(options.json, json.dump(2) + "\n", options.csv, csv, options.plot,
                             chart, "the mean frame time by city size", table)
             ? 0
             : 1;
}

}  // namespace shadowvol
