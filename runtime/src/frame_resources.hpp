#pragma once
// What the passes of one frame share: the frame's inputs, the textures one
// pass writes and later passes read (by name, so a new input is not a new
// parameter), and the history that outlives a frame.
#include "deepgi/gl_objects.hpp"
#include "deepgi/renderer.hpp"
#include "scene/scene_gpu.hpp"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi {

// A ping-pong pair: one texture is written this frame, the other holds what
// the previous frame wrote. FrameResources swaps them at the end of a frame.
struct HistoryPair {
    gl::Texture slots[2];
    int written_slot = 0;
    GLenum clear_format = GL_RGBA;  // GL_DEPTH_COMPONENT for depth textures
    // What the slots were created as: a reallocation that asks for the same
    // keeps them, and the history they hold.
    GLenum internal_format = 0;
    int width = 0, height = 0;

    GLuint written() const { return slots[written_slot].get(); }
    GLuint previous() const { return slots[1 - written_slot].get(); }
};

// The key light's shadow projection, which both the shadow pass and the frame
// constants need.
struct ShadowProjection {
    glm::mat4 light_view_projection{1.0f};
    float normal_offset = 0.0f;  // metres along the normal before the lookup, against acne
                                 // (point light: per metre of distance from the light)
    // Point light: the light's position and the near and far planes of the
    // six 90-degree faces of its shadow cube.
    glm::vec3 cube_centre{0.0f};
    float cube_near = 0.0f, cube_far = 0.0f;
    int size = 0;
};

class FrameResources {
public:
    // ---- inputs, valid while the passes resize or run ----
    const RenderSettings* settings = nullptr;
    const Scene* scene = nullptr;
    const SceneGpu* scene_gpu = nullptr;
    FrameLayout layout;
    ShadowProjection shadow;
    Camera camera;
    // The camera of the last frame; equals `camera` when there is no history,
    // so motion is zero on the first frame after an invalidation.
    Camera previous_camera;
    GLuint empty_vertex_array = 0;
    // Counts changes of the key light (Renderer::set_key_light). A pass whose
    // history holds lit radiance (radiosity, reflections) keeps the version
    // it last ran with: on a change it treats every pixel as moving for one
    // frame, so the new lighting takes over at the motion blend's pace rather
    // than the still running mean's hundreds of frames.
    std::uint64_t lighting_version = 0;

    // ---- named textures of this frame ----
    // Throws GraphicsError when the running pass did not declare `name` as a
    // write (the frame sets the running pass's writes around run()).
    void publish(const std::string& name, GLuint texture);
    // Throws GraphicsError naming the texture when no earlier pass published it.
    GLuint texture(std::string_view name) const;
    // The frame's bookkeeping around one pass's run(): forget what the last
    // frame published before the first pass, and check what a pass published
    // against what it declared.
    void begin_frame_textures();
    // `writes` and `value_reads` must outlive the pass's run (the frame's
    // checked declarations).
    void begin_pass(std::string_view pass, const std::vector<std::string>& writes,
                    const std::vector<std::string>& value_reads = {});
    // Throws GraphicsError naming the pass and the first declared write it
    // did not publish.
    void end_pass();
    // Named integers a pass computes for later ones (e.g. the pyramid's depth).
    void publish_int(const std::string& name, int value);
    int integer(std::string_view name) const;
    // Values the passes give each other from their settings (PassValue),
    // set by the frame from the checked declarations whenever the settings
    // change. value() throws GraphicsError when the running pass did not
    // declare the read.
    void set_values(std::map<std::string, float, std::less<>> values) {
        values_ = std::move(values);
    }
    float value(std::string_view name) const;

    // ---- the displayed image: viewport-sized RGBA8 that the last pass writes ----
    gl::Texture display;
    gl::Framebuffer display_framebuffer;
    void allocate_display(int width, int height);

    // ---- history ----
    // Allocates a named pair, both slots cleared; a pair of that name, format
    // and size that exists already is kept as it is, history and all.
    HistoryPair& allocate_history(const std::string& name, GLenum internal_format, int width,
                                  int height);
    HistoryPair& history(std::string_view name);
    // False until a frame has been rendered since the last invalidation.
    bool history_valid() const { return history_valid_; }
    // Forgets the previous frame: clears every pair's previous slot and the
    // previous camera. The reason goes to the log (and to a GL debug message,
    // so it shows in a capture).
    void invalidate_history(const std::string& reason);
    const std::vector<std::string>& history_log() const { return history_log_; }
    // Swaps every pair and remembers this frame's camera.
    void end_frame();

private:
    std::map<std::string, GLuint, std::less<>> textures_;
    std::string running_pass_;                                   // empty outside a pass's run()
    const std::vector<std::string>* declared_writes_ = nullptr;  // the running pass's
    std::vector<std::string> published_;                         // what it has published so far
    std::map<std::string, int, std::less<>> integers_;
    std::map<std::string, float, std::less<>> values_;
    const std::vector<std::string>* declared_value_reads_ = nullptr;  // the running pass's
    std::map<std::string, HistoryPair, std::less<>> history_;
    bool history_valid_ = false;
    std::vector<std::string> history_log_;
};

}  // namespace deepgi
