#include "scene/scene_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <ios>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>
#include <nlohmann/json.hpp>

#include "core/shapes.h"
#include "core/volume.h"
#include "scene/input_file.h"
#include "scene/mesh_io.h"
#include "scene/stage.h"

namespace shadowvol {
namespace {

using nlohmann::json;

// Where the parser is, as a key path, kept by its callback: an error thrown while a value is read
// (a number beyond a double's range) names the key the value belongs to.
class ParsePosition {
 public:
  bool on(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        levels_.push_back({false, {}, 0});
        break;
      case json::parse_event_t::array_start:
        levels_.push_back({true, {}, 0});
        break;
      case json::parse_event_t::key:
        levels_.back().key = parsed.get<std::string>();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        levels_.pop_back();
        [[fallthrough]];
      case json::parse_event_t::value:  // the value is whole: the next is another's
        if (!levels_.empty()) {
          ++levels_.back().index;
          levels_.back().key.clear();
        }
        break;
    }
    return true;  // keep every value
  }
  std::string path() const {
    std::string p = "scene";
    for (const Level& l : levels_)
      p += l.array ? "[" + std::to_string(l.index) + "]" : l.key.empty() ? "" : "." + l.key;
    return p;
  }

 private:
  struct Level {
    bool array;
    std::string key;
    std::size_t index;
  };
  std::vector<Level> levels_;
};

}  // namespace

std::string describe_json_error(const nlohmann::json::exception& e, const std::string& path) {
  const std::string what = e.what();
  // nlohmann's text is "[json.exception.KIND.ID] detail"; the detail is what a person needs.
  const auto close = what.find("] ");
  const std::string detail = close == std::string::npos ? what : what.substr(close + 2);
  if (dynamic_cast<const json::parse_error*>(&e) != nullptr)
    return path + ": not valid JSON (" + detail + ")";
  if (dynamic_cast<const json::out_of_range*>(&e) != nullptr && e.id == 406) {
    const auto open = detail.find('\'');
    const std::string value =
        open == std::string::npos ? detail : detail.substr(open + 1, detail.rfind('\'') - open - 1);
    return path + ": the number " + value + " is beyond the range of a double";
  }
  const char* kind =
      dynamic_cast<const json::type_error*>(&e) != nullptr         ? "a value of the wrong type"
      : dynamic_cast<const json::out_of_range*>(&e) != nullptr     ? "a value out of range"
      : dynamic_cast<const json::invalid_iterator*>(&e) != nullptr ? "an invalid position"
                                                                   : "a JSON error";
  return path + ": " + kind + " (" + detail + ")";
}

namespace {

// Errors carry the key path; Reader methods return false after recording the first one. `at` is
// the last path a method was given, for an exception that escapes one.
struct Reader {
  std::string file;
  std::string error;
  std::string at = "scene";

  bool fail(const std::string& path, const std::string& what) {
    if (error.empty()) error = file + ": " + path + ": " + what;
    return false;
  }
  static std::string kind(const json& j) { return std::string(j.type_name()); }

