# `cmake --install BUILD --prefix P` (SPEC 5): included by the top-level
# CMakeLists.txt when SOUNDPAINT_INSTALL is on. Installs
#   P/include/soundpaint/      the public headers
#   P/<libdir>/libsoundpaint.a (or .so with BUILD_SHARED_LIBS)
#   P/bin/soundpaint           the command line
#   P/<libdir>/cmake/soundpaint/   find_package(soundpaint CONFIG): targets
#                              soundpaint::soundpaint, soundpaint::capi, soundpaint::cli
#   P/<libdir>/pkgconfig/soundpaint.pc
include(CMakePackageConfigHelpers)

set(SOUNDPAINT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/soundpaint
    CACHE STRING "Where the CMake package goes, relative to the install prefix")
mark_as_advanced(SOUNDPAINT_INSTALL_CMAKEDIR)

# Public headers: include/soundpaint/*.h. They include only each other, the
# standard library and (the interop headers) Vulkan: the consumer test
# consumer_installed_headers checks it.
file(GLOB soundpaint_public_headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/include/soundpaint/*.h)
install(FILES ${soundpaint_public_headers}
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/soundpaint COMPONENT soundpaint_development)

install(TARGETS soundpaint soundpaint_c_api EXPORT soundpaintTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT soundpaint_development
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT soundpaint_runtime
                NAMELINK_COMPONENT soundpaint_development
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT soundpaint_runtime)

# The command line; with a shared libsoundpaint it finds it from bin/.
if(BUILD_SHARED_LIBS)
  file(RELATIVE_PATH bin_to_lib ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
       ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR})
  set_target_properties(soundpaint_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${bin_to_lib}")
endif()
install(TARGETS soundpaint_cli EXPORT soundpaintTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT soundpaint_runtime)

install(EXPORT soundpaintTargets NAMESPACE soundpaint:: DESTINATION ${SOUNDPAINT_INSTALL_CMAKEDIR}
        COMPONENT soundpaint_development)

# The OpenAL adapter, where it was built: its own export set, which
# find_package(soundpaint COMPONENTS openal) loads, so the core package
# never needs OpenAL.
if(SOUNDPAINT_HAVE_OPENAL)
  install(FILES ${PROJECT_SOURCE_DIR}/openal/include/soundpaint/openal.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/soundpaint COMPONENT soundpaint_development)
  install(TARGETS soundpaint_openal EXPORT soundpaintOpenALTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT soundpaint_development
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT soundpaint_runtime
                  NAMELINK_COMPONENT soundpaint_development)
  install(EXPORT soundpaintOpenALTargets NAMESPACE soundpaint:: DESTINATION ${SOUNDPAINT_INSTALL_CMAKEDIR}
          COMPONENT soundpaint_development)
endif()

# What the config file must find again: a static libsoundpaint brings its
# link-only dependencies along.
if(BUILD_SHARED_LIBS)
  set(SOUNDPAINT_STATIC_LIBRARY OFF)
else()
  set(SOUNDPAINT_STATIC_LIBRARY ON)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/soundpaintConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/package/soundpaintConfig.cmake
                              INSTALL_DESTINATION ${SOUNDPAINT_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/soundpaintConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/soundpaintConfig.cmake
              ${PROJECT_BINARY_DIR}/package/soundpaintConfigVersion.cmake
        DESTINATION ${SOUNDPAINT_INSTALL_CMAKEDIR} COMPONENT soundpaint_development)

# soundpaint.pc. For the static library, what it needs goes in Libs and
# Requires themselves, so that a plain `pkg-config --libs soundpaint` links
# (a C program also needs the C++ runtime, SOUNDPAINT_CXX_RUNTIME).
set(cxx_runtime ${SOUNDPAINT_CXX_RUNTIME})
list(TRANSFORM cxx_runtime PREPEND "-l")
list(JOIN cxx_runtime " " cxx_runtime)
if(BUILD_SHARED_LIBS)
  set(SOUNDPAINT_PC_REQUIRES "vulkan")
  set(SOUNDPAINT_PC_REQUIRES_PRIVATE "tinygltf")
  set(SOUNDPAINT_PC_LIBS "-L\${libdir} -lsoundpaint")
  set(SOUNDPAINT_PC_LIBS_PRIVATE "-pthread ${cxx_runtime}")
else()
  set(SOUNDPAINT_PC_REQUIRES "vulkan tinygltf")
  set(SOUNDPAINT_PC_REQUIRES_PRIVATE "")
  set(SOUNDPAINT_PC_LIBS "-L\${libdir} -lsoundpaint -pthread ${cxx_runtime}")
  set(SOUNDPAINT_PC_LIBS_PRIVATE "")
endif()
# The prefix is found from the file's own place, so the installed tree can move.
file(RELATIVE_PATH pc_to_prefix ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
if(IS_ABSOLUTE ${CMAKE_INSTALL_LIBDIR} OR IS_ABSOLUTE ${CMAKE_INSTALL_INCLUDEDIR})
  message(FATAL_ERROR "soundpaint.pc needs CMAKE_INSTALL_LIBDIR and CMAKE_INSTALL_INCLUDEDIR relative to the prefix")
endif()
# Embree (SOUNDPAINT_EMBREE) ships no .pc on Debian: linked by name.
if(SOUNDPAINT_EMBREE)
  if(BUILD_SHARED_LIBS)
    string(APPEND SOUNDPAINT_PC_LIBS_PRIVATE " -lembree3")
  else()
    string(APPEND SOUNDPAINT_PC_LIBS " -lembree3")
  endif()
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/soundpaint.pc.in ${PROJECT_BINARY_DIR}/package/soundpaint.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/soundpaint.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT soundpaint_development)
