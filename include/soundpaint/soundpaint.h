/* soundpaint C API: a C99 interface over the C++ library for game engines
 * (C# / Unity P/Invoke, Godot GDExtension, Rust FFI).
 *
 * Units: metres and seconds; energies are in units of a source's loudness E0.
 *
 * Conventions that hold for every function below:
 * - Handles (sp_scene, sp_simulation, sp_visualizer) are opaque. Each
 *   *_create / *_load has one *_destroy; the caller owns what it creates and
 *   must destroy it exactly once. Destroying NULL is a no-op returning SP_OK.
 * - Misuse of handles is detected where it can be: the library keeps a
 *   process-wide registry of live handles, and every function taking a
 *   handle (destroy included) checks it, so a handle that was destroyed or
 *   never created gives SP_ERROR_INVALID_ARGUMENT ("... handle is not live")
 *   instead of undefined behaviour. Not detectable: a handle destroyed and
 *   whose address the allocator then reused for a new handle of the same
 *   type (the call then acts on the new one), and a handle destroyed by one
 *   thread while another thread is inside a call on it.
 * - An sp_sound_scene is borrowed, never created or destroyed by the caller:
 *   it is live exactly while the simulation or visualizer it came from is.
 * - Functions returning sp_result never throw or abort on bad input: they
 *   return SP_OK on success, or an error code and set the calling thread's
 *   last error message (see sp_last_error_message). On error, out-parameters
 *   are left unchanged and nothing is half-applied, unless stated otherwise.
 * - Pointers documented as "non-NULL" are checked: NULL gives
 *   SP_ERROR_INVALID_ARGUMENT. Every float and double argument, and every
 *   field of a struct argument that the call uses, is checked finite.
 * - Thread-safety: different handles may be used from different threads at
 *   the same time. An sp_scene is read-only after creation and may be shared
 *   by threads creating simulations from it. A game drives one simulation
 *   (or visualizer) from two threads, and may:
 *   - Render thread, one call at a time: sp_simulation_step,
 *     sp_simulation_set_config, sp_simulation_live_indicators,
 *     sp_simulation_stats and sp_simulation_destroy (and every sp_visualizer_* call but
 *     sp_visualizer_scene and sp_visualizer_backend, soundpaint_vulkan.h).
 *     A call made while another thread is inside one of these on the same
 *     handle is refused with SP_ERROR_INVALID_ARGUMENT ("another thread is
 *     inside a call on this handle"), in every build; calls that do not
 *     overlap may come from different threads.
 *   - Any thread, the audio thread included, at the same time as the above
 *     and as each other: every sp_sound_scene_* function,
 *     sp_simulation_set_listener, sp_simulation_play,
 *     sp_simulation_source_count, sp_simulation_scene and
 *     sp_visualizer_scene. The changes are checked at the call (errors as
 *     documented) and queued; the next step applies them, in call order,
 *     before it plans. They wait at most for another such call's turn at a
 *     short lock, never for a step; they may allocate. Ids are decided at
 *     the call (sp_sound_scene_emit's id is usable at once).
 *   Destroying a handle while another thread is inside any call on it (or
 *   on its sp_sound_scene) is undefined behaviour: stop the audio thread's
 *   calls first. Last-error messages are per thread, so each thread reads
 *   its own.
 * - Sound sources come from the scene (glTF nodes) and the JSON config
 *   ("sources") given at creation, and can be added, changed, moved, played,
 *   emitted once and removed at run time through the owner's sp_sound_scene
 *   (sp_simulation_scene, sp_visualizer_scene); every change applies from
 *   the next step on. Moving parts (sp_scene_create_with_instances; a
 *   loaded glTF file has none) are placed the same way
 *   (sp_sound_scene_set_instance_transform).
 * - The visualizer (simulation recorded into, and indicators drawn by, the
 *   host's own Vulkan command buffers) is in soundpaint_vulkan.h, so that
 *   engines without Vulkan never need Vulkan headers.
 * - Versions: SOUNDPAINT_VERSION (export.h) is the version of these headers,
 *   sp_get_version() the library's; sp_context_create refuses a caller
 *   compiled against another major version.
 * - Structs come in two kinds, so that the ABI holds across versions:
 *   - Sized: uint32_t struct_size comes first, and the struct's _init
 *     function sets it to sizeof as the caller compiled it. The library
 *     checks it (0, or a size this version does not know, is
 *     SP_ERROR_INVALID_ARGUMENT naming the struct); a later version may
 *     append fields and still read a struct of an earlier size. Sized:
 *     sp_context_settings, sp_scene_load_options, sp_simulation_options,
 *     sp_draw_options and sp_visualizer_options (soundpaint_vulkan.h).
 *   - Fixed forever: the layout never changes; a later version that needs
 *     more adds a new struct and function beside it. Fixed: sp_indicator
 *     (108 bytes, its offsets pinned by static_asserts in the library and
 *     the consumer test), sp_stats, sp_layer_stats, sp_allocator,
 *     sp_source_desc, sp_display_settings, sp_voice_state
 *     (soundpaint_signal.h), sp_host_vulkan and sp_draw_target
 *     (soundpaint_vulkan.h). Those with an _init still want it called: it
 *     gives the defaults.
 * - Contexts (sp_context): the log callback, the allocator and the thread
 *   cap a host sets once. The *_in functions create objects in a context;
 *   the functions without _in use the default context (no log, malloc and
 *   free, one thread per core).
 * - Visibility: a shared libsoundpaint exports the SP_API functions below
 *   and the public C++ API, nothing else (export.h).
 */