  bool number(const json& j, const std::string& path, float& out) {
    at = path;
    if (!j.is_number()) return fail(path, "expected a number, got " + kind(j));
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > 1e18)
      return fail(path, "the number is not finite or is too large");
    out = static_cast<float>(v);
    return true;
  }
  bool vec3(const json& j, const std::string& path, glm::vec3& out) {
    if (!j.is_array() || j.size() != 3)
      return fail(path, "expected 3 numbers [x, y, z], got " + kind(j));
    for (int i = 0; i < 3; ++i)
      if (!number(j[i], path + "[" + std::to_string(i) + "]", out[i])) return false;
    return true;
  }
  bool color(const json& j, const std::string& path, glm::vec3& out) {
    if (!vec3(j, path, out)) return false;
    for (int i = 0; i < 3; ++i)
      if (out[i] < 0.0f || out[i] > 1000.0f)
        return fail(path, "a colour channel must lie in [0, 1000]");
    return true;
  }
  // Optional key: absent leaves `out` as it is.
  template <class F>
  bool optional(const json& object, const std::string& path, const char* key, F&& read) {
    const auto it = object.find(key);
    return it == object.end() || read(*it, path + "." + key);
  }
  bool keys(const json& object, const std::string& path,
            std::initializer_list<const char*> allowed) {
    at = path;
    if (!object.is_object()) return fail(path, "expected an object {...}, got " + kind(object));
    for (const auto& [key, value] : object.items()) {
      bool known = false;
      for (const char* a : allowed) known |= key == a;
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        return fail(path + "." + key, "unknown key (expected one of: " + list + ")");
      }
    }
    return true;
  }

  bool transform(const json& j, const std::string& path, glm::mat4& out) {
    if (!keys(j, path, {"translate", "rotate", "scale"})) return false;
    glm::vec3 translate(0.0f), rotate(0.0f), scale(1.0f);
    if (!optional(j, path, "translate",
                  [&](const json& v, const std::string& p) { return vec3(v, p, translate); }))
      return false;
    if (!optional(j, path, "rotate",
                  [&](const json& v, const std::string& p) { return vec3(v, p, rotate); }))
      return false;
    if (!optional(j, path, "scale", [&](const json& v, const std::string& p) {
          if (v.is_number()) {
            float s = 1.0f;
            if (!number(v, p, s)) return false;
            scale = glm::vec3(s);
            return true;
          }
          return vec3(v, p, scale);
        }))
      return false;
    for (int i = 0; i < 3; ++i)
      if (scale[i] == 0.0f) return fail(path + ".scale", "a scale of 0 flattens the object");
    // translate * rotate (x, then y, then z, in degrees) * scale
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotate.z), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rotate.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotate.x), glm::vec3(1, 0, 0));
    out = glm::scale(m, scale);
    return true;
  }

  bool shape(const json& j, const std::string& path, Mesh& out) {
    if (!j.is_string()) return fail(path, "expected a shape name, got " + kind(j));
    const std::string name = j.get<std::string>();
    if (name == "box")
      out = make_box(glm::vec3(-0.5f), glm::vec3(0.5f));
    else if (name == "open_box")
      out = make_box(glm::vec3(-0.5f), glm::vec3(0.5f), false);
    else if (name == "ground")
      out = make_ground(1.0f);
    else if (name == "torus")
      out = make_bumpy_torus(96, 32, 1.0f, 0.35f, 0);
    else if (name == "bumpy_torus")
      out = make_bumpy_torus(96, 32);
    else if (name == "tube")  // along y, from -0.5 to 0.5, radius 0.5: scaled into rods and pipes
      out = make_tube(glm::vec3(0, -0.5f, 0), glm::vec3(0, 0.5f, 0), 0.5f, 0.5f, 24);
    else if (name == "sphere")
      out = make_sphere(glm::vec3(0.0f), 0.5f, 24, 48);
    else
      return fail(path, "unknown shape '" + name +
                            "' (expected box, open_box, ground, torus, bumpy_torus, tube or "
                            "sphere)");
    return true;
  }
};

}  // namespace

