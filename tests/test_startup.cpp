// What the first frame compiles (docs/startup.md), checked as properties rather than timings:
//   - the texture slots of set 0 look alike to the driver for a textured and an untextured scene
//     (format, a mip chain, power-of-two sides): llvmpipe compiles one shader variant per such
//     "static" texture state, so a difference made every new scene miss Mesa's shader cache;
//   - `--gi none` creates no pipeline of a GI system, and `--gi evolve` does (the log of created
//     pipelines, vk/pipeline_log.h, is what BOUNCE_PIPELINE_TIMES prints).
#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "frame/hybrid_frame.h"
#include "harness.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "shared/scene_layout.h"
#include "vk/context.h"
#include "vk/pipeline_log.h"

namespace bounce {
namespace {

// What llvmpipe's shader key keeps of a sampled image (lp_sampler_static_texture_state): the
// format, whether the view has more than one mip, whether the sides are powers of two. The view
// type is 2D_ARRAY for every sampled image (vk/resources.cpp).
struct SlotKey {
  VkFormat format;
  bool mipmapped;
  bool powerOfTwo;
  bool operator==(const SlotKey&) const = default;
};

std::vector<SlotKey> slotKeys(const GpuScene& gpuScene) {
  std::vector<SlotKey> keys;
  for (uint32_t slot = 0; slot < 2 * gpu::TEXTURE_SIZE_CLASSES; ++slot) {
    const vk::Image& image = gpuScene.textureImage(slot);
    keys.push_back({image.format(), image.mips() > 1,
                    std::has_single_bit(image.width()) && std::has_single_bit(image.height())});
  }
  return keys;
}

TEST(StartupShaderKeys, TextureSlotsLookTheSameForATexturedAndAnUntexturedScene) {
  vk::Context context(vk::contextOptionsFromEnvironment());
  Scene untextured = loadScene("cornell");
  Scene textured = loadScene(test::sharedDir() + "/scenes/damaged_helmet/glTF/DamagedHelmet.gltf");
  GpuScene plain(context, untextured);
  GpuScene helmet(context, textured);
  // The comparison must set real arrays against placeholders, or it could not fail.
  ASSERT_TRUE(plain.textures().arrays.empty());
  ASSERT_FALSE(helmet.textures().arrays.empty());
  std::vector<SlotKey> a = slotKeys(plain), b = slotKeys(helmet);
  for (uint32_t slot = 0; slot < a.size(); ++slot) {
    SCOPED_TRACE(slot);
    EXPECT_EQ(a[slot], b[slot]);
    EXPECT_TRUE(b[slot].mipmapped);
  }
}

// The names of the pipelines created while `make` runs.
template <typename Make>
std::vector<std::string> pipelinesCreatedBy(Make make) {
  size_t before = vk::pipelineLog().size();
  make();
  std::vector<vk::PipelineLogEntry> log = vk::pipelineLog();
  std::vector<std::string> names;
  for (size_t i = before; i < log.size(); ++i) names.push_back(log[i].name);
  return names;
}

bool isGiPipeline(const std::string& name) {
  return name.rfind("gi/", 0) == 0 || name.rfind("denoise/gi_", 0) == 0;
}

TEST(StartupPipelines, GiNoneCreatesNoGiPipelineAndEvolveDoes) {
  vk::Context context(vk::contextOptionsFromEnvironment());
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  auto created = [&](GiMode gi) {
    return pipelinesCreatedBy([&] {
      HybridSettings settings;
      settings.width = 64;
      settings.height = 36;
      settings.gi = gi;
      HybridFrame frame(context, gpuScene, scene, settings);
    });
  };
  std::vector<std::string> none = created(GiMode::None);
  std::vector<std::string> evolve = created(GiMode::Evolve);
  EXPECT_FALSE(none.empty());
  EXPECT_TRUE(std::none_of(none.begin(), none.end(), isGiPipeline));
  EXPECT_TRUE(std::any_of(evolve.begin(), evolve.end(), isGiPipeline));
  EXPECT_GT(evolve.size(), none.size());
}

}  // namespace
}  // namespace bounce
