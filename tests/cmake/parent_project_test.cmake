# ctest: configures tests/cmake/parent_project (which add_subdirectory()s the repository) in a
# scratch folder, compiles its one host file, and checks what the host got: no Specula tools or
# tests, no -Werror or sanitizer flags on the host's compile line, Specula's include paths.
#   cmake -DSPECULA_ROOT=<repo> -DWORK=<scratch folder> -P parent_project_test.cmake
file(REMOVE_RECURSE "${WORK}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SPECULA_ROOT}/tests/cmake/parent_project -B ${WORK} -G Ninja
          -DSPECULA_ROOT=${SPECULA_ROOT} -DCMAKE_BUILD_TYPE=Release
  RESULT_VARIABLE configured OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "the parent project does not configure:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target
                        CMakeFiles/host_probe_user.dir/host_probe_user.cpp.o
                RESULT_VARIABLE built OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "the host's file does not compile against Specula's headers:\n${out}\n${err}")
endif()
file(READ ${WORK}/compile_commands.json commands)
string(JSON count LENGTH "${commands}")
math(EXPR last "${count} - 1")
set(host_line "")
foreach(i RANGE ${last})
  string(JSON file GET "${commands}" ${i} file)
  if(file MATCHES "host_probe_user.cpp$")
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
file(REMOVE_RECURSE "${WORK}")
message(STATUS "parent project: configured, the host file compiled with its own flags")
