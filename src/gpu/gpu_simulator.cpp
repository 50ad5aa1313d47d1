// The GPU backend on a device it submits to itself. Per step it records the
// StepEngine's commands (a few dozen; the step's inputs travel inside the
// command buffer), submits and waits on a fence; indicators stay on the GPU
// unless a caller asks for them.
#include "gpu/gpu_simulator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <tuple>

#include "gpu/gpu_resize.h"
#include "gpu/gpu_resources.h"
#include "gpu/step_engine.h"
#include "sim/config_change.h"
#include "sim/indicator_ring.h"
#include "sim/memory_estimate.h"
#include "sim/sound_scene_backend.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "vk/handle.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::gpu {
namespace {

// A stuck step on a broken device fails instead of hanging the caller.
constexpr std::uint64_t kStepTimeoutNs = 120ull * 1'000'000'000ull;

std::uint64_t join64(std::uint32_t lo, std::uint32_t hi) { return (std::uint64_t{hi} << 32) | lo; }

void sort_canonically(std::vector<Indicator>& indicators) {
  std::sort(indicators.begin(), indicators.end(), [](const Indicator& a, const Indicator& b) {
    // kind last: a sheet's hit (0) and exit (1) share their ray and iteration.
    return std::tie(a.step, a.iteration, a.ray_index, a.kind) < std::tie(b.step, b.iteration, b.ray_index, b.kind);
  });
}

class GpuSimulator final : public Simulator {
 public:
  GpuSimulator(World world, vk::Context& context, std::unique_ptr<vk::Context> owned, std::uint64_t memory_budget_bytes)
      : owned_context_(std::move(owned)),
        context_(context),
        memory_budget_bytes_(memory_budget_bytes),
        scene_(std::move(world)),
        engine_(context_, scene_),
        resources_(engine_.resources()) {
    command_pool_ = vk::create_command_pool(context_, context_.queue_family(),
                                            VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, "soundpaint step pool");
    command_buffer_ = vk::allocate_command_buffer(context_, command_pool_.get(), "soundpaint step");
    fence_ = vk::create_fence(context_, "soundpaint step fence");
    if (timestamps_supported()) timestamps_ = vk::create_timestamp_pool(context_, 2, "soundpaint step timestamps");
  }

  ~GpuSimulator() override { vkDeviceWaitIdle(context_.device()); }

  Backend backend() const override { return Backend::Gpu; }
  std::string device_description() const override { return context_.description(); }
  SoundScene& scene() override { return scene_; }
  const SoundScene& scene() const override { return scene_; }
  std::uint64_t steps_run() const override { return steps_run_; }
  std::uint64_t last_step_casts() const override { return last_control_.step_casts; }

  Result<bool> step() override {
    return capture_errors(
        [&] {
          last_step_kept_.reset();
          record_one_step();
          context_.submit(command_buffer_, fence_.get());
          VkFence fence = fence_.get();
          VkResult waited = vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, kStepTimeoutNs);
          if (waited == VK_TIMEOUT) throw Exception(ErrorCode::Vulkan, "a GPU step did not finish within 120 s");
          SP_VK_CHECK(waited);
          SP_VK_CHECK(vkResetFences(context_.device(), 1, &fence));
          std::memcpy(&last_control_, resources_.control_readback.mapped(), sizeof last_control_);
          read_timestamps();
          read_profile();
          steps_run_ += 1;
          return true;
        },
        ErrorCode::Vulkan);
  }

  // Everything that can fail is made aside first (the checked config, the
  // new buffers, a copy of the last step's indicators when their buffer
  // goes); one submit then carries the ring's spots and the layers'
  // acoustics across, and moves alone commit the rest.
  Result<bool> set_config(const Config& config) override {
    return capture_errors(
        [&] {
          ConfigChange change = prepare_config_change(scene_.world(), config, steps_run_);
          check_memory_budget(change.config, Backend::Gpu, memory_budget_bytes_);
          const World& world = scene_.world();
          if (change.config.diffraction.enabled) world.geometry->ensure_exposed_edges();
          GpuResize resize(context_, resources_, change.config, world.geometry->bvh);
          std::optional<std::vector<Indicator>> last_step;
          if (resize.replaces_capture()) last_step = last_step_indicators().value();
          vk::UniqueQueryPool profile_pool;
          const std::uint32_t iterations = 2 * change.config.max_bounces + 1;
          if (profile_pool_ && iterations != engine_.iterations())
            profile_pool =
                vk::create_timestamp_pool(context_, stage_queries_per_step(iterations), "soundpaint step profile");
          const std::vector<shader::LayerAcoustics> layer_table = make_layer_table(change.layer_properties);
          context_.submit_and_wait([&](VkCommandBuffer cmd) {
            engine_.record_pending_uploads(cmd);
            resize.record(cmd, resources_, last_control_, layer_table);
          });

          resize.commit(context_, resources_, last_control_);
          detail::SoundSceneBackend::apply_config(scene_, std::move(change.config), std::move(change.layer_properties));
          if (last_step) last_step_kept_ = std::move(last_step);
          if (profile_pool) profile_pool_ = std::move(profile_pool);
          return true;
        },
        ErrorCode::Vulkan);
  }

