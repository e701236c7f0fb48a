# One static library per pipeline stage (see DESIGN.md): sources under src/<stage>/,
# includes read from src/ ("#include \"core/image.h\"").
function(inet_stage_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  inet_set_warnings(${name})
endfunction()

# One GoogleTest executable per test file, registered with CTest under a label.
function(inet_stage_test name)
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES;DEPS" ${ARGN})
  if(NOT ARG_LABEL)
    set(ARG_LABEL unit)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    INET_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    INET_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared"
    INET_BINARY="$<TARGET_FILE:interiornet>")
  inet_set_warnings(${name})
  if(TARGET inet_test_pch)
    target_precompile_headers(${name} REUSE_FROM inet_test_pch)
  endif()
  gtest_discover_tests(${name} PROPERTIES LABELS ${ARG_LABEL} DISCOVERY_TIMEOUT 60)
endfunction()
