# specula_embed_shaders(TARGET FUNCTION FOLDER...): compiles every GLSL file (*.glsl, *.glsl.h,
# *.vert, *.frag, *.comp) under the FOLDERs (relative to the repository root) into TARGET, as
# specula::gpu::embedded::FUNCTION() (engine/gpu/shader_files.h). The table is regenerated
# when a file changes; a new file is found at the next build (CONFIGURE_DEPENDS).
function(specula_embed_shaders target function)
  specula_embed_files(${target} ${function} "*.glsl;*.glsl.h;*.vert;*.frag;*.comp" ${ARGN})
endfunction()

# specula_embed_files(TARGET FUNCTION PATTERNS FOLDER...): the same for any text files matching
# PATTERNS (a list of globs), e.g. the manifests' JSON Schemas the runtime reads.
function(specula_embed_files target function patterns)
  set(files)
  foreach(folder ${ARGN})
    foreach(pattern ${patterns})
      file(GLOB_RECURSE found CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}
           ${PROJECT_SOURCE_DIR}/${folder}/${pattern})
      list(APPEND files ${found})
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES files)
  list(SORT files)
  list(TRANSFORM files PREPEND ${PROJECT_SOURCE_DIR}/ OUTPUT_VARIABLE inputs)
  string(REPLACE ";" "|" joined "${files}")
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${function}.cpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DNAME=${function} -DOUT=${out}
            -DFILES=${joined} -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    DEPENDS ${inputs} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    COMMENT "Embedding ${function} (${target})"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()
