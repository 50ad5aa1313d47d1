/* soundpaint C API: a C99 interface over the C++ library for game engines
 * (C# / Unity P/Invoke, Godot GDExtension, Rust FFI).
 *
 * Units: metres and seconds; energies are in units of a source's loudness E0.
 *
 * Conventions that hold for every function below:
 * - Handles (sp_scene, sp_simulation) are opaque. Each *_create / *_load has
 *   one *_destroy; the caller owns what it creates and must destroy it exactly
 *   once. Destroying NULL is a no-op. Using a handle after destroying it is
 *   undefined behaviour (it cannot be detected).
 * - Functions returning sp_result never throw or abort on bad input: they
 *   return SP_OK on success, or an error code and set the calling thread's
 *   last error message (see sp_last_error_message). On error, out-parameters
 *   are left unchanged unless stated otherwise.
 * - Pointers documented as "non-NULL" are checked: NULL gives
 *   SP_ERROR_INVALID_ARGUMENT.
 * - Thread-safety: different handles may be used from different threads at
 *   the same time. One sp_simulation must be used by one thread at a time
 *   (calls on it are not synchronised). An sp_scene is read-only after
 *   creation and may be shared by threads creating simulations from it.
 * - Sound sources come from the scene (glTF nodes) and the JSON config
 *   ("sources") given at simulation creation; this version cannot add, move
 *   or remove sources at run time.
 */
#ifndef SOUNDPAINT_SOUNDPAINT_H
#define SOUNDPAINT_SOUNDPAINT_H

#include <stdint.h>

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
  SP_ERROR_INVALID_ARGUMENT, /* an argument is NULL, non-finite or out of range */
  SP_ERROR_INVALID_SCENE,    /* a scene file or scene arrays are missing, malformed or unsupported */
  SP_ERROR_INVALID_CONFIG,   /* the JSON configuration is malformed or a value is out of range */
  SP_ERROR_IO,               /* reading a file failed */
  SP_ERROR_VULKAN,           /* a Vulkan call failed or no suitable device exists */
  SP_ERROR_LIMIT_EXCEEDED,   /* a request exceeds a device or library limit */
  SP_ERROR_OUT_OF_MEMORY,    /* an allocation failed */
  SP_ERROR_INTERNAL          /* an unexpected failure inside the library (a bug) */
} sp_result;

typedef enum sp_backend {
  SP_BACKEND_CPU = 0,  /* multithreaded CPU backend; always available */
  SP_BACKEND_GPU = 1,  /* Vulkan compute backend; any Vulkan device, fails with SP_ERROR_VULKAN if none */
  SP_BACKEND_AUTO = 2  /* the GPU backend on a real GPU, else the CPU backend */
} sp_backend;

/* Indicator kinds (sp_indicator.kind). */
#define SP_INDICATOR_KIND_HIT 0u  /* a ray hit a surface */
#define SP_INDICATOR_KIND_EXIT 1u /* a ray left a surface after penetrating it */

/* A triangle soup with a collision layer per triangle, plus sound sources and
 * a camera when loaded from glTF. Immutable once created. */
typedef struct sp_scene sp_scene;

/* A running simulation of one scene under one configuration. */
typedef struct sp_simulation sp_simulation;

/* One visible sound indicator: where a ray hit (or left) a surface. */
typedef struct sp_indicator {
  float position[3];   /* metres, world space */
  float normal[3];     /* unit; faces the side the ray came from (hit) or leaves to (exit) */
  float energy;        /* remaining ray energy, units of E0 */
  float size;          /* metres: indicator_size * energy / loudness */
  float color[3];      /* the source's linear RGB, each in [0, 1] */
  float intensity;     /* 1 - listener distance / max_distance of the source at emission, [0, 1] */
  uint32_t kind;       /* SP_INDICATOR_KIND_* */
  uint32_t source_id;  /* index of the source: scene sources first, then config sources */
  uint32_t bounces;    /* reflections before this indicator */
  uint32_t penetrations; /* completed penetrations before this indicator */
  float path_length;   /* metres travelled by the ray from its source */
  uint32_t step;       /* the step that created it */
} sp_indicator;

/* Totals over every step run so far. */
typedef struct sp_stats {
  uint64_t steps;        /* steps run */
  uint64_t casts;        /* ray casts (forward casts + backcasts) */
  uint64_t rays_emitted; /* rays emitted by sources */
  uint64_t indicators;   /* indicators created (including ones no longer live) */
} sp_stats;

/* The message of the last error returned on the calling thread: one line
 * naming the problem (for files, the path; for config, the key). Never NULL;
 * "" when no call on this thread has failed yet. The text is owned by the
 * library and stays valid until the next failing sp_* call on the same thread.
 * A successful call does not clear it. Thread-safe (thread-local). */
