# Dear ImGui and GLFW for the viewer (`soundpaint view`, src/view/).
#
# Defines the static library soundpaint_imgui: ImGui's GLFW and Vulkan
# backends, compiled here from the sources Debian's libimgui-dev ships as
# examples (its headers are in /usr/include/imgui/backends), linked with the
# ImGui core (libimgui.a), GLFW and Vulkan. Sets SOUNDPAINT_VIEWER_AVAILABLE
# to ON, or to OFF with a message, and defines nothing else, when a part is
# missing: the library and the other commands build without a display stack.
#
# libimgui.a holds compiled backends too, but we compile our own so that they
# are built with our compiler, standard and build type (IM_ASSERT follows
# NDEBUG) against the Vulkan headers we build with; being first on the link
# line, ours are the ones the linker takes.

set(SOUNDPAINT_VIEWER_AVAILABLE OFF)

# Where the backends' sources are, for a distribution that puts them
# elsewhere; some compress examples (*.cpp.gz).
set(SOUNDPAINT_IMGUI_BACKENDS_DIR /usr/share/doc/libimgui-dev/examples/backends
    CACHE PATH "Folder holding imgui_impl_glfw.cpp and imgui_impl_vulkan.cpp (or .cpp.gz)")

find_package(glfw3 3.3 QUIET)
find_path(SOUNDPAINT_IMGUI_INCLUDE_DIR imgui.h PATH_SUFFIXES imgui)
find_path(SOUNDPAINT_IMGUI_BACKENDS_INCLUDE_DIR imgui_impl_vulkan.h PATH_SUFFIXES imgui/backends)
find_library(SOUNDPAINT_IMGUI_LIBRARY NAMES imgui)
# Debian builds the ImGui core against its shared stb (font rasterising and
# rectangle packing): imgui.pc says `Requires: stb`.
find_library(SOUNDPAINT_IMGUI_STB_LIBRARY NAMES stb)

# Either the source or its gzip, decompressed into the build folder at
# configure time. Sets <out_var> to the path to compile, or to "" if neither.
function(_soundpaint_imgui_backend_source name out_var)
  set(plain ${SOUNDPAINT_IMGUI_BACKENDS_DIR}/${name})
  set(gz ${plain}.gz)
  set(${out_var} "" PARENT_SCOPE)
  if(EXISTS ${plain})
    set(${out_var} ${plain} PARENT_SCOPE)
  elseif(EXISTS ${gz})
    find_program(SOUNDPAINT_GZIP gzip)
    if(NOT SOUNDPAINT_GZIP)
      return()
    endif()
    set(out_dir ${PROJECT_BINARY_DIR}/imgui_backends)
    file(MAKE_DIRECTORY ${out_dir})
    execute_process(COMMAND ${SOUNDPAINT_GZIP} -dc ${gz} OUTPUT_FILE ${out_dir}/${name} RESULT_VARIABLE status)
    if(status EQUAL 0)
      # A new package version reconfigures and decompresses again.
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${gz})
      set(${out_var} ${out_dir}/${name} PARENT_SCOPE)
    endif()
  endif()
endfunction()

_soundpaint_imgui_backend_source(imgui_impl_glfw.cpp soundpaint_imgui_glfw_source)
_soundpaint_imgui_backend_source(imgui_impl_vulkan.cpp soundpaint_imgui_vulkan_source)

set(soundpaint_imgui_missing)
if(NOT glfw3_FOUND)
  list(APPEND soundpaint_imgui_missing "GLFW 3.3 (libglfw3-dev)")
endif()
if(NOT SOUNDPAINT_IMGUI_INCLUDE_DIR OR NOT SOUNDPAINT_IMGUI_BACKENDS_INCLUDE_DIR OR NOT SOUNDPAINT_IMGUI_LIBRARY)
  list(APPEND soundpaint_imgui_missing "Dear ImGui (libimgui-dev)")
elseif(NOT soundpaint_imgui_glfw_source OR NOT soundpaint_imgui_vulkan_source)
  list(APPEND soundpaint_imgui_missing "ImGui's GLFW and Vulkan backend sources in ${SOUNDPAINT_IMGUI_BACKENDS_DIR}")
endif()
if(NOT SOUNDPAINT_IMGUI_STB_LIBRARY)
  list(APPEND soundpaint_imgui_missing "stb, which Debian's ImGui links (libstb-dev)")
endif()
if(NOT TARGET Vulkan::Vulkan)
  find_package(Vulkan QUIET)
  if(NOT TARGET Vulkan::Vulkan)
    list(APPEND soundpaint_imgui_missing "Vulkan (libvulkan-dev)")
  endif()
endif()

if(soundpaint_imgui_missing)
  list(JOIN soundpaint_imgui_missing ", " soundpaint_imgui_missing)
  message(STATUS "soundpaint: no viewer (`soundpaint view`): missing ${soundpaint_imgui_missing}")
  return()
endif()

add_library(soundpaint_imgui STATIC ${soundpaint_imgui_glfw_source} ${soundpaint_imgui_vulkan_source})
# Third-party code as it is shipped: no warnings of ours (soundpaint_warnings
# is not linked) and none at all, so that -Werror in CMAKE_CXX_FLAGS cannot
# fail on it.
target_compile_options(soundpaint_imgui PRIVATE -w)
# SYSTEM, for us too: our -Werror code includes imgui.h, whose warnings under
# -Wconversion and -Wshadow are not ours to fix.
target_include_directories(soundpaint_imgui SYSTEM PUBLIC ${SOUNDPAINT_IMGUI_INCLUDE_DIR}
                                                          ${SOUNDPAINT_IMGUI_BACKENDS_INCLUDE_DIR})
target_link_libraries(soundpaint_imgui PUBLIC ${SOUNDPAINT_IMGUI_LIBRARY} ${SOUNDPAINT_IMGUI_STB_LIBRARY} glfw
                                              Vulkan::Vulkan m)
set(SOUNDPAINT_VIEWER_AVAILABLE ON)
message(STATUS "soundpaint: viewer with Dear ImGui (${SOUNDPAINT_IMGUI_LIBRARY}) and GLFW ${glfw3_VERSION}")
