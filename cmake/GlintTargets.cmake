# glint_library(NAME SOURCES... DEPS ...): one static library per folder of renderer/, with the
# project's warning set. Dependencies point downward only (docs/architecture.md).
function(glint_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(glint_${name} STATIC ${ARG_SOURCES})
  target_include_directories(glint_${name} PUBLIC ${PROJECT_SOURCE_DIR}/renderer)
  target_link_libraries(glint_${name} PUBLIC ${ARG_DEPS})
  if(GLINT_PYTHON)  # linked into the Python module too (cmake/GlintPython.cmake)
    set_target_properties(glint_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  glint_warnings(glint_${name})
endfunction()

function(glint_warnings target)
  # -Wno-restrict: GCC 12 reports false positives on `"literal" + std::string` (GCC bug 105651).
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Werror=return-type
                                           $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  # Glint never reads errno after maths calls: without this, every std::sqrt carries a branch
  # to the library call that would set it, and loops with square roots do not vectorise.
  target_compile_options(${target} PRIVATE -fno-math-errno)
  # No fused multiply-adds formed from a * b + c: files built for AVX2 or AVX-512 (and
  # GLINT_NATIVE_ARCH builds) must round as the baseline build does, so that an image does not
  # depend on the instruction set (geometry/shape_lanes.h).
  target_compile_options(${target} PRIVATE -ffp-contract=off)
  if(GLINT_NATIVE_ARCH)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()

# Hardening builds (docs/hardening.md). Directory-wide, so every Glint target is instrumented;
# the Debian libraries (Embree, TBB, OIIO, ...) stay as built, which ASan and UBSan tolerate.
if(GLINT_SANITIZE)
  # No recovery: a UBSan report must fail the test that triggered it, not scroll past.
  add_compile_options(-fsanitize=${GLINT_SANITIZE} -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${GLINT_SANITIZE})
endif()
if(GLINT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "GLINT_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
  endif()
  # Coverage feedback from every library the loader calls; the no-link runtime satisfies the
  # instrumentation in executables other than the fuzzer.
  add_compile_options(-fsanitize=fuzzer-no-link)
  add_link_options(-fsanitize=fuzzer-no-link)
endif()
