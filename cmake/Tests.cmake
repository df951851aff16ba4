# Test executables: GoogleTest (+ rapidcheck) discovered into ctest with a label. Properties run with a fixed
# rapidcheck seed so CI never flakes; set RC_PARAMS yourself to explore other seeds.
set(HPSF_RAPIDCHECK_PARAMS "seed=20261121 max_success=500" CACHE STRING "RC_PARAMS for property tests run by ctest")

if(NOT HPSF_BUILD_TESTING)
  function(hpsf_add_test name)
  endfunction()
  return()
endif()

function(hpsf_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBRARIES} rapidcheck_gtest rapidcheck GTest::gtest_main)
  gtest_discover_tests(${name}
    PROPERTIES ENVIRONMENT "RC_PARAMS=${HPSF_RAPIDCHECK_PARAMS}"
    DISCOVERY_TIMEOUT 60)
  # Labels and environments are applied after discovery, from the list of discovered tests: a list value passed
  # through gtest_discover_tests' PROPERTIES loses its semicolons, and a test would get only the first label.
  # Each test gets a temporary folder of its own (TMPDIR for std::filesystem, TEST_TMPDIR for GoogleTest), so
  # tests that ctest runs side by side never share a file name.
  set(label_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  set(temp_root ${CMAKE_CURRENT_BINARY_DIR}/test-tmp/${name})
  file(WRITE ${label_file}
    "foreach(test IN LISTS ${name}_TESTS)\n"
    "  string(MAKE_C_IDENTIFIER \"\${test}\" folder)\n"
    "  file(MAKE_DIRECTORY \"${temp_root}/\${folder}\")\n"
    "  set_tests_properties(\${test} PROPERTIES LABELS [==[${ARG_LABELS}]==]\n"
    "    ENVIRONMENT \"RC_PARAMS=${HPSF_RAPIDCHECK_PARAMS};TMPDIR=${temp_root}/\${folder};TEST_TMPDIR=${temp_root}/\${folder}\")\n"
    "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${label_file})
endfunction()