#ifndef SOUNDPAINT_SOUNDPAINT_H
#define SOUNDPAINT_SOUNDPAINT_H

#include <stddef.h>
#include <stdint.h>

#include "soundpaint/export.h"

/* In C++ every function is declared noexcept: none throws. */
#if defined(__cplusplus)
#define SP_NOEXCEPT noexcept
#else
#define SP_NOEXCEPT
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sp_result {
  SP_OK = 0,
  SP_ERROR_INVALID_ARGUMENT, /* an argument is NULL, non-finite, out of range, or a handle not live */
  SP_ERROR_INVALID_SCENE,    /* a scene file or scene arrays are missing, malformed or unsupported */
  SP_ERROR_INVALID_CONFIG,   /* the JSON configuration is malformed or a value is out of range */
  SP_ERROR_IO,               /* reading a file failed */
  SP_ERROR_VULKAN,           /* a Vulkan call failed or no suitable device exists */
  SP_ERROR_LIMIT_EXCEEDED,   /* a request exceeds a device or library limit */
  SP_ERROR_OUT_OF_MEMORY,    /* an allocation failed */
  SP_ERROR_INTERNAL          /* an unexpected failure inside the library (a bug) */
} sp_result;

typedef enum sp_backend {
  SP_BACKEND_CPU = 0, /* multithreaded CPU backend; always available */
  SP_BACKEND_GPU = 1, /* Vulkan compute backend; any Vulkan device, fails with SP_ERROR_VULKAN if none */
  SP_BACKEND_AUTO = 2 /* the GPU backend on a real GPU, else the CPU backend */
} sp_backend;

/* Indicator kinds (sp_indicator.kind). */
#define SP_INDICATOR_KIND_HIT 0u  /* a ray hit a surface */
#define SP_INDICATOR_KIND_EXIT 1u /* a ray left a surface after penetrating it */

/* Per-triangle instance id of a triangle that never moves
 * (sp_scene_create_with_instances). */
#define SP_STATIC_INSTANCE 0xFFFFFFFFu

/* A triangle soup with a collision layer per triangle, plus sound sources,
 * a camera (when loaded from glTF) and moving parts. Immutable once created. */
typedef struct sp_scene sp_scene;

/* A running simulation of one scene under one configuration. */
typedef struct sp_simulation sp_simulation;

/* What the host changes while a simulation or visualizer runs: listener,
 * sources, moving parts. Borrowed from its owner (sp_simulation_scene,
 * sp_visualizer_scene): live while the owner is, never destroyed by the
 * caller, used by the owner's thread. */
typedef struct sp_sound_scene sp_sound_scene;

/* One visible sound indicator: where a ray hit (or left) a surface.
 * Fixed forever: 108 bytes, every field at the offset it has now (4-byte
 * fields, no padding), checked by static_asserts in the library. A later
 * version that has more to say per indicator adds another struct. */
typedef struct sp_indicator {
  float position[3];     /* metres, world space */
  float normal[3];       /* unit; faces the side the ray came from (hit) or leaves to (exit) */
  float energy;          /* remaining ray energy, units of E0 */
  float size;            /* metres: indicator_size * energy / loudness */
  float color[3];        /* the source's linear RGB, each in [0, 1] */
  float intensity;       /* 1 - listener distance / max_distance of the source at emission, [0, 1] */
  uint32_t kind;         /* SP_INDICATOR_KIND_* */
  uint32_t source_id;    /* id of the source (scene sources first, then config sources, then added ones) */
  uint32_t bounces;      /* reflections before this indicator */
  uint32_t penetrations; /* completed penetrations before this indicator */
  float path_length;     /* metres travelled by the ray from its source */
  uint32_t step;         /* the step that created it */
  float direction[3];    /* unit; the ray's direction of travel: incoming (hit), outgoing (exit) */
  uint32_t diffractions; /* times the ray turned at an edge before this indicator */
  /* What reaches the player (config "cues"; docs/model.md "Cues for the player"): */
  float heard_energy; /* energy arriving at the listener from this spot, units of E0; 0: not heard */
  float arrival[3];   /* unit; from the listener to the spot, the way its sound arrives */
  float toward;       /* [0, 1]: how nearly `arrival` points at the source; 0 when not heard */
} sp_indicator;

/* Totals over every step run so far. Fixed forever (32 bytes). */
typedef struct sp_stats {
  uint64_t steps;        /* steps run */
  uint64_t casts;        /* ray casts (closest-hit casts + matter queries) */
  uint64_t rays_emitted; /* rays emitted by sources */
  uint64_t indicators;   /* indicators created (including ones no longer live) */
} sp_stats;

/* A sound source added at run time (sp_sound_scene_add_source). It plays at
 * time t when t >= phase and fmod(t - phase, interval) < duration.
 * Fill it with sp_source_desc_init first (the defaults). Fixed forever. */
