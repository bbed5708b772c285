// The smallest Bounce program: load a scene (a built-in name or a glTF path), render a few frames
// with full GI from the scene's own camera, print the per-pass GPU times of the last one, and
// write the image if an output path (.png or .exr) is given.
//
//   bounce_example_minimal [scene] [out.png] [exposure stops]
//   scene: cornell (default), sunroom, ..., or a .gltf
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <bounce/bounce.h>

int main(int argc, char** argv) {
  std::string sceneName = argc > 1 ? argv[1] : "cornell";
  try {
    bounce::Scene scene = bounce::Scene::load(sceneName);
    bounce::RendererSettings settings = bounce::presetSettings(bounce::Preset::Mobile);
    settings.width = 320;  // small, so that a CPU device (lavapipe) renders it in seconds
    settings.height = 180;
    // Automatic exposure (the default) shows a scene lit by its emitters alone (cornell) as
    // well as one under the sun; a third argument fixes the exposure instead, in stops.
    if (argc > 3) {
      settings.autoExposure = false;
      settings.exposureStops = std::strtof(argv[3], nullptr);
    }
    bounce::Renderer renderer = bounce::Renderer::create(scene, settings);

    bounce::FrameStatistics statistics;
    for (int frame = 0; frame < 8; ++frame) statistics = renderer.render(scene.camera());
    std::printf("%s: %ux%u on %s, frame %llu: %.3f ms GPU\n", sceneName.c_str(), settings.width,
                settings.height, renderer.deviceName().c_str(),
                static_cast<unsigned long long>(statistics.frameIndex),
                statistics.gpuMilliseconds());
    for (const bounce::PassTime& pass : statistics.passes)
      std::printf("  %-36s %8.3f ms\n", pass.name.c_str(), pass.milliseconds);

    if (argc > 2) {
      bounce::writeImage(argv[2], renderer.readImage("tonemap"));
      std::printf("wrote %s\n", argv[2]);
    }
    return 0;
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce_example_minimal: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce_example_minimal: unexpected error: %s\n", e.what());
  }
  return 1;
}
