/* soundpaint C API, Vulkan part: the visualizer, which records the
 * simulation into the host's command buffers and draws the indicators inside
 * the host's own dynamic-rendering pass, on the host's instance, device and
 * queues. The C counterpart of include/soundpaint/visualizer.h.
 *
 * The conventions of soundpaint.h hold here too (opaque handles checked for
 * liveness, sp_result plus sp_last_error_message, no exceptions, every
 * pointer and float checked). In addition:
 * - soundpaint creates no instance or device and never submits to, waits on
 *   or idles a queue: the host submits what it records, and synchronises
 *   the simulation and the draw as it does its own passes.
 * - The host's Vulkan objects are borrowed for the visualizer's lifetime:
 *   destroy the visualizer before the device.
 * - Threads: every sp_visualizer_* call but sp_visualizer_scene and
 *   sp_visualizer_backend belongs to the render thread, the one recording
 *   its command buffers; a call made while another thread is inside one on
 *   the same visualizer returns SP_ERROR_INVALID_ARGUMENT. sp_visualizer_scene,
 *   sp_visualizer_backend and the sp_sound_scene_* changes may come from any
 *   thread (an audio thread): they are queued to the next step.
 */
#ifndef SOUNDPAINT_SOUNDPAINT_VULKAN_H
#define SOUNDPAINT_SOUNDPAINT_VULKAN_H

#include <vulkan/vulkan.h>

#include "soundpaint/soundpaint.h"

