# Compiles every shader under shaders/ to SPIR-V with glslc and embeds the words in the
# library, so `bounce` needs no files beside it. A shader is looked up by its path without the
# extension, e.g. "rt/trace_rays" (see src/vk/shader_registry.h). Graphics stages keep their
# extension, since a pass's vertex and fragment shaders share a base name: "passes/vbuffer.vert";
# so do the ray-tracing stages (.rgen, .rchit, .rahit, .rmiss): "rt/bench_rays.rgen".
file(GLOB_RECURSE BOUNCE_SHADER_SOURCES CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/shaders/*.comp ${PROJECT_SOURCE_DIR}/shaders/*.vert ${PROJECT_SOURCE_DIR}/shaders/*.frag
  ${PROJECT_SOURCE_DIR}/shaders/*.rgen ${PROJECT_SOURCE_DIR}/shaders/*.rchit ${PROJECT_SOURCE_DIR}/shaders/*.rahit
  ${PROJECT_SOURCE_DIR}/shaders/*.rmiss)

add_executable(bounce_embed_spirv ${PROJECT_SOURCE_DIR}/cmake/embed_spirv.cpp)

set(spv_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
set(spv_files)
set(spv_names)
foreach(src ${BOUNCE_SHADER_SOURCES})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR}/shaders ${src})
  string(REGEX REPLACE "\\.comp$" "" name ${rel})
  set(spv ${spv_dir}/${rel}.spv)
  get_filename_component(spv_parent ${spv} DIRECTORY)
  add_custom_command(
    OUTPUT ${spv}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${spv_parent}
    COMMAND ${GLSLC} --target-env=vulkan1.3 -O -Werror -I ${PROJECT_SOURCE_DIR}/shaders
            -MD -MF ${spv}.d -o ${spv} ${src}
    DEPENDS ${src}
    DEPFILE ${spv}.d
    COMMENT "glslc ${rel}"
    VERBATIM)
  list(APPEND spv_files ${spv})
  list(APPEND spv_names ${name})
endforeach()

set(BOUNCE_SHADER_EMBED_CPP ${CMAKE_CURRENT_BINARY_DIR}/generated/embedded_shaders.cpp)
set(manifest ${CMAKE_CURRENT_BINARY_DIR}/generated/shader_manifest.txt)
set(manifest_lines "")
foreach(name spv IN ZIP_LISTS spv_names spv_files)
  string(APPEND manifest_lines "${name} ${spv}\n")
endforeach()
file(GENERATE OUTPUT ${manifest} CONTENT "${manifest_lines}")
add_custom_command(
  OUTPUT ${BOUNCE_SHADER_EMBED_CPP}
  COMMAND bounce_embed_spirv ${manifest} ${BOUNCE_SHADER_EMBED_CPP}
  DEPENDS bounce_embed_spirv ${spv_files} ${manifest}
  COMMENT "Embedding SPIR-V"
  VERBATIM)
add_custom_target(bounce_shaders DEPENDS ${BOUNCE_SHADER_EMBED_CPP})