typedef struct sp_source_desc {
  float position[3];    /* metres, world space, finite; default 0, 0, 0 */
  float color[3];       /* linear RGB, each in [0, 1]; or all three negative (the default, -1):
                           the colour of its category in the display palette */
  const char* category; /* UTF-8 free text, copied; NULL: "sound" (the default) */
  float max_distance;   /* metres a ray travels (and listener range), >= 0; default 30 */
  float loudness;       /* E0, initial ray energy, >= 0; default 1 */
  double duration;      /* seconds of sound per interval, >= 0; default 1 */
  double interval;      /* seconds between sound starts, > 0; default 1 */
  double phase;         /* seconds before the first start, >= 0; default 0 */
} sp_source_desc;

/* The message of the last error returned on the calling thread: one line
 * naming the problem (for files, the path; for config, the key). Never NULL;
 * "" when no call on this thread has failed yet. The text is owned by the
 * library and stays valid until the next failing sp_* call on the same thread.
 * A successful call does not clear it. Thread-safe (thread-local). */
SP_API const char* sp_last_error_message(void) SP_NOEXCEPT;

/* --- Version and context */

/* The library's version, packed as SOUNDPAINT_VERSION (export.h): compare
 * with the SOUNDPAINT_VERSION the caller compiled against. Thread-safe. */
SP_API uint32_t sp_get_version(void) SP_NOEXCEPT;

/* What the library decides once per host: see sp_context_settings. */
typedef struct sp_context sp_context;

typedef enum sp_log_level {
  SP_LOG_ERROR = 0,   /* a call failed: the message is sp_last_error_message's */
  SP_LOG_WARNING = 1, /* something the host should fix (the Vulkan validation layer's messages) */
  SP_LOG_INFO = 2
} sp_log_level;

/* Receives the library's messages: one line naming the problem (a config
 * value out of range names its key, a scene problem its file or triangle).
 * Called on the thread making the call that failed, possibly several
 * threads at once; message is only valid during the call. Must not call
 * back into soundpaint. */
typedef void (*sp_log_callback)(void* user_data, sp_log_level level, const char* message);

/* Memory for the handles the C layer allocates (sp_context, sp_scene,
 * sp_simulation, sp_visualizer and the small structs behind them): size
 * bytes aligned to `alignment` (a power of two, at most 16). NULL fails the
 * call with SP_ERROR_OUT_OF_MEMORY. Not routed through it: what the C++
 * core allocates inside them (std containers, the BVH, the ring of
 * indicators, thread stacks, Vulkan's own memory, for which
 * sp_host_vulkan.allocator is the hook), which uses the global operator
 * new. Both callbacks may run on any thread. */
typedef void* (*sp_allocate_callback)(void* user_data, size_t size, size_t alignment);
typedef void (*sp_free_callback)(void* user_data, void* memory);
/* Fixed forever. Both callbacks, or both NULL (malloc and free). */
typedef struct sp_allocator {
  sp_allocate_callback allocate;
  sp_free_callback free;
  void* user_data;
} sp_allocator;

/* sp_context_settings.flags: */
/* Simulations created in the context with the GPU backend enable the Vulkan
 * validation layer, whose messages go to the log (SP_LOG_WARNING) after the
 * call that made them (creation, step, destroy). The layer reports for the
 * whole process: messages of other devices the process validates at the
 * same time may come along. */
#define SP_CONTEXT_VULKAN_VALIDATION 1u

/* Sized (struct_size first). Fill it with sp_context_settings_init. */
typedef struct sp_context_settings {
  uint32_t struct_size;   /* sizeof(sp_context_settings), set by _init */
  uint32_t version;       /* SOUNDPAINT_VERSION the caller compiled against, set by _init */
  sp_log_callback log;    /* NULL (default): no log; errors still reach sp_last_error_message */
  void* log_user_data;    /* passed to log */
  sp_allocator allocator; /* default both NULL: malloc and free */
  /* At most this many threads for each simulation of the context (the
   * CPU backend's workers, the calling thread included, and the BVH build);
   * 0 (default): one per core. */
  uint32_t max_threads;
  uint32_t flags; /* SP_CONTEXT_* bits; default 0 */
} sp_context_settings;

/* Fills *settings with the defaults and this header's struct_size and
 * version. NULL is a no-op. Thread-safe. */
SP_API void sp_context_settings_init(sp_context_settings* settings) SP_NOEXCEPT;

/* Creates a context. settings: non-NULL, read during the call only.
 * *out: non-NULL; receives a new context owned by the caller.
 * Errors (SP_ERROR_INVALID_ARGUMENT, naming the field): struct_size 0 or
 * unknown, a version of another major (or a newer one than the library),
 * one allocator callback without the other, unknown flag bits. The message
 * also goes to settings->log when struct_size is known. Thread-safe. */
SP_API sp_result sp_context_create(const sp_context_settings* settings, sp_context** out) SP_NOEXCEPT;

/* Gives up the caller's context. Objects created in it keep it (their log,
 * allocator and thread cap) until they are destroyed, so the order does
 * not matter; the last one frees it through its own allocator. NULL is a
 * no-op. Errors: SP_ERROR_INVALID_ARGUMENT when `context` is not live. */
SP_API sp_result sp_context_destroy(sp_context* context) SP_NOEXCEPT;

