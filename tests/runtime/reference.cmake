# ---- Ray-traced reference (Embree, CPU only: no GL context needed) ----
add_executable(deepgi_reference_tests ${CMAKE_CURRENT_LIST_DIR}/reference_test.cpp)
target_link_libraries(deepgi_reference_tests PRIVATE deepgi::reference spiral_catch_main)
target_compile_definitions(deepgi_reference_tests PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_reference_tests deepgi)
catch_discover_tests(deepgi_reference_tests PROPERTIES LABELS runtime TIMEOUT 300)
