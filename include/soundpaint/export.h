/* What libsoundpaint exports, and the library's version. C99 and C++.
 *
 * libsoundpaint is compiled with hidden visibility (-fvisibility=hidden
 * -fvisibility-inlines-hidden): a shared libsoundpaint exports the C API
 * (functions marked SP_API) and the public C++ API (the declarations that
 * the public headers put between SP_CPP_API_BEGIN and SP_CPP_API_END), and
 * nothing else, so that an engine never binds to an internal symbol that
 * the next version renames. A linker version script (cmake/exports.map)
 * keeps the exported set to sp_* and sp::*: template code the library
 * instantiates for the standard library stays local to it. */
#ifndef SOUNDPAINT_EXPORT_H
#define SOUNDPAINT_EXPORT_H

/* The version of these headers. CMakeLists.txt reads these three lines and
 * stops the configure when they differ from project(VERSION), so the two
 * cannot drift apart. sp_get_version() (soundpaint.h) returns the library's
 * own: a host compares them at run time (sp_context_settings.version). */
#define SOUNDPAINT_VERSION_MAJOR 0
#define SOUNDPAINT_VERSION_MINOR 2
#define SOUNDPAINT_VERSION_PATCH 0

/* A version as one number: major in bits 16..31, minor in 8..15, patch in
 * 0..7 (each part below 256, as Steam Audio packs it). */
#define SOUNDPAINT_MAKE_VERSION(major, minor, patch) \
  ((((unsigned long)(major)) << 16) | (((unsigned long)(minor)) << 8) | ((unsigned long)(patch)))
#define SOUNDPAINT_VERSION \
  SOUNDPAINT_MAKE_VERSION(SOUNDPAINT_VERSION_MAJOR, SOUNDPAINT_VERSION_MINOR, SOUNDPAINT_VERSION_PATCH)

#if defined(_WIN32)
#if defined(SOUNDPAINT_BUILDING_SHARED)
#define SP_API __declspec(dllexport)
#elif defined(SOUNDPAINT_SHARED)
#define SP_API __declspec(dllimport)
#else
#define SP_API
#endif
#define SP_CPP_API_BEGIN
#define SP_CPP_API_END
#elif defined(__GNUC__) || defined(__clang__)
#define SP_API __attribute__((visibility("default")))
#define SP_CPP_API_BEGIN _Pragma("GCC visibility push(default)")
#define SP_CPP_API_END _Pragma("GCC visibility pop")
#else
#define SP_API
#define SP_CPP_API_BEGIN
#define SP_CPP_API_END
#endif

#endif /* SOUNDPAINT_EXPORT_H */
