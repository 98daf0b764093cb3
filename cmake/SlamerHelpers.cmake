# Small helpers so every target gets the same flags and include layout.

# slamer_library(NAME SOURCES... [DEPS ...]): a static library of our own code.
function(slamer_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE slamer_warnings)
  slamer_use_pch(${name} code)
endfunction()

# slamer_executable(NAME SOURCES... [DEPS ...]): a program, installed to bin/.
function(slamer_executable name)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} slamer_warnings)
  slamer_use_pch(${name} code)
  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${name} RUNTIME DESTINATION bin)
  endif()
endfunction()

# slamer_test(NAME SOURCES... [DEPS ...] [LABELS ...] [REAL_TIME]): a GoogleTest program run by ctest.
# REAL_TIME: its tests run a live stack that must keep up with 40 Hz scans (a simulator or
# lcm-logplayer at real time); no two run at once (resource lock `real_time_stack`), and under
# the sanitizers each takes two of ctest's -j slots (PROCESSORS 2: on a 2-core machine nothing
# runs beside it). There the stack alone needs more than one core (the recognizer 14 ms a scan,
# the localizer 5.5 ms, at 40 Hz): beside another test its scans went late, the recognizer
# fell seconds behind and the localizer rightly said "no LINE_OBJECTS", for no fault of the code.
# Optimized, the whole stack needs a third to a half of a core: one other test may run beside it.
function(slamer_test name)
  cmake_parse_arguments(ARG "REAL_TIME" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main slamer_warnings)
  slamer_use_pch(${name} test)
  target_compile_options(${name} PRIVATE ${SLAMER_TEST_COMPILE_OPTIONS})
  target_compile_definitions(${name} PRIVATE SLAMER_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             SLAMER_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  set(lock)
  if(ARG_REAL_TIME)
    set(lock RESOURCE_LOCK real_time_stack)
    if(SLAMER_SANITIZE)
      list(APPEND lock PROCESSORS 2)
    endif()
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT} ${lock})
endfunction()

# slamer_fuzzer(NAME SOURCE [DEPS ...]): a libFuzzer target, only with -DSLAMER_FUZZ=ON.
function(slamer_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  if(NOT SLAMER_FUZZ)
    return()
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} slamer_warnings)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  add_dependencies(fuzz_targets ${name})
endfunction()

# `make fuzz_targets` builds every fuzzer (only with -DSLAMER_FUZZ=ON).
if(NOT TARGET fuzz_targets)
  add_custom_target(fuzz_targets)
endif()