  Result<std::vector<Indicator>> last_step_indicators() override {
    if (last_step_kept_) return *last_step_kept_;
    return capture_errors(
        [&] {
          std::vector<Indicator> indicators(std::min(last_control_.step_indicators, resources_.capture_capacity));
          if (!indicators.empty())
            vk::download(context_, resources_.capture, indicators.data(), indicators.size() * sizeof(Indicator));
          sort_canonically(indicators);
          return indicators;
        },
        ErrorCode::Vulkan);
  }

  Result<std::vector<Indicator>> live_indicators() override {
    return capture_errors(
        [&] {
          std::vector<Indicator> stored(last_control_.ring_filled);
          if (!stored.empty())
            vk::download(context_, resources_.ring, stored.data(), stored.size() * sizeof(Indicator));
          std::vector<Indicator> live;
          for (const Indicator& ind : stored)
            if (is_live(ind.step, steps_run_, scene_.world().config)) live.push_back(ind);
          sort_canonically(live);
          return live;
        },
        ErrorCode::Vulkan);
  }

  Result<SimulationStats> stats() override {
    return capture_errors(
        [&] {
          const std::size_t layers = scene_.world().layer_names.size();
          std::vector<std::uint32_t> counters(layers * SP_COUNTERS_PER_LAYER * 3);
          if (!counters.empty())
            vk::download(context_, resources_.counters, counters.data(), counters.size() * sizeof(std::uint32_t));
          const shader::Control& c = last_control_;
          SimulationStats stats;
          stats.steps = c.steps;
          stats.casts = join64(c.total_casts_lo, c.total_casts_hi);
          stats.max_casts_per_step = c.max_step_casts;
          stats.casts_cut_short = join64(c.total_cut_short_lo, c.total_cut_short_hi);
          stats.connections = join64(c.total_connections_lo, c.total_connections_hi);
          stats.rays_emitted = join64(c.total_rays_lo, c.total_rays_hi);
          stats.indicators = join64(c.total_indicators_lo, c.total_indicators_hi);
          const std::size_t totals = layers * SP_COUNTERS_PER_LAYER;
          for (std::size_t l = 0; l < layers; ++l) {
            auto total = [&](std::size_t which) {
              std::size_t k = totals + 2 * (l * SP_COUNTERS_PER_LAYER + which);
              return join64(counters[k], counters[k + 1]);
            };
            stats.layers.push_back({total(SP_COUNTER_HITS), total(SP_COUNTER_REFLECTIONS),
                                    total(SP_COUNTER_PENETRATIONS), total(SP_COUNTER_NO_WAY_OUT),
                                    total(SP_COUNTER_BACK_FACE_HITS), total(SP_COUNTER_DIFFRACTIONS)});
          }
          return stats;
        },
        ErrorCode::Vulkan);
  }

  IndicatorView view() { return engine_.view(); }

  std::optional<double> last_gpu_ms() const override {
    if (!timestamps_) return std::nullopt;
    return last_gpu_ms_;
  }

 private:
  bool timestamps_supported() const {
    if (!context_.properties().limits.timestampComputeAndGraphics) return false;
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context_.physical_device(), &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(context_.physical_device(), &count, families.data());
    return context_.queue_family() < count && families[context_.queue_family()].timestampValidBits > 0;
  }

  // Per-kernel timestamps for later steps (StepProfile).
 public:
  bool enable_profile() {
    if (!timestamps_) return false;
    const std::uint32_t queries = stage_queries_per_step(engine_.iterations());
    profile_pool_ = vk::create_timestamp_pool(context_, queries, "soundpaint step profile");
    return true;
  }
  std::optional<StepProfile> profile() const {
    if (!profile_pool_) return std::nullopt;
    return profile_;
  }

 private:
  void record_one_step() {
    SP_VK_CHECK(vkResetCommandBuffer(command_buffer_, 0));
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    SP_VK_CHECK(vkBeginCommandBuffer(command_buffer_, &begin));
    RecordOptions options;
    options.readback_control = true;
    options.timestamps = timestamps_.get();
    profile_counts_ = RecordCounts{};
    options.counts = &profile_counts_;
    if (profile_pool_) {
      const std::uint32_t queries = stage_queries_per_step(engine_.iterations());
      vkCmdResetQueryPool(command_buffer_, profile_pool_.get(), 0, queries);
      profile_stages_ = StageQueries{profile_pool_.get(), 0, queries, {}};
      options.stages = &profile_stages_;
    }
    engine_.record(command_buffer_, scene_, steps_run_, 1, options);
    SP_VK_CHECK(vkEndCommandBuffer(command_buffer_));
  }

