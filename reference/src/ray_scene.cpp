// The scene's triangles in an Embree 3 BVH, with the two queries the
// reference needs: any nearest hit (occlusion rays) and the nearest front
// face (camera rays, matching the G-buffer's back-face culling).
#include "deepgi/errors.hpp"
#include "deepgi/reference.hpp"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace deepgi {

struct RayScene::State {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<glm::vec3> face_normals;  // unit, counter-clockwise side
    // Shading inputs, as the G-buffer pass reads them.
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<int> triangle_material;  // -1: the default material
    std::vector<Material> materials;
    std::vector<TextureImage> textures;
    KeyLight key_light;
    std::vector<RayScene::Emitter> emitters;
    std::vector<double> emitter_cdf;  // running sum of the probabilities
    std::vector<int> emitter_of;      // per triangle: index into emitters, or -1
    std::vector<int> surface_of;      // per triangle: surface_id()
    glm::vec3 ambient{0.0f}, background{0.0f};
    ~State() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

RayScene::RayScene(const Scene& scene) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.device = rtcNewDevice(nullptr);
    if (!s.device) throw GraphicsError("cannot create an Embree device");
    s.scene = rtcNewScene(s.device);
    // Robust traversal: rays that graze an edge between two triangles of a
    // plane must not slip through the crack.
    rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_HIGH);

    const std::size_t triangles = scene.indices.size() / 3;
    RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
        std::max<std::size_t>(scene.vertices.size(), 1)));
    for (std::size_t i = 0; i < scene.vertices.size(); ++i) {
        vertices[3 * i + 0] = scene.vertices[i].position.x;
        vertices[3 * i + 1] = scene.vertices[i].position.y;
        vertices[3 * i + 2] = scene.vertices[i].position.z;
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    s.face_normals.resize(triangles);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t a = scene.indices[3 * t], b = scene.indices[3 * t + 1],
                            c = scene.indices[3 * t + 2];
        if (a >= scene.vertices.size() || b >= scene.vertices.size() || c >= scene.vertices.size())
            throw InputError(
                fmt::format("scene '{}': triangle {} indexes past the vertices", scene.name, t));
        indices[3 * t + 0] = a;
        indices[3 * t + 1] = b;
        indices[3 * t + 2] = c;
        const glm::vec3 p0 = scene.vertices[a].position, p1 = scene.vertices[b].position,
                        p2 = scene.vertices[c].position;
        const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
        const float length = glm::length(n);
        s.face_normals[t] = length > 0.0f ? n / length : glm::vec3(0.0f);
        lo = glm::min(lo, glm::min(p0, glm::min(p1, p2)));
        hi = glm::max(hi, glm::max(p0, glm::max(p1, p2)));
    }
    if (triangles > 0) scale_ = std::max(glm::length(hi - lo), 1e-6f);
    s.vertices = scene.vertices;
    s.indices.assign(scene.indices.begin(), scene.indices.begin() + 3 * triangles);
    s.materials = scene.materials;
    s.textures = scene.textures;
    s.key_light = scene.key_light;
    s.ambient = scene.ambient;
    s.background = scene.background;
    s.triangle_material.assign(triangles, -1);
    for (const DrawBatch& batch : scene.batches) {
        if (batch.material < 0 || std::size_t(batch.material) >= scene.materials.size()) continue;
        const std::size_t first = batch.first_index / 3;
        const std::size_t last = std::min<std::size_t>(
            triangles, (std::size_t(batch.first_index) + batch.index_count) / 3);
        for (std::size_t t = first; t < last; ++t) s.triangle_material[t] = batch.material;
    }
    // Planar surfaces: triangles of one material in one plane, keyed by the
    // rounded plane; the surface is named by its first triangle.
    {
        std::map<std::array<long long, 5>, int> first_of;
        s.surface_of.assign(triangles, 0);
        const double offset_unit = 1e-4 * double(scale_);
        for (std::size_t t = 0; t < triangles; ++t) {
            const glm::dvec3 n(s.face_normals[t]);
            const double offset =
                glm::dot(n, glm::dvec3(scene.vertices[scene.indices[3 * t]].position));
            const std::array<long long, 5> key = {s.triangle_material[t], std::llround(n.x * 1e4),
                                                  std::llround(n.y * 1e4), std::llround(n.z * 1e4),
                                                  std::llround(offset / offset_unit)};
            s.surface_of[t] = first_of.emplace(key, int(t)).first->second;
        }
    }
    // Emitters, in triangle order, with their power-times-area weights.
    s.emitter_of.assign(triangles, -1);
    double total = 0.0;
    for (std::size_t t = 0; t < triangles; ++t) {
        const int m = s.triangle_material[t];
        if (m < 0) continue;
        const glm::dvec3 emissive(s.materials[std::size_t(m)].emissive);
        const double power = (emissive.x + emissive.y + emissive.z) / 3.0;
        if (!(power > 0.0) || !std::isfinite(power)) continue;
        const glm::dvec3 p0(scene.vertices[scene.indices[3 * t]].position);
        const glm::dvec3 p1(scene.vertices[scene.indices[3 * t + 1]].position);
        const glm::dvec3 p2(scene.vertices[scene.indices[3 * t + 2]].position);
        const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
        const double area = 0.5 * glm::length(cross);
        if (!(area > 0.0) || !std::isfinite(area)) continue;
        RayScene::Emitter emitter;
        emitter.primitive = unsigned(t);
        emitter.p0 = p0;
        emitter.edge1 = p1 - p0;
        emitter.edge2 = p2 - p0;
        // The same normal the hits report, so both ways of reaching an
        // emitter agree on which side faces the point.
        emitter.normal = glm::dvec3(s.face_normals[t]);
        emitter.emissive = emissive;
        emitter.area = area;
        emitter.probability = power * area;
        total += power * area;
        s.emitter_of[t] = int(s.emitters.size());
        s.emitters.push_back(emitter);
    }
    double running = 0.0;
    for (RayScene::Emitter& emitter : s.emitters) {
        emitter.probability /= total;
        running += emitter.probability;
        s.emitter_cdf.push_back(running);
    }
    if (!s.emitter_cdf.empty()) s.emitter_cdf.back() = 1.0;  // no gap left by rounding

    rtcCommitGeometry(geometry);
    rtcAttachGeometry(s.scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(s.scene);
}

