# The renderer against the ray-traced reference: each suite needs a GL
# context (headless EGL) and Embree, and runs its scenes in one process (one
# ctest entry per scene would repeat the context set-up). Each suite's
# targets-missed entry prints the table of its targets (targets_missed.cmake).
#
# deepgi_add_accuracy_suite(NAME <test> SOURCE <file> TAG <catch tag>
#                           TIMEOUT <s> LABELS <label>... TITLE <title> TABLE <table.md>)
# adds the executable <test>_tests, the test <test> running TAG, and
# <test>_targets_missed.
function(deepgi_add_accuracy_suite)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "" "NAME;SOURCE;TAG;TIMEOUT;TITLE;TABLE" "LABELS")
  add_executable(${ARG_NAME}_tests ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/${ARG_SOURCE})
  target_link_libraries(${ARG_NAME}_tests PRIVATE deepgi::reference spiral_catch_main fmt::fmt)
  target_include_directories(${ARG_NAME}_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  add_test(NAME ${ARG_NAME} COMMAND ${ARG_NAME}_tests "${ARG_TAG}")
  set_tests_properties(${ARG_NAME} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
  deepgi_add_targets_missed(NAME ${ARG_NAME}_targets_missed TITLE "${ARG_TITLE}"
    TABLE ${ARG_TABLE} SUITE ${ARG_NAME} LABELS ${ARG_LABELS})
endfunction()

# Deep SAO (docs/deep-sao.md). Five estimators on seven scenes, the thick
# spiral over 64 still frames: up to about 20 minutes on llvmpipe, 2 cores.
deepgi_add_accuracy_suite(NAME deepgi_ao_accuracy SOURCE ao_accuracy_test.cpp
  TAG "[ao-accuracy]" TIMEOUT 1800 LABELS runtime sao
  TITLE "AO accuracy targets" TABLE ao-accuracy-targets.md)
target_include_directories(deepgi_ao_accuracy_tests PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src)
# The blur's reach in pixels, for what counts as open after the blur.
target_compile_definitions(deepgi_ao_accuracy_tests PRIVATE SAO_TEST_BLUR_RADIUS=${BLUR_RADIUS})

# Deep radiosity against the reference's one-bounce irradiance.
deepgi_add_accuracy_suite(NAME deepgi_radiosity_accuracy SOURCE radiosity_accuracy_test.cpp
  TAG "[radiosity-accuracy]" TIMEOUT 600 LABELS runtime radiosity
  TITLE "Radiosity accuracy targets" TABLE radiosity-accuracy-targets.md)

# The march behind a thin beam (ao_march_beam_test.cpp, in deepgi_sao_tests):
# its known miss, printed (sao.cmake, which defines that test, is read first).
deepgi_add_targets_missed(NAME deepgi_ao_march_beam_targets_missed TITLE "AO march beam targets"
  TABLE ao-march-beam-targets.md SUITE deepgi_sao_march LABELS runtime sao)

# The direct light's shadow map against traced shadow rays.
deepgi_add_accuracy_suite(NAME deepgi_shadow_accuracy SOURCE shadow_accuracy_test.cpp
  TAG "[shadow-accuracy]" TIMEOUT 600 LABELS runtime
  TITLE "Shadow accuracy targets" TABLE shadow-accuracy-targets.md)
