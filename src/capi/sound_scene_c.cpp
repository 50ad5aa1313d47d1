// The C API's run-time scene controls (sp_sound_scene_*): thin wrappers over
// sp::SoundScene, which validates ids and source fields and names the
// problem. Checked here is what C adds (NULL pointers, live handles) and the
// scalar arguments, whose messages then name the C function.
#include <cmath>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "capi/capi_internal.h"

namespace {

using sp::capi::guarded;
using sp::capi::HandleKind;
using sp::capi::require;
using sp::capi::scene_of;
using sp::capi::unwrap;

bool finite(float x, float y, float z) { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }

// Field checks are left to SoundScene (check_source), the one place that
// knows what a valid source is.
sp::SourceDesc to_cpp(const sp_source_desc& in) {
  sp::SourceDesc out;
  out.position = glm::vec3(in.position[0], in.position[1], in.position[2]);
  // All three negative: no colour of its own (the palette's).
  if (!(in.color[0] < 0.0f && in.color[1] < 0.0f && in.color[2] < 0.0f))
    out.color = glm::vec3(in.color[0], in.color[1], in.color[2]);
  if (in.category != nullptr) out.category = in.category;
  out.max_distance = in.max_distance;
  out.loudness = in.loudness;
  out.duration = in.duration;
  out.interval = in.interval;
  out.phase = in.phase;
  return out;
}

void require_duration(double duration, const char* fn) {
  require(std::isfinite(duration) && duration >= 0.0, fn, "duration_seconds must be finite and >= 0");
}

}  // namespace

extern "C" {

void sp_source_desc_init(sp_source_desc* desc) noexcept {
  if (desc == nullptr) return;
  // Cannot throw: the default category fits std::string's inline buffer.
  const sp::SourceDesc defaults;
  sp_source_desc out{};
  for (int k = 0; k < 3; ++k) {
    out.position[k] = defaults.position[k];
    out.color[k] = -1.0f;  // defaults.color is empty: the category's palette colour
  }
  out.category = nullptr;  // stands for defaults.category
  out.max_distance = defaults.max_distance;
  out.loudness = defaults.loudness;
  out.duration = defaults.duration;
  out.interval = defaults.interval;
  out.phase = defaults.phase;
  *desc = out;
}

sp_result sp_sound_scene_set_listener(sp_sound_scene* scene, float x, float y, float z) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_set_listener";
    sp::SoundScene& s = scene_of(scene, fn);
    require(finite(x, y, z), fn, "position is not finite");
    unwrap(s.set_listener(glm::vec3(x, y, z)));
  });
}

sp_result sp_sound_scene_add_source(sp_sound_scene* scene, const sp_source_desc* desc, uint32_t* out_id) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_add_source";
    sp::SoundScene& s = scene_of(scene, fn);
    require(desc != nullptr, fn, "desc is NULL");
    require(out_id != nullptr, fn, "out_id is NULL");
    *out_id = unwrap(s.add_source(to_cpp(*desc)));
  });
}

sp_result sp_sound_scene_update_source(sp_sound_scene* scene, uint32_t id, const sp_source_desc* desc) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_update_source";
    sp::SoundScene& s = scene_of(scene, fn);
    require(desc != nullptr, fn, "desc is NULL");
    unwrap(s.update_source(id, to_cpp(*desc)));
  });
}

sp_result sp_sound_scene_move_source(sp_sound_scene* scene, uint32_t id, float x, float y, float z) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_move_source";
    sp::SoundScene& s = scene_of(scene, fn);
    require(finite(x, y, z), fn, "position is not finite");
    unwrap(s.move_source(id, glm::vec3(x, y, z)));
  });
}

sp_result sp_sound_scene_remove_source(sp_sound_scene* scene, uint32_t id) noexcept {
  return guarded([&] { unwrap(scene_of(scene, "sp_sound_scene_remove_source").remove_source(id)); });
}

sp_result sp_sound_scene_play(sp_sound_scene* scene, uint32_t id, double duration_seconds) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_play";
    sp::SoundScene& s = scene_of(scene, fn);
    require_duration(duration_seconds, fn);
    unwrap(s.play(id, duration_seconds));
  });
}

sp_result sp_sound_scene_emit(sp_sound_scene* scene, const sp_source_desc* desc, double duration_seconds,
                              uint32_t* out_id) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_emit";
    sp::SoundScene& s = scene_of(scene, fn);
    require(desc != nullptr, fn, "desc is NULL");
    require(out_id != nullptr, fn, "out_id is NULL");
    require_duration(duration_seconds, fn);
    *out_id = unwrap(s.emit(to_cpp(*desc), duration_seconds));
  });
}

sp_result sp_sound_scene_set_instance_transform(sp_sound_scene* scene, uint32_t instance,
                                                const float column_major_4x4[16]) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_set_instance_transform";
    sp::SoundScene& s = scene_of(scene, fn);
    require(column_major_4x4 != nullptr, fn, "column_major_4x4 is NULL");
    for (int k = 0; k < 16; ++k)
      if (!std::isfinite(column_major_4x4[k]))
        sp::capi::throw_invalid(fn, "column_major_4x4[" + std::to_string(k) + "] is not finite");
    unwrap(s.set_instance_transform(instance, glm::make_mat4(column_major_4x4)));
  });
}

sp_result sp_sound_scene_instance_count(const sp_sound_scene* scene, uint32_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_instance_count";
    const sp::SoundScene& s = scene_of(scene, fn);
    require(out != nullptr, fn, "out is NULL");
    *out = s.instance_count();
  });
}

sp_result sp_sound_scene_has_source(const sp_sound_scene* scene, uint32_t id, int* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_has_source";
    const sp::SoundScene& s = scene_of(scene, fn);
    require(out != nullptr, fn, "out is NULL");
    *out = s.has_source(id) ? 1 : 0;
  });
}

sp_result sp_sound_scene_source_capacity(const sp_sound_scene* scene, uint32_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_source_capacity";
    const sp::SoundScene& s = scene_of(scene, fn);
    require(out != nullptr, fn, "out is NULL");
    *out = s.source_capacity();
  });
}

}  // extern "C"
