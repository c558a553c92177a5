# Compiles shaders/*.glsl to SPIR-V with glslangValidator and embeds them
# in a generated C++ source as uint32_t arrays (see engine/gpu/shader_blobs.h).
# Each shader is rebuilt when it or any file in shaders/include changes.
function(animorph_embed_shaders target)
  set(options)
  set(multi SHADERS)
  cmake_parse_arguments(ARG "${options}" "" "${multi}" ${ARGN})
  set(gen_dir ${CMAKE_CURRENT_BINARY_DIR}/shaders)
  file(MAKE_DIRECTORY ${gen_dir})
  file(GLOB shader_includes CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/shaders/include/*.h ${PROJECT_SOURCE_DIR}/shaders/include/*.glsl)
  set(spv_files)
  set(names)
  foreach(src ${ARG_SHADERS})
    get_filename_component(fname ${src} NAME)            # mesh.vert.glsl
    string(REGEX REPLACE "\\.glsl$" "" base ${fname})     # mesh.vert
    string(REGEX MATCH "[^.]+$" stage ${base})            # vert
    string(REPLACE "." "_" sym ${base})                   # mesh_vert
    set(spv ${gen_dir}/${base}.spv)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -S ${stage}
              -I${PROJECT_SOURCE_DIR}/shaders/include -I${PROJECT_SOURCE_DIR}/engine/gpu/include_shared
              -o ${spv} ${PROJECT_SOURCE_DIR}/shaders/${fname}
      DEPENDS ${PROJECT_SOURCE_DIR}/shaders/${fname} ${shader_includes}
      COMMENT "glslang ${fname}"
      VERBATIM)
    list(APPEND spv_files ${spv})
    list(APPEND names ${sym})
  endforeach()
  set(out_cpp ${gen_dir}/shader_blobs.cpp)
  add_custom_command(
    OUTPUT ${out_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out_cpp} -DGEN_DIR=${gen_dir} "-DNAMES=${names}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    DEPENDS ${spv_files} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    COMMENT "Embedding SPIR-V"
    VERBATIM)
  target_sources(${target} PRIVATE ${out_cpp})
endfunction()
