# examples/consumer built as a team would build it, then run: against hpsf installed into a scratch prefix
# (MODE installed: cmake --install, then find_package(hpsf)), against hpsf's sources (MODE subdirectory:
# add_subdirectory), or fetched from its repository at the commit checked out (MODE fetchcontent: FetchContent).
# The consumer compiles with -ffp-contract=fast and checks its keys against hpsf::core's, its table with the
# checker, and that a planted lost update is named; it captures its table through the installed header, which
# hpsf judge then passes.
# -DSOURCE=<hpsf source tree> -DBUILD=<hpsf build tree> -DOUT=<scratch folder>
# -DMODE=installed|subdirectory|fetchcontent
file(REMOVE_RECURSE ${OUT})
set(consumer_args)
if(MODE STREQUAL "installed")
  execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${OUT}/prefix
    RESULT_VARIABLE code OUTPUT_QUIET)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "cmake --install ${BUILD} failed: ${code}")
  endif()
  foreach(installed bin/hpsf lib/cmake/hpsf/hpsfConfig.cmake include/hpsf/vulkan/shaders/table_interface.glsl
          include/hpsf/core/capture_writer.h
          include/hpsf/core/shared/key.h include/hpsf/verifier/checker/table_checker.h)
    if(NOT EXISTS ${OUT}/prefix/${installed})
      message(FATAL_ERROR "the install lacks ${installed}")
    endif()
  endforeach()
  file(GLOB_RECURSE tests_installed ${OUT}/prefix/*_test.cpp ${OUT}/prefix/*_test.h)
  if(tests_installed)
    message(FATAL_ERROR "the install holds test sources: ${tests_installed}")
  endif()
  set(consumer_args -DCMAKE_PREFIX_PATH=${OUT}/prefix)
elseif(MODE STREQUAL "subdirectory")
  set(consumer_args -DHPSF_SOURCE_DIR=${SOURCE})
elseif(MODE STREQUAL "fetchcontent")  # the commit checked out in SOURCE, fetched from its repository
  execute_process(COMMAND git -C ${SOURCE} rev-parse HEAD OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE code)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${SOURCE} is not a git repository")
  endif()
  set(consumer_args -DHPSF_GIT_REPOSITORY=${SOURCE} -DHPSF_GIT_TAG=${commit})
else()
  message(FATAL_ERROR "MODE must be installed, subdirectory or fetchcontent")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/examples/consumer -B ${OUT}/build -G Ninja
  -DCMAKE_BUILD_TYPE=Release ${consumer_args} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "configuring the consumer failed:\n${out}")
endif()
foreach(hpsf_build ${OUT}/build/hpsf ${OUT}/build/_deps/hpsf-build)
  if(NOT EXISTS ${hpsf_build}/CTestTestfile.cmake)
    continue()
  endif()
  file(READ ${hpsf_build}/CTestTestfile.cmake ctest_file)
  if(ctest_file MATCHES "add_test")
    message(FATAL_ERROR "hpsf added its own tests to the consumer's project")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${OUT}/build RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "building the consumer failed:\n${out}")
endif()
# The exactness flags travel with hpsf::core and come after the consumer's own, so they win.
file(STRINGS ${OUT}/build/build.ninja flags REGEX "FLAGS = .*-ffp-contract=fast")
if(NOT flags MATCHES "-ffp-contract=fast.* -ffp-contract=off -fno-fast-math")
  message(FATAL_ERROR "hpsf::core's exactness flags do not follow the consumer's own: ${flags}")
endif()
execute_process(COMMAND ${OUT}/build/check_my_table ${OUT}/team.hpsfc RESULT_VARIABLE code OUTPUT_VARIABLE out
  ERROR_VARIABLE out)
message(STATUS "${out}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the consumer's check failed (${code})")
endif()
# The capture its engine wrote through the installed header, judged by hpsf (the installed one where there is one).
set(hpsf_bin ${BUILD}/bin/hpsf)
if(MODE STREQUAL "installed")
  set(hpsf_bin ${OUT}/prefix/bin/hpsf)
endif()
execute_process(COMMAND ${hpsf_bin} judge ${OUT}/team.hpsfc RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "${out}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "hpsf judge failed the consumer's captured table (${code})")
endif()
