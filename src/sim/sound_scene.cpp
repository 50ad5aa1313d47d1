// SoundScene, the host's side: every change is checked at the call, against
// the source slots as the queued changes will leave them, and queued for
// the next step (scene_inbox.h says why; sound_scene_step.cpp applies
// them). Source ids are slots; removing frees a slot for the next add.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/invalid_argument.h"
#include "core/finite.h"
#include "display/display_checks.h"
#include "sim/geometry_update.h"
#include "sim/instance_placement.h"
#include "sim/scene_inbox.h"
#include "sim/source_checks.h"
#include "sim/source_display.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

Result<bool> check_duration(const char* what, double duration) {
  if (!(duration >= 0.0) || !std::isfinite(duration))
    return invalid_argument_error(std::string(what) + ": duration must be finite and >= 0");
  return true;
}

// check_source's message, prefixed with the call.
Result<bool> check_source_for(const char* what, const SourceDesc& source, std::uint32_t id) {
  auto checked = capture_errors([&] {
    check_source(source, id);  // names the id the source has or would get
    return true;
  });
  if (!checked) return invalid_argument_error(std::string(what) + ": " + checked.error().message);
  return true;
}

// A World is make_world's: an entry a source in each per-source table, the
// categories resolved, a transform an instance. One made or edited by hand
// that breaks this is refused, naming what disagrees, rather than repaired.
void require_consistent(const World& world) {
  const std::size_t sources = world.sources.size();
  std::string problem;
  if (world.source_active.size() != sources || world.source_colors.size() != sources)
    problem = std::to_string(sources) + " sources but " + std::to_string(world.source_active.size()) +
              " source_active and " + std::to_string(world.source_colors.size()) + " source_colors entries";
  else if (world.category_names.empty()) problem = "no category_names";
  else if (world.instance_transforms.size() != world.instance_names.size())
    problem = std::to_string(world.instance_names.size()) + " instances but " +
              std::to_string(world.instance_transforms.size()) + " instance_transforms";
  if (!problem.empty())
    throw Exception(ErrorCode::InvalidArgument,
                    "the World's tables disagree (" + problem + "): make Worlds with make_world");
}

}  // namespace

SoundScene::SoundScene(World world) : world_(std::move(world)), inbox_(std::make_unique<detail::SceneInbox>()) {
  require_consistent(world_);
  capacity_ = std::max<std::uint32_t>(kDefaultSourceCapacity, static_cast<std::uint32_t>(world_.sources.size()));
  play_windows_.resize(world_.sources.size());
  one_shot_.resize(world_.sources.size(), false);
  instance_triangles_ = triangles_by_instance(*world_.geometry, world_.instance_names.size());
  inbox_->slot_taken = world_.source_active;
  inbox_->taken =
      static_cast<std::uint32_t>(std::count(world_.source_active.begin(), world_.source_active.end(), true));
  inbox_->listener = world_.listener;
}

SoundScene::~SoundScene() = default;

const World& SoundScene::world() const {
  detail::expect_stepping_thread(*inbox_, "world()");
  return world_;
}

Vec3 SoundScene::listener() const {
  std::lock_guard lock(inbox_->mutex);
  return inbox_->listener;
}

bool SoundScene::has_source(std::uint32_t id) const {
  std::lock_guard lock(inbox_->mutex);
  return id < inbox_->slot_taken.size() && inbox_->slot_taken[id];
}

std::uint32_t SoundScene::source_slot_count() const {
  std::lock_guard lock(inbox_->mutex);
  return static_cast<std::uint32_t>(inbox_->slot_taken.size());
}

bool SoundScene::geometry_pending() const {
  std::lock_guard lock(inbox_->mutex);
  return inbox_->transform_queued;
}

Result<bool> SoundScene::check_id(const char* what, std::uint32_t id) const {
  const std::vector<bool>& slots = inbox_->slot_taken;
  if (id >= slots.size())
    return invalid_argument_error(std::string(what) + ": unknown source id " + std::to_string(id) + " (there are " +
                                  std::to_string(slots.size()) + " source slots)");
  if (!slots[id]) return invalid_argument_error(std::string(what) + ": source " + std::to_string(id) + " was removed");
  return true;
}

Result<bool> SoundScene::set_listener(Vec3 position) {
  if (!all_finite(position)) return invalid_argument_error("set_listener: position must be finite");
  std::lock_guard lock(inbox_->mutex);
  inbox_->commands.emplace_back(detail::SetListener{position});
  inbox_->listener = position;
  return true;
}