  void read_profile() {
    profile_.counts = profile_counts_;
    if (!profile_pool_ || profile_stages_.kinds.empty()) return;
    const auto count = static_cast<std::uint32_t>(profile_stages_.kinds.size());
    std::vector<std::uint64_t> ticks(count);
    SP_VK_CHECK(vkGetQueryPoolResults(context_.device(), profile_pool_.get(), 0, count,
                                      ticks.size() * sizeof(std::uint64_t), ticks.data(), sizeof(std::uint64_t),
                                      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    profile_.kernel_ms.fill(0.0);
    const double tick_ms = double(context_.properties().limits.timestampPeriod) * 1e-6;
    // Each timestamp ends the work of the kernel it is labelled with.
    for (std::uint32_t k = 1; k < count; ++k)
      profile_.kernel_ms[static_cast<std::size_t>(profile_stages_.kinds[k])] +=
          double(ticks[k] - ticks[k - 1]) * tick_ms;
    profile_.measured = true;
  }

  void read_timestamps() {
    if (!timestamps_) return;
    std::uint64_t ticks[2] = {};
    SP_VK_CHECK(vkGetQueryPoolResults(context_.device(), timestamps_.get(), 0, 2, sizeof ticks, ticks,
                                      sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    last_gpu_ms_ = static_cast<double>(ticks[1] - ticks[0]) * context_.properties().limits.timestampPeriod * 1e-6;
  }

  std::unique_ptr<vk::Context> owned_context_;  // set when the simulator made its own
  vk::Context& context_;
  std::uint64_t memory_budget_bytes_;  // checked again by set_config
  SoundScene scene_;
  StepEngine engine_;
  GpuResources& resources_;
  vk::UniqueCommandPool command_pool_;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;  // freed with the pool
  vk::UniqueFence fence_;
  vk::UniqueQueryPool timestamps_;
  vk::UniqueQueryPool profile_pool_;  // per-kernel timestamps, once enable_profile() ran
  StageQueries profile_stages_;
  RecordCounts profile_counts_;
  StepProfile profile_;
  shader::Control last_control_{};
  // The last step's indicators, kept on the host when set_config replaced
  // the buffer that held them; until the next step.
  std::optional<std::vector<Indicator>> last_step_kept_;
  double last_gpu_ms_ = 0.0;
  std::uint64_t steps_run_ = 0;
};

}  // namespace

std::optional<IndicatorView> indicator_view(Simulator& simulator) {
  if (auto* gpu = dynamic_cast<GpuSimulator*>(&simulator)) return gpu->view();
  return std::nullopt;
}

bool enable_step_profile(Simulator& simulator) {
  auto* gpu = dynamic_cast<GpuSimulator*>(&simulator);
  return gpu != nullptr && gpu->enable_profile();
}

std::optional<StepProfile> last_step_profile(const Simulator& simulator) {
  const auto* gpu = dynamic_cast<const GpuSimulator*>(&simulator);
  if (gpu == nullptr) return std::nullopt;
  return gpu->profile();
}

Result<std::unique_ptr<Simulator>> create_simulator(World world, vk::Context& context,
                                                    std::uint64_t memory_budget_bytes) {
  return capture_errors(
      [&]() -> std::unique_ptr<Simulator> {
        return std::make_unique<GpuSimulator>(std::move(world), context, nullptr, memory_budget_bytes);
      },
      ErrorCode::Vulkan);
}

}  // namespace sp::gpu

namespace sp {

Result<std::unique_ptr<Simulator>> create_gpu_simulator(World world, const GpuSettings& settings) {
  return capture_errors(
      [&]() -> std::unique_ptr<Simulator> {
        vk::ContextSettings context_settings;
        context_settings.validation = settings.validation;
        context_settings.device_name = settings.device_name;
        context_settings.kernels.workgroup_size = settings.workgroup_size;
        std::unique_ptr<vk::Context> context = vk::Context::create(context_settings).value();
        if (!settings.allow_cpu_device && context->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
          throw Exception(ErrorCode::Vulkan, "the only Vulkan device is a CPU device (" +
                                                 std::string(context->properties().deviceName) + ")");
        check_memory_budget(world.config, Backend::Gpu, settings.memory_budget_bytes);  // before any buffer exists
        vk::Context& ref = *context;
        return std::make_unique<gpu::GpuSimulator>(std::move(world), ref, std::move(context),
                                                   settings.memory_budget_bytes);
      },
      ErrorCode::Vulkan);
}

}  // namespace sp
