// SoundScene: the host's run-time changes, validated and applied between
// steps. Source ids are slots; removing frees a slot for the next add.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "core/finite.h"
#include "core/glm_interop.h"
#include "display/display_checks.h"
#include "sim/source_checks.h"
#include "sim/source_display.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

// Refits that have made the tree this much costlier than its build trigger
// a rebuild: a door swung open keeps its leaves' old neighbours otherwise.
constexpr double kRebuildCostRatio = 2.0;

// bvh_sah_cost is relative to the root box, so geometry leaving the level
// can lower it while every node grew; scaled by the root's area it is the
// absolute expected work per ray, which does grow.
double absolute_sah_cost(const Bvh& bvh) {
  if (bvh.nodes.empty()) return 0.0;
  const glm::vec3 e = bvh.nodes[0].bmax - bvh.nodes[0].bmin;
  const double half_area =
      static_cast<double>(e.x) * e.y + static_cast<double>(e.y) * e.z + static_cast<double>(e.z) * e.x;
  return bvh_sah_cost(bvh) * std::max(half_area, 1e-12);
}

Error invalid(std::string message) { return Error{ErrorCode::InvalidArgument, std::move(message), 0}; }

Result<bool> check_duration(const char* what, double duration) {
  if (!(duration >= 0.0) || !std::isfinite(duration))
    return invalid(std::string(what) + ": duration must be finite and >= 0");
  return true;
}

}  // namespace

SoundScene::SoundScene(World world) : world_(std::move(world)) {
  if (world_.source_active.size() != world_.sources.size()) world_.source_active.assign(world_.sources.size(), true);
  // A World made by hand rather than by make_world.
  if (world_.source_colors.size() != world_.sources.size() || world_.category_names.empty())
    resolve_all_source_display(world_);
  capacity_ = std::max<std::uint32_t>(kDefaultSourceCapacity, static_cast<std::uint32_t>(world_.sources.size()));
  active_count_ =
      static_cast<std::uint32_t>(std::count(world_.source_active.begin(), world_.source_active.end(), true));
  play_windows_.resize(world_.sources.size());
  one_shot_.resize(world_.sources.size(), false);
  if (!world_.instance_names.empty()) world_.geometry->build_sah_cost = absolute_sah_cost(world_.geometry->bvh);
}

Result<bool> SoundScene::check_id(const char* what, std::uint32_t id) const {
  if (id >= world_.sources.size())
    return invalid(std::string(what) + ": unknown source id " + std::to_string(id) + " (there are " +
                   std::to_string(world_.sources.size()) + " source slots)");
  if (!world_.source_active[id]) return invalid(std::string(what) + ": source " + std::to_string(id) + " was removed");
  return true;
}

Result<bool> SoundScene::set_listener(Vec3 position) {
  if (!all_finite(position)) return invalid("set_listener: position must be finite");
  world_.listener = position;
  return true;
}

Result<std::uint32_t> SoundScene::add_source(const SourceDesc& source) { return add_slot("add_source", source); }

Result<std::uint32_t> SoundScene::add_slot(const char* what, const SourceDesc& source) {
  if (active_count_ >= capacity_)
    return Error{
        ErrorCode::LimitExceeded,
        std::string(what) + ": all " + std::to_string(capacity_) + " source slots are in use; remove one first", 0};
  const auto free_slot = std::find(world_.source_active.begin(), world_.source_active.end(), false);
  const auto id = static_cast<std::uint32_t>(free_slot - world_.source_active.begin());
  auto checked = capture_errors([&] {
    check_source(source, id);  // names the id the source would get
    return true;
  });
  if (!checked) return invalid(std::string(what) + ": " + checked.error().message);
  if (id == world_.sources.size()) {
    world_.sources.push_back(source);
    world_.source_active.push_back(true);
    play_windows_.emplace_back();
    one_shot_.push_back(false);
  } else {
    world_.sources[id] = source;
    world_.source_active[id] = true;
    play_windows_[id] = {};
    one_shot_[id] = false;
  }
  resolve_source_display(world_, id);
  active_count_ += 1;
  return id;
}

Result<bool> SoundScene::update_source(std::uint32_t id, const SourceDesc& source) {
  if (auto known = check_id("update_source", id); !known) return known;
  auto checked = capture_errors([&] {
    check_source(source, id);
    return true;
  });
  if (!checked) return invalid("update_source: " + checked.error().message);
  const SourceDesc previous = world_.sources[id];
  world_.sources[id] = source;
  if (one_shot_[id]) {
    // A one-shot keeps sounding by its window only, never by a pattern.
    world_.sources[id].duration = previous.duration;
    world_.sources[id].interval = previous.interval;
    world_.sources[id].phase = previous.phase;
  }
  resolve_source_display(world_, id);
  return true;
}

