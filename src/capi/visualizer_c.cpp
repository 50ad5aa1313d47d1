// The C API's visualizer (include/soundpaint/soundpaint_vulkan.h) over
// sp::Visualizer: the C structs turned into the C++ ones, the handle made
// and checked like a simulation's.
#include "soundpaint/soundpaint_vulkan.h"

#include <bit>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "capi/capi_internal.h"
#include "capi/display_c.h"
#include "soundpaint/visualizer.h"

struct sp_visualizer {
  sp::capi::ContextRef context;  // its allocator gave this handle's memory
  std::unique_ptr<sp::Visualizer> visualizer;
  sp_sound_scene sound_scene;
  sp::capi::OneThreadAtATime rendering;  // every call but backend, scene and create
};

namespace {

using sp::capi::guarded;
using sp::capi::guarded_in;
using sp::capi::HandleKind;
using sp::capi::require;
using sp::capi::require_live;
using sp::capi::unwrap;

// sp_host_vulkan and sp_draw_target are sp::HostVulkan and sp::DrawTarget
// field for field, so the host's handles and formats cross the C boundary
// as one bit copy each rather than a field-by-field mirror.
#define SP_SAME(c, cpp, field) (offsetof(c, field) == offsetof(cpp, field))
#define SP_HOST(field) SP_SAME(sp_host_vulkan, sp::HostVulkan, field)
static_assert(sizeof(sp_host_vulkan) == sizeof(sp::HostVulkan) && SP_HOST(instance) && SP_HOST(physical_device) &&
                  SP_HOST(device) && SP_HOST(queue_family) && SP_HOST(compute_queue_family) &&
                  SP_HOST(pipeline_cache) && SP_HOST(allocator) && SP_HOST(enabled_features),
              "sp_host_vulkan (soundpaint_vulkan.h) and sp::HostVulkan (visualizer.h) must keep one layout");
#define SP_TARGET(field) SP_SAME(sp_draw_target, sp::DrawTarget, field)
static_assert(sizeof(sp_draw_target) == sizeof(sp::DrawTarget) && SP_TARGET(color_format) && SP_TARGET(depth_format) &&
                  SP_TARGET(stencil_format) && SP_TARGET(samples) && SP_TARGET(depth_compare),
              "sp_draw_target (soundpaint_vulkan.h) and sp::DrawTarget (visualizer.h) must keep one layout");
#undef SP_TARGET
#undef SP_HOST
#undef SP_SAME

sp::HostVulkan to_cpp(const sp_host_vulkan& in) { return std::bit_cast<sp::HostVulkan>(in); }
sp::DrawTarget to_cpp(const sp_draw_target& in) { return std::bit_cast<sp::DrawTarget>(in); }

// A column-major matrix from C, NULL and non-finite values rejected here so
// that the message names the parameter.
glm::mat4 to_matrix(const float* m, const char* fn, const char* what) {
  if (m == nullptr) sp::capi::throw_invalid(fn, std::string(what) + " is NULL");
  for (int k = 0; k < 16; ++k)
    if (!std::isfinite(m[k]))
      sp::capi::throw_invalid(fn, std::string(what) + "[" + std::to_string(k) + "] is not finite");
  return glm::make_mat4(m);
}

sp::Visualizer& visualizer_of(const sp_visualizer* visualizer, const char* fn) {
  require_live(HandleKind::Visualizer, visualizer, fn, "visualizer");
  return *visualizer->visualizer;
}

// A live visualizer for a call of the render thread's (soundpaint.h,
// Thread-safety), entered for as long as the returned scope lives.
struct RenderCall {
  RenderCall(const sp_visualizer* visualizer, const char* fn)
      : v(visualizer_of(visualizer, fn)), one_thread(visualizer->rendering.enter(fn, v.scene())) {}
  sp::Visualizer& v;
  sp::capi::OneThreadAtATime::Scope one_thread;
};

}  // namespace

