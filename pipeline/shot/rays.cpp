// Embree device, scenes and queries. Opaque surfaces and stroke casters live in two Embree
// scenes: a shadow ray first asks the opaque one whether anything blocks it (any hit ends the
// query), then walks the casters with an occlusion filter that evaluates each stroke's mask.
#include "pipeline/shot/rays.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <stdexcept>
#include <string>

#include "shading/portable_math.h"

namespace pleinair {

FlushDenormals::FlushDenormals() : saved_(_mm_getcsr()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

FlushDenormals::~FlushDenormals() { _mm_setcsr(saved_); }

float ray_epsilon(const glm::dvec3& p) {
    double m = std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return static_cast<float>(32.0 * std::numeric_limits<float>::epsilon() * m);
}

namespace {

// A caster as the filter reads it: its card relative to the anchor, as Embree sees it.
struct Card {
    glm::vec3 center;
    glm::vec3 axis_s, axis_t;
    float half_w, half_l;
    StrokeNoise noise;
};

// What the caster filter reads, per caster geometry.
struct CasterSet {
    std::vector<Card> cards;
    const StrokeShaderParams* shader = nullptr;
    const EdgeTable* edge = nullptr;
};

// The filter's per-ray state rides behind Embree's context (Embree's documented way to pass
// data to callbacks).
struct ShadowContext {
    RTCIntersectContext ctx;
    ShadowMode mode = ShadowMode::kTransmissive;
    // Optical depth in fixed point (1/65536 of a halving): an integer sum does not depend on
    // the order Embree reports the cards in, so neither do the bytes of the image.
    uint64_t depth = 0;
    bool blocked = false;
    // A mirror's ray (transmittance_depth): every card along it is counted (none blocks), and
    // the distances of the cards, weighed by the depth each adds, summed in fixed point (1/64 of
    // a unit), so the sum, like the depth, does not depend on the order of the cards.
    bool through = false;
    uint64_t depth_distance = 0;
    // Embree may report a primitive more than once (spatial splits): count each card once,
    // keyed by its instance (or geometry) and primitive.
    static constexpr int kSeen = 32;
    uint64_t seen[kSeen];
    int n_seen = 0;
    int overflow = 0;
    // The sun's card frame (sun_card_frame) for the last direction a member's filter saw: one
    // per instance's space, not one per card the ray passes.
    glm::vec3 frame_dir{0.0f}, sun{0.0f}, a0{0.0f}, b0{0.0f};
};

constexpr uint64_t kOpaqueDepth = 10 * 65536;  // 2^-10: a thousandth of the light

// The stroke mask's opacity at (s, t) on a card (0 outside it), its noise asked for only
// inside.
template <class Noise>
float card_opacity(const StrokeShaderParams& p, const EdgeTable& edge, float s, float t,
                   Noise&& noise) {
    if (!(s > 0.0f && s < 1.0f && t > 0.0f && t < 1.0f)) return 0.0f;
    const float e = edge_mask(edge, s, t, p.stroke_fullness);
    if (e <= p.stroke_feather_min) return 0.0f;
    return stroke_opacity(p, stroke_noise(noise(), s, t, 1), e);
}

// Opacity of caster `c` where the ray crosses its card.
float caster_opacity(const CasterSet& set, uint32_t prim, const glm::vec3& org,
                     const glm::vec3& dir) {
    const Card& c = set.cards[prim];
    const glm::vec3 n = glm::cross(c.axis_s, c.axis_t);
    const float dn = glm::dot(dir, n);
    if (std::abs(dn) < 1e-12f) return 0.0f;
    const glm::vec3& center = c.center;
    const float t = glm::dot(center - org, n) / dn;
    const glm::vec3 rel = org + dir * t - center;
    const float s = 0.5f + 0.5f * glm::dot(rel, c.axis_s) / c.half_w;
    const float tt = 0.5f + 0.5f * glm::dot(rel, c.axis_t) / c.half_l;
    return card_opacity(*set.shader, *set.edge, s, tt, [&] { return c.noise; });
}

// What a member's card keeps of its leaf for the filter: the same values member_opacity would
// compute from the label at every hit (two hashes, a cosine, a sine and two powers).
struct CardConstants {
    float cos_a = 1, sin_a = 0;  // its stroke's angle jitter
    float half_w = 0, half_l = 0;
    float outer = 0;  // stroke_outer: its lightness term that no light changes
};

CardConstants card_constants(const MemberCasters& m, size_t j) {
    const StrokeShaderParams& p = *m.shader;
    const float label = m.label[j];
    const double ang = stroke_angle_jitter(p, label);
    CardConstants c;
    c.cos_a = static_cast<float>(pmath::cos(ang)), c.sin_a = static_cast<float>(pmath::sin(ang));
    c.half_w = 0.5f * m.stroke_width * stroke_size_jitter(p, label);
    c.half_l = c.half_w * p.stroke_aspect;
    c.outer = stroke_outer(p, m.center_distance[j], m.branch_distance[j]);
    return c;
}

// Opacity of a member's card j where a ray (in the member's space, running towards the sun
// `sc->sun`, its frame set) crosses it: the card leaf_casters places in the world, built here
// from the ray's direction as sun_card_axes turns it.
float member_opacity(const MemberCasters& m, const CardConstants& c, uint32_t j,
                     const ShadowContext& sc, const glm::vec3& org) {
    const StrokeShaderParams& p = *m.shader;
    glm::vec3 axis_s, axis_t;
    sun_card_turn(c.cos_a, c.sin_a, sc.a0, sc.b0, axis_s, axis_t);
    const glm::vec3& center = m.position[j];
    const glm::vec3 rel = org + sc.sun * glm::dot(center - org, sc.sun) - center;
    const float s = 0.5f + 0.5f * glm::dot(rel, axis_s) / c.half_w;
    const float tt = 0.5f + 0.5f * glm::dot(rel, axis_t) / c.half_l;
    return card_opacity(p, *m.edge, s, tt, [&] {
        return lit_stroke_noise(p, glm::dot(m.normal[j], sc.sun), c.outer, m.center_distance[j],
                                m.label[j]);
    });
}

// Sets the context's sun and its card frame for a ray of direction `dir` (nonzero).
void set_sun_frame(ShadowContext* sc, const glm::vec3& dir) {
    // Bit for bit (a -0 is not a +0 here), so the frame is the one the direction gives.
    if (std::memcmp(&dir, &sc->frame_dir, sizeof dir) == 0) return;
    sc->frame_dir = dir;
    sc->sun = dir / glm::length(dir);
    sun_card_frame(sc->sun, sc->a0, sc->b0);
}

// Whether the ray has met card `key` before (then it is not counted again).
bool seen_before(ShadowContext* sc, uint64_t key) {
    for (int k = 0; k < sc->n_seen; ++k)
        if (sc->seen[k] == key) return true;
    if (sc->n_seen < ShadowContext::kSeen)
        sc->seen[sc->n_seen++] = key;
    else
        ++sc->overflow;
    return false;
}

// Adds a card of opacity a to the ray's optical depth; true when the ray is now blocked
// (the hit is accepted and the query ends), false to keep walking through the cards.
// `t` is the card's distance along the ray.
bool absorb(ShadowContext* sc, float a, float t) {
    if (sc->mode == ShadowMode::kThreshold && !sc->through) {
        if (a > 0.5f) sc->blocked = true;
        return sc->blocked;
    }
    if (a > 0.0f) {
        const uint64_t d =
            static_cast<uint64_t>(std::lround(-pmath::log2(std::max(1.0f - a, 1e-6f)) * 65536.0f));
        sc->depth += d;
        if (sc->through) {
            sc->depth_distance += d * static_cast<uint64_t>(std::lround(std::max(t, 0.0f) * 64.0f));
            return false;
        }
        if (sc->depth >= kOpaqueDepth) sc->blocked = true;
    }
    return sc->blocked;
}

glm::vec3 ray_org(const RTCFilterFunctionNArguments* args, unsigned i) {
    return {RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
            RTCRayN_org_z(args->ray, args->N, i)};
}
glm::vec3 ray_dir(const RTCFilterFunctionNArguments* args, unsigned i) {
    return {RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
            RTCRayN_dir_z(args->ray, args->N, i)};
}

void caster_filter(const RTCFilterFunctionNArguments* args) {
    auto* sc = reinterpret_cast<ShadowContext*>(const_cast<RTCIntersectContext*>(args->context));
    const auto* set = static_cast<const CasterSet*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        const uint64_t geom = 0x80000000u | RTCHitN_geomID(args->hit, args->N, i);
        if (seen_before(sc, geom << 32 | prim) ||
            !absorb(sc, caster_opacity(*set, prim, ray_org(args, i), ray_dir(args, i)),
                    RTCRayN_tfar(args->ray, args->N, i)))
            args->valid[i] = 0;  // reject: keep walking through the cards
    }
}

// A member's cards are Embree user primitives (a disc's built-in test skips hits within two
// radii of the ray's origin, which is where a leaf's neighbours shade it): bounded by the
// card's half diagonal about its centre, crossed where the ray passes its centre.
struct MemberPrimitives {
    MemberCasters casters;
    std::vector<float> radius;  // the card's half diagonal, a hair wider
    std::vector<CardConstants> cards;
};

void member_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* m = static_cast<const MemberPrimitives*>(args->geometryUserPtr);
    const glm::vec3& c = m->casters.position[args->primID];
    const float r = m->radius[args->primID];
    RTCBounds* b = args->bounds_o;
    b->lower_x = c.x - r, b->lower_y = c.y - r, b->lower_z = c.z - r;
    b->upper_x = c.x + r, b->upper_y = c.y + r, b->upper_z = c.z + r;
}

// Shadow rays only: Embree hands the ray in the instanced scene's space and the instance in
// the context. A card that blocks the ray ends it (tfar = -inf, Embree's "occluded").
void member_occluded(const RTCOccludedFunctionNArguments* args) {
    auto* sc = reinterpret_cast<ShadowContext*>(args->context);
    const auto* m = static_cast<const MemberPrimitives*>(args->geometryUserPtr);
    const uint32_t prim = args->primID;
    const uint64_t inst = args->context->instID[0];
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::vec3 org(RTCRayN_org_x(args->ray, args->N, i),
                            RTCRayN_org_y(args->ray, args->N, i),
                            RTCRayN_org_z(args->ray, args->N, i));
        const glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i),
                            RTCRayN_dir_y(args->ray, args->N, i),
                            RTCRayN_dir_z(args->ray, args->N, i));
        const float dd = glm::dot(dir, dir);
        if (!(dd > 0.0f)) continue;
        const float t = glm::dot(m->casters.position[prim] - org, dir) / dd;
        if (!(t >= RTCRayN_tnear(args->ray, args->N, i) &&
              t <= RTCRayN_tfar(args->ray, args->N, i)))
            continue;
        if (seen_before(sc, inst << 32 | prim)) continue;
        set_sun_frame(sc, dir);
        if (absorb(sc, member_opacity(m->casters, m->cards[prim], prim, *sc, org), t))
            RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

