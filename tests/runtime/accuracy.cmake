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
set_tests_properties(deepgi_ao_accuracy PROPERTIES LABELS "runtime;sao" TIMEOUT 1800)
# Every target deepgi_ao_accuracy measures, printed (targets_missed.cmake).
deepgi_add_targets_missed(NAME deepgi_ao_accuracy_targets_missed TITLE "AO accuracy targets"
  TABLE ao-accuracy-targets.md SUITE deepgi_ao_accuracy LABELS runtime sao)

# Deep radiosity against the reference's one-bounce irradiance (headless EGL
# and Embree, one process for its scenes).
add_executable(deepgi_radiosity_accuracy_tests ${CMAKE_CURRENT_LIST_DIR}/radiosity_accuracy_test.cpp)
target_link_libraries(deepgi_radiosity_accuracy_tests PRIVATE deepgi::reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_radiosity_accuracy_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
add_test(NAME deepgi_radiosity_accuracy COMMAND deepgi_radiosity_accuracy_tests "[radiosity-accuracy]")
set_tests_properties(deepgi_radiosity_accuracy PROPERTIES LABELS "runtime;radiosity" TIMEOUT 600)
deepgi_add_targets_missed(NAME deepgi_radiosity_accuracy_targets_missed
  TITLE "Radiosity accuracy targets" TABLE radiosity-accuracy-targets.md
  SUITE deepgi_radiosity_accuracy LABELS runtime radiosity)

# The march behind a thin beam (ao_march_beam_test.cpp, in deepgi_sao_tests):
# its known miss, printed (sao.cmake, which defines that test, is read first).
deepgi_add_targets_missed(NAME deepgi_ao_march_beam_targets_missed TITLE "AO march beam targets"
  TABLE ao-march-beam-targets.md SUITE deepgi_sao_march LABELS runtime sao)

# The direct light's shadow map against traced shadow rays (headless EGL and
# Embree, one process for its scenes).
add_executable(deepgi_shadow_accuracy_tests ${CMAKE_CURRENT_LIST_DIR}/shadow_accuracy_test.cpp)
target_link_libraries(deepgi_shadow_accuracy_tests PRIVATE deepgi::reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_shadow_accuracy_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
add_test(NAME deepgi_shadow_accuracy COMMAND deepgi_shadow_accuracy_tests "[shadow-accuracy]")
set_tests_properties(deepgi_shadow_accuracy PROPERTIES LABELS "runtime" TIMEOUT 600)
deepgi_add_targets_missed(NAME deepgi_shadow_accuracy_targets_missed
  TITLE "Shadow accuracy targets" TABLE shadow-accuracy-targets.md
  SUITE deepgi_shadow_accuracy LABELS runtime)
