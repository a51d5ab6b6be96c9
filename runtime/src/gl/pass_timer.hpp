#pragma once
// Per-pass timing. On a real GPU: GL_TIME_ELAPSED queries. On llvmpipe the GL
// calls run on the CPU and queries report little, so the timer brackets each
// pass with glFinish and reads a CPU clock.
#include "deepgi/gl_objects.hpp"
#include "deepgi/renderer.hpp"

#include <chrono>
#include <string>
#include <vector>

namespace deepgi {

class PassTimer {
public:
    explicit PassTimer(bool use_cpu_clock) : use_cpu_clock_(use_cpu_clock) {}
    void begin_frame();
    void begin(const std::string& pass);
    void end();
    // Collects the query results of this frame (waits for the GPU).
    void end_frame();
    const std::vector<PassTiming>& timings() const { return timings_; }
    bool uses_cpu_clock() const { return use_cpu_clock_; }

private:
    bool use_cpu_clock_;
    std::vector<PassTiming> timings_;
    std::vector<gl::Query> queries_;
    std::chrono::steady_clock::time_point started_;
};

// Times one pass for the duration of a scope, inside a GL debug group of the
// same name so a RenderDoc or apitrace capture reads like the timer table.
class ScopedPass {
public:
    ScopedPass(PassTimer& timer, const std::string& pass) : timer_(timer) {
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, pass.c_str());
        timer_.begin(pass);
    }
    ~ScopedPass() {
        timer_.end();
        glPopDebugGroup();
    }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    PassTimer& timer_;
};

}  // namespace deepgi
