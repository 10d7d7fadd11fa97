# Run after tessera_tests is built (tests/CMakeLists.txt): lists its tests and writes OUTPUT, the
# file ctest includes. Consecutive GoogleTest suites (in the listing's order, which is the
# source files') are packed into one ctest test of at least TESTS_PER_PROCESS tests, run as one
# process with --gtest_filter=A.*:B.*:..., so that their tests share one Vulkan context and its
# pipelines (tests/vulkan_fixture.cpp): lavapipe builds every pipeline anew in each process, the
# shading pipeline alone about 1 CPU s, which made up about a third of the suite's CPU time when
# each suite had a process of its own (docs/development.md, "Test processes"). A ctest test is
# named after the suites it runs, so `ctest -R Suite` still finds a suite's process.
# Two keep a process of their own under their own name, because scripts leave them out by it
# (scripts/test-sanitize.sh): the window tests `View` (they need an X server) and
# `Sizes/AccuracySizes.DefaultScene/4096x4096` (minutes under ASan). Suites whose name starts with
# DISABLED_ are left out, as GoogleTest leaves them out.
# Each test's COST orders a run that has no timings of an earlier one (a fresh build): ctest starts
# the costliest first, so the longest process, View, must not start last. A group's cost is its
# number of tests, about a second each; the two alone have their seconds on the 2-core VM.
# glibc.malloc.hugetlb=1 (glibc 2.35 and later; older ones ignore it) backs the heap with
# transparent huge pages, for the test program and the tools it runs: lavapipe's translation of a
# pipeline touches tens of MB of fresh heap, 55,000 page faults in a one-frame `tessera render`
# with 4 KiB pages against 6,700 with huge pages. Where the memory lies changes no result.
# Inputs: TEST_EXECUTABLE, WORKING_DIRECTORY, OUTPUT.
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in a script run with -P
set(TESTS_PER_PROCESS 32)
set(alone "View" "Sizes/AccuracySizes.DefaultScene/4096x4096")
set(alone_costs 70 25)
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  OUTPUT_VARIABLE listing RESULT_VARIABLE status TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${status}):\n${listing}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(script "")
set(count 0)
macro(add_one name filter cost)
  string(APPEND script "add_test([==[${name}]==] [==[${TEST_EXECUTABLE}]==] "
    "[==[--gtest_filter=${filter}]==])\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==]"
    " ENVIRONMENT [==[VK_LOADER_DEBUG=none;GLIBC_TUNABLES=glibc.malloc.hugetlb=1]==]"
    " COST ${cost})\n")
  math(EXPR count "${count} + 1")
endmacro()

# The group being packed: its suites' names, their filters and its number of tests.
set(group_names "")
set(group_filters "")
set(group_tests 0)
macro(flush_group)
  if(group_tests GREATER 0)
    string(JOIN " " name ${group_names})
    string(JOIN ":" filter ${group_filters})
    add_one("${name}" "${filter}" ${group_tests})
  endif()
  set(group_names "")
  set(group_filters "")
  set(group_tests 0)
endmacro()

set(suite "")
set(suite_tests 0)
set(suite_filters "")  # its tests by name, where one of them runs alone
set(suite_split FALSE)
# Adds the suite just read (`suite`, `suite_tests` tests) to the group, and closes the group
# once it holds TESTS_PER_PROCESS tests.
macro(end_suite)
  if(suite_tests GREATER 0)
    list(APPEND group_names "${suite}")
    if(suite_split)
      list(APPEND group_filters ${suite_filters})
    else()
      list(APPEND group_filters "${suite}.*")
    endif()
    math(EXPR group_tests "${group_tests} + ${suite_tests}")
    if(group_tests GREATER_EQUAL TESTS_PER_PROCESS)
      flush_group()
    endif()
  endif()
  set(suite_tests 0)
  set(suite_filters "")
  set(suite_split FALSE)
endmacro()

foreach(line IN LISTS lines)
  if(line MATCHES "^([^ ]+)\\.( .*)?$")
    # A suite's line: "Suite." (a typed suite adds "  # TypeParam = ...").
    set(next "${CMAKE_MATCH_1}")
    end_suite()
    set(suite "${next}")
  elseif(line MATCHES "^  ([^ ]+)" AND NOT suite STREQUAL "")
    # Read the match before any other MATCHES, which would replace it.
    set(test "${CMAKE_MATCH_1}")
    if(suite MATCHES "^DISABLED_" OR test MATCHES "^DISABLED_")
      continue()
    elseif(suite IN_LIST alone)
      if(suite_tests EQUAL 0)
        list(FIND alone "${suite}" i)
        list(GET alone_costs ${i} cost)
        add_one("${suite}" "${suite}.*" ${cost})
        set(suite_tests -1)  # added; end_suite adds nothing more
      endif()
    elseif("${suite}.${test}" IN_LIST alone)
      list(FIND alone "${suite}.${test}" i)
      list(GET alone_costs ${i} cost)
      add_one("${suite}.${test}" "${suite}.${test}" ${cost})
      set(suite_split TRUE)  # the suite's other tests join the group by name
    else()
      math(EXPR suite_tests "${suite_tests} + 1")
      list(APPEND suite_filters "${suite}.${test}")
    endif()
  endif()
endforeach()
end_suite()
flush_group()
if(count EQUAL 0)
  message(FATAL_ERROR "no tests found in the listing of ${TEST_EXECUTABLE}:\n${listing}")
endif()
file(WRITE "${OUTPUT}" "${script}")