// Never asked (the casters' scene answers shadow rays only), but Embree wants one.
void member_intersect(const RTCIntersectFunctionNArguments*) {}

void fill_ray(RTCRay& r, const glm::dvec3& world, const glm::dvec3& anchor, const glm::vec3& d,
              float tmax, const glm::vec3* n) {
    // Embree sees coordinates relative to the anchor, in float: their size sets the spacing, so
    // a tree far from the world's origin traces as the same tree near it. A point on a surface
    // (given its normal) may come from float world coordinates (terrain strokes): its offset
    // covers their spacing too.
    const float eps =
        n ? std::max(ray_epsilon(world), ray_epsilon(world - anchor)) : ray_epsilon(world - anchor);
    glm::vec3 o(world - anchor);
    if (n) o += (glm::dot(*n, d) < 0 ? -*n : *n) * eps;
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = eps;  // the offset along the ray
    r.tfar = std::max(tmax, eps);
    r.time = 0;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
}

// A quad mesh's vertex and index buffers, placed by offset - anchor.
void set_quad_buffers(RTCGeometry g, const QuadMesh& mesh, const glm::dvec3& shift) {
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        glm::dvec3 p = glm::dvec3(mesh.positions[i]) + shift;
        v[3 * i] = static_cast<float>(p.x);
        v[3 * i + 1] = static_cast<float>(p.y);
        v[3 * i + 2] = static_cast<float>(p.z);
    }
    auto* q = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), mesh.quads.size()));
    for (size_t i = 0; i < mesh.quads.size(); ++i)
        for (int k = 0; k < 4; ++k) q[4 * i + k] = mesh.quads[i][k];
}

