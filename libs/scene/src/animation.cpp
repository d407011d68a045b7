// Keyed values of scene files: {"keys": [[frame, value], ...], "interpolation": ...} anywhere a number or an array of
// numbers goes, evaluated at a frame before the document becomes a Scene (docs/scene-format.md, "Animation").
#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

#include "scene_json.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {
namespace {

using detail::Json;

enum class Interpolation { linear, smooth, step };

// A keyed value, checked: key frames strictly increasing, values all numbers or all arrays of numbers of one length
// (any JSON with "step").
struct Track {
  std::vector<double> frames;
  std::vector<Json> values;
  Interpolation interpolation = Interpolation::linear;
};

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

[[noreturn]] void fail(const std::string& name, const std::string& path, const std::string& what) {
  throw InvalidInput(located(name, (path.empty() ? std::string("(top level)") : path) + ": " + what));
}

// {"keys": [...]} or {"keys": [...], "interpolation": ...}: "keys" is reserved in objects of a scene for this.
bool is_keyed(const Json& v) {
  return v.is_object() && v.contains("keys") && v.size() <= 2 && (v.size() == 1 || v.contains("interpolation"));
}

bool numeric(const Json& v) {
  if (v.is_number()) return true;
  if (!v.is_array() || v.empty()) return false;
  for (const Json& x : v)
    if (!x.is_number()) return false;
  return true;
}

Track read_track(const Json& v, const std::string& name, const std::string& path) {
  Track track;
  if (v.contains("interpolation")) {
    const Json& how = v["interpolation"];
    const std::string at = child(path, "interpolation");
    if (!how.is_string()) fail(name, at, "expected linear, smooth or step");
    const std::string s = how.get<std::string>();
    if (s == "linear")
      track.interpolation = Interpolation::linear;
    else if (s == "smooth")
      track.interpolation = Interpolation::smooth;
    else if (s == "step")
      track.interpolation = Interpolation::step;
    else
      fail(name, at, "expected linear, smooth or step");
  }
  const Json& keys = v["keys"];
  const std::string keys_path = child(path, "keys");
  if (!keys.is_array() || keys.empty()) fail(name, keys_path, "expected an array of [frame, value] pairs");
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string at = fmt::format("{}[{}]", keys_path, i);
    const Json& key = keys[i];
    if (!key.is_array() || key.size() != 2 || !key[0].is_number()) fail(name, at, "expected [frame, value]");
    const double frame = key[0].get<double>();
    if (!std::isfinite(frame)) fail(name, at, "expected a finite frame number");
    if (i > 0 && !(frame > track.frames.back()))
      fail(name, at, fmt::format("key frames must increase: {} follows {}", frame, track.frames.back()));
    if (is_keyed(key[1])) fail(name, at, "a key's value cannot itself be keyed");
    if (track.interpolation != Interpolation::step) {
      if (!numeric(key[1]))
        fail(name, at,
             "expected a number or an array of numbers to interpolate (\"interpolation\": \"step\" holds any value)");
      if (i > 0 && (key[1].is_array() != track.values[0].is_array() ||
                    (key[1].is_array() && key[1].size() != track.values[0].size())))
        fail(name, at, "every key's value must have the shape of the first");
    }
    track.frames.push_back(frame);
    track.values.push_back(key[1]);
  }
  return track;
}

// Component `c` of a numeric value (a number has one).
double component(const Json& v, size_t c) { return v.is_number() ? v.get<double>() : v[c].get<double>(); }

