# glint_library(NAME SOURCES... DEPS ...): one static library per folder of renderer/, with the
# project's warning set. Dependencies point downward only (docs/architecture.md).
function(glint_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(glint_${name} STATIC ${ARG_SOURCES})
  target_include_directories(glint_${name} PUBLIC ${PROJECT_SOURCE_DIR}/renderer)
  target_link_libraries(glint_${name} PUBLIC ${ARG_DEPS})
  glint_warnings(glint_${name})
endfunction()

function(glint_warnings target)
  # -Wno-restrict: GCC 12 reports false positives on `"literal" + std::string` (GCC bug 105651).
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-restrict -Werror=return-type)
  if(GLINT_NATIVE_ARCH)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
