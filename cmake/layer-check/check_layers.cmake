# Builds the layer probes of tests/CMakeLists.txt in the project's build tree: each is one tiny
# source compiled with the usage requirements of a real layer target. The right-way probes must
# build; each wrong-way probe must fail on its missing header. Run by ctest as
# layers.wrong_way_include, with BINARY_DIR, CONFIG, RIGHT (targets, comma-separated) and WRONG
# (target:header pairs, comma-separated).
function(build target)
  execute_process(
    COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} --config ${CONFIG} --target ${target}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  set(rc ${rc} PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
endfunction()

string(REPLACE "," ";" RIGHT "${RIGHT}")
string(REPLACE "," ";" WRONG "${WRONG}")
if(NOT RIGHT OR NOT WRONG)
  message(FATAL_ERROR "nothing to check: RIGHT='${RIGHT}' WRONG='${WRONG}'")
endif()

foreach(target IN LISTS RIGHT)
  build(${target})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${target}: a right-way include does not build:\n${out}")
  endif()
  message(STATUS "${target}: builds")
endforeach()

foreach(pair IN LISTS WRONG)
  string(REPLACE ":" ";" pair ${pair})
  list(GET pair 0 target)
  list(GET pair 1 header)
  build(${target})
  if(rc EQUAL 0)
    message(FATAL_ERROR "${target}: including ${header} compiled: the layers can be crossed")
  endif()
  # GCC: "bounce/x.h: No such file or directory"; Clang: "'bounce/x.h' file not found".
  string(REPLACE "." "\\." header_regex ${header})
  if(NOT out MATCHES "${header_regex}'?:? (No such file or directory|file not found)")
    message(FATAL_ERROR "${target}: failed, but not on the missing header ${header}:\n${out}")
  endif()
  message(STATUS "${target}: ${header} is not found, as it must not be")
endforeach()