extern "C" {

void sp_host_vulkan_init(sp_host_vulkan* host) noexcept {
  if (host == nullptr) return;
  *host = std::bit_cast<sp_host_vulkan>(sp::HostVulkan{});
}

void sp_draw_target_init(sp_draw_target* target) noexcept {
  if (target == nullptr) return;
  *target = std::bit_cast<sp_draw_target>(sp::DrawTarget{});
}

void sp_visualizer_options_init(sp_visualizer_options* options) noexcept {
  if (options == nullptr) return;
  const sp::VisualizerSettings defaults;
  *options = sp_visualizer_options{};
  options->struct_size = sizeof(sp_visualizer_options);
  options->backend = SP_BACKEND_AUTO;
  options->memory_budget_bytes = defaults.cpu.memory_budget_bytes;
  options->max_steps_per_frame = defaults.max_steps_per_frame;
}

}  // extern "C"

namespace {

void create_visualizer(sp_context& context, const sp_host_vulkan* host, const sp_draw_target* target,
                       const sp_scene* scene, const char* config_json, const sp_visualizer_options& options,
                       sp_visualizer** out, const char* fn) {
  require(host != nullptr, fn, "host is NULL");
  require(target != nullptr, fn, "target is NULL");
  require_live(HandleKind::Scene, scene, fn, "scene");
  require(out != nullptr, fn, "out is NULL");
  sp::capi::require_struct_size(options.struct_size, sizeof(sp_visualizer_options), fn, "options");
  require(options.memory_budget_bytes > 0, fn, "options->memory_budget_bytes is 0");
  require(options.max_steps_per_frame > 0, fn, "options->max_steps_per_frame is 0");
  sp::VisualizerSettings settings;
  settings.backend = sp::capi::backend_choice(options.backend, fn);
  settings.cpu.threads = sp::capi::thread_count(context, options.threads);
  settings.cpu.memory_budget_bytes = options.memory_budget_bytes;
  settings.max_steps_per_frame = options.max_steps_per_frame;
  sp::capi::WorldOptions world_options;
  world_options.threads = settings.cpu.threads;
  auto visualizer = sp::capi::make_handle<sp_visualizer>(context);
  visualizer->visualizer = unwrap(sp::Visualizer::create(
      to_cpp(*host), to_cpp(*target), sp::capi::world_from(*scene, config_json, world_options), settings));
  visualizer->sound_scene.scene = &visualizer->visualizer->scene();
  sp::capi::register_handle(HandleKind::Visualizer, visualizer.get(), &visualizer->sound_scene);
  *out = visualizer.release();
}

}  // namespace

extern "C" {

sp_result sp_visualizer_create(const sp_host_vulkan* host, const sp_draw_target* target, const sp_scene* scene,
                               const char* config_json, sp_backend backend, sp_visualizer** out) noexcept {
  return guarded([&] {
    sp_visualizer_options options;
    sp_visualizer_options_init(&options);
    options.backend = backend;
    create_visualizer(sp::capi::default_context(), host, target, scene, config_json, options, out,
                      "sp_visualizer_create");
  });
}

sp_result sp_visualizer_create_in(sp_context* context, const sp_host_vulkan* host, const sp_draw_target* target,
                                  const sp_scene* scene, const char* config_json, const sp_visualizer_options* options,
                                  sp_visualizer** out) noexcept {
  sp_context* log_to = nullptr;
  return guarded_in(log_to, [&] {
    const char* fn = "sp_visualizer_create_in";
    log_to = &sp::capi::context_of(context, fn);
    sp_visualizer_options defaults;
    sp_visualizer_options_init(&defaults);
    create_visualizer(*log_to, host, target, scene, config_json, options != nullptr ? *options : defaults, out, fn);
  });
}

sp_result sp_visualizer_destroy(sp_visualizer* visualizer) noexcept {
  return guarded([&] {
    sp::capi::destroy_guarded_handle(HandleKind::Visualizer, visualizer, &sp_visualizer::rendering,
                                     "sp_visualizer_destroy", "visualizer");
  });
}

sp_result sp_visualizer_scene(sp_visualizer* visualizer, sp_sound_scene** out) noexcept {
  return guarded(
      [&] { sp::capi::hand_out_scene(HandleKind::Visualizer, visualizer, out, "sp_visualizer_scene", "visualizer"); });
}

sp_result sp_visualizer_backend(const sp_visualizer* visualizer, sp_backend* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_backend";
    const sp::Visualizer& v = visualizer_of(visualizer, fn);
    require(out != nullptr, fn, "out is NULL");
    *out = v.backend() == sp::Backend::Gpu ? SP_BACKEND_GPU : SP_BACKEND_CPU;
  });
}

