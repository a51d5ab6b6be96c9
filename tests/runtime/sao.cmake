# Deep SAO, depth pyramid and bilateral blur tests (labels runtime and sao).
# The CPU reference takes its taps from spiral::codegen; AO_TAPS / AO_TAU
# (cmake/GeneratedHeaders.cmake) say which pattern the build-time
# ao_taps.glsl holds, so the test can ask the library for the same one.
add_library(deepgi_sao_reference STATIC sao_reference.cpp)
target_link_libraries(deepgi_sao_reference PUBLIC deepgi::runtime spiral::codegen)
target_include_directories(deepgi_sao_reference PUBLIC ${CMAKE_CURRENT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/tests)

add_executable(deepgi_sao_tests
  sao_test.cpp
  sao_compose_test.cpp
  sao_thick_test.cpp
  depth_pyramid_test.cpp
  blur_test.cpp
  blur_reference.cpp
  pixel_rotation_test.cpp
  temporal_sequence_test.cpp
  antialias_test.cpp
  ao_march_beam_test.cpp
)
target_link_libraries(deepgi_sao_tests PRIVATE deepgi_sao_reference spiral_catch_main)
# Pass structs and the shared constants are private to the runtime library.
target_include_directories(deepgi_sao_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/shaders)
# AO_TAU empty means the optimum: 0 tells the test to ask spiral::search().
set(_sao_test_tau 0)
if(NOT "${AO_TAU}" STREQUAL "")
  set(_sao_test_tau ${AO_TAU})
endif()
target_compile_definitions(deepgi_sao_tests PRIVATE
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=${_sao_test_tau}
  SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS} SAO_TEST_BLUR_SIGMA="${BLUR_SIGMA}")

# One ctest entry per Catch tag, so ctest -j spreads them over the cores.
# (catch_discover_tests cannot carry two labels: Catch2 v2 splices the
# properties unquoted.)
foreach(tag reference thick march pyramid blur rotation sequence robustness compose antialias)
  add_test(NAME deepgi_sao_${tag} COMMAND deepgi_sao_tests "[${tag}]")
  set_tests_properties(deepgi_sao_${tag} PROPERTIES LABELS "runtime;sao" TIMEOUT 300)
endforeach()

# The slice estimators (gtao, bitmask) against their CPU evaluation and the
# corner's closed form.
add_executable(deepgi_ao_slice_tests ao_slice_test.cpp ao_slice_reference.cpp)
target_link_libraries(deepgi_ao_slice_tests PRIVATE deepgi_sao_reference spiral_catch_main)
target_include_directories(deepgi_ao_slice_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/shaders)
target_compile_definitions(deepgi_ao_slice_tests PRIVATE
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=${_sao_test_tau})
add_test(NAME deepgi_sao_slices COMMAND deepgi_ao_slice_tests "[slices]")
set_tests_properties(deepgi_sao_slices PROPERTIES LABELS "runtime;sao" TIMEOUT 300)