Result<bool> SoundScene::set_display(const DisplaySettings& settings) {
  auto checked = capture_errors(
      [&] {
        check_display_settings(settings);
        return true;
      },
      ErrorCode::InvalidConfig);
  if (!checked) return checked.error();
  world_.config.display = settings;
  for (std::uint32_t id = 0; id < world_.sources.size(); ++id) resolve_source_display(world_, id);
  return true;
}

Result<bool> SoundScene::move_source(std::uint32_t id, Vec3 position) {
  if (auto known = check_id("move_source", id); !known) return known;
  if (!all_finite(position)) return invalid("move_source: position must be finite");
  world_.sources[id].position = position;
  return true;
}

Result<bool> SoundScene::remove_source(std::uint32_t id) {
  if (auto known = check_id("remove_source", id); !known) return known;
  world_.source_active[id] = false;
  play_windows_[id] = {};
  one_shot_[id] = false;
  active_count_ -= 1;
  return true;
}

Result<bool> SoundScene::play(std::uint32_t id, double duration) {
  if (auto known = check_id("play", id); !known) return known;
  if (auto valid = check_duration("play", duration); !valid) return valid;
  play_windows_[id] = {next_step_time(), next_step_time() + duration};
  return true;
}

Result<std::uint32_t> SoundScene::emit(const SourceDesc& source, double duration) {
  if (auto valid = check_duration("emit", duration); !valid) return valid.error();
  SourceDesc one_shot = source;
  // Silent by pattern: only the play window below makes it sound.
  one_shot.duration = 0.0;
  one_shot.interval = 1.0;
  one_shot.phase = 0.0;
  Result<std::uint32_t> id = add_slot("emit", one_shot);
  if (!id) return id;
  play_windows_[*id] = {next_step_time(), next_step_time() + duration};
  one_shot_[*id] = true;
  return id;
}

Result<bool> SoundScene::set_instance_transform(std::uint32_t instance, const Mat4& transform) {
  if (instance >= world_.instance_names.size())
    return invalid("set_instance_transform: unknown instance " + std::to_string(instance) + " (the scene has " +
                   std::to_string(world_.instance_names.size()) + " moving parts)");
  if (!all_finite(transform)) return invalid("set_instance_transform: the transform must be finite");
  world_.instance_transforms[instance] = transform;
  geometry_pending_ = true;
  return true;
}

void SoundScene::plan(std::uint64_t step, StepPlan& out) {
  const double t = static_cast<double>(step) * world_.config.dt;
  // A one-shot whose window closed before this step is over: free its slot.
  for (std::uint32_t id = 0; id < world_.sources.size(); ++id) {
    if (one_shot_[id] && world_.source_active[id] && t >= play_windows_[id].end) (void)remove_source(id);
  }
  out = plan_step(world_, step, world_.listener, play_windows_);
  next_step_ = step + 1;
}

BvhChanges SoundScene::update_geometry() {
  if (!geometry_pending_) return {};
  geometry_pending_ = false;
  std::vector<glm::vec3> vertices(world_.geometry->rest_vertices.size());
  for (std::size_t tri = 0; tri < world_.geometry->triangle_instances.size(); ++tri) {
    const std::uint32_t instance = world_.geometry->triangle_instances[tri];
    for (std::size_t k = 3 * tri; k < 3 * tri + 3; ++k) {
      vertices[k] = instance == kStaticInstance ? world_.geometry->rest_vertices[k]
                                                : glm::vec3(to_glm(world_.instance_transforms[instance]) *
                                                            glm::vec4(world_.geometry->rest_vertices[k], 1.0f));
    }
  }
  BvhChanges changes = refit_bvh(world_.geometry->bvh, vertices).value();
  if (absolute_sah_cost(world_.geometry->bvh) > kRebuildCostRatio * world_.geometry->build_sah_cost) {
    const bool had_edges = !world_.geometry->bvh.edges.empty();
    world_.geometry->bvh = build_bvh(vertices, world_.geometry->triangle_layers, world_.geometry->triangle_solids);
    world_.geometry->build_sah_cost = absolute_sah_cost(world_.geometry->bvh);
    changes.nodes = {{0, static_cast<std::uint32_t>(world_.geometry->bvh.nodes.size())}};
    changes.triangles = {{0, static_cast<std::uint32_t>(world_.geometry->bvh.triangles.size())}};
    if (had_edges) {
      world_.geometry->bvh.edges = find_exposed_edges(world_.geometry->bvh);
      changes.edges = {{0, static_cast<std::uint32_t>(world_.geometry->bvh.edges.size())}};
    }
  }
  return changes;
}

}  // namespace sp
