# Image regression of the command line users run: 96x54 renders against the
# references in golden/ (golden_images.cpp says which cases and tolerances).
# Reported as skipped when the references were recorded on another GL
# renderer; re-record with tests/runtime/record_golden.sh.
add_executable(deepgi_golden_images ${CMAKE_CURRENT_LIST_DIR}/golden_images.cpp)
target_link_libraries(deepgi_golden_images PRIVATE deepgi::runtime fmt::fmt PkgConfig::DEEPGI_TEST_STB)
target_compile_definitions(deepgi_golden_images PRIVATE
  DEEPGI_EXECUTABLE="$<TARGET_FILE:deepgi>" DEEPGI_GOLDEN_DIR="${CMAKE_CURRENT_LIST_DIR}/golden")
add_dependencies(deepgi_golden_images deepgi)
add_test(NAME deepgi_golden_images
  COMMAND deepgi_golden_images check ${CMAKE_CURRENT_BINARY_DIR}/golden_images)
set_tests_properties(deepgi_golden_images PROPERTIES LABELS runtime TIMEOUT 300 SKIP_RETURN_CODE 77)
