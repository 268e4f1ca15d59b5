# ctest: configures tests/cmake/parent_project (which add_subdirectory()s the repository) in a
# scratch folder with Clang when there is one (the runtime builds with GCC and Clang), builds the
# runtime and a host program on it, and checks what the host got: no Specula tools, tests or
# tool packages, no -Werror or sanitizer flags on the host's compile line, and a program that
# needs none of the tools' shared libraries and reads a cooked probe.
#   cmake -DSPECULA_ROOT=<repo> -DWORK=<scratch folder> -P parent_project_test.cmake
include(${CMAKE_CURRENT_LIST_DIR}/host_checks.cmake)
file(REMOVE_RECURSE "${WORK}")
set(compiler)
find_program(CLANGXX clang++)
if(CLANGXX)
  set(compiler -DCMAKE_CXX_COMPILER=${CLANGXX})
endif()
# Debug: no optimisation, the quickest build of the runtime's sources.
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SPECULA_ROOT}/tests/cmake/parent_project -B ${WORK} -G Ninja
          -DSPECULA_ROOT=${SPECULA_ROOT} -DCMAKE_BUILD_TYPE=Debug ${compiler}
  RESULT_VARIABLE configured OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "the parent project does not configure:\n${out}\n${err}")
endif()
# The runtime alone never looks for a tool's package.
file(READ ${WORK}/CMakeCache.txt cache)
foreach(package embree TBB OpenImageIO draco glfw3 spdlog CLI11 Eigen3)
  if(cache MATCHES "\n${package}_DIR:")
    message(FATAL_ERROR "configuring the runtime looked for the tools' package ${package}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target read_probe
                RESULT_VARIABLE built OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "the runtime or the host's program does not build:\n${out}\n${err}")
endif()
file(READ ${WORK}/compile_commands.json commands)
string(JSON count LENGTH "${commands}")
math(EXPR last "${count} - 1")
set(host_line "")
foreach(i RANGE ${last})
  string(JSON file GET "${commands}" ${i} file)
  if(file MATCHES "read_probe.cpp$")
    string(JSON host_line GET "${commands}" ${i} command)
  endif()
endforeach()
if(host_line STREQUAL "")
  message(FATAL_ERROR "no compile line for the host's file in compile_commands.json")
endif()
foreach(flag -Werror -fsanitize -Wpedantic)
  string(FIND "${host_line}" "${flag}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "Specula hands ${flag} to its host: ${host_line}")
  endif()
endforeach()
specula_check_needed(${WORK}/read_probe needed)
specula_run_read_probe(${WORK}/read_probe ${SPECULA_ROOT})
file(REMOVE_RECURSE "${WORK}")
message(STATUS "parent project (${CLANGXX}): the runtime and the host's program built with the "
               "host's flags; it needs ${needed}")