namespace {

Expected<Scene> read_scene(const std::filesystem::path& path, const json& root, Reader& r,
                           std::vector<std::string>& warnings) {
  const std::string& name = r.file;
  Scene scene;
  scene.name = path.stem().string();
  if (!r.keys(root, "scene", {"camera", "lights", "objects", "ambient", "opaque"}))
    return make_error(r.error);

  if (!root.contains("camera")) return make_error(name + ": scene.camera: missing");
  const json& cam = root["camera"];
  if (!r.keys(cam, "scene.camera", {"position", "target", "up", "fov", "near", "orbit", "move"}))
    return make_error(r.error);
  for (const char* required : {"position", "target"})
    if (!cam.contains(required))
      return make_error(name + ": scene.camera." + required + ": missing");
  r.vec3(cam["position"], "scene.camera.position", scene.camera.position) &&
      r.vec3(cam["target"], "scene.camera.target", scene.camera.target) &&
      r.optional(
          cam, "scene.camera", "up",
          [&](const json& v, const std::string& p) { return r.vec3(v, p, scene.camera.up); }) &&
      r.optional(cam, "scene.camera", "fov",
                 [&](const json& v, const std::string& p) {
                   return r.number(v, p, scene.camera.fov_y_degrees) &&
                          (scene.camera.fov_y_degrees > 1.0f && scene.camera.fov_y_degrees < 179.0f
                               ? true
                               : r.fail(p, "the field of view must lie between 1 and 179 degrees"));
                 }) &&
      r.optional(cam, "scene.camera", "near",
                 [&](const json& v, const std::string& p) {
                   return r.number(v, p, scene.camera.near) &&
                          (scene.camera.near > 0.0f
                               ? true
                               : r.fail(p, "the near distance must be positive"));
                 }) &&
      r.optional(cam, "scene.camera", "orbit",
                 [&](const json& v, const std::string& p) {
                   return r.number(v, p, scene.camera.orbit_degrees_per_frame);
                 }) &&
      r.optional(cam, "scene.camera", "move", [&](const json& v, const std::string& p) {
        return r.vec3(v, p, scene.camera.move);
      });
  if (!r.error.empty()) return make_error(r.error);
  if (glm::length(scene.camera.target - scene.camera.position) == 0.0f)
    return make_error(name + ": scene.camera.target: the camera looks at its own position");
  const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
  if (glm::length(glm::cross(forward, scene.camera.up)) < 1e-6f * glm::length(scene.camera.up))
    return make_error(name +
                      ": scene.camera.up: parallel to the direction the camera looks in; "
                      "give an up vector across it");

  if (root.contains("ambient") && !r.color(root["ambient"], "scene.ambient", scene.ambient))
    return make_error(r.error);

  if (!root.contains("lights") || !root["lights"].is_array() || root["lights"].empty())
    return make_error(name + ": scene.lights: expected a list of at least one light");
  for (std::size_t i = 0; i < root["lights"].size(); ++i) {
    const json& l = root["lights"][i];
    const std::string p = "scene.lights[" + std::to_string(i) + "]";
    if (!r.keys(l, p, {"position", "direction", "color", "intensity", "orbit", "range"}))
      return make_error(r.error);
    SceneLight light;
    glm::vec3 v(0.0f);
    if (l.contains("position") == l.contains("direction"))
      return make_error(
          name + ": " + p +
          ": give either position (a point light) or direction (a directional light)");
    const bool point = l.contains("position");
    if (!r.vec3(point ? l["position"] : l["direction"], p + (point ? ".position" : ".direction"),
                v))
      return make_error(r.error);
    light.position = glm::vec4(v, point ? 1.0f : 0.0f);
    if (auto ok = check_light(light.position); !ok)
      return make_error(name + ": " + p + ": " + ok.error().message);
    if (!r.optional(
            l, p, "color",
            [&](const json& c, const std::string& q) { return r.color(c, q, light.color); }) ||
        !r.optional(l, p, "orbit",
                    [&](const json& c, const std::string& q) {
                      return r.number(c, q, light.orbit_degrees_per_frame);
                    }) ||
        !r.optional(l, p, "intensity",
                    [&](const json& c, const std::string& q) {
                      return r.number(c, q, light.intensity) &&
                             (light.intensity >= 0.0f ? true : r.fail(q, "must not be negative"));
                    }) ||
        !r.optional(l, p, "range", [&](const json& c, const std::string& q) {
          if (!point) return r.fail(q, "only a point light (position) has a range");
          return r.number(c, q, light.range) &&
                 (light.range > 0.0f ? true
                                     : r.fail(q, "must be positive (leave it out for none)"));
        }))
      return make_error(r.error);
    scene.lights.push_back(light);
  }

  if (!root.contains("objects") || !root["objects"].is_array())
    return make_error(name + ": scene.objects: expected a list of objects");
  for (std::size_t i = 0; i < root["objects"].size(); ++i) {
    const json& o = root["objects"][i];
    const std::string p = "scene.objects[" + std::to_string(i) + "]";
    if (!r.keys(
            o, p,
            {"name", "mesh", "shape", "transform", "color", "opacity", "animation", "split_plane",
             "decompose", "casts_shadows", "receives_shadows", "clip", "frames_per_second"}))
      return make_error(r.error);
    if (o.contains("mesh") == o.contains("shape"))
      return make_error(name + ": " + p +
                        ": give either mesh (a file) or shape (a built-in shape)");
    for (const char* key : {"clip", "frames_per_second"})
      if (o.contains(key) && !o.contains("mesh"))
        return make_error(name + ": " + p + "." + key +
                          ": only a mesh file has animations of its own");
    Mesh mesh;
    Expected<LoadedMesh> loaded = make_error("");  // a mesh file's whole (mesh_io.h)
    std::string object_name = "object" + std::to_string(i);
    if (o.contains("name")) {
      if (!o["name"].is_string()) return make_error(name + ": " + p + ".name: expected a string");
      object_name = o["name"].get<std::string>();
    }
    if (o.contains("mesh")) {
      if (!o["mesh"].is_string())
        return make_error(name + ": " + p + ".mesh: expected a file name");
      std::filesystem::path file = o["mesh"].get<std::string>();
      if (file.is_relative()) file = path.parent_path() / file;
      loaded = load_mesh(file);
      if (!loaded) return make_error(name + ": " + p + ".mesh: " + loaded.error().message);
      warnings.insert(warnings.end(), loaded->warnings.begin(), loaded->warnings.end());
    } else if (!r.shape(o["shape"], p + ".shape", mesh)) {
      return make_error(r.error);
    }
    glm::mat4 transform(1.0f);
    Material material;
    if (!r.optional(
            o, p, "transform",
            [&](const json& t, const std::string& q) { return r.transform(t, q, transform); }) ||
        !r.optional(
            o, p, "color",
            [&](const json& c, const std::string& q) { return r.color(c, q, material.color); }) ||
        !r.optional(o, p, "opacity", [&](const json& c, const std::string& q) {
          return r.number(c, q, material.opacity) &&
                 (material.opacity >= 0.0f && material.opacity <= 1.0f
                      ? true
                      : r.fail(q, "must lie in [0, 1] (1 is opaque)"));
        }))
      return make_error(r.error);
    if (material.transparent() && glm::any(glm::greaterThan(material.color, glm::vec3(1.0f))))
      return make_error(name + ": " + p +
                        ".color: a transparent object's colour filters the light it passes, so "
                        "each channel must lie in [0, 1]");
    Animation animation;
    if (!r.optional(o, p, "animation", [&](const json& a, const std::string& q) {
          return r.keys(a, q, {"spin", "degrees_per_frame", "move"}) &&
                 r.optional(a, q, "spin",
                            [&](const json& v, const std::string& k) {
                              return r.vec3(v, k, animation.spin_axis) &&
                                     (animation.spin_axis != glm::vec3(0.0f)
                                          ? true
                                          : r.fail(k, "the spin axis is 0"));
                            }) &&
                 r.optional(a, q, "degrees_per_frame",
                            [&](const json& v, const std::string& k) {
                              return r.number(v, k, animation.degrees_per_frame);
                            }) &&
                 r.optional(a, q, "move", [&](const json& v, const std::string& k) {
                   return r.vec3(v, k, animation.move);
                 });
        }))
      return make_error(r.error);
    SplitPlaneChoice split_plane = SplitPlaneChoice::automatic;
    if (o.contains("split_plane")) {
      const json& v = o["split_plane"];
      auto choice = v.is_string() ? parse_split_plane_choice(v.get<std::string>())
                                  : Expected<SplitPlaneChoice>(make_error("expected a string"));
      if (!choice) return make_error(name + ": " + p + ".split_plane: " + choice.error().message);
      split_plane = *choice;
    }
    bool decompose = false, casts = true, receives = true;
    for (auto [key, flag] : {std::pair{"decompose", &decompose}, std::pair{"casts_shadows", &casts},
                             std::pair{"receives_shadows", &receives}})
      if (o.contains(key)) {
        if (!o[key].is_boolean())
          return make_error(name + ": " + p + "." + key + ": expected true or false");
        *flag = o[key].get<bool>();
      }
    // A mesh file's objects as file_objects makes them (its materials unless the object gives
    // its own colour or opacity; its first animation, or `clip`, moving its nodes); a shape's one.
    std::vector<SceneObject> objects;
    if (loaded) {
      FileObjectOptions options;
      options.fallback = material;
      if (o.contains("color") || o.contains("opacity")) options.material = material;
      options.placement = glm::dmat4(transform);
      if (o.contains("clip")) {
        const json& c = o["clip"];
        if (c.is_null()) {
          options.clip = -1;
        } else if (!c.is_string()) {
          return make_error(name + ": " + p +
                            ".clip: expected an animation's name, or null to hold the file still");
        } else if (auto clip = find_clip(*loaded, c.get<std::string>()); !clip) {
          return make_error(name + ": " + p + ".clip: " + clip.error().message);
        } else {
          options.clip = *clip;
        }
      }
      float fps = static_cast<float>(kDefaultFramesPerSecond);
      if (!r.optional(o, p, "frames_per_second", [&](const json& v, const std::string& q) {
            return r.number(v, q, fps) &&
                   (fps > 0.0f ? true
                               : r.fail(q,
                                        "must be positive (frames a second of the "
                                        "file's animation)"));
          }))
        return make_error(r.error);
      options.frames_per_second = fps;
      objects = file_objects(object_name, *loaded, options, warnings);
    } else {
      objects.push_back(make_object(object_name, std::move(mesh), transform, material));
    }
    for (SceneObject& object : objects) {
      // Decomposed (Laine 2005 §6): each connected part an object of its own, with its own split
      // plane; vertices at equal positions join, since mesh files often repeat them per face.
      // The parts shade flat and untextured.
      std::vector<SceneObject> parts;
      std::vector<Mesh> meshes;
      if (decompose) meshes = connected_parts(*object.mesh, true);
      if (meshes.size() > 1) {
        for (std::size_t k = 0; k < meshes.size(); ++k) {
          Material flat = object.material;
          flat.base_color_map = nullptr;
          parts.push_back(make_object(object.name + "/" + std::to_string(k + 1),
                                      std::move(meshes[k]), object.transform, flat));
          parts.back().node = object.node;
        }
      } else {
        parts.push_back(std::move(object));
      }
      for (SceneObject& part : parts) {
        part.animation = animation;
        part.split_plane = split_plane;
        part.casts_shadows = casts;
        part.receives_shadows = receives;
        scene.objects.push_back(std::move(part));
      }
    }
  }
  if (root.contains("opaque")) {  // every caster opaque, whatever its material (make_opaque)
    if (!root["opaque"].is_boolean())
      return make_error(name + ": scene.opaque: expected true or false");
    if (root["opaque"].get<bool>()) make_opaque(scene);
  }
  return scene;
}

}  // namespace

