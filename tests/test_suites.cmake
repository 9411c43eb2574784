# ctest's tests for pleinair_tests, one a GoogleTest suite: a process start costs 0.3 s in the
# plain build and 0.6 s under the sanitizers, and a test a process paid it 550 times (CI's time,
# issue 51). A value-parameterised suite (a name with a /, such as Every/ShippedScene, a shipped
# scene a value) keeps a ctest test a value, so its long ones spread over the cores.
#   cmake -D EXE=pleinair_tests -D OUT=FILE -D WORKDIR=DIR -P test_suites.cmake
# Run after each link (tests/CMakeLists.txt); ctest reads OUT through TEST_INCLUDE_FILES.
execute_process(COMMAND "${EXE}" --gtest_list_tests OUTPUT_VARIABLE listing
                RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
    file(REMOVE "${OUT}")
    message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${rc}):\n${listing}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(script "")
set(suite "")
set(one_a_value FALSE)
foreach(line IN LISTS lines)
    if(line MATCHES "^([A-Za-z0-9_/]+)\\.( .*)?$")
        set(suite "${CMAKE_MATCH_1}")
        set(one_a_value FALSE)
        if(suite MATCHES "/")
            set(one_a_value TRUE)
        else()
            string(APPEND script "add_test([==[${suite}]==] \"${EXE}\" [==[--gtest_filter=${suite}.*]==])\n"
                "set_tests_properties([==[${suite}]==] PROPERTIES WORKING_DIRECTORY \"${WORKDIR}\")\n")
        endif()
    elseif(one_a_value AND line MATCHES "^  ([A-Za-z0-9_/]+)")
        set(name "${suite}.${CMAKE_MATCH_1}")
        string(APPEND script "add_test([==[${name}]==] \"${EXE}\" [==[--gtest_filter=${name}]==])\n"
            "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY \"${WORKDIR}\" "
            "SKIP_REGULAR_EXPRESSION [==[\\[  SKIPPED \\]]==])\n")
    endif()
endforeach()
file(WRITE "${OUT}" "${script}")
