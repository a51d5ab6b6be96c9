#include "gl/pass_timer.hpp"

namespace deepgi {

void PassTimer::begin_frame() {
    timings_.clear();
}

void PassTimer::begin(const std::string& pass) {
    timings_.push_back(PassTiming{pass, 0.0});
    if (use_cpu_clock_) {
        glFinish();
        started_ = std::chrono::steady_clock::now();
        return;
    }
    if (queries_.size() < timings_.size()) queries_.push_back(gl::create_query(GL_TIME_ELAPSED));
    glBeginQuery(GL_TIME_ELAPSED, queries_[timings_.size() - 1].get());
}

void PassTimer::end() {
    if (use_cpu_clock_) {
        glFinish();
        const auto elapsed = std::chrono::steady_clock::now() - started_;
        timings_.back().milliseconds = std::chrono::duration<double, std::milli>(elapsed).count();
        return;
    }
    glEndQuery(GL_TIME_ELAPSED);
}

void PassTimer::end_frame() {
    if (use_cpu_clock_) return;
    for (std::size_t i = 0; i < timings_.size(); ++i) {
        GLuint64 nanoseconds = 0;
        glGetQueryObjectui64v(queries_[i].get(), GL_QUERY_RESULT, &nanoseconds);
        timings_[i].milliseconds = double(nanoseconds) * 1e-6;
    }
}

}  // namespace deepgi
