// The real-time renderer: seed 000's hybrid frame (DESIGN.md §4: vbuffer, gbuffer, sun shadows,
// the chosen diffuse GI, sky, composite, tonemap) over one scene, headless. Each render()
// records, submits and waits for one frame, and returns its per-pass GPU times; readImage()
// then copies an image of that frame to the host.
//
//   bounce::Scene scene = bounce::Scene::load("cornell");
//   bounce::Renderer renderer = bounce::Renderer::create(scene, bounce::presetSettings(
//                                                                   bounce::Preset::Desktop));
//   for (int i = 0; i < 16; ++i) renderer.render(scene.camera());
//   bounce::Image image = renderer.readImage();  // "tonemap"
//   bounce::writeImage("out.png", image);
//
// Images by name (requestImage, readImage): "tonemap" (the default, always captured) is the
// display image, ACES-filmic values in [0, 1], linear (writeImage's .png applies the sRGB
// transfer function); "composite" is the HDR radiance before exposure and tone curve, in
// W/(m^2 sr). Any other pass name (FrameStatistics::passes) shows the first image that pass
// writes, and any resource name of the frame (e.g. "gbuffer.normals") shows that resource.
//
// Three ways in: Renderer::create(scene, settings) makes its own Vulkan device (a discrete GPU
// first, else lavapipe; the environment variables BOUNCE_DEVICE=N picks device N and
// BOUNCE_VALIDATE=1 turns on the Khronos validation layer); Renderer::create(externalDevice,
// scene, settings) runs on the host's device (bounce/external_device.h); and on such a
// renderer, renderGi(camera, hostGBuffer) is "bring your own G-buffer": the host rasterises its
// own G-buffer (depth, normal, albedo, motion; bounce/host_gbuffer.h has the contract) and
// Bounce returns its diffuse GI image for it, leaving the final lighting to the host.
#pragma once
#include <memory>
#include <string>

#include "bounce/camera.h"
#include "bounce/config.h"
#include "bounce/frame_statistics.h"
#include "bounce/host_gbuffer.h"
#include "bounce/image.h"
#include "bounce/scene.h"
#include "bounce/settings.h"

namespace bounce::api {

struct ExternalDevice;

class Renderer {
 public:
  // Uploads the scene (it is copied: later changes to `scene` do not reach the renderer) and
  // creates every GPU resource of the frame. Throws bounce::Error for a bad scene or settings,
  // or a device that cannot run Bounce.
  static Renderer create(const Scene& scene, const RendererSettings& settings = {});
  static Renderer create(const ExternalDevice& device, const Scene& scene,
                         const RendererSettings& settings = {});

  // Waits for the renderer's work on the GPU, then frees what it created. Move-only; a
  // moved-from Renderer may only be assigned to or destroyed.
  ~Renderer();
  Renderer(Renderer&& other) noexcept;
  Renderer& operator=(Renderer&& other) noexcept;

  // Renders one frame seen from `camera`, waits for it, and returns its statistics. Temporal
  // history (GI, denoisers) carries over from the last frame: for a camera cut, resetHistory().
  FrameStatistics render(const Camera& camera);

  // Bring your own G-buffer (bounce/host_gbuffer.h): one frame of Bounce's sun shadows and
  // diffuse GI on the host's G-buffer images seen from `camera` (the camera the host rendered
  // with), without Bounce's own primary visibility, sky, composite or tonemap. Waits for the
  // GPU, and returns the GI image, valid until the next renderGi/render. Temporal history
  // carries over as in render() (resetHistory() for a camera cut; `motion` reprojects it).
  // Only for a renderer created on an ExternalDevice, with settings.gi other than None; throws
  // bounce::Error otherwise, or naming the host image whose format, extent or handles are wrong.
  // requestImage() names work here too (e.g. "gbuffer.normals", "gi.diffuse"), except the
  // composite and tonemap images, which this frame has not.
  GiImage renderGi(const Camera& camera, const HostGBuffer& gbuffer);

  // Captures the image `name` (see above) from the next render() on. An unknown name makes that
  // render() throw bounce::Error listing the frame's passes and resources; the request is then
  // dropped and the renderer stays usable.
  void requestImage(const std::string& name);
  // The image `name` as the last render() left it. Throws bounce::Error when no frame has been
  // rendered yet or the name was not requested before the last render().
  Image readImage(const std::string& name = "tonemap") const;

  // The sun and sky from the next frame on (a moving sun, day and night). A large change (the
  // sun turning by more than 5 degrees, or its or the sky's brightness changing by more than
  // half) makes the GI rebuild its light quickly rather than blend it in over many frames.
  void setSunAndSky(const Sun& sun, const Sky& sky);
  // Plays the scene's own animation at `seconds` from the next frame on: glTF node animations,
  // skins and morph targets (posed on the GPU), animated KHR lights, a built-in scene's scripted
  // motion. Motion vectors follow the objects and the deforming surfaces, so temporal history
  // carries over. Times should not decrease. The scene's camera path and time of day are not
  // played: the camera is the one given to render(), the sun setSunAndSky's. Throws
  // bounce::Error for a negative or non-finite time.
  void setAnimationTime(double seconds);
  // Forgets temporal history (a camera cut): the next frame starts afresh.
  void resetHistory();

  const RendererSettings& settings() const;
  std::string deviceName() const;  // as the driver names it

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce::api
