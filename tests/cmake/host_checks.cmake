# Checks both host tests (parent_project_test.cmake, installed_package_test.cmake) make of the
# program a host built against Specula::runtime.

cmake_policy(SET CMP0057 NEW) # if(... IN_LIST ...) in a -P script

# The tool dependencies that must never reach a host through the runtime.
set(SPECULA_TOOL_LIBRARIES embree tbb OpenImageIO OpenEXR Imath draco tinygltf glfw spdlog fmt
                           CLI11 Eigen)

# Fails when the executable needs a shared library of a tool dependency, other than the ones
# the host itself chose (further arguments, e.g. glfw for a host with a window); NEEDED_OUT gets
# the list of what it needs (the note reports it).
function(specula_check_needed exe needed_out)
  set(host_own ${ARGN})
  execute_process(COMMAND readelf -d ${exe} RESULT_VARIABLE rc OUTPUT_VARIABLE dyn ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "readelf -d ${exe} failed: ${err}")
  endif()
  string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*\\[([^]\n]+)\\]" lines "${dyn}")
  set(needed)
  foreach(line ${lines})
    string(REGEX REPLACE ".*\\[([^]]+)\\].*" "\\1" lib "${line}")
    list(APPEND needed ${lib})
    foreach(tool ${SPECULA_TOOL_LIBRARIES})
      string(TOLOWER "${lib}" lower)
      string(TOLOWER "${tool}" tool_lower)
      if(lower MATCHES "${tool_lower}" AND NOT tool IN_LIST host_own)
        message(FATAL_ERROR "the host's program needs ${lib}: a tool dependency reached it")
      endif()
    endforeach()
  endforeach()
  set(${needed_out} "${needed}" PARENT_SCOPE)
endfunction()

# Runs the host's read_probe on the committed face-res 2 probe and on a missing one: the first
# prints its face size and layers, the second is an error value naming the file.
function(specula_run_read_probe exe root)
  set(manifest ${root}/tests/fuzz/data/probe/manifest.json)
  execute_process(COMMAND ${exe} ${manifest} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^face_res 2 layers 6 radiance")
    message(FATAL_ERROR "read_probe ${manifest}: status ${rc}\n${out}${err}")
  endif()
  execute_process(COMMAND ${exe} ${root}/missing/manifest.json RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "missing/manifest.json")
    message(FATAL_ERROR "read_probe of a missing probe: status ${rc}, '${err}'")
  endif()
endfunction()