std::string& device_config() {
    static std::string config = kPortableRayDevice;
    return config;
}

RTCDevice new_device() {
    RTCDevice d = rtcNewDevice(device_config().empty() ? nullptr : device_config().c_str());
    if (!d)
        throw std::runtime_error("Embree: cannot create a device (error " +
                                 std::to_string(rtcGetDeviceError(nullptr)) + ")");
    return d;
}

}  // namespace

void set_ray_device_config(const std::string& config) { device_config() = config; }

struct RayMeshes::Impl {
    RTCDevice device = nullptr;
    std::vector<RTCScene> scenes;  // one per mesh
    // One per member's caster set, and what its filter reads.
    std::vector<RTCScene> caster_scenes;
    std::vector<std::unique_ptr<MemberPrimitives>> casters;
    ~Impl() {
        for (RTCScene s : scenes) rtcReleaseScene(s);
        for (RTCScene s : caster_scenes) rtcReleaseScene(s);
        if (device) rtcReleaseDevice(device);
    }
};

RayMeshes::RayMeshes() : impl_(std::make_shared<Impl>()) { impl_->device = new_device(); }
RayMeshes::~RayMeshes() = default;

uint32_t RayMeshes::add(const QuadMesh& mesh) {
    RTCScene scene = rtcNewScene(impl_->device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_QUAD);
    set_quad_buffers(g, mesh, glm::dvec3(0.0));
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    impl_->scenes.push_back(scene);
    return static_cast<uint32_t>(impl_->scenes.size() - 1);
}

