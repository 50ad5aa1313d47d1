// soundpaint inside a host's Vulkan renderer: the simulation recorded into
// the host's command buffers and the indicators drawn inside the host's own
// dynamic-rendering pass, on the host's instance, device and queues.
// docs/integrating.md has the per-frame call sequence and the
// synchronization contract in full.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include <vulkan/vulkan.h>

#include "soundpaint/simulation.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// The host's Vulkan objects, borrowed for the visualizer's lifetime. In this
// mode soundpaint creates no instance or device and never submits to,
// waits on or idles a queue: the host submits what it records.
//
// Requirements, checked at creation (ErrorCode::Vulkan names what is
// missing): Vulkan 1.3 with synchronization2, dynamicRendering and
// maintenance4 enabled; queue families with compute (and graphics for the
// draw).
struct HostVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  // Family of the queue that runs record_draw's command buffers (graphics
  // and compute), and record_simulation's unless compute_queue_family is set.
  std::uint32_t queue_family = VK_QUEUE_FAMILY_IGNORED;
  // Family of an async compute queue that runs record_simulation's command
  // buffers; VK_QUEUE_FAMILY_IGNORED: queue_family. Buffers shared by both
  // are then VK_SHARING_MODE_CONCURRENT, and the host's semaphores order
  // simulation and draw (docs/integrating.md).
  std::uint32_t compute_queue_family = VK_QUEUE_FAMILY_IGNORED;
  VkPipelineCache pipeline_cache = VK_NULL_HANDLE;   // optional
  const VkAllocationCallbacks* allocator = nullptr;  // optional, used for every object soundpaint creates
  // Optional: the pNext chain given to vkCreateDevice, so that features are
  // checked as enabled and not only as supported.
  const void* enabled_features = nullptr;
};

// The attachments of the host's rendering that record_draw draws into.
struct DrawTarget {
  VkFormat color_format = VK_FORMAT_UNDEFINED;    // required
  VkFormat depth_format = VK_FORMAT_UNDEFINED;    // UNDEFINED: no depth attachment, indicators not depth-tested
  VkFormat stencil_format = VK_FORMAT_UNDEFINED;  // the rendering's stencil attachment, if it has one
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  // LESS_OR_EQUAL for depth cleared to 1; GREATER_OR_EQUAL for reversed-Z.
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
};

struct VisualizerSettings {
  // Gpu: the simulation is compute work in record_simulation's command
  // buffer. Cpu: it runs on worker threads one step ahead and
  // record_simulation uploads the finished step's indicators. Auto: Gpu on
  // a hardware GPU, Cpu on a CPU-type device (lavapipe), where it is faster.
  BackendChoice backend = BackendChoice::Auto;
  CpuSettings cpu;
  // Steps one record_simulation may record when frames are long; time
  // beyond that is dropped rather than accumulated (no spiral of death).
  std::uint32_t max_steps_per_frame = 4;
};

// What record_draw needs beyond the host's matrices.
struct DrawOptions {
  // Sets viewport and scissor to it; null: those already set in the
  // command buffer are used.
  const VkRect2D* area = nullptr;
  // The viewport's size in pixels (area's extent when area is given). With
  // it spots are never drawn smaller than their shapes need, and
  // off-screen arrows can be placed; 0 x 0 does without both.
  std::uint32_t viewport_width = 0;
  std::uint32_t viewport_height = 0;
  // The viewport's top-left corner in the framebuffer, in pixels (area's
  // offset when area is given): where a spot's centre is looked up in the
  // scene depth (below). Only needed with a viewport that does not start at
  // (0, 0) and no area, e.g. split screen with the viewport set by the host.
  // The viewport's height must be positive (flip y in the projection, not
  // the viewport); sizes and origins at most 65535.
  std::uint32_t viewport_x = 0;
  std::uint32_t viewport_y = 0;
  // Index of a view registered with set_scene_depth(): spots are then
  // clipped to the surface they lie on. That depth image must be in
  // VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL (or DEPTH_STENCIL_READ_ONLY)
  // during the draw, e.g. as the rendering's read-only depth attachment, and
  // the barrier that makes its depth writes visible to the draw must name
  // the vertex shader stage too (with the fragment shader and the fragment
  // tests): each spot's centre is looked up there. Negative: no clipping.
  std::int32_t scene_depth = -1;
};

