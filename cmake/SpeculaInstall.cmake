# `cmake --install`: the runtime as a CMake package (find_package(Specula 0.3 CONFIG) gives
# Specula::runtime), its headers and GLSL under include/specula/, the tools under bin/.
#
# Exported: the runtime and the four engine modules it is made of (core, math, image, gpu).
# Their link interface names only Threads, GLM, libepoxy and nlohmann_json, which
# SpeculaConfig.cmake finds again on the host's side; our warning flags are BUILD_INTERFACE
# only, so nothing of our build settings reaches a host.
include(CMakePackageConfigHelpers)

set(SPECULA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Specula)
set(runtime_modules specula_core specula_math specula_image specula_gpu)
foreach(module ${runtime_modules})
  string(REPLACE "specula_" "" short ${module})
  set_target_properties(${module} PROPERTIES EXPORT_NAME ${short})
endforeach()
install(TARGETS specula_runtime ${runtime_modules}
        EXPORT SpeculaTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/specula)
install(EXPORT SpeculaTargets NAMESPACE Specula:: DESTINATION ${SPECULA_CMAKE_DIR})

# Headers keep their repository paths (#include "components/reflection_probe/...") so the
# installed tree and the source tree compile alike. GLSL travels too: a host's shader
# #includes the lookups. The tools' folders (ECS integration, writers, scene, rendering) stay
# out.
foreach(folder engine/core engine/math engine/image engine/gpu components/reflection_probe)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/specula/${folder}
          FILES_MATCHING PATTERN "*.h" PATTERN "*.glsl" PATTERN "*.vert" PATTERN "*.frag"
                         PATTERN "*.comp"
          PATTERN "system" EXCLUDE PATTERN "writer" EXCLUDE)
endforeach()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/SpeculaConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/SpeculaConfig.cmake
                              INSTALL_DESTINATION ${SPECULA_CMAKE_DIR})
# 0.x: a minor version may change the API, so 0.3 accepts 0.3.z only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/SpeculaConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/SpeculaConfig.cmake
              ${PROJECT_BINARY_DIR}/SpeculaConfigVersion.cmake
        DESTINATION ${SPECULA_CMAKE_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/specula)

if(SPECULA_BUILD_TOOLS)
  install(TARGETS specula-cook specula-sandbox RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