uint32_t RayMeshes::add_casters(const MemberCasters& m) {
    RTCScene scene = rtcNewScene(impl_->device);
    // Medium quality builds without spatial splits: fewer repeated filter calls.
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    auto data = std::make_unique<MemberPrimitives>();
    data->casters = m;
    if (m.count > 0) {
        RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
        if (!g)
            throw std::runtime_error("Embree: cannot create a user geometry (error " +
                                     std::to_string(rtcGetDeviceError(impl_->device)) + ")");
        const StrokeShaderParams& p = *m.shader;
        const float diagonal = std::sqrt(1.0f + p.stroke_aspect * p.stroke_aspect);
        data->radius.resize(m.count);
        data->cards.resize(m.count);
        // A hair wider than the card, so float rounding at its corners loses nothing.
        for (size_t j = 0; j < m.count; ++j) {
            data->radius[j] =
                1.001f * 0.5f * m.stroke_width * stroke_size_jitter(p, m.label[j]) * diagonal;
            data->cards[j] = card_constants(m, j);
        }
        rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(m.count));
        rtcSetGeometryUserData(g, data.get());
        rtcSetGeometryBoundsFunction(g, member_bounds, nullptr);
        rtcSetGeometryIntersectFunction(g, member_intersect);
        rtcSetGeometryOccludedFunction(g, member_occluded);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
    }
    impl_->caster_scenes.push_back(scene);
    impl_->casters.push_back(std::move(data));
    return static_cast<uint32_t>(impl_->caster_scenes.size() - 1);
}

void RayMeshes::commit() {
    const size_t meshes = impl_->scenes.size();
    tbb::parallel_for(size_t{0}, meshes + impl_->caster_scenes.size(), [&](size_t i) {
        FlushDenormals ftz;
        rtcCommitScene(i < meshes ? impl_->scenes[i] : impl_->caster_scenes[i - meshes]);
    });
}

uint32_t RayMeshes::size() const { return static_cast<uint32_t>(impl_->scenes.size()); }
uint32_t RayMeshes::caster_sets() const {
    return static_cast<uint32_t>(impl_->caster_scenes.size());
}

struct RayScene::Impl {
    glm::dvec3 anchor;
    std::shared_ptr<RayMeshes::Impl> shared;  // keeps the device and instanced meshes alive
    // Per geometry id: how a hit's object-space normal turns into the world's (identity for
    // plain meshes; the inverse transpose of an instance's linear part).
    std::vector<glm::mat3> normal_to_world;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;    // opaque surfaces
    RTCScene casters = nullptr;  // stroke cards, created on first use
    uint32_t meshes = 0;
    uint32_t caster_total = 0;   // cards, counting each instance's
    uint32_t caster_stored = 0;  // cards held here
    std::vector<std::unique_ptr<CasterSet>> sets;
};

RayScene::RayScene(const glm::dvec3& anchor, const RayMeshes* shared)
    : impl_(std::make_unique<Impl>()) {
    FlushDenormals ftz;
    impl_->anchor = anchor;
    if (shared) {
        impl_->shared = shared->impl_;
        impl_->device = shared->impl_->device;
        rtcRetainDevice(impl_->device);
    } else {
        impl_->device = new_device();
    }
    impl_->scene = rtcNewScene(impl_->device);
    // Medium: scenes are built once per frame, and high quality costs more than it saves.
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_MEDIUM);
}