// The simulation's running totals as record_totals writes them: five
// little-endian 64-bit counts, 40 bytes, no padding.
struct SimulationTotals {
  std::uint64_t steps = 0;  // steps whose results reached the ring
  std::uint64_t casts = 0;  // forward casts and matter queries
  std::uint64_t rays_emitted = 0;
  std::uint64_t indicators = 0;   // every indicator created
  std::uint64_t ring_filled = 0;  // ring slots holding an indicator (drawn while live)
  // Casts that reached the per-cast work bound (SimulationStats::casts_cut_short).
  std::uint64_t casts_cut_short = 0;
};

// Where the simulation's time went in the newest frame the device has
// finished (stage_timings). GPU backend: GPU time of each kernel, summed
// over that frame's steps, from timestamps around its dispatches. CPU
// backend: the wall time of the last step on the worker threads.
struct StageTimings {
  bool measured = false;  // false until such a frame (or step) exists, or without timestamp support
  std::uint32_t steps = 0;
  double emit_ms = 0.0;
  double trace_ms = 0.0;     // closest-hit casts and matter queries
  double resolve_ms = 0.0;   // the ray model: indicators, reflect, penetrate, diffract
  double prepare_ms = 0.0;   // the next iteration's indirect arguments
  double admit_ms = 0.0;     // the ring's admission of the step's indicators
  double cpu_step_ms = 0.0;  // CPU backend
  double connect_ms = 0.0;   // the casts from spots to the listener (docs/model.md#cues-for-the-player)
};

// The indicator ring, for an engine that draws the spots itself
// (docs/integrating.md#drawing-the-ring-yourself); record_draw is the
// default painter and needs none of this.
//
// `buffer` holds `capacity` slots of sp::Indicator (simulation.h) in std430
// layout, `stride` = 128 bytes apart from `offset`; a slot's fields sit at
// the offsets of sp::Indicator's members (position 0, energy 12, normal 16,
// size 28, color 32, intensity 44, dir 48, path_length 60, kind 64,
// source_id 68, bounces 72, penetrations 76, diffractions 80, step 84,
// ray_index 88, iteration 92, arrival 96, heard_energy 108, emit_cell 112,
// source_slot 116, toward 120). Its usage includes STORAGE_BUFFER,
// VERTEX_BUFFER (per-instance attributes) and TRANSFER_SRC.
//
// `draw_args` at `draw_args_offset` is a VkDrawIndirectCommand: 4 vertices
// (a quad as a triangle strip) and one instance per filled slot, first
// vertex and first instance 0; usage INDIRECT_BUFFER, STORAGE_BUFFER, TRANSFER_SRC.
// Slots 0 .. instanceCount-1 hold indicators, in no order that matters.
//
// A filled slot is shown while it is live: its age
// (current_step - slot.step) * dt, 0 when slot.step > current_step, is
// below `lifetime` (sp_indicator_live in docs/model.md); its opacity then
// fades as intensity * (1 - age / lifetime). The display's other choices
// (hidden categories, caps per category, minimum opacity) are record_draw's.
//
// The buffers and the numbers are those of the last record_simulation:
// read them after it in the same frame. Its writes are visible to the
// vertex shader and draw-indirect stages of later commands on the queue
// that ran it (graphics queue); a host reading them in other stages, or on
// another queue, adds its own barrier or semaphore (source: compute shader
// and all transfer stages, storage and transfer writes). The next
// record_simulation waits for vertex-shader and indirect reads of earlier
// frames only. The buffers live as long as the visualizer.
static_assert(sizeof(Indicator) == 128 && offsetof(Indicator, energy) == 12 && offsetof(Indicator, color) == 32 &&
                  offsetof(Indicator, kind) == 64 && offsetof(Indicator, step) == 84 &&
                  offsetof(Indicator, arrival) == 96 && offsetof(Indicator, toward) == 120,
              "the ring's layout is a contract (IndicatorRing)");
struct IndicatorRing {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;  // capacity * stride bytes
  std::uint32_t capacity = 0;
  std::uint32_t stride = 0;  // sizeof(Indicator): 128
  VkBuffer draw_args = VK_NULL_HANDLE;
  VkDeviceSize draw_args_offset = 0;
  std::uint32_t current_step = 0;  // the newest step whose indicators the ring holds
  float dt = 0.0f;                 // seconds per step (config.dt)
  float lifetime = 0.0f;           // the display's lifetime in seconds: indicator_lifetime, at least 1/3 s
};

