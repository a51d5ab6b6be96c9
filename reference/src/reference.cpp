// The reference's driver: Monte Carlo ambient visibility (visibility.cpp)
// and one-bounce irradiance (irradiance.cpp) on the G-buffer's pixel grid,
// over threads. Every pixel draws the keys that scramble its sample points
// from its own random stream (seed, pixel index; sampling.hpp), so the images
// do not depend on the number of threads or on scheduling.
#include "deepgi/reference.hpp"
#include "sampling.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <system_error>
#include <thread>

namespace deepgi {

using namespace reference_sampling;

glm::vec3 camera_ray_direction(const Camera& camera, const RenderSettings& settings, float x,
                               float y) {
    // As camera_position_at() in gbuffer_encoding.glsl: ndc from the pixel
    // centre over the internal size, scaled by 1 / P00 and 1 / P11.
    const FrameLayout layout = frame_layout(settings);
    const glm::mat4 projection = guard_band_projection(camera, settings);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};
    const glm::vec2 ndc =
        glm::vec2(x, y) *
            glm::vec2(1.0f / float(layout.internal_width), 1.0f / float(layout.internal_height)) *
            2.0f -
        1.0f;
    return {ndc * ray_scale, -1.0f};
}

LayerClassifier layer_classifier(const RayScene& scene, const Camera& camera,
                                 const RenderSettings& render) {
    const FrameLayout layout = frame_layout(render);
    const int w = layout.internal_width, h = layout.internal_height;
    const glm::mat4 view = camera_view_matrix(camera);
    const glm::vec3 eye = glm::vec3(glm::inverse(view)[3]);
    const glm::mat4 projection = guard_band_projection(camera, render);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};
    const float near_plane = camera.near_plane, separation = render.min_separation;
    return [&scene, view, eye, ray_scale, w, h, near_plane, separation](glm::vec3 world) -> int {
        const glm::vec3 c = glm::vec3(view * glm::vec4(world, 1.0f));
        const float depth = -c.z;
        if (!(depth >= near_plane)) return -1;
        // Inside the guard-banded frame (the layers exist nowhere else).
        const glm::vec2 ndc = glm::vec2(c.x, c.y) / (depth * ray_scale);
        const float fx = (ndc.x * 0.5f + 0.5f) * float(w), fy = (ndc.y * 0.5f + 0.5f) * float(h);
        if (!(fx >= 0.0f && fy >= 0.0f && fx < float(w) && fy < float(h))) return -1;
        // The camera ray through the point, of unit depth as in the peel, so
        // distances along it are linear depths.
        const glm::vec3 direction = (world - eye) / depth;
        // The point and the ray's hit carry float error of the point's
        // coordinates and of its depth; a surface this close in depth is the
        // same surface.
        const float tolerance = 1e-4f * depth + surface_offset(world, 0.0f);
        const RayScene::Hit first = scene.intersect_front(eye, direction, near_plane, 1e30f);
        if (!first.hit) return -1;
        if (std::abs(first.distance - depth) <= tolerance) return 0;
        if (depth < first.distance) return -1;  // a face turned away from the camera
        const RayScene::Hit second =
            scene.intersect_front(eye, direction, first.distance + separation, 1e30f);
        if (second.hit && std::abs(second.distance - depth) <= tolerance) return 1;
        return -1;
    };
}