Expected<Scene> load_scene_file(const std::filesystem::path& path,
                                std::vector<std::string>* warnings) {
  const std::string name = path.string();
  if (auto ok = check_input_file(path, "scene file"); !ok) return ok.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(name + ": cannot be opened for reading");
  json root;
  ParsePosition position;
  try {
    root = json::parse(
        in,
        [&](int, json::parse_event_t event, json& parsed) { return position.on(event, parsed); },
        true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {  // every kind: a syntax error, a number past a double's
    return make_error(name + ": " + describe_json_error(e, position.path()));
  } catch (const std::ios_base::failure& e) {  // a read that failed part way (an I/O error)
    return make_error(name + ": cannot be read (" + e.code().message() + ")");
  }
  Reader r{name, {}};
  std::vector<std::string> ignored;
  try {
    return read_scene(path, root, r, warnings ? *warnings : ignored);
  } catch (const json::exception& e) {  // a check missed: still a message, never terminate
    return make_error(name + ": " + describe_json_error(e, r.at));
  }
}

Expected<LoadedScene> load_scene(const std::string& name) {
  if (name.starts_with("stage:")) {
    auto stage = load_stage(name.substr(6));
    if (!stage) return stage.error();
    return LoadedScene{std::move(*stage), {}, {}};
  }
  auto builtin = builtin_scene(name);
  if (builtin) return LoadedScene{std::move(*builtin), {}, {}};
  if (!names_a_path(name)) return builtin.error();  // lists the built-in names
  if (auto ok = check_input_file(name, "scene or mesh file"); !ok) return ok.error();
  if (lower_extension(name) == ".json") {
    std::vector<std::string> warnings;
    auto scene = load_scene_file(name, &warnings);
    if (!scene) return scene.error();
    return LoadedScene{std::move(*scene), std::move(warnings), {}};
  }
  auto loaded = load_mesh(name);
  if (!loaded) return loaded.error();
  std::vector<std::string> warnings = std::move(loaded->warnings);
  Scene scene = file_scene(std::filesystem::path(name).filename().string(), *loaded, warnings);
  return LoadedScene{std::move(scene), std::move(warnings), std::move(loaded->cameras)};
}

Expected<int> find_clip(const LoadedMesh& loaded, const std::string& name) {
  const std::vector<Clip> none;
  const std::vector<Clip>& clips = loaded.hierarchy ? loaded.hierarchy->clips : none;
  for (std::size_t i = 0; i < clips.size(); ++i)
    if (clips[i].name == name) return static_cast<int>(i);
  std::string names;
  for (const Clip& c : clips) names += (names.empty() ? "'" : ", '") + c.name + "'";
  return make_error("no animation named '" + name + "'; " +
                    (names.empty() ? std::string("the file has none") : "the file's are " + names));
}

std::vector<SceneObject> file_objects(const std::string& prefix, const LoadedMesh& loaded,
                                      const FileObjectOptions& options,
                                      std::vector<std::string>& warnings) {
  const std::size_t triangles = loaded.mesh.indices.size() / 3;
  const NodeHierarchy* hierarchy = loaded.hierarchy.get();
  const int clip =
      hierarchy && options.clip >= 0 && options.clip < static_cast<int>(hierarchy->clips.size())
          ? options.clip
          : -1;
  // Per node, whether the clip moves it, and how its mesh goes from rest to the node's space.
  std::vector<char> moving(hierarchy ? hierarchy->nodes.size() : 0, 0);
  std::vector<glm::dmat4> from_rest(moving.size(), glm::dmat4(1.0));
  for (std::size_t n = 0; n < moving.size() && clip >= 0; ++n) {
    if (!hierarchy->moves(static_cast<int>(n), clip)) continue;
    const glm::dmat4 rest = hierarchy->world_at(static_cast<int>(n), -1, 0.0);
    const double det = glm::determinant(rest);
    if (!std::isfinite(det) || std::abs(det) < 1e-300) {
      warnings.push_back(prefix + ": node '" + hierarchy->nodes[n].name +
                         "' is flat at rest (a scale of 0), so its motion cannot be recovered from "
                         "its mesh; drawn still");
      continue;
    }
    moving[n] = 1;
    from_rest[n] = glm::inverse(rest);
  }
  // The objects: a group of triangles per (moving node or -1 for all that stay, material).
  const bool by_node = clip >= 0 && loaded.triangle_node.size() == triangles;
  const bool by_material = !loaded.materials.empty() && !options.material;
  std::map<std::pair<int, std::uint32_t>, std::vector<std::uint32_t>> groups;
  for (std::uint32_t t = 0; t < triangles; ++t) {
    const std::uint32_t node = by_node ? loaded.triangle_node[t] : 0;
    const int key = by_node && moving[node] ? static_cast<int>(node) : -1;
    groups[{key, by_material ? loaded.triangle_material[t] : 0u}].push_back(t);
  }
  std::vector<SceneObject> objects;
  std::vector<std::uint32_t> remap(loaded.mesh.positions.size(), UINT32_MAX);
  for (const auto& [key, group] : groups) {
    const auto [node, material] = key;
    Mesh part;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    for (const std::uint32_t t : group) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = loaded.mesh.indices[3 * t + k];
        if (remap[v] == UINT32_MAX) {
          remap[v] = static_cast<std::uint32_t>(part.positions.size());
          part.positions.push_back(loaded.mesh.positions[v]);
        }
        part.indices.push_back(remap[v]);
        if (loaded.corner_normals.size() == 3 * triangles)
          normals.push_back(loaded.corner_normals[3 * t + k]);
        if (loaded.corner_uvs.size() == 3 * triangles) uvs.push_back(loaded.corner_uvs[3 * t + k]);
      }
    }
    for (const std::uint32_t t : group)
      for (int k = 0; k < 3; ++k) remap[loaded.mesh.indices[3 * t + k]] = UINT32_MAX;
    std::string name = prefix;
    if (node >= 0) name += "/" + hierarchy->nodes[static_cast<std::size_t>(node)].name;
    if (by_material) name += "/" + loaded.materials[material].name;
    const Material file_material =
        by_material ? loaded.materials[material].material : options.fallback;
    objects.push_back(make_object(std::move(name), std::move(part), glm::mat4(options.placement),
                                  options.material.value_or(file_material)));
    SceneObject& object = objects.back();
    set_shading_normals(object, std::move(normals));
    // Textured where the file's material has a map and every corner its coordinates.
    const bool mapped = std::all_of(uvs.begin(), uvs.end(), [](const glm::vec2& uv) {
      return std::isfinite(uv.x) && std::isfinite(uv.y);
    });
    if (object.material.base_color_map && !uvs.empty() && mapped)
      object.uvs = std::make_shared<const std::vector<glm::vec2>>(std::move(uvs));
    if (node >= 0) {
      object.node = NodeBinding{loaded.hierarchy,
                                node,
                                clip,
                                options.frames_per_second,
                                options.placement,
                                from_rest[static_cast<std::size_t>(node)]};
      object.transform = object.node.transform_at(0);
    }
  }
  return objects;
}

