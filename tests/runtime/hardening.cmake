# ---- Hostile scene files: the glTF loader on the CPU, no GL needed ----
pkg_check_modules(DEEPGI_TEST_STB REQUIRED IMPORTED_TARGET stb)
add_executable(deepgi_scene_tests ${CMAKE_CURRENT_LIST_DIR}/scene_gltf_test.cpp)
target_link_libraries(deepgi_scene_tests PRIVATE deepgi::scene spiral_catch_main fmt::fmt
                                                 PkgConfig::DEEPGI_TEST_STB)
catch_discover_tests(deepgi_scene_tests PROPERTIES LABELS runtime TIMEOUT 120)
