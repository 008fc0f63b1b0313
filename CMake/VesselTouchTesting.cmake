# vtouch_add_gtest(NAME <name> SOURCES <files...> LIBRARIES <targets...> [LABELS <labels...>])
# Builds one GoogleTest executable and registers each TEST() with ctest under one label: 'unit'
# (default) or 'threads' for the tests of threaded code (also run by the TSan build).
include(GoogleTest)

function(vtouch_add_gtest)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;LIBRARIES;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBRARIES} GTest::gtest GTest::gtest_main)
  vtouch_target_warnings(${ARG_NAME})
  target_compile_definitions(${ARG_NAME} PRIVATE
    VTOUCH_SHARED_DATA_DIR="${VESSELTOUCH_SHARED_DATA_DIR}")
  list(LENGTH ARG_LABELS _count)
  if(_count GREATER 1)
    # gtest_discover_tests flattens a label list on its way to the test script (CMake 3.25).
    message(FATAL_ERROR "vtouch_add_gtest(${ARG_NAME}): give one label (unit or threads)")
  endif()
  gtest_discover_tests(${ARG_NAME}
    PROPERTIES LABELS "${ARG_LABELS}"
    DISCOVERY_TIMEOUT 60)
endfunction()
