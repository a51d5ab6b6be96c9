# ---- Speed-against-error report (deepgi report; docs/report.md) ----
add_executable(deepgi_report_tests ${CMAKE_CURRENT_LIST_DIR}/report_test.cpp)
target_link_libraries(deepgi_report_tests PRIVATE deepgi::report spiral::optimizer fmt::fmt spiral_catch_main)
target_include_directories(deepgi_report_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
target_compile_definitions(deepgi_report_tests PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>"
  DEEPGI_PLOT_REPORT_SCRIPT="${PROJECT_SOURCE_DIR}/scripts/plot_report.py")
add_dependencies(deepgi_report_tests deepgi)
# Without matplotlib the summary test ends with status 77 (support/skip.hpp).
catch_discover_tests(deepgi_report_tests PROPERTIES LABELS runtime TIMEOUT 600 SKIP_RETURN_CODE 77)
