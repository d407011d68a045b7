// Embree 3 as the reference ray caster of the accel tests and benchmark.
#include "embree_reference.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <string>
#include <vector>

namespace tessera::reference {

struct EmbreeMesh::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeMesh::EmbreeMesh(const TriMesh& mesh, int threads) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(threads > 0 ? ("threads=" + std::to_string(threads)).c_str() : nullptr);
  impl_->scene = rtcNewScene(impl_->device);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + size_t(k)] = float(mesh.positions[i][k]);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.triangle_count()));
  std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl_->scene);
}

EmbreeMesh::~EmbreeMesh() {
  rtcReleaseScene(impl_->scene);
  rtcReleaseDevice(impl_->device);
}

namespace {

RTCRayHit to_embree(const Ray& ray) {
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

int EmbreeMesh::intersect(const Ray& ray, float& t) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(impl_->scene, &context, &rh);
  t = rh.ray.tfar;
  return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : int(rh.hit.primID);
}

void EmbreeMesh::intersect(std::span<const Ray> rays, std::span<int> prims, std::span<float> t) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);  // flags: incoherent
  constexpr size_t kChunk = 256;
  RTCRayHit rh[kChunk];
  for (size_t begin = 0; begin < rays.size(); begin += kChunk) {
    const size_t n = std::min(kChunk, rays.size() - begin);
    for (size_t i = 0; i < n; ++i) rh[i] = to_embree(rays[begin + i]);
    rtcIntersect1M(impl_->scene, &context, rh, unsigned(n), sizeof(RTCRayHit));
    for (size_t i = 0; i < n; ++i) {
      t[begin + i] = rh[i].ray.tfar;
      prims[begin + i] = rh[i].hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : int(rh[i].hit.primID);
    }
  }
}

}  // namespace tessera::reference
