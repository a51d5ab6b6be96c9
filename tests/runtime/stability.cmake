# Numerical hard cases of the deep G-buffer and deep SAO (labels runtime and sao).
add_executable(deepgi_stability_tests ${CMAKE_CURRENT_LIST_DIR}/stability_test.cpp)
target_link_libraries(deepgi_stability_tests PRIVATE deepgi_sao_reference deepgi::report spiral_catch_main)
target_include_directories(deepgi_stability_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src ${PROJECT_SOURCE_DIR}/shaders)
target_compile_definitions(deepgi_stability_tests PRIVATE
  SAO_TEST_AO_TAPS=${AO_TAPS} SAO_TEST_AO_TAU=0)
add_test(NAME deepgi_stability COMMAND deepgi_stability_tests "[stability]")
set_tests_properties(deepgi_stability PROPERTIES LABELS "runtime;sao" TIMEOUT 300)
