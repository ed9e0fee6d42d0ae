# Helpers that give every test and benchmark the same shape.

include(GoogleTest)

# irloc_add_test(NAME <name> SOURCES <files...> LIBS <targets...> [LABELS <labels...>] [ORACLE] [ONE_PROCESS])
# A GoogleTest executable linked with the test support library (allocation counter, child processes).
# make test runs each suite once, in one of its two builds: the suites labelled `algo` (the per-frame
# code) and `sanitized` (the file readers, the serial protocols) in the sanitizer build, except those
# also labelled `scene` (rendered drives and statistical checks, minutes under the sanitizers); every
# other suite in the native release build. There the sanitizer build's suites are left out of `all` and
# of ctest (build one by name to run it optimized); the aarch64 build registers the `algo` suites
# for make test-cross. `test_programs` builds the test executables of the build it is in.
# ORACLE marks a test that needs OpenCV or AprilTag: it is not built for aarch64.
# ONE_PROCESS registers the binary as one ctest test, for suites whose SetUpTestSuite renders a
# drive that every case shares (one ctest test per case would render it once per case).
# Label `algo` marks tests of algo/ alone; `make test-cross` runs those under qemu.
function(irloc_add_test)
  cmake_parse_arguments(ARG "ORACLE;ONE_PROCESS" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  if(ARG_ORACLE AND CMAKE_CROSSCOMPILING)
    return()
  endif()
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} irloc_test_support GTest::gtest_main)
  target_precompile_headers(${ARG_NAME} REUSE_FROM irloc_test_support)
  set(runs_under_sanitizers FALSE)
  if(("algo" IN_LIST ARG_LABELS OR "sanitized" IN_LIST ARG_LABELS) AND NOT "scene" IN_LIST ARG_LABELS)
    set(runs_under_sanitizers TRUE)
  endif()
  if((IRLOC_SANITIZE AND NOT runs_under_sanitizers)
     OR (NOT IRLOC_SANITIZE AND NOT CMAKE_CROSSCOMPILING AND runs_under_sanitizers))
    set_target_properties(${ARG_NAME} PROPERTIES EXCLUDE_FROM_ALL TRUE)
    return()
  endif()
  set_property(GLOBAL APPEND PROPERTY IRLOC_TEST_EXECUTABLES ${ARG_NAME})
  # The aarch64 build runs only the algo suites, under qemu-user; ctest's test discovery would run
  # every binary there, and those linking Debian's arm64 libcamera hang at start in qemu
  # (liblttng-ust). The others are built, not registered.
  if(CMAKE_CROSSCOMPILING AND NOT "algo" IN_LIST ARG_LABELS)
    return()
  endif()
  if(ARG_ONE_PROCESS)
    add_test(NAME ${ARG_NAME} COMMAND ${ARG_NAME} WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(${ARG_NAME} PROPERTIES LABELS "${ARG_LABELS}")
    return()
  endif()
  gtest_discover_tests(${ARG_NAME}
    DISCOVERY_MODE PRE_TEST
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    PROPERTIES LABELS "${ARG_LABELS}")
endfunction()

# irloc_optimize_in_debug(<sources...>): sources that render or solve at length are compiled -O2 in
# Debug too (the sanitizer build of make test; ASan and assertions stay on; UBSan, which checks the
# product's integer code, is left out of these, where it doubled the compile time). They do not
# take their target's precompiled header there, which is made at -O0 (GCC refuses it across -O).
function(irloc_optimize_in_debug)
  set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS "$<$<CONFIG:Debug>:-O2;-fno-sanitize=undefined>")
  if(CMAKE_BUILD_TYPE STREQUAL "Debug")
    set_source_files_properties(${ARGN} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

# irloc_add_benchmark(NAME <name> JSON <stem> SOURCES <files...> LIBS <targets...>)
# A Google Benchmark executable; `make bench` builds and runs it and writes build/bench/<stem>.json.
# Benchmarks compare against OpenCV/AprilTag, so they are host-only and not sanitized; they are
# not part of the default build (make test's time budget), only of the `bench` target.
function(irloc_add_benchmark)
  cmake_parse_arguments(ARG "" "NAME;JSON" "SOURCES;LIBS" ${ARGN})
  if(CMAKE_CROSSCOMPILING OR IRLOC_SANITIZE)
    return()
  endif()
  add_executable(${ARG_NAME} EXCLUDE_FROM_ALL ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} benchmark::benchmark)
  set_target_properties(${ARG_NAME} PROPERTIES IRLOC_BENCH_JSON ${ARG_JSON})
  set_property(GLOBAL APPEND PROPERTY IRLOC_BENCHMARKS ${ARG_NAME})
endfunction()

# Defines the `test_programs` target (every test executable of this build) once all are known.
function(irloc_finish_tests)
  get_property(executables GLOBAL PROPERTY IRLOC_TEST_EXECUTABLES)
  add_custom_target(test_programs DEPENDS ${executables})
endfunction()

# Defines the `bench` target once every benchmark is known.
function(irloc_finish_benchmarks)
  get_property(benchmarks GLOBAL PROPERTY IRLOC_BENCHMARKS)
  set(out ${CMAKE_BINARY_DIR}/bench)
  set(commands COMMAND ${CMAKE_COMMAND} -E make_directory ${out})
  foreach(benchmark IN LISTS benchmarks)
    list(APPEND commands COMMAND $<TARGET_FILE:${benchmark}>
         --benchmark_out=${out}/$<TARGET_PROPERTY:${benchmark},IRLOC_BENCH_JSON>.json --benchmark_out_format=json)
  endforeach()
  add_custom_target(bench ${commands} DEPENDS ${benchmarks} USES_TERMINAL
                    COMMENT "Running benchmarks; JSON in ${out}")
endfunction()