/* Fills *desc with the library's defaults (see sp_source_desc): a source at
 * the origin, in its category's palette colour, that plays always. NULL is
 * a no-op. Thread-safe. */
SP_API void sp_source_desc_init(sp_source_desc* desc) SP_NOEXCEPT;

/* Loads a .gltf or .glb scene. path: non-NULL, UTF-8, NUL-terminated.
 * *out: non-NULL; receives a new scene owned by the caller (sp_scene_destroy).
 * Errors: SP_ERROR_INVALID_SCENE or SP_ERROR_IO (message names the path).
 * Thread-safe. */
SP_API sp_result sp_scene_load(const char* path, sp_scene** out) SP_NOEXCEPT;

/* How sp_scene_load_with_options treats a scene that may come from a
 * stranger (a downloaded level, a mod); README "Security". Sized: fill it
 * with sp_scene_load_options_init first. */
typedef struct sp_scene_load_options {
  uint32_t struct_size;   /* sizeof(sp_scene_load_options), set by _init */
  uint32_t flags;         /* SP_SCENE_LOAD_* bits; default 0 */
  uint64_t max_triangles; /* a scene with more (every mesh instance counted) is refused before
                             its triangles are built; default 2,000,000, at most 2^32 / 3 */
} sp_scene_load_options;

/* Without this flag, buffer URIs name regular files inside the scene's
 * folder tree only, through relative symbolic links at most (a link with an
 * absolute target is refused). The flag lifts the folder rule: buffer URIs
 * may name regular files anywhere
 * (absolute paths, ".." and symbolic links leading out of the scene's
 * folder), for trusted asset pipelines only. Devices, /proc and /sys stay
 * refused, and images are never read either way. */
#define SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS 1u

/* Fills *options with the defaults sp_scene_load uses. NULL is a no-op. */
SP_API void sp_scene_load_options_init(sp_scene_load_options* options) SP_NOEXCEPT;

/* sp_scene_load with options (non-NULL; a bad struct_size, unknown flag
 * bits and max_triangles 0 are SP_ERROR_INVALID_ARGUMENT). By default a scene reads only regular
 * files inside its own folder tree; a refused buffer URI, JSON nested deeper
 * than 128 levels or too many triangles give SP_ERROR_INVALID_SCENE naming
 * the problem. Thread-safe. */
SP_API sp_result sp_scene_load_with_options(const char* path, const sp_scene_load_options* options,
                                            sp_scene** out) SP_NOEXCEPT;

/* sp_scene_load_with_options in `context` (non-NULL, live): the scene's
 * handle comes from its allocator, and a failure's message also goes to its
 * log. options: NULL for the defaults. */
SP_API sp_result sp_scene_load_in(sp_context* context, const char* path, const sp_scene_load_options* options,
                                  sp_scene** out) SP_NOEXCEPT;

/* Creates a scene from the host's arrays; the arrays are copied and may be
 * freed after the call. The scene has no sources and no camera: give them in
 * the simulation's JSON config ("sources", "listener") or add sources at run
 * time. Nothing in it moves (see sp_scene_create_with_instances).
 * vertices: non-NULL, 9 floats per triangle (3 corners x xyz), metres, finite.
 * triangle_count: > 0.
 * triangle_layers: non-NULL, one layer id per triangle, each < layer_count.
 * layer_names: non-NULL, layer_count non-NULL UTF-8 names; a name selects the
 *   layer's acoustics (presets such as "concrete", "wood", or the config's
 *   "layers" entries).
 * layer_count: > 0.
 * *out: non-NULL; receives a new scene owned by the caller.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL pointer, zero count),
 * SP_ERROR_INVALID_SCENE (non-finite vertex, layer id out of range).
 * Thread-safe. */
SP_API sp_result sp_scene_create(const float* vertices, uint32_t triangle_count, const uint32_t* triangle_layers,
                                 const char* const* layer_names, uint32_t layer_count, sp_scene** out) SP_NOEXCEPT;

/* sp_scene_create with moving parts (doors, lifts): triangles grouped into
 * instances that a running simulation places with
 * sp_sound_scene_set_instance_transform, relative to the positions given
 * here (the rest pose). Arguments as sp_scene_create, plus:
 * triangle_instances: one instance id per triangle, each < instance_count or
 *   SP_STATIC_INSTANCE (never moves); NULL: every triangle is static.
 * instance_names: instance_count non-NULL UTF-8 names (for messages and
 *   tools); may be NULL only when instance_count == 0.
 * instance_count: number of instances (ids 0 .. instance_count - 1); 0 with
 *   triangle_instances all SP_STATIC_INSTANCE (or NULL) is sp_scene_create.
 * Errors: as sp_scene_create; SP_ERROR_INVALID_ARGUMENT (NULL instance_names
 * or triangle_instances with instance_count > 0, a NULL name),
 * SP_ERROR_INVALID_SCENE (an instance id out of range, named with its
 * triangle). Thread-safe. */
SP_API sp_result sp_scene_create_with_instances(const float* vertices, uint32_t triangle_count,
                                                const uint32_t* triangle_layers, const char* const* layer_names,
                                                uint32_t layer_count, const uint32_t* triangle_instances,
                                                const char* const* instance_names, uint32_t instance_count,
                                                sp_scene** out) SP_NOEXCEPT;