sp_result sp_visualizer_record_simulation(sp_visualizer* visualizer, VkCommandBuffer cmd, double dt_seconds,
                                          uint32_t* out_steps) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_record_simulation";
    RenderCall call(visualizer, fn);
    sp::Visualizer& v = call.v;
    require(cmd != VK_NULL_HANDLE, fn, "cmd is VK_NULL_HANDLE");
    require(std::isfinite(dt_seconds) && dt_seconds >= 0.0, fn, "dt_seconds must be finite and >= 0");
    const std::uint32_t steps = unwrap(v.record_simulation(cmd, dt_seconds));
    if (out_steps != nullptr) *out_steps = steps;
  });
}

sp_result sp_visualizer_record_draw(sp_visualizer* visualizer, VkCommandBuffer cmd, const float view[16],
                                    const float projection[16], const VkRect2D* area) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_record_draw";
    RenderCall call(visualizer, fn);
    sp::Visualizer& v = call.v;
    require(cmd != VK_NULL_HANDLE, fn, "cmd is VK_NULL_HANDLE");
    const glm::mat4 view_matrix = to_matrix(view, fn, "view");
    const glm::mat4 projection_matrix = to_matrix(projection, fn, "projection");
    unwrap(v.record_draw(cmd, view_matrix, projection_matrix, area));
  });
}

sp_result sp_visualizer_record_draw_ex(sp_visualizer* visualizer, VkCommandBuffer cmd, const float view[16],
                                       const float projection[16], const sp_draw_options* options) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_record_draw_ex";
    RenderCall call(visualizer, fn);
    sp::Visualizer& v = call.v;
    require(cmd != VK_NULL_HANDLE, fn, "cmd is VK_NULL_HANDLE");
    const glm::mat4 view_matrix = to_matrix(view, fn, "view");
    const glm::mat4 projection_matrix = to_matrix(projection, fn, "projection");
    require(options != nullptr, fn, "options is NULL");
    unwrap(v.record_draw(cmd, view_matrix, projection_matrix, sp::capi::draw_options_from(*options, fn)));
  });
}

sp_result sp_visualizer_set_display(sp_visualizer* visualizer, const sp_display_settings* settings) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_set_display";
    RenderCall call(visualizer, fn);
    sp::Visualizer& v = call.v;
    require(settings != nullptr, fn, "settings is NULL");
    unwrap(v.set_display(sp::capi::display_settings_from(*settings, fn)));
  });
}

sp_result sp_visualizer_set_scene_depth(sp_visualizer* visualizer, const VkImageView* views, uint32_t count) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_set_scene_depth";
    RenderCall call(visualizer, fn);
    sp::Visualizer& v = call.v;
    require(count == 0 || views != nullptr, fn, "views is NULL but count is above 0");
    // Named by index here; the visualizer would only say that one is null.
    for (uint32_t i = 0; i < count; ++i)
      if (views[i] == VK_NULL_HANDLE) sp::capi::throw_invalid(fn, "views[" + std::to_string(i) + "] is VK_NULL_HANDLE");
    unwrap(v.set_scene_depth(std::span<const VkImageView>(views, count)));
  });
}

sp_result sp_visualizer_wait(sp_visualizer* visualizer) noexcept {
  return guarded([&] { unwrap(RenderCall(visualizer, "sp_visualizer_wait").v.wait_for_simulation()); });
}

sp_result sp_visualizer_steps_run(const sp_visualizer* visualizer, uint64_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_visualizer_steps_run";
    RenderCall call(visualizer, fn);
    const sp::Visualizer& v = call.v;
    require(out != nullptr, fn, "out is NULL");
    *out = v.steps_run();
  });
}

}  // extern "C"