Result<std::uint32_t> SoundScene::add_source(const SourceDesc& source) {
  return add_slot("add_source", source, false, 0.0);
}

Result<std::uint32_t> SoundScene::add_slot(const char* what, const SourceDesc& source, bool one_shot, double duration) {
  std::lock_guard lock(inbox_->mutex);
  const std::optional<std::uint32_t> id = inbox_->lowest_free(capacity_);
  if (!id)
    return Error{
        ErrorCode::LimitExceeded,
        std::string(what) + ": all " + std::to_string(capacity_) + " source slots are in use; remove one first", 0};
  if (auto valid = check_source_for(what, source, *id); !valid) return valid.error();
  // Queued before the slot is taken: a failed push_back leaves both as they were.
  inbox_->commands.emplace_back(detail::PutSource{*id, source, one_shot, duration});
  inbox_->take(*id);
  return *id;
}

Result<bool> SoundScene::update_source(std::uint32_t id, const SourceDesc& source) {
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("update_source", id); !known) return known;
  if (auto valid = check_source_for("update_source", source, id); !valid) return valid;
  inbox_->commands.emplace_back(detail::UpdateSource{id, source});
  return true;
}

Result<bool> SoundScene::move_source(std::uint32_t id, Vec3 position) {
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("move_source", id); !known) return known;
  if (!all_finite(position)) return invalid_argument_error("move_source: position must be finite");
  inbox_->commands.emplace_back(detail::MoveSource{id, position});
  return true;
}

Result<bool> SoundScene::remove_source(std::uint32_t id) {
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("remove_source", id); !known) return known;
  inbox_->commands.emplace_back(detail::RemoveSource{id});
  inbox_->release(id);
  return true;
}

Result<bool> SoundScene::play(std::uint32_t id, double duration) {
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("play", id); !known) return known;
  if (auto valid = check_duration("play", duration); !valid) return valid;
  inbox_->commands.emplace_back(detail::PlaySource{id, duration});
  return true;
}

Result<std::uint32_t> SoundScene::emit(const SourceDesc& source, double duration) {
  if (auto valid = check_duration("emit", duration); !valid) return valid.error();
  SourceDesc one_shot = source;
  // Silent by pattern: only its play window makes it sound.
  one_shot.duration = 0.0;
  one_shot.interval = 1.0;
  one_shot.phase = 0.0;
  return add_slot("emit", one_shot, true, duration);
}

Result<bool> SoundScene::set_display(const DisplaySettings& settings) {
  detail::expect_stepping_thread(*inbox_, "set_display()");
  auto checked = capture_errors(
      [&] {
        check_display_settings(settings);
        return true;
      },
      ErrorCode::InvalidConfig);
  if (!checked) return checked.error();
  // The changes queued before it come first, as they were made first.
  std::lock_guard lock(inbox_->mutex);
  take_changes();
  world_.config.display = settings;
  for (std::uint32_t id = 0; id < world_.sources.size(); ++id) resolve_source_display(world_, id);
  return true;
}

void SoundScene::apply_config(Config config, std::vector<LayerProperties> layer_properties) {
  detail::expect_stepping_thread(*inbox_, "set_config()");
  std::lock_guard lock(inbox_->mutex);
  take_changes();
  world_.config = std::move(config);
  world_.layer_properties = std::move(layer_properties);
  for (std::uint32_t id = 0; id < world_.sources.size(); ++id) resolve_source_display(world_, id);
}

Result<bool> SoundScene::set_instance_transform(std::uint32_t instance, const Mat4& transform) {
  const char* what = "set_instance_transform";
  if (instance >= instance_triangles_.size())
    return invalid_argument_error(std::string(what) + ": unknown instance " + std::to_string(instance) +
                                  " (the scene has " + std::to_string(instance_triangles_.size()) + " moving parts)");
  // The names and rest pose never change after construction: read without the lock.
  const std::string name = "instance " + std::to_string(instance) + " (\"" + world_.instance_names[instance] + "\")";
  const detail::WorldGeometry& geometry = *std::as_const(world_.geometry);
  if (!all_finite(transform))
    return invalid_argument_error(std::string(what) + ": " + name + ": the transform must be finite");
  if (const std::optional<std::string> problem = placement_problem(geometry, instance_triangles_[instance], transform))
    return invalid_argument_error(std::string(what) + ": " + name + ": refused, " + *problem +
                                  "; the previous transform stays");
  std::lock_guard lock(inbox_->mutex);
  inbox_->commands.emplace_back(detail::PlaceInstance{instance, transform});
  inbox_->transform_queued = true;
  return true;
}

}  // namespace sp