RayScene::~RayScene() {
    if (impl_->casters) rtcReleaseScene(impl_->casters);
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

// Commits g, attaches it to the opaque scene and records how its normals reach the world.
uint32_t RayScene::attach(void* geometry, const glm::mat3& normal_to_world) {
    auto g = static_cast<RTCGeometry>(geometry);
    if (!g)
        throw std::runtime_error("Embree: cannot create a geometry (error " +
                                 std::to_string(rtcGetDeviceError(impl_->device)) + ")");
    rtcCommitGeometry(g);
    uint32_t id = rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
    if (id == RTC_INVALID_GEOMETRY_ID)
        throw std::runtime_error("Embree: cannot attach a geometry (error " +
                                 std::to_string(rtcGetDeviceError(impl_->device)) + ")");
    ++impl_->meshes;
    impl_->normal_to_world.resize(std::max<size_t>(impl_->normal_to_world.size(), id + 1),
                                  glm::mat3(1.0f));
    impl_->normal_to_world[id] = normal_to_world;
    return id;
}

uint32_t RayScene::add_mesh(const QuadMesh& mesh, const glm::dvec3& offset) {
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_QUAD);
    set_quad_buffers(g, mesh, offset - impl_->anchor);
    return attach(g, glm::mat3(1.0f));
}

namespace {

// An instance of `scene` at world = offset + linear * p, relative to the anchor.
RTCGeometry new_instance(RTCDevice device, RTCScene scene, const glm::dmat3& linear,
                         const glm::dvec3& offset, const glm::dvec3& anchor) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, scene);
    // Column-major 3x4: the linear part's columns, then the translation from the anchor.
    const glm::dvec3 t = offset - anchor;
    float xfm[12];
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) xfm[3 * c + r] = static_cast<float>(linear[c][r]);
    xfm[9] = static_cast<float>(t.x), xfm[10] = static_cast<float>(t.y);
    xfm[11] = static_cast<float>(t.z);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    return g;
}

}  // namespace

uint32_t RayScene::add_instance(uint32_t mesh, const glm::dmat3& linear, const glm::dvec3& offset) {
    if (!impl_->shared || mesh >= impl_->shared->scenes.size())
        throw std::invalid_argument("RayScene::add_instance: no shared mesh " +
                                    std::to_string(mesh));
    RTCGeometry g =
        new_instance(impl_->device, impl_->shared->scenes[mesh], linear, offset, impl_->anchor);
    // Normals only need a direction: the matrix is scaled to unit size before it is inverted,
    // so tiny and huge placements alike give finite, well-conditioned normals.
    double big = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) big = std::max(big, std::abs(linear[c][r]));
    return attach(
        g, big > 0 ? glm::mat3(glm::transpose(glm::inverse(linear / big))) : glm::mat3(1.0f));
}

namespace {

RTCScene caster_scene(RTCDevice device, RTCScene& casters) {
    if (!casters) {
        casters = rtcNewScene(device);
        // Medium quality builds without spatial splits: fewer repeated filter calls.
        rtcSetSceneBuildQuality(casters, RTC_BUILD_QUALITY_MEDIUM);
    }
    return casters;
}

}  // namespace

uint32_t RayScene::add_caster_instance(uint32_t set, const glm::dmat3& linear,
                                       const glm::dvec3& offset) {
    if (!impl_->shared || set >= impl_->shared->caster_scenes.size())
        throw std::invalid_argument("RayScene::add_caster_instance: no shared caster set " +
                                    std::to_string(set));
    RTCGeometry g = new_instance(impl_->device, impl_->shared->caster_scenes[set], linear, offset,
                                 impl_->anchor);
    rtcCommitGeometry(g);
    uint32_t id = rtcAttachGeometry(caster_scene(impl_->device, impl_->casters), g);
    rtcReleaseGeometry(g);
    impl_->caster_total += static_cast<uint32_t>(impl_->shared->casters[set]->casters.count);
    return id;
}

