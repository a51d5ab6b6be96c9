# Deep radiosity tests (labels runtime and radiosity): the gather, its
# temporal filter and its visibility test, in one executable and one ctest
# entry. RADIOSITY_TAPS / RADIOSITY_TAU (cmake/GeneratedHeaders.cmake) say
# which pattern the build-time radiosity_taps.glsl holds, so the CPU
# evaluation uses the same.
add_executable(deepgi_radiosity_tests radiosity_gather_test.cpp radiosity_temporal_test.cpp
  radiosity_visibility_test.cpp)
target_link_libraries(deepgi_radiosity_tests PRIVATE deepgi_sao_reference spiral_catch_main)
target_include_directories(deepgi_radiosity_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/shaders)
set(_radiosity_test_tau 0)
if(NOT "${RADIOSITY_TAU}" STREQUAL "")
  set(_radiosity_test_tau ${RADIOSITY_TAU})
endif()
target_compile_definitions(deepgi_radiosity_tests PRIVATE
  RADIOSITY_TEST_TAPS=${RADIOSITY_TAPS} RADIOSITY_TEST_TAU=${_radiosity_test_tau}
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=0
  SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS} SAO_TEST_BLUR_SIGMA="${BLUR_SIGMA}")
add_test(NAME deepgi_radiosity COMMAND deepgi_radiosity_tests "[radiosity]")
set_tests_properties(deepgi_radiosity PROPERTIES LABELS "runtime;radiosity" TIMEOUT 600)
# The visibility test's targets behind thin occluders, printed; skipped while
# any is missed.
deepgi_add_targets_missed(NAME deepgi_radiosity_visibility_targets_missed
  TITLE "Radiosity visibility targets" TABLE radiosity-visibility-targets.md
  SUITE deepgi_radiosity LABELS runtime radiosity)

# Temporal filter of the AO (labels runtime and sao).
add_executable(deepgi_ao_temporal_tests ao_temporal_test.cpp)
target_link_libraries(deepgi_ao_temporal_tests PRIVATE deepgi_sao_reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_ao_temporal_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/shaders)
target_compile_definitions(deepgi_ao_temporal_tests PRIVATE
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=0
  SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS} SAO_TEST_BLUR_SIGMA="${BLUR_SIGMA}")
add_test(NAME deepgi_ao_temporal COMMAND deepgi_ao_temporal_tests "[ao_temporal]")
set_tests_properties(deepgi_ao_temporal PROPERTIES LABELS "runtime;sao" TIMEOUT 600)
# The filter's targets under camera motion, printed; skipped while any is missed.
deepgi_add_targets_missed(NAME deepgi_ao_temporal_targets_missed TITLE "AO temporal targets"
  TABLE ao-temporal-targets.md SUITE deepgi_ao_temporal LABELS runtime sao)

# The temporal filters under a light change (labels runtime and radiosity).
add_executable(deepgi_lighting_change_tests lighting_change_test.cpp)
target_link_libraries(deepgi_lighting_change_tests PRIVATE deepgi_sao_reference spiral_catch_main)
target_compile_definitions(deepgi_lighting_change_tests PRIVATE
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=0
  SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS} SAO_TEST_BLUR_SIGMA="${BLUR_SIGMA}")
add_test(NAME deepgi_lighting_change COMMAND deepgi_lighting_change_tests "[radiosity]")
set_tests_properties(deepgi_lighting_change PROPERTIES LABELS "runtime;radiosity" TIMEOUT 300)

# Still-camera convergence of the E and AO temporal filters against the
# converged image: the measurement is a library shared with the benchmark
# temporal_convergence (tests/bench/runtime), which prints the docs' table.
add_library(deepgi_still_convergence STATIC still_convergence.cpp)
target_link_libraries(deepgi_still_convergence PUBLIC deepgi::runtime PRIVATE spiral::codegen fmt::fmt)
target_include_directories(deepgi_still_convergence PUBLIC ${CMAKE_CURRENT_LIST_DIR} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
add_executable(deepgi_temporal_convergence_tests temporal_convergence_test.cpp)
target_link_libraries(deepgi_temporal_convergence_tests PRIVATE deepgi_still_convergence spiral_catch_main fmt::fmt)
target_include_directories(deepgi_temporal_convergence_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
add_test(NAME deepgi_temporal_convergence COMMAND deepgi_temporal_convergence_tests "[temporal_convergence]")
# 171 s at 160x90 on a lightly loaded 2-core machine (most of it the 256
# frames of the 76-tap converged images); the timeout leaves room for a
# loaded one, where it took 600 s.
set_tests_properties(deepgi_temporal_convergence PROPERTIES LABELS "runtime;radiosity" TIMEOUT 1200)
# The convergence targets, printed; skipped while any is missed.
deepgi_add_targets_missed(NAME deepgi_temporal_convergence_targets_missed
  TITLE "Temporal convergence targets" TABLE temporal-convergence-targets.md
  SUITE deepgi_temporal_convergence LABELS runtime radiosity)
