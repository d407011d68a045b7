// A scene as the ray tracer's RayScene.
#include "tessera/scene/trace.hpp"

#include "tessera/core/error.hpp"

namespace tessera {

RayScene to_ray_scene(const Scene& scene) {
  RayScene rs;
  std::map<std::string, int> index;
  for (const auto& [name, material] : scene.materials) {
    index[name] = int(rs.materials.size());
    rs.materials.push_back(material);
  }
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const auto m = index.find(o.material);
    if (m == index.end())
      throw InvalidInput(fmt::format("{}: objects[{}]: no material named '{}'", scene.name, i, o.material));
    try {
      const int id = o.shape ? rs.world.add_shape(*o.shape, o.transform, m->second, o.motion)
                             : rs.world.add_mesh(*o.mesh, o.transform, m->second, o.motion);
      rs.world.set_casts_shadows(id, o.casts_shadows);
    } catch (const InvalidInput& e) {
      // The world's own checks (a transform too close to singular to invert, say) know no JSON paths: name the object.
      throw InvalidInput(fmt::format("{}: objects[{}]: {}", scene.name, i, e.what()));
    }
  }
  rs.lights = scene.lights;
  add_light_surfaces(rs);
  rs.world.build();
  rs.camera = scene.camera.camera(1, 0.1, 100);  // render() sets the aspect; rays have no near or far plane
  rs.aperture = float(scene.camera.aperture);
  rs.focal_distance = float(scene.camera.focal_distance);
  rs.ambient = scene.ambient;
  rs.background = scene.image.background;
  return rs;
}

RenderSettings render_settings(const Scene& scene) {
  RenderSettings s;
  s.width = scene.image.width;
  s.height = scene.image.height;
  s.samples = scene.image.samples;
  s.max_depth = scene.image.max_depth;
  return s;
}

}  // namespace tessera
