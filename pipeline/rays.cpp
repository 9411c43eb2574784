// Embree device, scene and queries; flush-to-zero and denormals-are-zero in every thread that
// traces, as Embree asks for speed.
#include "pipeline/rays.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/task_scheduler_observer.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

namespace pleinair {

namespace {

void set_ftz_daz() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// Sets the modes in every TBB worker as it joins, and in the thread that builds the scene.
class DenormalsOff : public tbb::task_scheduler_observer {
  public:
    DenormalsOff() { observe(true); }
    ~DenormalsOff() override { observe(false); }
    void on_scheduler_entry(bool) override { set_ftz_daz(); }
};

}  // namespace

float ray_epsilon(const glm::dvec3& p) {
    double m = std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return static_cast<float>(32.0 * std::numeric_limits<float>::epsilon() * m);
}

struct RayScene::Impl {
    glm::dvec3 anchor;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    uint32_t meshes = 0;
    DenormalsOff denormals;
};

RayScene::RayScene(const glm::dvec3& anchor) : impl_(std::make_unique<Impl>()) {
    set_ftz_daz();
    impl_->anchor = anchor;
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        throw std::runtime_error("Embree: cannot create a device (error " +
                                 std::to_string(rtcGetDeviceError(nullptr)) + ")");
    impl_->scene = rtcNewScene(impl_->device);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
}

RayScene::~RayScene() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

uint32_t RayScene::add_mesh(const QuadMesh& mesh, const glm::dvec3& offset) {
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_QUAD);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    const glm::dvec3 shift = offset - impl_->anchor;
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
    rtcCommitGeometry(g);
    uint32_t id = rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
    ++impl_->meshes;
    return id;
}

void RayScene::commit() { rtcCommitScene(impl_->scene); }

uint32_t RayScene::mesh_count() const { return impl_->meshes; }

namespace {
void fill_ray(RTCRay& r, const glm::dvec3& world, const glm::dvec3& anchor, const glm::vec3& d,
              float tmax, const glm::vec3* n) {
    const float eps = ray_epsilon(world);
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
}  // namespace

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
    out.geometry = rh.hit.geomID;
    out.primitive = rh.hit.primID;
    glm::vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    float len = glm::length(ng);
    out.normal = len > 0 && std::isfinite(len) ? ng / len : glm::vec3(0, 1, 0);
    return out;
}

bool RayScene::occluded(const glm::dvec3& origin, const glm::vec3& dir, float tmax,
                        const glm::vec3* n) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    fill_ray(r, origin, impl_->anchor, dir, tmax, n);
    rtcOccluded1(impl_->scene, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace pleinair
