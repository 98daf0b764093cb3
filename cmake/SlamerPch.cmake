# Precompiled headers: the standard library, Eigen and (for tests) GoogleTest
# parsed once a tree instead of once a unity batch. Parsing them costs 3.5 s a
# translation unit at -O2 and loading the precompiled header 0.7 s (GCC 12),
# and most of our ~100 batches include them. One header for the libraries and
# programs, one with GoogleTest for the tests (its macros stay out of our
# libraries); every target reuses one of the two (REUSE_FROM), so each is
# compiled once. GCC only: clang rejects a precompiled header whose command
# line macros differ from the target's, and the fuzz tree is small.
# GCC uses a precompiled header only where the predefined macros that its
# headers test match: -Wpedantic (slamer_warnings) and -pthread (LCM's
# pkg-config flags: _REENTRANT) are on every target of ours and on the two
# headers alike. -Winvalid-pch in CMAKE_CXX_FLAGS shows a header not used.
option(SLAMER_PCH "Precompile the standard library, Eigen and GoogleTest headers (GCC)" ON)
set(SLAMER_PCH_ENABLED OFF)
if(SLAMER_PCH AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(SLAMER_PCH_ENABLED ON)
  set(slamer_pch_headers
      <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <cstring> <deque> <filesystem>
      <fstream> <functional> <iostream> <limits> <map> <memory> <numbers> <optional> <random>
      <set> <sstream> <stdexcept> <string> <string_view> <thread> <utility> <vector>
      <Eigen/Core> <Eigen/Geometry>)
  add_library(slamer_pch_flags INTERFACE)
  target_compile_options(slamer_pch_flags INTERFACE -pthread)
  file(WRITE ${CMAKE_BINARY_DIR}/slamer_pch_empty.cpp "// the precompiled headers' own translation unit\n")
  add_library(slamer_pch_code STATIC ${CMAKE_BINARY_DIR}/slamer_pch_empty.cpp)
  target_link_libraries(slamer_pch_code PRIVATE Eigen3::Eigen slamer_warnings slamer_pch_flags)
  target_precompile_headers(slamer_pch_code PRIVATE ${slamer_pch_headers})
  add_library(slamer_pch_test STATIC ${CMAKE_BINARY_DIR}/slamer_pch_empty.cpp)
  target_link_libraries(slamer_pch_test PRIVATE Eigen3::Eigen GTest::gtest slamer_warnings slamer_pch_flags)
  target_precompile_headers(slamer_pch_test PRIVATE ${slamer_pch_headers} <gtest/gtest.h>)
  target_compile_options(slamer_pch_test PRIVATE ${SLAMER_TEST_COMPILE_OPTIONS})
endif()

# slamer_use_pch(TARGET code|test): TARGET reuses the libraries' or the tests' precompiled header.
function(slamer_use_pch name kind)
  if(SLAMER_PCH_ENABLED)
    target_precompile_headers(${name} REUSE_FROM slamer_pch_${kind})
    # Include paths of the precompiled headers, for a target that does not link them itself.
    target_link_libraries(${name} PRIVATE Eigen3::Eigen slamer_pch_flags)
  endif()
endfunction()