/* sp_scene_create_with_instances in `context` (non-NULL, live): the
 * handle from its allocator, a failure's message also to its log. */
SP_API sp_result sp_scene_create_in(sp_context* context, const float* vertices, uint32_t triangle_count,
                                    const uint32_t* triangle_layers, const char* const* layer_names,
                                    uint32_t layer_count, const uint32_t* triangle_instances,
                                    const char* const* instance_names, uint32_t instance_count,
                                    sp_scene** out) SP_NOEXCEPT;

/* Destroys a scene. NULL is a no-op (SP_OK). Simulations and visualizers
 * created from the scene do not reference it and may outlive it.
 * Errors: SP_ERROR_INVALID_ARGUMENT when `scene` is not live (destroyed
 * already, or never created). */
SP_API sp_result sp_scene_destroy(sp_scene* scene) SP_NOEXCEPT;

/* Creates a simulation of `scene` (non-NULL, live, only read during the call).
 * config_json: NULL for every default, else a NUL-terminated JSON object with
 *   the keys of the configuration file (README "Configuration (JSON)").
 *   The listener starts at config "listener.position", else the scene's camera;
 *   one of the two must exist.
 * backend: SP_BACKEND_CPU, SP_BACKEND_GPU or SP_BACKEND_AUTO.
 * *out: non-NULL; receives a new simulation owned by the caller.
 * Errors: SP_ERROR_INVALID_CONFIG (message names the key),
 * SP_ERROR_INVALID_ARGUMENT (no listener, bad source field, unknown backend,
 * scene not live), SP_ERROR_VULKAN / SP_ERROR_LIMIT_EXCEEDED (GPU backend
 * only). Thread-safe. May take a while: builds the BVH (and the GPU device). */
SP_API sp_result sp_simulation_create(const sp_scene* scene, const char* config_json, sp_backend backend,
                                      sp_simulation** out) SP_NOEXCEPT;

/* What sp_simulation_create_with_options takes beyond the scene and config
 * (the C counterpart of sp::SimulatorSettings). Sized: fill it with
 * sp_simulation_options_init first. */
typedef struct sp_simulation_options {
  uint32_t struct_size;         /* sizeof(sp_simulation_options), set by _init */
  sp_backend backend;           /* default SP_BACKEND_AUTO */
  uint64_t memory_budget_bytes; /* creation fails with SP_ERROR_LIMIT_EXCEEDED, naming the config keys,
                                   when the config's rays and indicators could need more at worst
                                   (README "Security"); default 2 GiB, > 0 */
  /* CPU backend: threads that cast rays, the calling thread included (the
   * BVH build too); 0 (default): the context's max_threads, else one per
   * core. Never more than the context's max_threads. Results do not depend
   * on it. */
  uint32_t threads;
  /* New rays per step, all sources together, in place of the config's
   * "ray_budget" (which the memory budget then counts); 0 (default): the
   * config's. At most 2^24. */
  uint32_t ray_budget;
  /* GPU backend: a case-insensitive part of the device name to use; NULL
   * (default): the SOUNDPAINT_DEVICE environment variable, else the best
   * device. No such device is SP_ERROR_VULKAN. */
  const char* device_name;
  /* GPU backend: 1 (default) accepts a CPU posing as a GPU (lavapipe); 0
   * refuses it (SP_ERROR_VULKAN), the CPU backend being faster there. */
  int allow_cpu_device;
  /* GPU backend: threads per workgroup of the simulation's kernels
   * (sp::GpuSettings::workgroup_size); 0 (default): the device's choice, 64
   * on a GPU, the subgroup width on a CPU device (lavapipe). Otherwise a
   * multiple of the device's subgroup width within its limits, else
   * creation fails with SP_ERROR_INVALID_ARGUMENT naming workgroup_size.
   * Results do not depend on it. */
  uint32_t workgroup_size;
} sp_simulation_options;

/* Fills *options with the defaults (those of sp_simulation_create with
 * SP_BACKEND_AUTO). NULL is a no-op. */
SP_API void sp_simulation_options_init(sp_simulation_options* options) SP_NOEXCEPT;

/* sp_simulation_create with options (non-NULL; a bad struct_size,
 * memory_budget_bytes 0, ray_budget above 2^24 and allow_cpu_device not 0
 * or 1 are SP_ERROR_INVALID_ARGUMENT). sp_simulation_create checks the
 * default budget. Errors and thread-safety as sp_simulation_create. */
SP_API sp_result sp_simulation_create_with_options(const sp_scene* scene, const char* config_json,
                                                   const sp_simulation_options* options,
                                                   sp_simulation** out) SP_NOEXCEPT;

/* sp_simulation_create_with_options in `context` (non-NULL, live; the
 * scene may come from another context): its handle from the context's
 * allocator, its threads capped by the context's max_threads, and the
 * messages of its failures (config validation naming the key, creation,
 * steps, reads) also to the context's log, with the Vulkan validation
 * layer's when the context asks (SP_CONTEXT_VULKAN_VALIDATION). options:
 * NULL for the defaults. */
SP_API sp_result sp_simulation_create_in(sp_context* context, const sp_scene* scene, const char* config_json,
                                         const sp_simulation_options* options, sp_simulation** out) SP_NOEXCEPT;

