# ---- deepgi core: G-buffer, outputs, shader loader, CLI, image identity, pass interface ----
add_executable(deepgi_runtime_tests
  ${CMAKE_CURRENT_LIST_DIR}/gbuffer_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/outputs_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/camera_path_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frame_statistics_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shader_loader_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/help_test.cpp)
target_link_libraries(deepgi_runtime_tests PRIVATE deepgi::runtime spiral_catch_main fmt::fmt)
# runtime/src for the pass list (pass.hpp), which the shader loader test walks.
target_include_directories(deepgi_runtime_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests
                           ${PROJECT_SOURCE_DIR}/tests/support ${PROJECT_SOURCE_DIR}/runtime/src
                           ${PROJECT_SOURCE_DIR}/shaders)
target_compile_definitions(deepgi_runtime_tests PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_runtime_tests deepgi)
catch_discover_tests(deepgi_runtime_tests PROPERTIES LABELS runtime TIMEOUT 300)

# The delay and predict generators against peel, and the memory they add.
add_executable(deepgi_generator_prediction_tests
  ${CMAKE_CURRENT_LIST_DIR}/generator_prediction_test.cpp)
target_link_libraries(deepgi_generator_prediction_tests PRIVATE deepgi::runtime spiral_catch_main
                                                                fmt::fmt)
target_compile_definitions(deepgi_generator_prediction_tests
                           PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_generator_prediction_tests deepgi)
catch_discover_tests(deepgi_generator_prediction_tests PROPERTIES LABELS runtime TIMEOUT 300)

# The hidden GLFW window under Xvfb must render the same image as EGL.
find_program(DEEPGI_XVFB_RUN xvfb-run)
if(DEEPGI_XVFB_RUN)
  add_test(NAME deepgi_hidden_window_matches_egl
    COMMAND ${CMAKE_COMMAND} -DDEEPGI=$<TARGET_FILE:deepgi> -DXVFB_RUN=${DEEPGI_XVFB_RUN}
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/hidden_window
            -P ${CMAKE_CURRENT_LIST_DIR}/hidden_window_matches_egl.cmake)
  set_tests_properties(deepgi_hidden_window_matches_egl PROPERTIES LABELS runtime TIMEOUT 120)
endif()

# Every pixel of the final image and of every pass output, for every built-in
# scene and generator, against hashes recorded before the passes were restructured.
add_test(NAME deepgi_image_identity
  COMMAND ${CMAKE_COMMAND} -DDEEPGI=$<TARGET_FILE:deepgi>
          -DHASHES=${CMAKE_CURRENT_LIST_DIR}/image_identity_hashes.txt
          -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/image_identity
          -P ${CMAKE_CURRENT_LIST_DIR}/image_identity.cmake)
set_tests_properties(deepgi_image_identity PROPERTIES LABELS runtime TIMEOUT 300)

# The pass interface, frame resources and settings module, and who owns each
# settings row (settings_owner_test.cpp reads runtime/src; runtime/src is
# private to the library, so this suite adds it to its include path).
# example_pass/ is a pass written as one of runtime/src/passes would be,
# compiled into this test only, with its shader in the same folder.
add_executable(deepgi_pass_interface_tests ${CMAKE_CURRENT_LIST_DIR}/pass_interface_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/settings_owner_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/example_pass/ao_complement_pass.cpp)
target_link_libraries(deepgi_pass_interface_tests PRIVATE deepgi::runtime spiral_catch_main)
target_include_directories(deepgi_pass_interface_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/tests)
target_compile_definitions(deepgi_pass_interface_tests
                           PRIVATE DEEPGI_ARCHITECTURE_DOC="${PROJECT_SOURCE_DIR}/docs/architecture.md"
                                   DEEPGI_EXAMPLE_PASS_DIR="${CMAKE_CURRENT_LIST_DIR}/example_pass"
                                   DEEPGI_PASSES_DIR="${PROJECT_SOURCE_DIR}/runtime/src/passes"
                                   DEEPGI_FRAME_SOURCE="${PROJECT_SOURCE_DIR}/runtime/src/frame.cpp")
catch_discover_tests(deepgi_pass_interface_tests PROPERTIES LABELS runtime TIMEOUT 300)

# The interactive window: keys, settings table, script parser and the
# renderer's live edits (EGL, no window).
add_executable(deepgi_window_tests ${CMAKE_CURRENT_LIST_DIR}/window_controls_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/live_settings_test.cpp)
target_link_libraries(deepgi_window_tests PRIVATE deepgi::window spiral_catch_main fmt::fmt)
target_include_directories(deepgi_window_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
target_compile_definitions(deepgi_window_tests PRIVATE DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>")
add_dependencies(deepgi_window_tests deepgi)
catch_discover_tests(deepgi_window_tests PROPERTIES LABELS runtime TIMEOUT 120)

# The window itself, scripted, under Xvfb; reported as skipped without xvfb-run.
if(DEEPGI_XVFB_RUN)
  add_executable(deepgi_window_xvfb_tests ${CMAKE_CURRENT_LIST_DIR}/window_xvfb_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/window_camera_xvfb_test.cpp)
  target_link_libraries(deepgi_window_xvfb_tests PRIVATE deepgi::runtime spiral_catch_main fmt::fmt)
  target_include_directories(deepgi_window_xvfb_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(deepgi_window_xvfb_tests PRIVATE
    DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>" DEEPGI_XVFB_RUN="${DEEPGI_XVFB_RUN}")
  add_dependencies(deepgi_window_xvfb_tests deepgi)
  # xvfb-run gone since configuring: the test exits 77, reported as skipped.
  catch_discover_tests(deepgi_window_xvfb_tests PROPERTIES LABELS runtime TIMEOUT 300
                       SKIP_RETURN_CODE 77)
else()
  add_test(NAME deepgi_window_xvfb_skipped
    COMMAND sh -c "echo 'xvfb-run not found: the scripted window test is skipped (install xvfb, scripts/install-deps.sh)'; exit 77")
  set_tests_properties(deepgi_window_xvfb_skipped PROPERTIES LABELS runtime SKIP_RETURN_CODE 77)
endif()
