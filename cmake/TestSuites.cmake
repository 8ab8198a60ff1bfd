# Runs inside ctest, each time it starts (the build directory's TEST_INCLUDE_FILES): one ctest test
# per GoogleTest suite of the test executable, not one per test. Each ctest test is a process, and
# a process of lfcam_tests takes 0.4 s to start in the release build and 0.85 s under the
# sanitizers (the loader binds some 250 shared libraries that OpenCV and FFmpeg bring), so a
# process per test cost CI about two minutes of its two cores; a suite's tests also share their
# fixture's set-up (docs/robustness.md, "What CI runs").
#
# In:  LFCAM_TESTS_EXECUTABLE    the GoogleTest executable
#      LFCAM_TESTS_DIRECTORY     where its tests run
#      LFCAM_TESTS_LEFT_OUT      optional: a file of tests to leave out (one regular expression a
#                                line, matched against the whole SUITE.TEST name; '#' starts a
#                                comment): .ci/asan-release-only.txt for the asan preset
#      LFCAM_TESTS_TIMEOUT       seconds a suite may take
#      LFCAM_TESTS_RUN_SERIAL    suites that run with nothing beside them (timing-sensitive ones)
#
# A suite all of whose tests skipped (data or a device absent) exits 77 (src/lfcam/tests_main.cpp)
# and is reported skipped; the tests skipped in a suite that ran are named in its output
# ("[  SKIPPED ]"), and scripts/test.sh lists them at the end.
if(NOT EXISTS "${LFCAM_TESTS_EXECUTABLE}")
  add_test(lfcam_tests_NOT_BUILT "${LFCAM_TESTS_EXECUTABLE}")
  return()
endif()
execute_process(COMMAND "${LFCAM_TESTS_EXECUTABLE}" --gtest_list_tests
                WORKING_DIRECTORY "${LFCAM_TESTS_DIRECTORY}" TIMEOUT 120
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR
          "${LFCAM_TESTS_EXECUTABLE} --gtest_list_tests failed (${result}):\n${listing}${errors}")
endif()

set(left_out)
if(LFCAM_TESTS_LEFT_OUT)
  file(STRINGS "${LFCAM_TESTS_LEFT_OUT}" lines)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "#.*" "" line "${line}")
    string(STRIP "${line}" line)
    if(NOT line STREQUAL "")
      list(APPEND left_out "${line}")
    endif()
  endforeach()
endif()

# GoogleTest's listing: "Suite." lines, each followed by its "  Test" lines (either may end in
# "  # GetParam() = ..." for parameterised tests).
string(REPLACE "\n" ";" lines "${listing}")
set(suites)
set(suite "")
foreach(line IN LISTS lines)
  string(REGEX REPLACE "  #.*$" "" line "${line}")
  if(line MATCHES "^([A-Za-z0-9_/]+)\\.$")
    set(suite "${CMAKE_MATCH_1}")
    list(APPEND suites "${suite}")
    set(kept_${suite} 0)
    set(dropped_${suite})
  elseif(line MATCHES "^  ([A-Za-z0-9_/]+)$" AND NOT suite STREQUAL "")
    set(name "${suite}.${CMAKE_MATCH_1}")
    set(drop OFF)
    foreach(pattern IN LISTS left_out)
      if(name MATCHES "^(${pattern})$")
        set(drop ON)
        break()
      endif()
    endforeach()
    if(drop)
      list(APPEND dropped_${suite} "${name}")
    else()
      math(EXPR kept_${suite} "${kept_${suite}} + 1")
    endif()
  endif()
endforeach()

foreach(suite IN LISTS suites)
  if(kept_${suite} EQUAL 0)
    continue()  # every test of the suite left out
  endif()
  set(filter "${suite}.*")
  if(dropped_${suite})
    list(JOIN dropped_${suite} ":" dropped)
    string(APPEND filter "-${dropped}")
  endif()
  add_test("${suite}" "${LFCAM_TESTS_EXECUTABLE}" "--gtest_filter=${filter}")
  set_tests_properties("${suite}" PROPERTIES
    WORKING_DIRECTORY "${LFCAM_TESTS_DIRECTORY}" TIMEOUT "${LFCAM_TESTS_TIMEOUT}"
    SKIP_RETURN_CODE 77)
  list(FIND LFCAM_TESTS_RUN_SERIAL "${suite}" serial)  # (ctest's scripts predate IN_LIST)
  if(serial GREATER -1)
    set_tests_properties("${suite}" PROPERTIES RUN_SERIAL ON)
  endif()
endforeach()
