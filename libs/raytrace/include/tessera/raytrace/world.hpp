#pragma once
// The objects a ray tracer sees: shapes under affine transforms (accel's Instance) and triangle meshes (MeshAccel),
// each with a material index and optional motion, gathered under a top-level BVH (planes, whose boxes are infinite,
// are tested separately).
#include <memory>
#include <variant>
#include <vector>

#include "tessera/accel/shapes.hpp"
#include "tessera/math/ray.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

class Bvh;
class MeshAccel;

/// How an object moves while the shutter is open (ray time t in [0, 1)): its placement at time t is
/// (1 - t) M0 + t M1 followed by a translation t * velocity, where M0 is the placement it was added with.
struct Motion {
  Vec3f velocity{0.0f};     ///< displacement over the whole shutter interval
  bool has_end = false;     ///< when true, end_transform is M1 (else M1 = M0)
  Mat4 end_transform{1.0};  ///< the object's placement at t = 1 (object to world)

  /// True when the object moves at all.
  bool moving() const { return has_end || velocity != Vec3f(0.0f); }
};

/// A hit on an object: the geometric hit (world space: t, point, normal), which object, and the shading normal (smooth
/// normals for meshes with them). Texture coordinates are computed on demand by World::texture_uv (hit.uv is an
/// intermediate).
struct SurfaceHit {
  Hit hit;
  int object = -1;
  Vec3f shading_normal{0.0f};  ///< unit, on the same side as hit.normal
};

/// The scene's geometry. Add objects, call build(), then query from any number of threads.
class World {
 public:
  World();
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  /// Adds a shape placed by `to_world`; returns its object index. Throws InvalidInput for a singular transform.
  int add_shape(const Shape& shape, const Mat4& to_world, int material, const Motion& motion = {});
  /// Adds a triangle mesh placed by `to_world` (its positions and normals are transformed once, here). Vertex normals,
  /// when present, give smooth shading; vertex uvs give texture coordinates. Throws InvalidInput for an empty mesh.
  int add_mesh(const TriMesh& mesh, const Mat4& to_world, int material, const Motion& motion = {});
  /// Keeps object `index` out of shadow rays (e.g. the visible surface of an area light). Call before build().
  void set_casts_shadows(int index, bool casts);

  /// Builds the query structures: a flat list of the few fixed spheres and planes placed by the identity (tested in a
  /// plain loop, cheaper than any tree for a handful) and a top-level BVH over the rest. Must be called after the last
  /// add or set_casts_shadows and before any query.
  void build();

  /// The nearest hit along the ray within [tmin, tmax] at ray.time; shrinks ray.tmax to it. Candidates are tested for
  /// t only where possible; the point and normals are computed for the winner.
  bool intersect(Ray& ray, SurfaceHit& hit) const;
  /// The texture coordinates of a hit returned by intersect(ray, hit) (same ray): the shape's uv (see accel's shapes),
  /// or for meshes the interpolated vertex uvs (the barycentrics when the mesh has none).
  Vec2f texture_uv(const Ray& ray, const SurfaceHit& hit) const;
  /// True when something that casts shadows lies on the ray within [tmin, tmax] (the notes' !visible(P, L)).
  bool occluded(const Ray& ray) const;

  /// Number of objects.
  int size() const { return int(objects_.size()); }
  /// The material index of object i.
  int material(int i) const { return objects_[size_t(i)].material; }
  /// True when some object moves (rays need distinct times).
  bool has_motion() const;
  /// World bounds of everything but planes, over the whole shutter interval.
  AABB bounds() const;

 private:
  struct MeshData;
  struct Object {
    // A shape placed by the identity is tested as is (no ray transform); others go through an Instance.
    std::variant<Shape, Instance, std::shared_ptr<const MeshData>> geometry;
    int material = 0;
    Motion motion;
    Mat4f start_inverse{1.0f};  // M0^-1, for the motion transform M(t) M0^-1
    Mat4f start{1.0f};
    bool casts_shadows = true;
    bool is_plane = false;
    bool flat = false;  // in the flat list (set by build)
  };

  // The flat list's entries: a fixed sphere or plane placed by the identity.
  struct FlatSphere {
    Vec3f center;
    float radius, inv_radius;
    int object;
    bool casts_shadows;
  };
  struct FlatPlane {
    Vec3f point, normal;  // normal as given (the plane kernel's t uses it unnormalized)
    Vec3f unit_normal;
    int object;
    bool casts_shadows;
  };
  static constexpr size_t kMaxFlatSpheres = 8;  // beyond this the spheres go into the BVH

  bool intersect_object(const Object& object, Ray& ray, Hit& hit) const;
  AABB object_bounds(const Object& object) const;
  void finish_hit(const Object& object, SurfaceHit& hit) const;

  std::vector<Object> objects_;
  std::vector<FlatSphere> flat_spheres_;
  std::vector<FlatPlane> flat_planes_;
  std::vector<int> bvh_objects_;  // BVH primitive -> object
  std::vector<int> planes_;       // planes not in the flat list (placed by a transform, or moving)
  std::unique_ptr<Bvh> bvh_;
};

}  // namespace tessera
