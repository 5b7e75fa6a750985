# SPDX-License-Identifier: MIT
# Record, replay and diverge through the elan binary: keyframes, the body and field named at the
# first divergent step, perturbed replays, old and future recording versions, corrupt files.
add_executable(test_cli_replay ${CMAKE_CURRENT_LIST_DIR}/replay_test.cpp)
target_link_libraries(test_cli_replay PRIVATE elan elan_options nlohmann_json::nlohmann_json GTest::gtest
                                              GTest::gtest_main)
target_compile_definitions(test_cli_replay PRIVATE ELAN_CLI="$<TARGET_FILE:elan_cli>"
  ELAN_REPRODUCERS="${CMAKE_CURRENT_LIST_DIR}/reproducers"
  ELAN_SCENE_DIR="${ELAN_SCENE_DIR}")
target_include_directories(test_cli_replay PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
add_dependencies(test_cli_replay elan_cli)
gtest_discover_tests(test_cli_replay DISCOVERY_TIMEOUT 60 PROPERTIES LABELS cli TIMEOUT 300)
