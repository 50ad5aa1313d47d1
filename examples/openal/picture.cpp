#include "picture.h"

#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/view_camera.h"
#include "vk/context.h"

struct PictureWriter::State {
  std::unique_ptr<sp::vk::Context> context;
  std::unique_ptr<sp::draw::Renderer> renderer;
  std::optional<sp::Camera> camera;
  unsigned width = 0, height = 0;
};

PictureWriter::PictureWriter(const sp::Scene& scene, const sp::World& world, unsigned width, unsigned height)
    : state_(std::make_unique<State>()) {
  state_->context = sp::vk::Context::create().value();
  sp::draw::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  state_->renderer = std::make_unique<sp::draw::Renderer>(*state_->context, world, settings);
  state_->camera = scene.camera;
  state_->width = width;
  state_->height = height;
}

PictureWriter::~PictureWriter() = default;

void PictureWriter::write(const std::filesystem::path& png, sp::Simulator& simulator, sp::Vec3 eye, sp::Vec3 look_at) {
  sp::draw::CameraOverrides overrides;
  overrides.position = glm::vec3(eye);
  overrides.look_at = glm::vec3(look_at);
  const sp::draw::ViewCamera camera =
      sp::draw::make_view_camera(state_->camera, simulator.world(), overrides, state_->width, state_->height);
  sp::draw::write_png(png.string(), state_->renderer->render(camera, simulator));
}
