// The frame's passes in the order they run, one line each. DEEPGI_PASS(x)
// stands for the factory `make_x_pass(const ShaderLoader&, const Scene&)`
// that the pass's own file in runtime/src/passes/ defines. passes.hpp
// declares every factory from this list and default_pass_list() (frame.cpp)
// lists them, so adding a pass to the frame is one line here, after the
// passes whose outputs it reads. No include guard: each includer defines
// DEEPGI_PASS first.
DEEPGI_PASS(shadow)
DEEPGI_PASS(gbuffer)
DEEPGI_PASS(backface_depth)  // the march, the thick spiral, mirrors, radiosity visibility
DEEPGI_PASS(direct_light)
DEEPGI_PASS(depth_pyramid)
DEEPGI_PASS(normal_pair)  // the march, the thick spiral and the solid angle
DEEPGI_PASS(sao)
DEEPGI_PASS(ao_temporal)
DEEPGI_PASS(radiosity_prepare)
DEEPGI_PASS(radiosity)
DEEPGI_PASS(blur)        // AO and radiosity E share one bilateral blur (bilateral_blur_pass.cpp)
DEEPGI_PASS(reflection)  // scenes with mirrors only
DEEPGI_PASS(reflection_temporal)
DEEPGI_PASS(compose)
DEEPGI_PASS(frame_statistics)  // exposure, depth ranges
DEEPGI_PASS(tonemap)           // final image only
DEEPGI_PASS(debug_view)        // any other view
DEEPGI_PASS(antialias)         // final image only, after the tonemap
