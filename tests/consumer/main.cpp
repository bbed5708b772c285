// A host program that sees only Bounce's public API: builds a lit quad in code, renders two
// frames at a tiny resolution and checks the image. Exit code 0 on success.
#include <cmath>
#include <cstdio>
#include <vector>

#include <bounce/bounce.h>

// bounce::bounce's public include directory is include/ alone.
#if __has_include("vk/context.h") || __has_include("scene/scene.h") || \
                                                   __has_include("shared/camera.h")
#error "Bounce's internal headers are on the consumer's include path"
#endif

int main() {
  try {
    bounce::Scene scene;
    bounce::MaterialId white = scene.addMaterial({.baseColor = {0.8f, 0.8f, 0.8f}});
    std::vector<bounce::Vec3> positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    scene.addInstance(scene.addMesh(positions, {}, indices, white));
    scene.setSun({.direction = {0.2f, -1.0f, 0.1f}, .irradiance = 100.0f});

    bounce::RendererSettings settings{.width = 32, .height = 24, .gi = bounce::GiMode::None};
    bounce::Renderer renderer = bounce::Renderer::create(scene, settings);
    bounce::Camera camera{.position = {0.0f, 1.5f, 1.5f}, .target = {0.0f, 0.0f, 0.0f}};
    renderer.render(camera);
    bounce::FrameStatistics statistics = renderer.render(camera);
    bounce::Image image = renderer.readImage();

    for (float v : image.rgba) {
      if (!std::isfinite(v)) {
        std::fprintf(stderr, "bounce_consumer: the image has NaN or infinite values\n");
        return 1;
      }
    }
    const float* centre = image.pixel(image.width / 2, image.height / 2);
    if (!(centre[0] > 0.1f)) {
      std::fprintf(stderr, "bounce_consumer: the lit floor renders black\n");
      return 1;
    }
    std::printf("bounce_consumer: %ux%u on %s, frame %llu, %zu passes, centre %.3f: ok\n",
                image.width, image.height, renderer.deviceName().c_str(),
                static_cast<unsigned long long>(statistics.frameIndex), statistics.passes.size(),
                centre[0]);
    return 0;
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce_consumer: %s\n", e.what());
    return 1;
  }
}
