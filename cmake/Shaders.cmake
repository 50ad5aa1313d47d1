# soundpaint_embed_shaders(<target> <shader files...>)
# Compiles each GLSL compute/graphics shader to SPIR-V at build time with
# glslangValidator and emits ${PROJECT_BINARY_DIR}/shaders/<file>.spv.h, a
# header holding `const uint32_t sp_spirv_<name>[]` (<name>: the file name
# with dots turned into underscores). Dependencies on included headers come
# from glslang's depfile, so editing shaders/shared/*.h recompiles them.
# The headers stay in soundpaint's own build folder even when a parent
# project adds soundpaint with add_subdirectory (never CMAKE_BINARY_DIR).
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(soundpaint_embed_shaders target)
  # This file's folder, not the caller's: shaders/ is found from wherever
  # the function is called.
  get_filename_component(shader_root ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../shaders ABSOLUTE)
  set(out_dir ${PROJECT_BINARY_DIR}/shaders)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  foreach(shader ${ARGN})
    get_filename_component(file_name ${shader} NAME)
    string(REPLACE "." "_" symbol ${file_name})
    set(header ${out_dir}/${file_name}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.3 -I${shader_root}/shared
              -I${shader_root} --vn sp_spirv_${symbol} --depfile ${header}.d -o ${header} ${shader}
      MAIN_DEPENDENCY ${shader}
      DEPFILE ${header}.d
      COMMENT "glslang: ${file_name}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  target_sources(${target} PRIVATE ${headers})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()