class Visualizer {
 public:
  // Errors: InvalidArgument (null handles, bad formats or settings), Vulkan
  // (device below 1.3, missing feature, named), LimitExceeded (a buffer
  // beyond a device limit, or the config's rays and indicators could need
  // more than settings.cpu.memory_budget_bytes, whichever backend runs). Takes the BVH and buffer setup time; uploads
  // happen in the first record_simulation.
  static Result<std::unique_ptr<Visualizer>> create(const HostVulkan& host, const DrawTarget& target, World world,
                                                    const VisualizerSettings& settings = {});

  // The host must have finished every command buffer recorded by this
  // visualizer (a fence or vkDeviceWaitIdle) before destroying it.
  virtual ~Visualizer() = default;

  virtual Backend backend() const = 0;

  // Listener, sources and moving parts; changes apply from the next step.
  // SoundScene's changes may come from the audio thread while this thread
  // records (SoundScene documents which calls are any thread's).
  virtual SoundScene& scene() = 0;

  // Steps whose indicators record_draw draws (recorded for Gpu, finished
  // and handed over for Cpu).
  virtual std::uint64_t steps_run() const = 0;

  // Records the frame's simulation into `cmd` (recording, outside any
  // render pass; submitted to queue_family or compute_queue_family) for
  // `dt` seconds of game time: as many fixed steps of config.dt as fit
  // (at most max_steps_per_frame), the rest carried to the next frame.
  // Never waits on the device or on worker threads. Returns the steps
  // recorded (Gpu) or handed over (Cpu) by this call; the CPU backend
  // starts at most one step per call. After an error, discard `cmd` and
  // recreate the visualizer (arguments are checked before recording).
  virtual Result<std::uint32_t> record_simulation(VkCommandBuffer cmd, double dt) = 0;

  // Records the indicator draw into `cmd`, inside the host's dynamic
  // rendering whose attachments match the DrawTarget, after the host drew
  // its depth. Uses the viewport and scissor set in `cmd` unless `area` is
  // given (then sets both to it). Binds its own pipeline, descriptor set
  // and push constants: rebind yours afterwards. view and projection as
  // the host's own draws use them (Vulkan clip space).
  virtual Result<bool> record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                                   const VkRect2D* area = nullptr) = 0;
  // The same with the display's options: clipping to surfaces (scene depth)
  // and the viewport size the minimum spot size and off-screen arrows need.
  // Off-screen arrows are drawn when the display settings ask for them.
  virtual Result<bool> record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                                   const DrawOptions& options) = 0;

  // The indicator ring and how to read it (IndicatorRing above), for an
  // engine that draws the spots itself. Errors: InvalidArgument before the
  // first record_simulation (the ring is initialised by it).
  virtual Result<IndicatorRing> indicator_ring() = 0;

  // How the indicators are drawn (docs/model.md#the-display; initially the
  // world's config.display). Checked (InvalidConfig naming the key); applies
  // from the next record_simulation. The palette colours sources without their
  // own colour from their next indicators on.
  virtual Result<bool> set_display(const DisplaySettings& settings) = 0;
  virtual const DisplaySettings& display() const = 0;

  // Registers the depth image views record_draw may clip against (e.g. one
  // per swapchain image), replacing earlier ones; DrawOptions::scene_depth
  // indexes them. Depth aspect, single-sample (resolve a multisampled depth
  // first). At most 8. Only when no recorded draw is pending (after the
  // host's vkDeviceWaitIdle when it recreates its swapchain, say).
  virtual Result<bool> set_scene_depth(std::span<const VkImageView> views) = 0;

  // Records a copy of the running totals as of the simulation recorded so
  // far into `destination` (host-visible, VK_BUFFER_USAGE_TRANSFER_DST_BIT)
  // at `offset`: sizeof(SimulationTotals) bytes, readable by the host once
  // this command buffer's fence has signalled (the copy ends with a
  // transfer-to-host barrier). Record it after record_simulation, outside
  // any render pass. It never reads back itself, so frames in flight stay
  // the host's choice: give each its own destination. Errors:
  // InvalidArgument (null handles).
  virtual Result<bool> record_totals(VkCommandBuffer cmd, VkBuffer destination, VkDeviceSize offset) = 0;

  // The per-stage timings of the newest frame whose timestamps the device
  // has written (the GPU backend keeps the last 8 frames' worth). Never
  // waits; `measured` is false until there is one.
  virtual StageTimings stage_timings() const = 0;

  // Blocks until the CPU backend's step in progress (if any) is finished and
  // handed over by the next record_simulation. For loading screens,
  // shutdown and tests; never needed in a frame. No-op for Gpu.
  virtual Result<bool> wait_for_simulation() = 0;
};

}  // namespace sp

SP_CPP_API_END