const char* sp_last_error_message(void) SP_NOEXCEPT;

/* Loads a .gltf or .glb scene. path: non-NULL, UTF-8, NUL-terminated.
 * *out: non-NULL; receives a new scene owned by the caller (sp_scene_destroy).
 * Errors: SP_ERROR_INVALID_SCENE or SP_ERROR_IO (message names the path).
 * Thread-safe. */
sp_result sp_scene_load(const char* path, sp_scene** out) SP_NOEXCEPT;

/* Creates a scene from the host's arrays; the arrays are copied and may be
 * freed after the call. The scene has no sources and no camera: give them in
 * the simulation's JSON config ("sources", "listener").
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
sp_result sp_scene_create(const float* vertices, uint32_t triangle_count, const uint32_t* triangle_layers,
                          const char* const* layer_names, uint32_t layer_count, sp_scene** out) SP_NOEXCEPT;

/* Destroys a scene. NULL is a no-op. Simulations created from the scene do
 * not reference it and may outlive it. Call once per scene. */
void sp_scene_destroy(sp_scene* scene) SP_NOEXCEPT;

/* Creates a simulation of `scene` (non-NULL, only read during the call).
 * config_json: NULL for every default, else a NUL-terminated JSON object with
 *   the keys of the configuration file (README "Configuration (JSON)").
 *   The listener starts at config "listener.position", else the scene's camera;
 *   one of the two must exist.
 * backend: SP_BACKEND_CPU, SP_BACKEND_GPU or SP_BACKEND_AUTO.
 * *out: non-NULL; receives a new simulation owned by the caller.
 * Errors: SP_ERROR_INVALID_CONFIG (message names the key),
 * SP_ERROR_INVALID_ARGUMENT (no listener, bad source field, unknown backend),
 * SP_ERROR_VULKAN / SP_ERROR_LIMIT_EXCEEDED (GPU backend only).
 * Thread-safe. May take a while: builds the BVH (and the GPU device). */
sp_result sp_simulation_create(const sp_scene* scene, const char* config_json, sp_backend backend,
                               sp_simulation** out) SP_NOEXCEPT;

/* Destroys a simulation and its resources. NULL is a no-op. Call once, and
 * not while another thread uses the simulation. */
void sp_simulation_destroy(sp_simulation* simulation) SP_NOEXCEPT;

/* Moves the listener to (x, y, z) metres, used from the next step on.
 * Errors: SP_ERROR_INVALID_ARGUMENT for NULL or a non-finite coordinate. */
sp_result sp_simulation_set_listener(sp_simulation* simulation, float x, float y, float z) SP_NOEXCEPT;

/* Makes source `source_id` (< sp_simulation_source_count) play for
 * duration_seconds (finite, >= 0) from the next step on, regardless of its
 * emission pattern.
 * Errors: SP_ERROR_INVALID_ARGUMENT for NULL, an unknown id, or a negative or
 * non-finite duration. */
sp_result sp_simulation_play(sp_simulation* simulation, uint32_t source_id, double duration_seconds) SP_NOEXCEPT;

/* Runs the next step (config "dt" seconds of simulated time).
 * Errors: only device failures (SP_ERROR_VULKAN) on the GPU backend. */
sp_result sp_simulation_step(sp_simulation* simulation) SP_NOEXCEPT;

/* *out (non-NULL) receives the number of sources (scene's, then config's);
 * source ids are 0 .. count - 1. */
sp_result sp_simulation_source_count(const sp_simulation* simulation, uint32_t* out) SP_NOEXCEPT;

/* The indicators still visible (younger than indicator_lifetime), oldest
 * first. *count (non-NULL) receives how many exist; min(*count, capacity)
 * are written to out. out may be NULL only when capacity == 0 (size query).
 * Calling twice between steps gives the same list.
 * Errors: SP_ERROR_INVALID_ARGUMENT (NULL simulation or count, NULL out with
 * capacity > 0); SP_ERROR_VULKAN on a GPU read-back failure. */
sp_result sp_simulation_live_indicators(sp_simulation* simulation, sp_indicator* out, uint32_t capacity,
                                        uint32_t* count) SP_NOEXCEPT;

/* *out (non-NULL) receives the totals over every step run so far.
 * Errors: SP_ERROR_INVALID_ARGUMENT for NULL; SP_ERROR_VULKAN on a GPU
 * read-back failure. */
sp_result sp_simulation_stats(sp_simulation* simulation, sp_stats* out) SP_NOEXCEPT;

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* SOUNDPAINT_SOUNDPAINT_H */