Json evaluate(const Track& track, double frame) {
  const auto& t = track.frames;
  if (frame <= t.front()) return track.values.front();
  if (frame >= t.back()) return track.values.back();
  size_t i = 0;
  while (t[i + 1] <= frame) ++i;
  if (track.interpolation == Interpolation::step) return track.values[i];
  const double h = t[i + 1] - t[i], s = (frame - t[i]) / h;
  const Json& p0 = track.values[i];
  const Json& p1 = track.values[i + 1];
  const size_t n = p0.is_number() ? 1 : p0.size();
  Json out = p0.is_number() ? Json(0.0) : Json::array();
  for (size_t c = 0; c < n; ++c) {
    const double a = component(p0, c), b = component(p1, c);
    double value;
    if (track.interpolation == Interpolation::linear) {
      value = a + s * (b - a);
    } else {
      // Catmull-Rom through the keys on their own frame spacing: the tangent at a key is the slope between its
      // neighbours (one-sided at the first and last key), and each segment is the cubic Hermite curve between two
      // keys with those tangents (in units per frame, scaled by the segment's length h).
      const auto slope = [&](size_t k) {
        const size_t lo = k == 0 ? 0 : k - 1, hi = k + 1 == t.size() ? k : k + 1;
        return (component(track.values[hi], c) - component(track.values[lo], c)) / (t[hi] - t[lo]);
      };
      const double s2 = s * s, s3 = s2 * s;
      value = (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * h * slope(i) + (-2 * s3 + 3 * s2) * b +
              (s3 - s2) * h * slope(i + 1);
    }
    if (p0.is_number())
      out = value;
    else
      out.push_back(value);
  }
  return out;
}

// Checks every keyed value in `v` (so that a bad key fails on loading, whatever frame is asked for); true if any.
// The recursion is as deep as the document, which parse_scene_json bounds (64 levels).
bool check_keyed(const Json& v, const std::string& name, const std::string& path) {
  if (is_keyed(v)) return read_track(v, name, path), true;
  bool any = false;
  if (v.is_object())
    for (const auto& [key, value] : v.items()) any = check_keyed(value, name, child(path, key)) || any;
  if (v.is_array())
    for (size_t i = 0; i < v.size(); ++i) any = check_keyed(v[i], name, fmt::format("{}[{}]", path, i)) || any;
  return any;
}

// `v` with each keyed value replaced by its value at `frame`.
Json resolve(const Json& v, double frame, const std::string& name, const std::string& path) {
  if (is_keyed(v)) return evaluate(read_track(v, name, path), frame);
  if (v.is_object()) {
    Json out = Json::object();
    for (const auto& [key, value] : v.items()) out[key] = resolve(value, frame, name, child(path, key));
    return out;
  }
  if (v.is_array()) {
    Json out = Json::array();
    for (size_t i = 0; i < v.size(); ++i) out.push_back(resolve(v[i], frame, name, fmt::format("{}[{}]", path, i)));
    return out;
  }
  return v;
}

SceneAnimation read_animation(const Json& doc, const std::string& name) {
  SceneAnimation a;
  if (!doc.is_object() || !doc.contains("animation")) return a;
  const Json& n = doc["animation"];
  if (!n.is_object()) fail(name, "animation", "expected an object");
  for (const auto& [key, value] : n.items())
    if (key != "frames" && key != "fps" && key != "shutter") fail(name, child("animation", key), "unknown key");
  if (n.contains("frames")) {
    const Json& f = n["frames"];
    constexpr long long kMaxFrame = 10'000'000;
    const auto frame_ok = [](const Json& x) {
      return x.is_number_integer() && x.get<long long>() >= 0 && x.get<long long>() <= kMaxFrame;
    };
    if (!f.is_array() || f.size() != 2 || !frame_ok(f[0]) || !frame_ok(f[1]) ||
        f[0].get<long long>() > f[1].get<long long>())
      fail(name, "animation.frames",
           fmt::format("expected [first, last]: integers, 0 <= first <= last <= {}", kMaxFrame));
    a.first = int(f[0].get<long long>());
    a.last = int(f[1].get<long long>());
  }
  if (n.contains("fps")) {
    const Json& fps = n["fps"];
    if (!fps.is_number() || !(fps.get<double>() > 0) || !(fps.get<double>() <= 1000))
      fail(name, "animation.fps", "expected a number of frames per second in (0, 1000]");
    a.fps = fps.get<double>();
  }
  if (n.contains("shutter")) {
    const Json& shutter = n["shutter"];
    if (!shutter.is_number() || !(shutter.get<double>() >= 0) || !(shutter.get<double>() <= 1))
      fail(name, "animation.shutter", "expected the open fraction of a frame, in [0, 1]");
    a.shutter = shutter.get<double>();
  }
  return a;
}

}  // namespace

// Held by a unique_ptr, never copied or moved. The document starts as an object (nlohmann's noexcept default
// constructor checks an invariant that clang-tidy sees can throw; this one is not noexcept).
struct AnimatedScene::Data {
  Data() : doc(Json::object()) {}
  Data(const Data&) = delete;
  Data& operator=(const Data&) = delete;
  ~Data() = default;
  Json doc;
  std::string name;
  std::filesystem::path base_dir;
  SceneAnimation animation;
  bool keyed = false;
};

AnimatedScene::AnimatedScene(std::string_view json, std::string name, std::filesystem::path base_dir)
    : data_(std::make_unique<Data>()) {
  data_->doc = detail::parse_scene_json(json, name);
  data_->animation = read_animation(data_->doc, name);
  data_->keyed = check_keyed(data_->doc, name, "");
  data_->name = std::move(name);
  data_->base_dir = std::move(base_dir);
}

AnimatedScene::AnimatedScene(AnimatedScene&&) noexcept = default;
AnimatedScene& AnimatedScene::operator=(AnimatedScene&&) noexcept = default;
AnimatedScene::~AnimatedScene() = default;

const SceneAnimation& AnimatedScene::animation() const { return data_->animation; }

bool AnimatedScene::keyed() const { return data_->keyed; }

Scene AnimatedScene::at(int frame) const {
  const Data& d = *data_;
  if (frame < d.animation.first || frame > d.animation.last)
    throw InvalidInput(fmt::format("{}: frame {} is outside the scene's frames {}..{}", d.name, frame,
                                   d.animation.first, d.animation.last));
  if (!d.keyed) return detail::scene_from_json(d.doc, d.name, d.base_dir);
  try {
    return frame_scene(d, frame);
  } catch (const InvalidInput& e) {
    // A value that is wrong at some frames only: the message says which.
    throw InvalidInput(fmt::format("{} (at frame {})", e.what(), frame));
  }
}

Scene AnimatedScene::frame_scene(const Data& d, int frame) {
  Json doc = resolve(d.doc, frame, d.name, "");
  // Motion blur: an object whose placement is keyed (and that states no motion of its own) moves from its transform
  // at the frame to its transform when the shutter closes; the ray tracer interpolates the steps in between.
  if (d.animation.shutter > 0 && d.doc.contains("objects") && d.doc["objects"].is_array()) {
    const Json& objects = d.doc["objects"];
    for (size_t i = 0; i < objects.size(); ++i) {
      const Json& o = objects[i];
      if (!o.is_object() || !o.contains("transform") || o.contains("transform_end") || o.contains("velocity") ||
          !check_keyed(o["transform"], d.name, ""))
        continue;
      doc["objects"][i]["transform_end"] =
          resolve(o["transform"], frame + d.animation.shutter, d.name, fmt::format("objects[{}].transform", i));
    }
  }
  return detail::scene_from_json(doc, d.name, d.base_dir);
}

AnimatedScene load_animated_scene(const std::string& name_or_path) {
  if (std::filesystem::exists(name_or_path)) {
    const std::filesystem::path path(name_or_path);
    return AnimatedScene(read_file(path), path.string(), path.parent_path());
  }
  return AnimatedScene(builtin_scene_text(name_or_path), name_or_path, std::filesystem::path());
}

}  // namespace tessera