ReferenceImages render_reference(const RayScene& scene, const Camera& camera,
                                 const ReferenceSettings& settings) {
    const RenderSettings& render = settings.render;
    const FrameLayout layout = frame_layout(render);
    const int w = layout.internal_width, h = layout.internal_height;
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    const glm::mat4 view = camera_view_matrix(camera);
    const glm::mat4 camera_to_world = glm::inverse(view);
    const glm::vec3 eye = glm::vec3(camera_to_world[3]);
    const glm::mat4 projection = guard_band_projection(camera, render);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};

    auto image = [&](int channels, float fill) {
        FloatImage result;
        result.width = w;
        result.height = h;
        result.channels = channels;
        result.pixels.assign(pixels * std::size_t(channels), fill);
        return result;
    };
    ReferenceImages out;
    out.depth_layer0 = image(1, 0.0f);
    out.depth_layer1 = image(1, 0.0f);
    out.ambient_visibility = image(1, 1.0f);
    out.hit_visibility = image(1, 1.0f);
    out.occlusion_split = image(3, 0.0f);
    out.standard_error = image(1, 0.0f);
    out.rays = image(1, 0.0f);
    if (settings.irradiance) {
        out.irradiance = image(3, 0.0f);
        out.irradiance_standard_error = image(3, 0.0f);
        out.irradiance_rays = image(1, 0.0f);
        out.irradiance_layer0 = image(3, 0.0f);
        out.irradiance_layer1 = image(3, 0.0f);
        out.irradiance_neither = image(3, 0.0f);
        out.direct_radiance = image(3, 0.0f);
    }
    const bool reflections = settings.reflections && scene.has_mirrors(render.mirror_roughness);
    if (reflections) {
        out.reflection_radiance = image(3, 0.0f);
        out.reflection_hit = image(3, -2.0f);
        out.surface_layers = image(3, -1.0f);
    }
    std::vector<glm::vec3> positions(pixels), normals(pixels);
    std::vector<RayScene::Hit> first_hits(pixels);

    // More workers than rows would idle; the count is also what the system
    // grants: a thread that cannot be created leaves the work to the others.
    const int thread_count =
        std::min(h, settings.threads > 0 ? settings.threads
                                         : int(std::max(1u, std::thread::hardware_concurrency())));
    auto parallel_rows = [&](auto&& row_work, bool report) {
        std::atomic<int> next_row{0};
        std::atomic<long long> done{0};
        std::vector<std::thread> workers;
        auto work = [&] {
            for (int y = next_row++; y < h; y = next_row++) {
                row_work(y);
                done += w;
            }
        };
        for (int i = 0; i < thread_count; ++i) {
            try {
                workers.emplace_back(work);
            } catch (const std::system_error&) {
                if (workers.empty()) throw;
                break;
            }
        }
        if (report && settings.progress) {
            while (done.load() < (long long)pixels) {
                settings.progress(done.load(), (long long)pixels);
                std::this_thread::sleep_for(std::chrono::milliseconds(200));
            }
            settings.progress((long long)pixels, (long long)pixels);
        }
        for (auto& worker : workers) worker.join();
    };

    // Camera rays: layer 0 is the nearest front face past the near plane;
    // layer 1 the nearest front face at least dz behind it (the peel).
    // With a camera-space direction of unit depth, t is linear depth.
    parallel_rows(
        [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const glm::vec2 ndc =
                    (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f -
                    1.0f;
                const glm::vec3 direction_camera(ndc * ray_scale, -1.0f);
                const glm::vec3 direction =
                    glm::vec3(camera_to_world * glm::vec4(direction_camera, 0.0f));
                const RayScene::Hit first =
                    scene.intersect_front(eye, direction, camera.near_plane, 1e30f);
                if (!first.hit) continue;
                out.depth_layer0.pixels[i] = first.distance;
                positions[i] = eye + direction * first.distance;
                normals[i] = first.normal;
                first_hits[i] = first;
                const RayScene::Hit second = scene.intersect_front(
                    eye, direction, first.distance + render.min_separation, 1e30f);
                if (second.hit) out.depth_layer1.pixels[i] = second.distance;
                if (reflections) {
                    out.surface_layers.pixels[3 * i + 0] = float(scene.surface_id(first.primitive));
                    if (second.hit)
                        out.surface_layers.pixels[3 * i + 1] =
                            float(scene.surface_id(second.primitive));
                    out.surface_layers.pixels[3 * i + 2] =
                        scene.mirror(first.primitive, render.mirror_roughness) ? 1.0f : 0.0f;
                }
            }
        },
        false);

    const LayerClassifier classify = layer_classifier(scene, camera, render);

    if (settings.ambient_visibility)
        parallel_rows(
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    if (out.depth_layer0.pixels[i] <= 0.0f) continue;
                    const AoSample s = ambient_visibility_at(
                        scene, positions[i], normals[i], render.ao.radius, settings.rays,
                        stream_seed(settings.seed, i), classify);
                    out.ambient_visibility.pixels[i] = float(s.visibility);
                    out.hit_visibility.pixels[i] = float(s.hit_visibility);
                    out.standard_error.pixels[i] = float(s.standard_error);
                    out.rays.pixels[i] = float(s.rays);
                    out.occlusion_split.pixels[3 * i + 0] = float(s.occlusion_layer0);
                    out.occlusion_split.pixels[3 * i + 1] = float(s.occlusion_layer1);
                    out.occlusion_split.pixels[3 * i + 2] = float(s.occlusion_neither);
                }
            },
            true);

    // Irradiance streams are offset by the pixel count, so they share no
    // random numbers with the ambient visibility of any pixel.
    if (settings.irradiance)
        parallel_rows(
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    if (out.depth_layer0.pixels[i] <= 0.0f) continue;
                    const IrradianceSample s = irradiance_at(
                        scene, positions[i], normals[i], settings.radiosity_radius,
                        settings.irradiance_rays, stream_seed(settings.seed, pixels + i),
                        settings.bounces, classify);
                    for (int c = 0; c < 3; ++c) {
                        out.irradiance.pixels[3 * i + c] = float(s.irradiance[c]);
                        out.irradiance_standard_error.pixels[3 * i + c] =
                            float(s.standard_error[c]);
                        out.irradiance_layer0.pixels[3 * i + c] = float(s.by_layer[0][c]);
                        out.irradiance_layer1.pixels[3 * i + c] = float(s.by_layer[1][c]);
                        out.irradiance_neither.pixels[3 * i + c] = float(s.by_layer[2][c]);
                    }
                    out.irradiance_rays.pixels[i] = float(s.rays);
                    const glm::dvec3 direct =
                        direct_outgoing_radiance(scene, first_hits[i], positions[i]) -
                        glm::dvec3(scene.surface(first_hits[i]).emissive);
                    for (int c = 0; c < 3; ++c)
                        out.direct_radiance.pixels[3 * i + c] = float(direct[c]);
                }
            },
            true);

    // Reflection streams are offset by twice the pixel count, past the
    // ambient visibility's and the irradiance's.
    if (reflections)
        parallel_rows(
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    if (out.surface_layers.pixels[3 * i + 2] != 1.0f) continue;
                    const ReflectionSample s = mirror_reflection_at(
                        scene, eye, positions[i], normals[i],
                        scene.surface(first_hits[i]).shading_normal, settings.radiosity_radius,
                        render.environment, settings.irradiance_rays,
                        stream_seed(settings.seed, 2 * pixels + i), render.mirror_roughness);
                    for (int c = 0; c < 3; ++c)
                        out.reflection_radiance.pixels[3 * i + c] = float(s.radiance[c]);
                    out.reflection_hit.pixels[3 * i + 0] =
                        s.hit.hit ? float(scene.surface_id(s.hit.primitive)) : -1.0f;
                    out.reflection_hit.pixels[3 * i + 1] =
                        s.hit.hit ? float(s.hit.primitive) : -1.0f;
                    out.reflection_hit.pixels[3 * i + 2] = s.hit.hit ? s.hit.distance : 0.0f;
                }
            },
            true);
    return out;
}

}  // namespace deepgi