#ifdef __cplusplus
extern "C" {
#endif

/* soundpaint inside a host's Vulkan renderer. */
typedef struct sp_visualizer sp_visualizer;

/* The host's Vulkan objects (see sp::HostVulkan). Requirements, checked at
 * creation (SP_ERROR_VULKAN names what is missing): Vulkan 1.3 with
 * synchronization2, dynamicRendering and maintenance4 enabled; queue
 * families with graphics and compute (queue_family) or compute
 * (compute_queue_family). Fill it with sp_host_vulkan_init first: a zeroed
 * struct would name queue family 0 as an async compute family. */
typedef struct sp_host_vulkan {
  VkInstance instance;              /* required */
  VkPhysicalDevice physical_device; /* required */
  VkDevice device;                  /* required */
  /* Family of the queue that runs sp_visualizer_record_draw's command
   * buffers (graphics and compute), and record_simulation's unless
   * compute_queue_family is set. Required. */
  uint32_t queue_family;
  /* Family of an async compute queue that runs record_simulation's command
   * buffers; VK_QUEUE_FAMILY_IGNORED (the default): queue_family. */
  uint32_t compute_queue_family;
  VkPipelineCache pipeline_cache;         /* optional */
  const VkAllocationCallbacks* allocator; /* optional, used for every object soundpaint creates */
  /* Optional: the pNext chain given to vkCreateDevice, so that features are
   * checked as enabled and not only as supported. */
  const void* enabled_features;
} sp_host_vulkan;

/* The attachments of the host's rendering that record_draw draws into.
 * Fixed forever (sp::DrawTarget bit for bit). */
typedef struct sp_draw_target {
  VkFormat color_format;         /* required: a blendable colour attachment format */
  VkFormat depth_format;         /* VK_FORMAT_UNDEFINED (default): no depth attachment, indicators not depth-tested */
  VkFormat stencil_format;       /* the rendering's stencil attachment format, if it has one; default UNDEFINED */
  VkSampleCountFlagBits samples; /* default VK_SAMPLE_COUNT_1_BIT */
  /* VK_COMPARE_OP_LESS_OR_EQUAL (default) for depth cleared to 1;
   * GREATER_OR_EQUAL for reversed-Z. */
  VkCompareOp depth_compare;
} sp_draw_target;

/* Fill *host / *target (NULL: no-op) with the defaults: null handles,
 * VK_QUEUE_FAMILY_IGNORED families, UNDEFINED formats, one sample,
 * LESS_OR_EQUAL. Set the required fields afterwards. Thread-safe. */
SP_API void sp_host_vulkan_init(sp_host_vulkan* host) SP_NOEXCEPT;
SP_API void sp_draw_target_init(sp_draw_target* target) SP_NOEXCEPT;

/* Creates a visualizer of `scene` on the host's device.
 * host, target: non-NULL, only read during the call (the Vulkan handles they
 *   name are borrowed until sp_visualizer_destroy).
 * scene: non-NULL, live, only read during the call.
 * config_json: as sp_simulation_create (NULL: every default; the listener
 *   from config "listener.position", else the scene's camera).
 * backend: SP_BACKEND_GPU (the simulation is compute work recorded into
 *   record_simulation's command buffer), SP_BACKEND_CPU (it runs on worker
 *   threads one step ahead and record_simulation uploads finished steps) or
 *   SP_BACKEND_AUTO (GPU on a hardware GPU, CPU on lavapipe-like devices).
 * *out: non-NULL; receives a new visualizer owned by the caller.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL pointer, null handle, unset queue
 * family, bad format, unknown backend, no listener, scene not live),
 * SP_ERROR_INVALID_CONFIG, SP_ERROR_VULKAN (device below 1.3, missing
 * feature, named), SP_ERROR_LIMIT_EXCEEDED (a buffer beyond a device limit).
 * Thread-safe as far as soundpaint goes; Vulkan's rules for the host's
 * objects still hold (an externally synchronised pipeline cache, say).
 * Builds the BVH and the pipelines; uploads happen in the first
 * sp_visualizer_record_simulation. */
SP_API sp_result sp_visualizer_create(const sp_host_vulkan* host, const sp_draw_target* target, const sp_scene* scene,
                                      const char* config_json, sp_backend backend, sp_visualizer** out) SP_NOEXCEPT;

/* What sp_visualizer_create_in takes beyond the scene and config (the C
 * counterpart of sp::VisualizerSettings). Sized: fill it with
 * sp_visualizer_options_init first. */
typedef struct sp_visualizer_options {
  uint32_t struct_size;         /* sizeof(sp_visualizer_options), set by _init */
  sp_backend backend;           /* default SP_BACKEND_AUTO */
  uint64_t memory_budget_bytes; /* as sp_simulation_options (CPU backend); default 2 GiB, > 0 */
  /* CPU backend: worker threads, as sp_simulation_options.threads (capped
   * by the context's max_threads); 0 (default): the context's cap. */
  uint32_t threads;
  /* Steps one sp_visualizer_record_simulation may record when frames are
   * long; game time beyond them is dropped, not carried (no spiral of
   * death). > 0; default 4. */
  uint32_t max_steps_per_frame;
} sp_visualizer_options;

/* Fills *options (NULL: no-op) with the defaults of sp_visualizer_create. */
SP_API void sp_visualizer_options_init(sp_visualizer_options* options) SP_NOEXCEPT;

/* sp_visualizer_create in `context` (non-NULL, live), with options (NULL:
 * the defaults; a bad struct_size, memory_budget_bytes 0 or
 * max_steps_per_frame 0 are SP_ERROR_INVALID_ARGUMENT): the handle from the
 * context's allocator, the CPU backend's threads capped by its max_threads,
 * a failure's message also to its log. Otherwise as sp_visualizer_create. */
SP_API sp_result sp_visualizer_create_in(sp_context* context, const sp_host_vulkan* host, const sp_draw_target* target,
                                         const sp_scene* scene, const char* config_json,
                                         const sp_visualizer_options* options, sp_visualizer** out) SP_NOEXCEPT;

/* Destroys a visualizer and the Vulkan objects it created; its
 * sp_sound_scene stops being live. The host must first have finished every
 * command buffer recorded with it (a fence or vkDeviceWaitIdle). NULL is a
 * no-op (SP_OK). Errors: SP_ERROR_INVALID_ARGUMENT when not live. */
SP_API sp_result sp_visualizer_destroy(sp_visualizer* visualizer) SP_NOEXCEPT;

/* *out (non-NULL) receives the visualizer's sound scene, borrowed: the same
 * pointer on every call, live until sp_visualizer_destroy. */
SP_API sp_result sp_visualizer_scene(sp_visualizer* visualizer, sp_sound_scene** out) SP_NOEXCEPT;

/* *out (non-NULL) receives the backend chosen at creation: SP_BACKEND_CPU
 * or SP_BACKEND_GPU (never AUTO). */
SP_API sp_result sp_visualizer_backend(const sp_visualizer* visualizer, sp_backend* out) SP_NOEXCEPT;

/* Records the frame's simulation into `cmd` (non-NULL, recording, outside
 * any render pass; submitted by the host to queue_family or
 * compute_queue_family) for dt_seconds (finite, >= 0) of game time: as many
 * fixed steps of config "dt" as fit (at most 4 per call, or
 * sp_visualizer_options.max_steps_per_frame), the rest carried to the next
 * frame. Never waits on the device or on worker threads.
 * out_steps: may be NULL; else receives the steps recorded (GPU backend) or
 * handed over (CPU backend) by this call.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live, NULL cmd, bad dt),
 * SP_ERROR_VULKAN. */
SP_API sp_result sp_visualizer_record_simulation(sp_visualizer* visualizer, VkCommandBuffer cmd, double dt_seconds,
                                                 uint32_t* out_steps) SP_NOEXCEPT;

/* Records the indicator draw into `cmd` (non-NULL), inside the host's
 * dynamic rendering whose attachments match the sp_draw_target, after the
 * host drew its depth, in a command buffer submitted after the one holding
 * the last record_simulation. view, projection: non-NULL, 16 finite floats
 * each, column-major, as the host's own draws use them (Vulkan clip space).
 * area: NULL to use the viewport and scissor set in `cmd`; else both are set
 * to it (non-empty). Binds its own pipeline, descriptor set and push
 * constants: rebind yours afterwards.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live, NULL cmd or matrix,
 * non-finite matrix, empty area, no record_simulation recorded yet),
 * SP_ERROR_VULKAN. */
SP_API sp_result sp_visualizer_record_draw(sp_visualizer* visualizer, VkCommandBuffer cmd, const float view[16],
                                           const float projection[16], const VkRect2D* area) SP_NOEXCEPT;

/* What sp_visualizer_record_draw_ex needs beyond the host's matrices
 * (see sp::DrawOptions). Sized: fill it with sp_draw_options_init first. */
typedef struct sp_draw_options {
  uint32_t struct_size; /* sizeof(sp_draw_options), set by _init */
  /* NULL (the default): the viewport and scissor set in the command buffer
   * are used; else both are set to it (non-empty). Only read during the call. */
  const VkRect2D* area;
  /* The viewport's size in pixels: with it spots are never drawn smaller
   * than their shapes need, and off-screen arrows can be placed. Both 0
   * (the default) or both > 0; 0 x 0 with an area takes the area's extent,
   * 0 x 0 without one does without both. With an area, equal to its extent. */
  uint32_t viewport_width;
  uint32_t viewport_height;
  /* Index of a view registered with sp_visualizer_set_scene_depth: spots are
   * then clipped to the surface they lie on (no colour bleeding under a
   * wall or into the air). That depth image must be in
   * VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL (or DEPTH_STENCIL_READ_ONLY)
   * during the draw, e.g. as the rendering's read-only depth attachment.
   * The barrier that makes its depth writes visible to the draw must name
   * the vertex shader stage too (with the fragment shader and the fragment
   * tests): each spot's centre is looked up there. -1 (the default): no
   * clipping. */
  int32_t scene_depth;
  /* The viewport's top-left corner in the framebuffer, in pixels: where a
   * spot's centre is looked up in the scene depth. 0, 0 (the default) with
   * an area takes the area's offset; with an area, 0, 0 or equal to its
   * offset. Needed only without an area, for a viewport not at (0, 0) (split
   * screen). The viewport's height must be positive (flip y in the
   * projection, not the viewport); sizes and origins at most 65535. */
  uint32_t viewport_x;
  uint32_t viewport_y;
} sp_draw_options;

/* Fills *options (NULL: no-op) with the defaults: no area, 0 x 0 at 0, 0,
 * no scene depth. Thread-safe. */
SP_API void sp_draw_options_init(sp_draw_options* options) SP_NOEXCEPT;

/* sp_visualizer_record_draw with the display's options (*options non-NULL,
 * struct_size and every field checked): clipping to surfaces, and the viewport size that the
 * minimum spot size and off-screen arrows need. Off-screen arrows are drawn
 * when the display settings ask for them and the viewport size is known.
 * Errors: as sp_visualizer_record_draw, plus SP_ERROR_INVALID_ARGUMENT
 * naming the field (NULL options, one viewport side 0, a size unlike the
 * area's, an origin unlike the area's, a size, origin or area past 65535,
 * a negative area offset, scene_depth below -1 or not a registered view). */
SP_API sp_result sp_visualizer_record_draw_ex(sp_visualizer* visualizer, VkCommandBuffer cmd, const float view[16],
                                              const float projection[16], const sp_draw_options* options) SP_NOEXCEPT;

/* How the indicators are drawn from now on (initially the config's
 * "display"): *settings (non-NULL, filled by sp_display_settings_init and
 * then changed) replaces every display setting; its strings are copied.
 * Applies from the next sp_visualizer_record_simulation; sources without
 * their own colour take the new palette's colour from their next indicators
 * on. Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live; a bad field,
 * named: an unknown palette or shape, a flag not 0 or 1, offscreen_arrows
 * not -1, 0 or 1, a non-finite or out-of-range number, a NULL array with a
 * count above 0, a NULL or empty category, a category given two shapes);
 * on error nothing changes. */
SP_API sp_result sp_visualizer_set_display(sp_visualizer* visualizer, const sp_display_settings* settings) SP_NOEXCEPT;

/* Registers the depth image views that sp_draw_options.scene_depth indexes
 * (e.g. one per swapchain image), replacing earlier ones; count 0 (views
 * may then be NULL) registers none. views: count non-null views of a depth
 * aspect, single-sample (resolve a multisampled depth first), each with
 * VK_IMAGE_USAGE_SAMPLED_BIT; only read during the call, the views
 * borrowed until replaced or the visualizer is destroyed. At most 8.
 * Only when no recorded draw is pending (after the host's vkDeviceWaitIdle
 * when it recreates its swapchain, say).
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live, NULL views with a
 * count above 0, a VK_NULL_HANDLE view, named by index),
 * SP_ERROR_LIMIT_EXCEEDED (count above 8), SP_ERROR_VULKAN. */
SP_API sp_result sp_visualizer_set_scene_depth(sp_visualizer* visualizer, const VkImageView* views,
                                               uint32_t count) SP_NOEXCEPT;

/* Blocks until the CPU backend's step in progress (if any) is finished, so
 * that the next record_simulation hands it over. For loading screens,
 * shutdown and tests; never needed in a frame. No-op for the GPU backend.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live). */
SP_API sp_result sp_visualizer_wait(sp_visualizer* visualizer) SP_NOEXCEPT;

/* *out (non-NULL) receives the steps whose indicators record_draw draws
 * (recorded for the GPU backend, finished and handed over for the CPU one). */
SP_API sp_result sp_visualizer_steps_run(const sp_visualizer* visualizer, uint64_t* out) SP_NOEXCEPT;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SOUNDPAINT_SOUNDPAINT_VULKAN_H */