Scene file_scene(const std::string& name, const LoadedMesh& loaded,
                 std::vector<std::string>& warnings) {
  // The stage around the whole mesh at rest: its ground, camera and light.
  Scene scene = stage_around(name, loaded.mesh);
  FileObjectOptions options;
  options.fallback = Material{kStageColor};
  std::vector<SceneObject> objects = file_objects(name, loaded, options, warnings);
  objects.push_back(std::move(scene.objects.back()));  // the ground
  scene.objects = std::move(objects);
  if (!loaded.cameras.empty()) scene.camera = loaded.cameras.front().camera;
  if (!loaded.lights.empty()) {
    scene.lights.clear();
    for (const FileLight& l : loaded.lights) scene.lights.push_back(l.light);
  }
  return scene;
}

Expected<void> use_camera(LoadedScene& loaded, const std::string& name) {
  for (const FileCamera& c : loaded.cameras)
    if (c.name == name) {
      loaded.scene.camera = c.camera;
      return {};
    }
  std::string names;
  for (const FileCamera& c : loaded.cameras) names += (names.empty() ? "" : ", ") + c.name;
  return make_error("--camera " + name + ": " +
                    (names.empty() ? std::string("the scene has no cameras of its own")
                                   : "no camera of that name; the scene's are " + names));
}

}  // namespace shadowvol
