# SPDX-License-Identifier: MIT
# The supported ranges through the elan binary: each fuzzing reproducer of a valid-looking scene
# that used to print non-finite totals (or freeze bodies) is refused with exit 2 and one line, and
# a scene at the bounds runs to a summary whose every number is finite.
add_executable(test_cli_limits ${CMAKE_CURRENT_LIST_DIR}/limits_test.cpp)
target_link_libraries(test_cli_limits PRIVATE elan_options nlohmann_json::nlohmann_json GTest::gtest
                                              GTest::gtest_main)
target_compile_definitions(test_cli_limits PRIVATE
  ELAN_CLI="$<TARGET_FILE:elan_cli>"
  ELAN_REPRODUCERS="${CMAKE_CURRENT_LIST_DIR}/reproducers")
target_include_directories(test_cli_limits PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
add_dependencies(test_cli_limits elan_cli)
gtest_discover_tests(test_cli_limits DISCOVERY_TIMEOUT 60 PROPERTIES LABELS cli TIMEOUT 300)