RayScene::~RayScene() = default;

RayScene::Hit RayScene::intersect(glm::vec3 origin, glm::vec3 direction, float t_near,
                                  float t_far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray.org_x = origin.x;
    query.ray.org_y = origin.y;
    query.ray.org_z = origin.z;
    query.ray.dir_x = direction.x;
    query.ray.dir_y = direction.y;
    query.ray.dir_z = direction.z;
    query.ray.tnear = t_near;
    query.ray.tfar = t_far;
    query.ray.mask = 0xFFFFFFFFu;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(state_->scene, &context, &query);
    Hit hit;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.distance = query.ray.tfar;
    hit.primitive = query.hit.primID;
    hit.normal = state_->face_normals[query.hit.primID];
    hit.barycentric = {query.hit.u, query.hit.v};
    return hit;
}

namespace {

float srgb_decode(std::uint8_t encoded) {
    const float c = float(encoded) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

RayScene::Surface RayScene::surface(const Hit& hit) const {
    const State& s = *state_;
    Surface result;
    result.shading_normal = hit.normal;
    result.albedo = glm::vec3(1.0f);
    if (!hit.hit || hit.primitive >= s.triangle_material.size()) return result;
    const Vertex& a = s.vertices[s.indices[3 * hit.primitive]];
    const Vertex& b = s.vertices[s.indices[3 * hit.primitive + 1]];
    const Vertex& c = s.vertices[s.indices[3 * hit.primitive + 2]];
    const float u = hit.barycentric.x, v = hit.barycentric.y, w = 1.0f - u - v;
    const glm::vec3 n = a.normal * w + b.normal * u + c.normal * v;
    const float length = glm::length(n);
    if (length > 0.0f && std::isfinite(length)) result.shading_normal = n / length;
    const int m = s.triangle_material[hit.primitive];
    if (m < 0) return result;
    const Material& material = s.materials[std::size_t(m)];
    result.albedo = glm::vec3(material.base_colour);
    result.emissive = material.emissive;
    if (material.base_colour_texture >= 0 &&
        std::size_t(material.base_colour_texture) < s.textures.size()) {
        // Nearest texel with repeat wrapping; rows are stored top to bottom
        // and uv (0, 0) is the top-left corner, as the G-buffer samples them.
        const TextureImage& image = s.textures[std::size_t(material.base_colour_texture)];
        if (image.width > 0 && image.height > 0) {
            const glm::vec2 uv = a.uv * w + b.uv * u + c.uv * v;
            const auto wrap = [](float t, int size) {
                const int i = int(std::floor((t - std::floor(t)) * float(size)));
                return std::clamp(i, 0, size - 1);
            };
            const std::size_t texel = (std::size_t(wrap(uv.y, image.height)) * image.width +
                                       std::size_t(wrap(uv.x, image.width))) *
                                      4;
            result.albedo *=
                glm::vec3(srgb_decode(image.rgba8[texel]), srgb_decode(image.rgba8[texel + 1]),
                          srgb_decode(image.rgba8[texel + 2]));
        }
    }
    return result;
}

const KeyLight& RayScene::key_light() const {
    return state_->key_light;
}

bool RayScene::mirror(unsigned primitive, float mirror_roughness) const {
    const State& s = *state_;
    if (primitive >= s.triangle_material.size()) return false;
    const int m = s.triangle_material[primitive];
    if (m < 0) return false;
    const Material& material = s.materials[std::size_t(m)];
    return material.roughness <= mirror_roughness && material.metallic >= 0.5f;
}

bool RayScene::has_mirrors(float mirror_roughness) const {
    for (std::size_t t = 0; t < state_->triangle_material.size(); ++t)
        if (mirror(unsigned(t), mirror_roughness)) return true;
    return false;
}

int RayScene::surface_id(unsigned primitive) const {
    return primitive < state_->surface_of.size() ? state_->surface_of[primitive] : -1;
}

glm::dvec3 RayScene::environment_radiance(glm::vec3 direction) const {
    // environment_irradiance() of environment.glsl over pi.
    const glm::dvec3 ambient(state_->ambient), background(state_->background);
    if (background.x + background.y + background.z <= 0.0) return ambient;
    const double up = 0.5 + 0.5 * double(glm::normalize(direction).y);
    const glm::dvec3 sky = ambient + 0.25 * background, ground = ambient * 0.5;
    return ground + (sky - ground) * up;
}

const std::vector<RayScene::Emitter>& RayScene::emitters() const {
    return state_->emitters;
}

int RayScene::emitter_index(unsigned primitive) const {
    return primitive < state_->emitter_of.size() ? state_->emitter_of[primitive] : -1;
}

std::size_t RayScene::pick_emitter(double u) const {
    const std::vector<double>& cdf = state_->emitter_cdf;
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min<std::size_t>(std::size_t(it - cdf.begin()), cdf.size() - 1);
}

std::size_t RayScene::pick_emitter(double u, double& within) const {
    const std::vector<double>& cdf = state_->emitter_cdf;
    const std::size_t i = pick_emitter(u);
    const double low = i == 0 ? 0.0 : cdf[i - 1], high = cdf[i];
    within = high > low ? std::clamp((u - low) / (high - low), 0.0, std::nextafter(1.0, 0.0)) : 0.0;
    return i;
}

bool RayScene::occluded(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_near;
    ray.tfar = t_far;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(state_->scene, &context, &ray);
    // Embree marks an occluded ray by setting tfar to -infinity.
    return ray.tfar < 0.0f;
}

RayScene::Hit RayScene::intersect_front(glm::vec3 origin, glm::vec3 direction, float t_near,
                                        float t_far) const {
    // Step past back faces; a few dozen layers at most in practice.
    for (int guard = 0; guard < 1024; ++guard) {
        Hit hit = intersect(origin, direction, t_near, t_far);
        if (!hit.hit || glm::dot(hit.normal, direction) < 0.0f) return hit;
        t_near = std::nextafter(hit.distance, std::numeric_limits<float>::infinity()) +
                 hit.distance * 1e-6f;
    }
    return {};
}

}  // namespace deepgi
