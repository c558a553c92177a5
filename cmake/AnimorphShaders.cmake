# Compiles shaders/*.{vert,frag,comp}.glsl to SPIR-V with glslangValidator and
# embeds them in a generated C++ source as uint32_t arrays, looked up by name
# ("mesh.vert") through animorph::gpu::shaderBlob (engine/gpu/vulkan/shader_blobs.h).
# A shader is rebuilt when it or anything it #includes changes (glslang writes
# a depfile); the include paths are shaders/include and engine/gpu/include_shared.
function(animorph_embed_shaders target)
  cmake_parse_arguments(ARG "" "" "SHADERS" ${ARGN})
  set(gen_dir ${CMAKE_CURRENT_BINARY_DIR}/shaders)
  file(MAKE_DIRECTORY ${gen_dir})
  # Fallback dependencies for generators without depfile support.
  file(GLOB shader_includes CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/shaders/include/*.h ${PROJECT_SOURCE_DIR}/shaders/include/*.glsl
       ${PROJECT_SOURCE_DIR}/engine/gpu/include_shared/*.h)
  set(spv_files)
  set(bases)
  foreach(src ${ARG_SHADERS})
    get_filename_component(src_abs ${src} ABSOLUTE BASE_DIR ${PROJECT_SOURCE_DIR})
    get_filename_component(fname ${src_abs} NAME)          # mesh.vert.glsl
    string(REGEX REPLACE "\\.glsl$" "" base ${fname})       # mesh.vert
    string(REGEX MATCH "[^.]+$" stage ${base})              # vert
    if(NOT stage MATCHES "^(vert|frag|comp|geom|tesc|tese)$")
      message(FATAL_ERROR "shader ${fname}: name must end in .<stage>.glsl")
    endif()
    set(spv ${gen_dir}/${base}.spv)
    set(depfile_args)
    if(CMAKE_GENERATOR MATCHES "Ninja|Makefiles")
      set(depfile_args DEPFILE ${spv}.d)
    endif()
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -S ${stage} --quiet
              -I${PROJECT_SOURCE_DIR}/shaders/include -I${PROJECT_SOURCE_DIR}/engine/gpu/include_shared
              --depfile ${spv}.d -o ${spv} ${src_abs}
      DEPENDS ${src_abs} ${shader_includes}
      ${depfile_args}
      COMMENT "glslang ${fname}"
      VERBATIM)
    list(APPEND spv_files ${spv})
    list(APPEND bases ${base})
  endforeach()
  # The list travels to the script comma-separated: a ';' inside a custom
  # command argument would be split into separate arguments.
  string(REPLACE ";" "," bases_csv "${bases}")
  set(out_cpp ${gen_dir}/shader_blobs.cpp)
  add_custom_command(
    OUTPUT ${out_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out_cpp} -DGEN_DIR=${gen_dir} -DBASES=${bases_csv}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    DEPENDS ${spv_files} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    COMMENT "Embedding SPIR-V"
    VERBATIM)
  target_sources(${target} PRIVATE ${out_cpp})
endfunction()
