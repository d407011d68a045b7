// The world: shapes and meshes under a top-level BVH, with motion by transforming rays.
#include "tessera/raytrace/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tessera/accel/bvh.hpp"
#include "tessera/accel/mesh_accel.hpp"
#include "tessera/accel/shape_t.hpp"
#include "tessera/core/error.hpp"
#include "tessera/math/transform.hpp"

namespace tessera {

struct World::MeshData {
  TriMesh mesh;  // world-space copy, for normals and uvs
  MeshAccel accel;
};

World::World() = default;
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

namespace {

/// M(t) M0^-1: where the object's time-0 placement goes at time t (see Motion).
Mat4f motion_delta(const Motion& m, const Mat4f& start, const Mat4f& start_inverse, float t) {
  Mat4f placed = start;
  if (m.has_end) placed = (1.0f - t) * start + t * Mat4f(m.end_transform);
  Mat4f delta = placed * start_inverse;
  delta[3] += Vec4f(t * m.velocity, 0.0f);
  return delta;
}

/// The ray carried into a moving object's time-0 placement by the inverse of delta (direction unnormalized, so t is
/// unchanged).
Ray untransformed(const Ray& ray, const Mat4f& delta) {
  const Mat4f inv = glm::inverse(delta);
  Ray r = ray;
  r.origin = Vec3f(inv * Vec4f(ray.origin, 1.0f));
  r.dir = Vec3f(inv * Vec4f(ray.dir, 0.0f));
  return r;
}

/// Whether the ray hits a World object (its geometry at the ray's time) in [tmin, tmax]: the shapes' and meshes'
/// any-hit tests, which stop at the first hit and compute no normal or uv (shadow rays).
template <class Object>
bool occludes_object(const Object& o, const Ray& ray) {
  const Ray r =
      o.motion.moving() ? untransformed(ray, motion_delta(o.motion, o.start, o.start_inverse, ray.time)) : ray;
  if (const auto* shape = std::get_if<Shape>(&o.geometry)) return occludes(*shape, r);
  if (const auto* inst = std::get_if<Instance>(&o.geometry)) return inst->occludes(r);
  return (*std::get_if<2>(&o.geometry))->accel.occluded(r);
}

}  // namespace

int World::add_shape(const Shape& shape, const Mat4& to_world, int material, const Motion& motion) {
  Object o{to_world == Mat4(1.0) ? decltype(Object::geometry)(shape) : Instance(shape, to_world), material, motion};
  o.start = Mat4f(to_world);
  o.start_inverse = glm::inverse(o.start);
  o.is_plane = std::holds_alternative<Plane>(shape);
  objects_.push_back(std::move(o));
  return size() - 1;
}

int World::add_mesh(const TriMesh& mesh, const Mat4& to_world, int material, const Motion& motion) {
  if (mesh.triangle_count() == 0) throw InvalidInput("a mesh object has no triangles");
  if (std::abs(glm::determinant(to_world)) < 1e-300) throw InvalidInput("a mesh object's transform is singular");
  auto data = std::make_shared<MeshData>();
  data->mesh = mesh;
  for (auto& p : data->mesh.positions) p = transform_point(to_world, p);
  const Mat3 nm = glm::transpose(glm::inverse(Mat3(to_world)));
  for (auto& n : data->mesh.normals) n = glm::normalize(nm * n);
  data->accel = MeshAccel(data->mesh);
  Object o{std::shared_ptr<const MeshData>(std::move(data)), material, motion};
  o.start = Mat4f(to_world);
  o.start_inverse = glm::inverse(o.start);
  objects_.push_back(std::move(o));
  return size() - 1;
}

void World::set_casts_shadows(int index, bool casts) { objects_.at(size_t(index)).casts_shadows = casts; }

AABB World::object_bounds(const Object& o) const {
  AABB box;
  if (const auto* shape = std::get_if<Shape>(&o.geometry))
    box = tessera::bounds(*shape);
  else if (const auto* inst = std::get_if<Instance>(&o.geometry))
    box = inst->bounds();
  else
    box = std::get<std::shared_ptr<const MeshData>>(o.geometry)->accel.bvh().bounds();
  if (!o.motion.moving()) return box;
  // Points move affinely in t under the interpolated placement, so the boxes at t = 0 and t = 1 bound the sweep.
  AABB swept = box;
  const Mat4f end = motion_delta(o.motion, o.start, o.start_inverse, 1.0f);
  for (int c = 0; c < 8; ++c) {
    const Vec3f p((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z);
    swept.expand(Vec3f(end * Vec4f(p, 1.0f)));
  }
  return swept;
}

void World::build() {
  std::vector<AABB> boxes;
  bvh_objects_.clear();
  planes_.clear();
  flat_spheres_.clear();
  flat_planes_.clear();
  const auto fixed_shape = [&](int i) -> const Shape* {
    const Object& o = objects_[size_t(i)];
    return o.motion.moving() ? nullptr : std::get_if<Shape>(&o.geometry);
  };
  size_t sphere_count = 0;
  for (int i = 0; i < size(); ++i)
    if (const Shape* shape = fixed_shape(i)) sphere_count += std::holds_alternative<Sphere>(*shape) ? 1 : 0;
  for (int i = 0; i < size(); ++i) {
    Object& o = objects_[size_t(i)];
    const Shape* shape = fixed_shape(i);
    const auto* plane = shape ? std::get_if<Plane>(shape) : nullptr;
    const auto* sphere = shape && sphere_count <= kMaxFlatSpheres ? std::get_if<Sphere>(shape) : nullptr;
    o.flat = plane || sphere;
    if (plane) {
      flat_planes_.push_back({plane->point, plane->normal, glm::normalize(plane->normal), i, o.casts_shadows});
    } else if (sphere) {
      flat_spheres_.push_back({sphere->center, sphere->radius, 1.0f / sphere->radius, i, o.casts_shadows});
    } else if (o.is_plane) {
      planes_.push_back(i);
    } else {
      bvh_objects_.push_back(i);
      boxes.push_back(object_bounds(objects_[size_t(i)]));
    }
  }
  BvhSettings settings;
  settings.max_leaf_size = 2;
  bvh_ = std::make_unique<Bvh>(boxes, settings);
}

bool World::has_motion() const {
  return std::any_of(objects_.begin(), objects_.end(), [](const Object& o) { return o.motion.moving(); });
}

AABB World::bounds() const { return bvh_ ? bvh_->bounds() : AABB{}; }

bool World::intersect_object(const Object& o, Ray& ray, Hit& hit) const {
  Ray r = ray;
  Mat4f delta(1.0f);
  const bool moving = o.motion.moving();
  if (moving) {
    delta = motion_delta(o.motion, o.start, o.start_inverse, ray.time);
    r = untransformed(ray, delta);
  }
  bool found;
  if (const auto* shape = std::get_if<Shape>(&o.geometry)) {
    found = tessera::intersect(*shape, r, hit);
  } else if (const auto* inst = std::get_if<Instance>(&o.geometry)) {
    found = inst->intersect(r, hit);
  } else {
    found = std::get<std::shared_ptr<const MeshData>>(o.geometry)->accel.intersect(r, hit);
  }
  if (!found) return false;
  if (moving) {
    hit.point = ray.at(hit.t);
    hit.normal = glm::normalize(glm::transpose(glm::inverse(Mat3f(delta))) * hit.normal);
  }
  ray.tmax = hit.t;
  return true;
}

void World::finish_hit(const Object& o, SurfaceHit& h) const {
  h.shading_normal = h.hit.normal;
  // A mesh that changes placement over the shutter keeps its geometric normal (its vertex normals are time-0's).
  if (const auto* mesh = std::get_if<std::shared_ptr<const MeshData>>(&o.geometry); mesh && !o.motion.has_end)
    h.shading_normal = shading_normal((*mesh)->mesh, h.hit);
}

Vec2f World::texture_uv(const Ray& ray, const SurfaceHit& h) const {
  const Object& o = objects_[size_t(h.object)];
  if (const auto* mesh = std::get_if<std::shared_ptr<const MeshData>>(&o.geometry)) {
    const TriMesh& m = (*mesh)->mesh;
    const uint32_t* idx = &m.indices[size_t(h.hit.prim) * 3];
    const float b1 = h.hit.uv.x, b2 = h.hit.uv.y, b0 = 1.0f - b1 - b2;
    return m.uvs.empty() ? Vec2f(b1, b2)
                         : b0 * Vec2f(m.uvs[idx[0]]) + b1 * Vec2f(m.uvs[idx[1]]) + b2 * Vec2f(m.uvs[idx[2]]);
  }
  if (!o.flat) return h.hit.uv;
  // The flat list found t only: the shape's full kernel gives the uv (the same nearest root, from the same tmin).
  Ray r = ray;
  r.tmax = std::numeric_limits<float>::infinity();
  Hit full;
  return tessera::intersect(std::get<Shape>(o.geometry), r, full) ? full.uv : Vec2f(0.0f);
}

bool World::intersect(Ray& ray, SurfaceHit& out) const {
  TESSERA_CHECK(bvh_ != nullptr);
  // The flat list first, t only.
  const FlatSphere* sphere = nullptr;
  const FlatPlane* plane = nullptr;
  for (const FlatPlane& f : flat_planes_) {
    const float t = plane_t_ahead(f.point, f.normal, ray);
    if (ray.in_range(t)) {
      ray.tmax = t;
      plane = &f;
    }
  }
  const float a = glm::dot(ray.dir, ray.dir), inv_a = 1.0f / a;
  for (const FlatSphere& f : flat_spheres_) {
    const float t = sphere_t(f.center, f.radius, ray, a, inv_a);
    if (ray.in_range(t)) {
      ray.tmax = t;
      sphere = &f;
      plane = nullptr;
    }
  }
  // Then the rest, with full hits, nearer than the flat list's best.
  Hit hit;
  int object = -1;
  for (int i : planes_)
    if (intersect_object(objects_[size_t(i)], ray, hit)) object = i;
  if (!bvh_objects_.empty())
    bvh_->intersect(ray, [&](int prim, Ray& r) {
      const int i = bvh_objects_[size_t(prim)];
      if (!intersect_object(objects_[size_t(i)], r, hit)) return false;
      object = i;
      return true;
    });
  if (object >= 0) {
    out.hit = hit;
  } else if (sphere || plane) {
    // The flat winner's point and normal (the sphere's as (p - c) / r: unit within float rounding).
    object = sphere ? sphere->object : plane->object;
    out.hit.t = ray.tmax;
    out.hit.point = ray.at(ray.tmax);
    out.hit.normal = sphere ? (out.hit.point - sphere->center) * sphere->inv_radius : plane->unit_normal;
    out.hit.uv = Vec2f(0.0f);
    out.hit.prim = -1;
  } else {
    return false;
  }
  out.object = object;
  finish_hit(objects_[size_t(object)], out);
  return true;
}

bool World::occluded(const Ray& ray) const {
  TESSERA_CHECK(bvh_ != nullptr);
  for (const FlatPlane& f : flat_planes_)
    if (f.casts_shadows && plane_blocks(f.point, f.normal, ray)) return true;
  const float a = glm::dot(ray.dir, ray.dir);
  for (const FlatSphere& f : flat_spheres_)
    if (f.casts_shadows && sphere_blocks(f.center, f.radius, ray, a)) return true;
  for (int i : planes_)
    if (objects_[size_t(i)].casts_shadows && occludes_object(objects_[size_t(i)], ray)) return true;
  if (bvh_objects_.empty()) return false;
  return bvh_->occluded(ray, [&](int prim, const Ray& r) {
    const Object& o = objects_[size_t(bvh_objects_[size_t(prim)])];
    return o.casts_shadows && occludes_object(o, r);
  });
}

}  // namespace tessera
