# Run after tessera_tests is built (tests/CMakeLists.txt): lists its tests and writes OUTPUT, the
# file ctest includes, with one ctest test per GoogleTest suite, run as one process with
# --gtest_filter=Suite.*, so that the suite's tests share one Vulkan context and its pipelines
# (tests/vulkan_fixture.cpp). A value-parameterized suite (its tests' names hold a '/', as
# Sizes/AccuracySizes.DefaultScene/4096x4096) keeps one ctest test per test, so that scripts can
# leave single instances out by name (scripts/test-sanitize.sh). Suites whose name starts with
# DISABLED_ are left out, as GoogleTest leaves them out.
# Inputs: TEST_EXECUTABLE, WORKING_DIRECTORY, OUTPUT.
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  OUTPUT_VARIABLE listing RESULT_VARIABLE status TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${status}):\n${listing}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(script "")
set(suite "")
set(count 0)
macro(add_one name filter)
  string(APPEND script "add_test([==[${name}]==] [==[${TEST_EXECUTABLE}]==] "
    "[==[--gtest_filter=${filter}]==])\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==]"
    " ENVIRONMENT VK_LOADER_DEBUG=none)\n")
  math(EXPR count "${count} + 1")
endmacro()
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ ]+)\\.( .*)?$")
    # A suite's line: "Suite." (a typed suite adds "  # TypeParam = ...").
    set(suite "${CMAKE_MATCH_1}")
    set(suite_added FALSE)
  elseif(line MATCHES "^  ([^ ]+)" AND NOT suite STREQUAL "")
    # Read the match before any other MATCHES, which would replace it.
    set(test "${CMAKE_MATCH_1}")
    if(suite MATCHES "^DISABLED_" OR test MATCHES "^DISABLED_")
      continue()
    elseif(test MATCHES "/")
      add_one("${suite}.${test}" "${suite}.${test}")
    elseif(NOT suite_added)
      add_one("${suite}" "${suite}.*")
      set(suite_added TRUE)
    endif()
  endif()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "no tests found in the listing of ${TEST_EXECUTABLE}:\n${listing}")
endif()
file(WRITE "${OUTPUT}" "${script}")