/* Destroys a simulation and its resources; its sp_sound_scene stops being
 * live. NULL is a no-op (SP_OK). Render thread; not while another thread is
 * inside any call on it or its scene (undefined behaviour; overlapping a
 * step or read is detected and refused).
 * Errors: SP_ERROR_INVALID_ARGUMENT when `simulation` is not live, or when
 * another thread is inside sp_simulation_step, _live_indicators or _stats. */
SP_API sp_result sp_simulation_destroy(sp_simulation* simulation) SP_NOEXCEPT;

/* *out (non-NULL) receives the simulation's sound scene, borrowed: the same
 * pointer on every call, live until sp_simulation_destroy. Any thread; its
 * functions too (see Thread-safety above). */
SP_API sp_result sp_simulation_scene(sp_simulation* simulation, sp_sound_scene** out) SP_NOEXCEPT;

/* Shorthand for sp_sound_scene_set_listener on the simulation's scene.
 * Any thread. Errors: SP_ERROR_INVALID_ARGUMENT for NULL, a handle not live, or a
 * non-finite coordinate. */
SP_API sp_result sp_simulation_set_listener(sp_simulation* simulation, float x, float y, float z) SP_NOEXCEPT;

/* Shorthand for sp_sound_scene_play on the simulation's scene.
 * Any thread. Errors: SP_ERROR_INVALID_ARGUMENT for NULL, a handle not live, an unknown
 * or removed id, or a negative or non-finite duration. */
SP_API sp_result sp_simulation_play(sp_simulation* simulation, uint32_t source_id, double duration_seconds) SP_NOEXCEPT;

/* Runs the next step (config "dt" seconds of simulated time): first the
 * sound-scene changes queued since the last step, in call order, then the
 * rays. Render thread (see Thread-safety above).
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not live; another thread
 * inside a render-thread call on it); device failures
 * (SP_ERROR_VULKAN) on the GPU backend; SP_ERROR_LIMIT_EXCEEDED when the
 * CPU backend runs out of memory, after which the simulation has stopped:
 * every later step returns the same error (indicators and stats still
 * describe the steps before it); destroy it and create another. */
SP_API sp_result sp_simulation_step(sp_simulation* simulation) SP_NOEXCEPT;

/* Takes another configuration from the next step on (sp::Simulator::
 * set_config, include/soundpaint/simulation.h), without loading or
 * building the level again. config_json as for sp_simulation_create (NULL:
 * every default): the whole configuration, so a key it leaves out takes its
 * default, not the running value, and the ray_budget of the creation's
 * sp_simulation_options no longer applies. The simulation keeps its sound
 * scene: every source (the scene's, the creation config's and those added
 * since, by id; the new "sources" and "listener" are not read), play
 * window, voice, the listener and moving parts; and the spots on screen,
 * as many of the newest as the new "max_indicators" holds. "dt" cannot
 * change once a step has run. Render thread (see Thread-safety above).
 * Errors, after which the simulation is as it was: SP_ERROR_INVALID_ARGUMENT
 * (NULL or not live; another thread inside a render-thread call on it),
 * SP_ERROR_INVALID_CONFIG (the message names the key),
 * SP_ERROR_LIMIT_EXCEEDED (over the creation's memory budget, naming the
 * keys, or a device limit); SP_ERROR_VULKAN (a device failure); a
 * simulation stopped by a failed step returns that step's error. */
SP_API sp_result sp_simulation_set_config(sp_simulation* simulation, const char* config_json) SP_NOEXCEPT;

/* *out (non-NULL) receives the number of source slots: source ids are
 * 0 .. count - 1 (scene's, then config's, then added ones, counted from the
 * call that added them); a slot whose source was removed (or whose one-shot
 * ended) stays counted until an added source reuses it
 * (sp_sound_scene_has_source tells which are live). Any thread. */
SP_API sp_result sp_simulation_source_count(const sp_simulation* simulation, uint32_t* out) SP_NOEXCEPT;

/* The indicators still live, oldest first: exactly those the display draws
 * (a hidden, capped, back-facing or too faint spot aside), younger than the
 * display lifetime, max(indicator_lifetime, 1/3 s), counted in whole steps
 * from the last step run. *count (non-NULL) receives how many exist; min(*count, capacity)
 * are written to out. out may be NULL only when capacity == 0 (size query).
 * Calling twice between steps gives the same list. Render thread.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL or not-live simulation, NULL
 * count, NULL out with capacity > 0, another thread inside a render-thread
 * call on it); SP_ERROR_VULKAN on a GPU read-back failure. */
SP_API sp_result sp_simulation_live_indicators(sp_simulation* simulation, sp_indicator* out, uint32_t capacity,
                                               uint32_t* count) SP_NOEXCEPT;

/* *out (non-NULL) receives the totals over every step run so far. Render
 * thread. Errors: SP_ERROR_INVALID_ARGUMENT for NULL, a handle not live or
 * another thread inside a render-thread call on it;
 * SP_ERROR_VULKAN on a GPU read-back failure. */
SP_API sp_result sp_simulation_stats(sp_simulation* simulation, sp_stats* out) SP_NOEXCEPT;

/* Counters of one collision layer over every step run so far (the C++
 * API's sp::LayerCounters; README "Command line", --stats). Fixed forever. */
