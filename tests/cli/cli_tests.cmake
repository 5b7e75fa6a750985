# SPDX-License-Identifier: MIT
# Tests of the elan command: a GoogleTest program that runs the built binary and checks exit
# status, stderr messages, the summary JSON, trajectories and recordings.
add_executable(test_cli_elan ${CMAKE_CURRENT_LIST_DIR}/elan_cli_test.cpp)
target_link_libraries(test_cli_elan PRIVATE elan_recording elan_options nlohmann_json::nlohmann_json
                                            GTest::gtest GTest::gtest_main)
target_compile_definitions(test_cli_elan PRIVATE
  ELAN_CLI="$<TARGET_FILE:elan_cli>"
  ELAN_BAD_SCENES="${CMAKE_CURRENT_LIST_DIR}/bad_scenes"
  ELAN_REPRODUCERS="${CMAKE_CURRENT_LIST_DIR}/reproducers"
  ELAN_SCENE_DIR="${ELAN_SCENE_DIR}")
target_include_directories(test_cli_elan PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
add_dependencies(test_cli_elan elan_cli)
gtest_discover_tests(test_cli_elan DISCOVERY_TIMEOUT 60 PROPERTIES LABELS cli TIMEOUT 300)