uint32_t RayScene::add_casters(const std::vector<StrokeCaster>& casters,
                               const StrokeShaderParams& shader, const EdgeTable& edge) {
    caster_scene(impl_->device, impl_->casters);
    auto set = std::make_unique<CasterSet>();
    set->shader = &shader;
    set->edge = &edge;
    const size_t n = casters.size();
    set->cards.resize(n);
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_QUAD);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * n));
    auto* q = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), n));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const StrokeCaster& c = casters[i];
            const glm::vec3 center(c.center - impl_->anchor);
            set->cards[i] = {center, c.axis_s, c.axis_t, c.half_w, c.half_l, c.noise};
            const glm::vec3 a = c.axis_s * c.half_w, b = c.axis_t * c.half_l;
            const glm::vec3 corners[4] = {center - a - b, center + a - b, center + a + b,
                                          center - a + b};
            for (int k = 0; k < 4; ++k) {
                v[12 * i + 3 * k] = corners[k].x;
                v[12 * i + 3 * k + 1] = corners[k].y;
                v[12 * i + 3 * k + 2] = corners[k].z;
                q[4 * i + k] = static_cast<unsigned>(4 * i + k);
            }
        }
    });
    rtcSetGeometryUserData(g, set.get());
    rtcSetGeometryOccludedFilterFunction(g, caster_filter);
    rtcCommitGeometry(g);
    uint32_t id = rtcAttachGeometry(impl_->casters, g);
    rtcReleaseGeometry(g);
    impl_->caster_total += static_cast<uint32_t>(n);
    impl_->caster_stored += static_cast<uint32_t>(n);
    impl_->sets.push_back(std::move(set));
    return id;
}

void RayScene::commit() {
    FlushDenormals ftz;
    rtcCommitScene(impl_->scene);
    if (impl_->casters) rtcCommitScene(impl_->casters);
}

uint32_t RayScene::mesh_count() const { return impl_->meshes; }
uint32_t RayScene::caster_count() const { return impl_->caster_total; }
uint32_t RayScene::caster_cards_stored() const { return impl_->caster_stored; }

RayHit RayScene::intersect(const glm::dvec3& origin, const glm::vec3& dir, float tmax,
                           const glm::vec3* n) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    fill_ray(rh.ray, origin, impl_->anchor, dir, tmax, n);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &ctx, &rh);
    RayHit out;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
    out.hit = true;
    out.t = rh.ray.tfar;
    // On an instance, Embree names the instance in instID and reports the normal in the
    // instanced mesh's own space.
    const bool instanced = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
    out.geometry = instanced ? rh.hit.instID[0] : rh.hit.geomID;
    out.primitive = rh.hit.primID;
    glm::vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    if (instanced) ng = impl_->normal_to_world[out.geometry] * ng;
    float len = glm::length(ng);
    out.normal = len > 0 && std::isfinite(len) ? ng / len : glm::vec3(0, 1, 0);
    return out;
}

bool RayScene::occluded(const glm::dvec3& origin, const glm::vec3& dir, float tmax,
                        const glm::vec3* n) const {
    return transmittance(origin, dir, ShadowMode::kThreshold, tmax, n) < 0.5f;
}

float RayScene::through_casters(const glm::dvec3& origin, const glm::vec3& dir, ShadowMode mode,
                                float tmax, const glm::vec3* n, float* distance) const {
    if (distance) *distance = 0.0f;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    fill_ray(r, origin, impl_->anchor, dir, tmax, n);
    rtcOccluded1(impl_->scene, &ctx, &r);
    if (r.tfar < 0) return 0.0f;  // Embree sets tfar to -inf on a hit
    if (!impl_->casters || impl_->caster_total == 0) return 1.0f;
    ShadowContext sc;
    rtcInitIntersectContext(&sc.ctx);
    sc.mode = mode;
    sc.through = distance != nullptr;
    fill_ray(r, origin, impl_->anchor, dir, tmax, n);
    rtcOccluded1(impl_->casters, &sc.ctx, &r);
    if (distance && sc.depth > 0)
        *distance = static_cast<float>(static_cast<double>(sc.depth_distance) /
                                       (64.0 * static_cast<double>(sc.depth)));
    // Walking through, nothing blocks: light under a thousandth is none, as for a shadow ray.
    if (r.tfar < 0 || sc.blocked || sc.depth >= kOpaqueDepth) return 0.0f;
    return pmath::exp2(-static_cast<float>(sc.depth) / 65536.0f);
}

float RayScene::transmittance(const glm::dvec3& origin, const glm::vec3& dir, ShadowMode mode,
                              float tmax, const glm::vec3* n) const {
    return through_casters(origin, dir, mode, tmax, n, nullptr);
}

float RayScene::transmittance_depth(const glm::dvec3& origin, const glm::vec3& dir, float tmax,
                                    const glm::vec3* n, float& distance) const {
    return through_casters(origin, dir, ShadowMode::kTransmissive, tmax, n, &distance);
}

}  // namespace pleinair