typedef struct sp_layer_stats {
  uint64_t hits;           /* every surface hit on this layer */
  uint64_t reflections;    /* hits that reflected */
  uint64_t penetrations;   /* decisions to penetrate (no_way_out included) */
  uint64_t no_way_out;     /* penetrations that found no way out of matter within max_wall_thickness */
  uint64_t back_face_hits; /* rays in air that struck the back of a face (a leak); counted in hits too */
  uint64_t diffractions;   /* rays that turned round an exposed edge of this layer; 0 without diffraction */
} sp_layer_stats;

/* The counters of every layer, by layer id (the scene's layer order):
 * *count (non-NULL) receives the layer count and min(*count, capacity) are
 * written to out (NULL only with capacity 0: a size query). Render thread.
 * Errors as sp_simulation_stats, plus NULL out with capacity > 0. */
SP_API sp_result sp_simulation_layer_stats(sp_simulation* simulation, sp_layer_stats* out, uint32_t capacity,
                                           uint32_t* count) SP_NOEXCEPT;

/* *out (non-NULL) receives the threads the simulation casts rays with: the
 * CPU backend's pool (the calling thread included); 0 for the GPU backend.
 * Render thread. */
SP_API sp_result sp_simulation_thread_count(sp_simulation* simulation, uint32_t* out) SP_NOEXCEPT;

/* --- Sound scene: run-time changes, through a simulation's or a
 * visualizer's sp_sound_scene. Each is checked at the call and applies from
 * the next step on; on error nothing changes. Every function fails with
 * SP_ERROR_INVALID_ARGUMENT for a NULL scene or one whose owner was
 * destroyed. Any thread, while the render thread steps (the audio thread's
 * "this sound just started" included): see Thread-safety above. Queries
 * (has_source, instance_count, source_capacity) answer as the queued
 * changes will leave the scene. */

/* Moves the listener to (x, y, z) metres (finite). */
SP_API sp_result sp_sound_scene_set_listener(sp_sound_scene* scene, float x, float y, float z) SP_NOEXCEPT;

/* Adds a source described by *desc (non-NULL; every field checked: the
 * message names the field) and writes its id to *out_id (non-NULL): the
 * lowest free slot, so ids of removed sources are reused.
 * Errors: SP_ERROR_INVALID_ARGUMENT (bad field), SP_ERROR_LIMIT_EXCEEDED
 * (sp_sound_scene_source_capacity sources are live: remove one first). */
SP_API sp_result sp_sound_scene_add_source(sp_sound_scene* scene, const sp_source_desc* desc,
                                           uint32_t* out_id) SP_NOEXCEPT;

/* Replaces everything about live source `id` with *desc (non-NULL): position,
 * colour, category, range, loudness and emission pattern.
 * Errors: SP_ERROR_INVALID_ARGUMENT (unknown or removed id, bad field). */
SP_API sp_result sp_sound_scene_update_source(sp_sound_scene* scene, uint32_t id,
                                              const sp_source_desc* desc) SP_NOEXCEPT;

/* Moves live source `id` to (x, y, z) metres (finite).
 * Errors: SP_ERROR_INVALID_ARGUMENT (unknown or removed id, non-finite). */
SP_API sp_result sp_sound_scene_move_source(sp_sound_scene* scene, uint32_t id, float x, float y, float z) SP_NOEXCEPT;

/* Removes live source `id`: it stops emitting, its indicators already drawn
 * fade as usual, and its id may be reused by a later add or emit.
 * Errors: SP_ERROR_INVALID_ARGUMENT (unknown or already removed id). */
SP_API sp_result sp_sound_scene_remove_source(sp_sound_scene* scene, uint32_t id) SP_NOEXCEPT;

/* Makes live source `id` play for duration_seconds (finite, >= 0) from the
 * next step on, whatever its emission pattern says ("this sound just
 * started", from the game's audio engine).
 * Errors: SP_ERROR_INVALID_ARGUMENT (unknown or removed id, bad duration). */
SP_API sp_result sp_sound_scene_play(sp_sound_scene* scene, uint32_t id, double duration_seconds) SP_NOEXCEPT;

/* A one-shot sound: adds a source described by *desc (non-NULL; its
 * duration, interval and phase are ignored) that plays for duration_seconds
 * (finite, >= 0) from the next step on and then removes itself. *out_id
 * (non-NULL) receives its id, valid until the sound ends: after that the id
 * is free for a later add or emit, so stop using it (a later add may get
 * it; sp_sound_scene_has_source tells whether it is still live).
 * Errors: as sp_sound_scene_add_source, plus a bad duration. */
SP_API sp_result sp_sound_scene_emit(sp_sound_scene* scene, const sp_source_desc* desc, double duration_seconds,
                                     uint32_t* out_id) SP_NOEXCEPT;

/* Places moving part `instance` (< sp_sound_scene_instance_count) at the
 * transform column_major_4x4 (non-NULL, 16 finite floats, column-major as
 * in glm, GLSL and the glTF spec) applied to its rest pose: a door swings
 * by a rotation about its hinge. Replaces the previous transform.
 * Every vertex of the part it would place must be finite and within
 * 1e10 m of the origin on each axis (sp::kMaxCoordinate, simulation.h):
 * the BVH computes in float. A transform that breaks this (a finite but
 * huge scale, a translation of 1e12 m) is refused, naming the instance and
 * the vertex; the previous transform stays and the steps go on.
 * Errors: SP_ERROR_INVALID_ARGUMENT (instance out of range, non-finite
 * element, a vertex placed out of bounds). */
