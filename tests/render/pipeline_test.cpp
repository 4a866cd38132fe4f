// The frame pipeline (render/renderer.h) runs the same sequence of verbs on any backend: a
// backend that records the verbs it is given shows the sequence, and what it is not given.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

class RecordingBackend final : public FrameBackend {
 public:
  explicit RecordingBackend(std::vector<std::string>& log, bool device = false)
      : log_(log), device_(device) {}
  std::string_view name() const override { return "recording"; }
  Expected<void> supports(const RenderOptions&) const override { return {}; }
  bool counts_cpu_volumes() const override { return true; }
  bool can_present() const override { return device_; }
  VolumeCosts measure_volume_costs() override {
    log("measure volume costs");
    return {1e-6, 1e-6};
  }
  void begin_frame(const FrameInputs&) override { log("begin_frame"); }
  void begin_depth(Layer layer) override { log("depth " + name(layer)); }
  void draw_depth(std::span<const std::uint32_t>) override {}
  void end_depth() override {}
  QueryId issue_query(std::span<const glm::vec4>, bool) override { return 0; }
  bool query_ready(QueryId) override { return true; }
  bool query_visible(QueryId) override { return true; }
  void read_ids(Layer layer, SurfaceLayer& out) override {
    out.object.assign(1, -1);
    log("ids " + name(layer));
  }
  void volumes_ready(std::size_t l, const std::vector<std::uint8_t>& rebuilt) override {
    log("volumes " + std::to_string(l) + " rebuilt " + std::to_string(count(rebuilt)));
  }
  void begin_mask(std::size_t l) override { log("mask " + std::to_string(l)); }
  void begin_light_map(std::size_t l) override { log("light map " + std::to_string(l)); }
  void count_volume(std::size_t, std::size_t o) override { log("count " + std::to_string(o)); }
  void end_group(std::size_t g) override { log("group " + std::to_string(g)); }
  void end_counts() override { log("end counts"); }
  void read_mask(std::size_t l, SurfaceLayer&) override { log("read mask " + std::to_string(l)); }
  void read_light_map(std::size_t l, SurfaceLayer&) override {
    log("read light " + std::to_string(l));
  }
  void light_pass(std::size_t l, Layer layer) override {
    log("light " + std::to_string(l) + " " + name(layer));
  }
  void read_facing(std::size_t l, Layer layer, SurfaceLayer&) override {
    log("read facing " + std::to_string(l) + " " + name(layer));
  }
  void see_through() override { log("see through"); }
  void shade() override { log("shade"); }
  void read_image(Image&) override { log("read image"); }
  void present() override { log("present"); }

 private:
  static std::string name(Layer layer) { return layer == Layer::opaque ? "opaque" : "glass"; }
  static int count(const std::vector<std::uint8_t>& flags) {
    int n = 0;
    for (const std::uint8_t f : flags) n += f;
    return n;
  }
  void log(std::string line) { log_.push_back(std::move(line)); }
  std::vector<std::string>& log_;
  bool device_;
};

// Two transparent casters of two materials, one opaque caster and a ground, one light.
Scene two_glass_groups() {
  Scene scene = *builtin_scene("demo");
  scene.lights.resize(1);
  scene.objects[1].material = {{1.0f, 0.2f, 0.2f}, 0.5f};
  scene.objects[3].material = {{0.2f, 0.2f, 1.0f}, 0.4f};
  return scene;
}

TEST(Pipeline, WalksLayersLightsAndVolumesInOneSequence) {
  const Scene scene = two_glass_groups();
  ASSERT_EQ(scene.objects.size(), 4u);
  std::vector<std::string> log;
  Renderer renderer(std::make_unique<RecordingBackend>(log));
  Frame frame;
  renderer.render(scene, {32, 18}, frame);
  const std::vector<std::string> per_light_opaque = {
      "volumes 0 rebuilt 4", "mask 0",  "count 0", "count 2", "end counts", "read mask 0",
      "light map 0",         "count 1", "group 0", "count 3", "group 1",    "end counts",
      "read light 0"};
  std::vector<std::string> expected = {"begin_frame", "depth opaque", "ids opaque"};
  expected.insert(expected.end(), per_light_opaque.begin(), per_light_opaque.end());
  expected.insert(expected.end(), {"light 0 opaque", "see through", "depth glass", "ids glass"});
  expected.insert(expected.end(), per_light_opaque.begin(), per_light_opaque.end());
  expected[expected.size() - per_light_opaque.size()] = "volumes 0 rebuilt 0";  // cached
  expected.insert(expected.end(), {"light 0 glass", "shade", "read image"});
  EXPECT_EQ(log, expected);
  // The masks and light are sized for the backend to fill: one per light and pixel.
  ASSERT_EQ(frame.shadowed.size(), 1u);
  EXPECT_EQ(frame.shadowed[0].size(), 32u * 18u);
  ASSERT_EQ(frame.glass.transmitted.size(), 1u);
  EXPECT_GT(frame.stats.volume_primitives, 0u);
}

TEST(Pipeline, RecordsWhichSurfacesFaceEachLightAfterItsLitPassWhereAsked) {
  const Scene scene = two_glass_groups();
  std::vector<std::string> log;
  Renderer renderer(std::make_unique<RecordingBackend>(log));
  Frame frame;
  RenderOptions options{32, 18};
  renderer.render(scene, options, frame);
  EXPECT_EQ(std::count(log.begin(), log.end(), "read facing 0 opaque"), 0);
  EXPECT_TRUE(frame.faces_light.empty());
  log.clear();
  options.record_facing = true;
  renderer.render(scene, options, frame);
  for (const char* layer : {"opaque", "glass"}) {
    const auto lit = std::find(log.begin(), log.end(), std::string("light 0 ") + layer);
    ASSERT_NE(lit, log.end());
    ASSERT_NE(lit + 1, log.end());
    EXPECT_EQ(*(lit + 1), std::string("read facing 0 ") + layer);
  }
  for (const SurfaceLayer* layer :
       {static_cast<const SurfaceLayer*>(&frame), static_cast<const SurfaceLayer*>(&frame.glass)}) {
    ASSERT_EQ(layer->faces_light.size(), 1u);
    EXPECT_EQ(layer->faces_light[0], std::vector<std::uint8_t>(32u * 18u, 0));  // zeroed
  }
}

TEST(Pipeline, APresentedFrameIsReadBackNowhere) {
  Scene scene = *builtin_scene("demo");
  std::vector<std::string> log;
  Renderer renderer(std::make_unique<RecordingBackend>(log, true));
  Frame frame;
  RenderOptions options{32, 18};
  options.record_facing = true;
  renderer.present(scene, options, frame);
  for (const std::string& line : log) EXPECT_EQ(line.rfind("read", 0), std::string::npos) << line;
  EXPECT_EQ(log.back(), "present");
  EXPECT_EQ(std::count(log.begin(), log.end(), "depth opaque"), 1);
  EXPECT_EQ(std::count(log.begin(), log.end(), "see through"), 0);  // no transparent casters
}

}  // namespace
}  // namespace shadowvol
