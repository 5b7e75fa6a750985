# SPDX-License-Identifier: MIT
# Tests of `elan view`, when the viewer is built. The picture tests need an X display: without
# one (DISPLAY unset) they are skipped, with the reason; tools/test.sh runs ctest under
# `xvfb-run -a` so that they run on Mesa's software renderer, with Xvfb's `-noreset` (a server
# that resets when its last client leaves refuses the next test's connection for a moment).
if(TARGET elan_viewer)
  add_executable(test_cli_viewer ${CMAKE_CURRENT_LIST_DIR}/viewer_test.cpp)
  target_link_libraries(test_cli_viewer PRIVATE elan elan_options nlohmann_json::nlohmann_json
                                                ${ELAN_STB_LIBRARY} GTest::gtest GTest::gtest_main)
  target_include_directories(test_cli_viewer PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
  target_include_directories(test_cli_viewer SYSTEM PRIVATE ${ELAN_STB_INCLUDE_DIR})
  target_compile_definitions(test_cli_viewer PRIVATE ELAN_CLI="$<TARGET_FILE:elan_cli>")
  add_dependencies(test_cli_viewer elan_cli)
  # Mesa's and X11's libraries keep allocations until exit by design; LeakSanitizer is told so.
  gtest_discover_tests(test_cli_viewer DISCOVERY_TIMEOUT 60
                       PROPERTIES LABELS "cli;viewer" TIMEOUT 300
                       ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_LIST_DIR}/viewer_lsan.supp")
endif()

# The viewer's simulation, live settings and timeline, without a window: no display needed.
if(TARGET elan_viewer_core)
  add_executable(test_cli_viewer_simulation ${CMAKE_CURRENT_LIST_DIR}/viewer_simulation_test.cpp)
  target_link_libraries(test_cli_viewer_simulation PRIVATE elan_viewer_core elan_options
                        nlohmann_json::nlohmann_json GTest::gtest GTest::gtest_main)
  target_include_directories(test_cli_viewer_simulation PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
  target_compile_definitions(test_cli_viewer_simulation PRIVATE ELAN_CLI="$<TARGET_FILE:elan_cli>")
  add_dependencies(test_cli_viewer_simulation elan_cli)
  gtest_discover_tests(test_cli_viewer_simulation DISCOVERY_TIMEOUT 60
                       PROPERTIES LABELS "cli;viewer" TIMEOUT 300)
endif()
