# soundpaint_embed_shaders(<target> <shader files...>)
# Compiles each GLSL compute/graphics shader to SPIR-V at build time with
# glslangValidator and emits ${CMAKE_BINARY_DIR}/shaders/<file>.spv.h, a
# header holding `const uint32_t sp_spirv_<name>[]` (<name>: the file name
# with dots turned into underscores). Dependencies on included headers come
# from glslang's depfile, so editing shaders/shared/*.h recompiles them.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(soundpaint_embed_shaders target)
  set(out_dir ${CMAKE_BINARY_DIR}/shaders)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  foreach(shader ${ARGN})
    get_filename_component(file_name ${shader} NAME)
    string(REPLACE "." "_" symbol ${file_name})
    set(header ${out_dir}/${file_name}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.3 -I${PROJECT_SOURCE_DIR}/shaders/shared
              -I${PROJECT_SOURCE_DIR}/shaders --vn sp_spirv_${symbol} --depfile ${header}.d -o ${header} ${shader}
      MAIN_DEPENDENCY ${shader}
      DEPFILE ${header}.d
      COMMENT "glslang: ${file_name}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  target_sources(${target} PRIVATE ${headers})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()
