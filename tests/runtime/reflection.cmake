# Mirror reflections (labels runtime and reflection): the reflection pass
# against a CPU march on the read-back layers, on the gallery scene; a mirror
# seen in a mirror against the traced reflections, on ref-mirrors.
add_executable(deepgi_reflection_tests reflection_test.cpp mirror_chain_test.cpp)
target_link_libraries(deepgi_reflection_tests PRIVATE deepgi::runtime deepgi::reference spiral_catch_main fmt::fmt)
target_include_directories(deepgi_reflection_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
add_test(NAME deepgi_reflection COMMAND deepgi_reflection_tests "[reflection]")
set_tests_properties(deepgi_reflection PROPERTIES LABELS "runtime;reflection" TIMEOUT 600)
