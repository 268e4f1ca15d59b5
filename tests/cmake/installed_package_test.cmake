# ctest: installs the build to a scratch prefix and builds a host project against it
# (tests/cmake/installed_package: find_package(Specula 0.3 CONFIG REQUIRED), Specula::runtime),
# then checks what the host got: the exported targets name no tool dependency, the program needs
# none of the tools' shared libraries and reads a cooked probe, the installed headers hold no
# tool code, and the version rule (0.3 accepts 0.3.z only) holds.
#   cmake -DSPECULA_ROOT=<repo> -DBUILD=<Specula's build> -DWORK=<scratch folder>
#         -P installed_package_test.cmake
include(${CMAKE_CURRENT_LIST_DIR}/host_checks.cmake)
file(REMOVE_RECURSE "${WORK}")
set(prefix ${WORK}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} failed: ${err}")
endif()

file(GLOB targets_files ${prefix}/lib/cmake/Specula/SpeculaTargets*.cmake)
if(NOT targets_files)
  message(FATAL_ERROR "no SpeculaTargets.cmake under ${prefix}/lib/cmake/Specula")
endif()
foreach(f ${targets_files})
  file(READ ${f} text)
  foreach(tool ${SPECULA_TOOL_LIBRARIES} specula_warnings Werror)
    string(FIND "${text}" "${tool}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "the exported targets (${f}) mention ${tool}")
    endif()
  endforeach()
endforeach()
foreach(tool_header engine/scene engine/render engine/raytrace engine/image_io engine/log
                    engine/context components/reflection_probe/system assetcooker sandbox)
  if(EXISTS ${prefix}/include/specula/${tool_header})
    message(FATAL_ERROR "the tools' ${tool_header} was installed with the runtime")
  endif()
endforeach()
foreach(needed_file include/specula/components/reflection_probe/distance/shaders/distance_lookup.glsl.h
                    include/specula/engine/image/ktx2.h bin/specula-cook)
  if(NOT EXISTS ${prefix}/${needed_file})
    message(FATAL_ERROR "cmake --install did not install ${needed_file}")
  endif()
endforeach()

function(configure_host want out_dir result_var)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${SPECULA_ROOT}/tests/cmake/installed_package -B ${out_dir} -G Ninja
            -DCMAKE_PREFIX_PATH=${prefix} -DSPECULA_WANT_VERSION=${want} -DCMAKE_BUILD_TYPE=Release
            -DHOST_SOURCE=${SPECULA_ROOT}/tests/cmake/host/read_probe.cpp
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${result_var} ${rc} PARENT_SCOPE)
  set(configure_log "${out}${err}" PARENT_SCOPE)
endfunction()
foreach(incompatible 0.4 1.0)
  configure_host(${incompatible} ${WORK}/want-${incompatible} rc)
  if(rc EQUAL 0)
    message(FATAL_ERROR "find_package(Specula ${incompatible}) accepted version 0.3")
  endif()
endforeach()
configure_host(0.3 ${WORK}/host rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the host does not configure against the installed package:\n${configure_log}")
endif()
# Specula's source tree must not be needed: the host's only include path is the prefix's.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/host RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the host does not build against the installed package:\n${out}\n${err}")
endif()
file(READ ${WORK}/host/build.ninja ninja)
string(FIND "${ninja}" "-I${SPECULA_ROOT}" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "the installed package points the host into the source tree")
endif()
specula_check_needed(${WORK}/host/read_probe needed)
specula_run_read_probe(${WORK}/host/read_probe ${SPECULA_ROOT})

# examples/minimal as its README builds it: a separate project against the prefix, run headless
# on the committed probe (tests/probe/host_example_test.cpp holds its image to the twin).
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SPECULA_ROOT}/examples/minimal -B ${WORK}/minimal -G Ninja
          -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/minimal RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "examples/minimal does not build against the installed package:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK}/minimal/minimal ${SPECULA_ROOT}/tests/fuzz/data/probe/manifest.json
                        --headless --out ${WORK}/minimal.ppm --size 64 48
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/minimal.ppm)
  message(FATAL_ERROR "examples/minimal (installed) did not render: status ${rc}\n${out}${err}")
endif()
specula_check_needed(${WORK}/minimal/minimal example_needed glfw) # its window is its own
file(REMOVE_RECURSE "${WORK}")
message(STATUS "installed package: found as 0.3, refused as 0.4 and 1.0; the host's program "
               "needs ${needed}; examples/minimal needs ${example_needed}")
