# ---- Hostile scene files: the glTF loader on the CPU, no GL needed ----
# Its geometry and file handling in one file, what it reads besides geometry
# (materials, lights, cameras) in the other.
pkg_check_modules(DEEPGI_TEST_STB REQUIRED IMPORTED_TARGET stb)
add_executable(deepgi_scene_tests ${CMAKE_CURRENT_LIST_DIR}/scene_gltf_geometry_test.cpp
                                  ${CMAKE_CURRENT_LIST_DIR}/scene_gltf_materials_test.cpp)
target_link_libraries(deepgi_scene_tests PRIVATE deepgi::scene spiral_catch_main fmt::fmt
                                                 PkgConfig::DEEPGI_TEST_STB)
catch_discover_tests(deepgi_scene_tests PROPERTIES LABELS runtime TIMEOUT 120)

# ---- Output files: full disk, symlinks, special files, signals, --dump ----
add_executable(deepgi_output_tests ${CMAKE_CURRENT_LIST_DIR}/output_paths_test.cpp)
target_link_libraries(deepgi_output_tests PRIVATE deepgi::runtime spiral::fileio
                                                  spiral_catch_main fmt::fmt)
target_compile_definitions(deepgi_output_tests PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_output_tests deepgi)
# Without unshare the tmpfs case ends with status 77 (support/skip.hpp).
catch_discover_tests(deepgi_output_tests PROPERTIES LABELS runtime TIMEOUT 300 SKIP_RETURN_CODE 77)

# ---- Frame size and memory limits ----
add_executable(deepgi_frame_limits_tests ${CMAKE_CURRENT_LIST_DIR}/frame_limits_test.cpp)
target_link_libraries(deepgi_frame_limits_tests PRIVATE deepgi::runtime spiral_catch_main
                                                        fmt::fmt)
target_compile_definitions(deepgi_frame_limits_tests
                           PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_frame_limits_tests deepgi)
catch_discover_tests(deepgi_frame_limits_tests PROPERTIES LABELS runtime TIMEOUT 120)

# ---- glTF rendered end to end: built files and the Debian sample models ----
# Geometry and materials in one file, lights and shadows in the other; both
# share rendered_gltf.hpp.
add_executable(deepgi_gltf_render_tests ${CMAKE_CURRENT_LIST_DIR}/gltf_render_test.cpp
                                        ${CMAKE_CURRENT_LIST_DIR}/gltf_lights_test.cpp)
target_link_libraries(deepgi_gltf_render_tests PRIVATE deepgi::runtime spiral_catch_main fmt::fmt
                                                       PkgConfig::DEEPGI_TEST_STB)
# glTF sample models shipped by Debian's assimp-testmodels (scripts/install-deps.sh).
set(DEEPGI_SAMPLE_MODELS "/usr/share/assimp/models/glTF2"
    CACHE PATH "Folder of the glTF sample models the render test draws")
target_compile_definitions(deepgi_gltf_render_tests PRIVATE
  DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>" DEEPGI_SAMPLE_MODELS="${DEEPGI_SAMPLE_MODELS}")
add_dependencies(deepgi_gltf_render_tests deepgi)
# A sample model that is absent ends its test with status 77 (support/skip.hpp).
catch_discover_tests(deepgi_gltf_render_tests PROPERTIES LABELS runtime TIMEOUT 300 SKIP_RETURN_CODE 77)

# ---- Scene scale: `auto` lengths follow the scene ----
add_executable(deepgi_scene_scale_tests ${CMAKE_CURRENT_LIST_DIR}/scene_scale_test.cpp)
target_link_libraries(deepgi_scene_scale_tests PRIVATE deepgi::runtime spiral_catch_main)
target_compile_definitions(deepgi_scene_scale_tests PRIVATE
  DEEPGI_SAMPLE_MODELS="${DEEPGI_SAMPLE_MODELS}")
catch_discover_tests(deepgi_scene_scale_tests PROPERTIES LABELS runtime TIMEOUT 300)

# ---- Hostile scene files, second corpus: the loader's own reads, special files, total work ----
add_executable(deepgi_gltf_hostile_tests ${CMAKE_CURRENT_LIST_DIR}/gltf_hostile_test.cpp)
target_link_libraries(deepgi_gltf_hostile_tests PRIVATE deepgi::scene spiral_catch_main fmt::fmt
                                                        PkgConfig::DEEPGI_TEST_STB)
catch_discover_tests(deepgi_gltf_hostile_tests PROPERTIES LABELS runtime TIMEOUT 120)

# ---- Both command lines against the second corpus: paths, stdout, numbers ----
add_executable(deepgi_cli_hostile_tests ${CMAKE_CURRENT_LIST_DIR}/cli_hostile_test.cpp)
target_link_libraries(deepgi_cli_hostile_tests PRIVATE spiral_catch_main fmt::fmt)
target_compile_definitions(deepgi_cli_hostile_tests PRIVATE
  DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>" SPIRALGEN_EXECUTABLE="$<TARGET_FILE:spiralgen>")
add_dependencies(deepgi_cli_hostile_tests deepgi spiralgen)
catch_discover_tests(deepgi_cli_hostile_tests PROPERTIES LABELS runtime TIMEOUT 300)
