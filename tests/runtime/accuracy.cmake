# Deep SAO against the reference: the accuracy targets (docs/deep-sao.md).
# Needs a GL context (headless EGL) and Embree; one ctest entry per scene
# would repeat the context set-up, so the seven scenes run in one process.
add_executable(deepgi_ao_accuracy_tests ${CMAKE_CURRENT_LIST_DIR}/ao_accuracy_test.cpp)
target_link_libraries(deepgi_ao_accuracy_tests PRIVATE deepgi::reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_ao_accuracy_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/runtime/src)
# The blur's reach in pixels, for what counts as open after the blur.
target_compile_definitions(deepgi_ao_accuracy_tests PRIVATE SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS})
# Three estimators on seven scenes, the thick spiral over 64 still frames:
# up to about 20 minutes on llvmpipe, 2 cores.
add_test(NAME deepgi_ao_accuracy COMMAND deepgi_ao_accuracy_tests "[ao-accuracy]")
set_tests_properties(deepgi_ao_accuracy PROPERTIES LABELS "runtime;sao" TIMEOUT 1800
  FIXTURES_SETUP ao_accuracy_figures)
# Every target deepgi_ao_accuracy measures, target beside measured, printed by
# an entry of its own that reports itself skipped while any target is missed,
# so every ctest summary names the misses (print_targets.sh).
add_test(NAME deepgi_ao_accuracy_targets_missed
  COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/print_targets.sh "AO accuracy targets" ao-accuracy-targets.md)
set_tests_properties(deepgi_ao_accuracy_targets_missed PROPERTIES LABELS "runtime;sao"
  FIXTURES_REQUIRED ao_accuracy_figures SKIP_RETURN_CODE 77)

# Deep radiosity against the reference's one-bounce irradiance (headless EGL
# and Embree, one process for its scenes).
add_executable(deepgi_radiosity_accuracy_tests ${CMAKE_CURRENT_LIST_DIR}/radiosity_accuracy_test.cpp)
target_link_libraries(deepgi_radiosity_accuracy_tests PRIVATE deepgi::reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_radiosity_accuracy_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
add_test(NAME deepgi_radiosity_accuracy COMMAND deepgi_radiosity_accuracy_tests "[radiosity-accuracy]")
set_tests_properties(deepgi_radiosity_accuracy PROPERTIES LABELS "runtime;radiosity" TIMEOUT 600
  FIXTURES_SETUP radiosity_accuracy_figures)
add_test(NAME deepgi_radiosity_accuracy_targets_missed
  COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/print_targets.sh "Radiosity accuracy targets"
          radiosity-accuracy-targets.md)
set_tests_properties(deepgi_radiosity_accuracy_targets_missed PROPERTIES LABELS "runtime;radiosity"
  FIXTURES_REQUIRED radiosity_accuracy_figures SKIP_RETURN_CODE 77)