SP_API sp_result sp_sound_scene_set_instance_transform(sp_sound_scene* scene, uint32_t instance,
                                                       const float column_major_4x4[16]) SP_NOEXCEPT;

/* *out (non-NULL) receives the number of moving parts (instances). */
SP_API sp_result sp_sound_scene_instance_count(const sp_sound_scene* scene, uint32_t* out) SP_NOEXCEPT;

/* *out (non-NULL) receives 1 when `id` is a live source, else 0 (removed,
 * never added). Any id is accepted. A one-shot stays live until the first
 * step planned after its sound ended removes it. */
SP_API sp_result sp_sound_scene_has_source(const sp_sound_scene* scene, uint32_t id, int* out) SP_NOEXCEPT;

/* *out (non-NULL) receives how many sources may be live at once. */
SP_API sp_result sp_sound_scene_source_capacity(const sp_sound_scene* scene, uint32_t* out) SP_NOEXCEPT;

/* --- Display: how indicators are drawn, so that a player who cannot hear
 * reads where a sound is, what it is and how close. The config's "display"
 * object as a struct (the C counterpart of sp::DisplaySettings in
 * include/soundpaint/display.h), for settings a game changes at run time
 * (sp_visualizer_set_display, soundpaint_vulkan.h). It never changes the
 * simulation, except that a source without its own colour takes its
 * category's palette colour. */

/* Category colours for sources without their own colour. */
typedef enum sp_palette {
  SP_PALETTE_OKABE_ITO = 0,     /* colour-blind safe (Okabe & Ito), the default */
  SP_PALETTE_HIGH_CONTRAST = 1, /* saturated colours that stand out on dark and light levels */
  SP_PALETTE_SINGLE_HUE = 2     /* one hue for every category: shapes alone tell them apart */
} sp_palette;

/* Indicator shapes (sp_display_settings.shapes), one per kind of sound.
 * Macros, not an enum: they are the shaders' own ids, defined token for
 * token as in the library's shader header so that both may be included. */
#define SP_SHAPE_DISC 0u
#define SP_SHAPE_RING 1u
#define SP_SHAPE_DIAMOND 2u
#define SP_SHAPE_CROSS 3u /* a diagonal cross, x */
#define SP_SHAPE_PLUS 4u  /* an upright cross, + */
#define SP_SHAPE_TRIANGLE 5u
#define SP_SHAPE_SQUARE 6u
#define SP_SHAPE_STAR 7u
#define SP_SHAPE_HEXAGON 8u
#define SP_SHAPE_CLOVER 9u /* three small discs */

/* The display settings. Fill it with sp_display_settings_init first (the
 * defaults). Fixed forever. Every field is
 * checked by the call that takes it (SP_ERROR_INVALID_ARGUMENT naming the
 * field); the strings and arrays are only read during that call (copied). */
typedef struct sp_display_settings {
  sp_palette palette;  /* default SP_PALETTE_OKABE_ITO */
  int direction;       /* 1 (default): each spot is elongated along its ray's direction of travel,
                          pointing away from where the sound came from; 0: round. 0 or 1 */
  int outline;         /* 1 (default): a two-tone halo keeps >= 3:1 contrast on any surface; 0 or 1 */
  float size_scale;    /* multiplies every spot's size; finite, > 0; default 1 */
  float opacity_scale; /* multiplies every spot's opacity; finite, >= 0; default 1 */
  float min_opacity;   /* live spots are never drawn fainter than this; in [0, 1]; default 0 */
  /* At most this many live indicators drawn per category, the most
   * energetic first; 0 (the default): no cap. (To draw none of a category,
   * hide it.) */
  uint32_t max_per_category;
  /* An arrow on a ring near the screen's edge, at the source's bearing, in
   * its colour, for each source heard (it has live indicators) but out of
   * view, or in view but occluded (docs/accessibility.md): 1 on, 0 off (none
   * at all), -1 (the default) the front end decides, which for the
   * visualizer is off. Needs the viewport's size (sp_draw_options). */
  int offscreen_arrows;
  /* Categories not drawn (the player's own footsteps, say): hide_category_count
   * non-NULL, non-empty UTF-8 names. hide_categories may be NULL only when
   * the count is 0 (the default: every category drawn). */
  const char* const* hide_categories;
  uint32_t hide_category_count;
  /* Shapes for categories, over the built-in map (footsteps, gunfire, ...;
   * other categories draw as discs): shape_categories[i] (non-NULL,
   * non-empty UTF-8, each named once) is drawn as shapes[i] (an SP_SHAPE_*).
   * Both arrays may be NULL only when shape_count is 0 (the default). */
  const char* const* shape_categories;
  const uint32_t* shapes;
  uint32_t shape_count;
} sp_display_settings;

/* Fills *settings with the library's defaults (those of a config without
 * "display", see sp_display_settings). NULL is a no-op. Thread-safe. */
SP_API void sp_display_settings_init(sp_display_settings* settings) SP_NOEXCEPT;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SOUNDPAINT_SOUNDPAINT_H */
