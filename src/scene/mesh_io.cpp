#include "scene/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>

#include "core/shading_normals.h"
#include "core/volume.h"
#include "scene/declared_size.h"
#include "scene/input_file.h"
#include "scene/texture_io.h"

namespace shadowvol {
namespace {

// Forwards assimp's progress to the caller. The importer owns it and deletes it.
class ProgressForwarder : public Assimp::ProgressHandler {
 public:
  explicit ProgressForwarder(LoadProgress progress) : progress_(std::move(progress)) {}
  bool Update(float fraction) override {
    if (fraction >= 0.0f) progress_(std::min(fraction, 1.0f));
    return true;  // never abort
  }

 private:
  LoadProgress progress_;
};

// What assimp's validation found, in the file's own terms where we can find it: OBJ faces of
// fewer than three vertices (a file cut short mid-line leaves one) and vertex numbers past the
// vertices written, by line. Empty where the file shows nothing such.
std::string explain_obj(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long long vertices = 0;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v") ++vertices;
    if (keyword != "f") continue;
    std::vector<std::string> corners;
    for (std::string w; words >> w;) corners.push_back(w);
    const std::string where = "line " + std::to_string(number) + ": ";
    if (corners.size() < 3)
      return where + "a face of " + std::to_string(corners.size()) +
             (corners.size() == 1 ? " vertex" : " vertices") + " ('" + line.substr(0, 60) +
             "'); a face needs three or more (is the file cut short?)";
    for (const std::string& c : corners) {
      const long long v = std::atoll(c.c_str());  // "7/2/3": the position's number
      if (v > vertices || v < -vertices || v == 0)
        return where + "the face uses vertex " + c.substr(0, c.find('/')) + " but only " +
               std::to_string(vertices) + " vertices come before it";
    }
  }
  return {};
}

// A reader's message, with what is wrong with the file first where assimp's is about its own
// data structures ("Validation failed: aiMesh::mFaces[6] is a LINE but ...").
std::string explain_failure(const std::filesystem::path& path, const std::string& why) {
  if (why.find("Validation failed") == std::string::npos) return why;
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string found = ext == ".obj" ? explain_obj(path) : std::string();
  return (found.empty() ? std::string("its data is inconsistent") : found) + "; assimp: " + why;
}

glm::vec3 to_vec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

struct Gather {
  const aiScene* scene;
  LoadedMesh* out;
  std::string error;  // the first problem found, empty if none

  // Cameras and lights are placed by their nodes' names: the world and local transforms.
  std::map<std::string, std::pair<aiMatrix4x4, aiMatrix4x4>> node_transforms;
  NodeHierarchy hierarchy;  // every node, parents first, for the animations

  void node(const aiNode* n, const aiMatrix4x4& parent, int parent_index) {
    const aiMatrix4x4 world = parent * n->mTransformation;
    node_transforms.emplace(n->mName.C_Str(), std::pair{world, n->mTransformation});
    const int index = static_cast<int>(hierarchy.nodes.size());
    hierarchy.nodes.push_back(rest_node(*n, parent_index));
    for (unsigned i = 0; i < n->mNumMeshes; ++i) mesh(scene->mMeshes[n->mMeshes[i]], world, index);
    for (unsigned i = 0; i < n->mNumChildren; ++i) node(n->mChildren[i], world, index);
  }

  static HierarchyNode rest_node(const aiNode& n, int parent) {
    HierarchyNode out{n.mName.C_Str(), parent, {}, {}, {}, {}};
    const aiMatrix4x4& m = n.mTransformation;  // row-major; glm is column-major
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) out.rest[c][r] = static_cast<double>(m[r][c]);
    aiVector3D scale, position;
    aiQuaternion rotation;
    m.Decompose(scale, rotation, position);
    out.rest_translation = {position.x, position.y, position.z};
    out.rest_rotation = glm::dquat(rotation.w, rotation.x, rotation.y, rotation.z);
    out.rest_scale = {scale.x, scale.y, scale.z};
    return out;
  }

  void mesh(const aiMesh* m, const aiMatrix4x4& world, int node_index) {
    Mesh& dst = out->mesh;
    const std::size_t base = dst.positions.size();
    // Normals turn by the inverse transpose; a corner without a usable one is left NaN, for
    // crease_normals to fill.
    aiMatrix3x3 turn_normals = aiMatrix3x3(world);
    turn_normals.Inverse().Transpose();
    const auto file_normal = [&](unsigned v) {
      constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
      if (!m->HasNormals()) return glm::vec3(kNone);
      const glm::vec3 n = to_vec3(turn_normals * m->mNormals[v]);
      const float len = glm::length(n);
      return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(kNone);
    };
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D p = world * m->mVertices[v];
      dst.positions.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices == 1) {
        ++out->points_ignored;
        continue;
      }
      if (face.mNumIndices == 2) {
        ++out->lines_ignored;
        continue;
      }
      if (face.mNumIndices != 3) continue;  // cannot happen after aiProcess_Triangulate
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m->mNumVertices && error.empty())
          error = "mesh '" + std::string(m->mName.C_Str()) + "' face " + std::to_string(f) +
                  " uses vertex " + std::to_string(face.mIndices[k]) + " of only " +
                  std::to_string(m->mNumVertices);
        dst.indices.push_back(static_cast<std::uint32_t>(base + face.mIndices[k]));
        out->corner_normals.push_back(
            face.mIndices[k] < m->mNumVertices ? file_normal(face.mIndices[k]) : glm::vec3(0.0f));
        constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
        const aiVector3D* uv = m->mTextureCoords[0];
        out->corner_uvs.push_back(uv && face.mIndices[k] < m->mNumVertices
                                      ? glm::vec2(uv[face.mIndices[k]].x, uv[face.mIndices[k]].y)
                                      : glm::vec2(kNone));
      }
      out->triangle_material.push_back(m->mMaterialIndex);
      out->triangle_node.push_back(static_cast<std::uint32_t>(node_index));
    }
  }

  aiMatrix4x4 world_of(const aiString& name) const {
    const auto it = node_transforms.find(name.C_Str());
    return it == node_transforms.end() ? aiMatrix4x4() : it->second.first;
  }
  aiVector3D local_translation(const aiString& name) const {
    const auto it = node_transforms.find(name.C_Str());
    if (it == node_transforms.end()) return {};
    const aiMatrix4x4& m = it->second.second;
    return {m.a4, m.b4, m.c4};
  }
};

// The material's base colour map, read from a file beside the mesh or from the file itself
// (assimp names an embedded texture "*N"); null, with a warning in `warnings`, where it cannot.
std::shared_ptr<const Texture> base_color_map(const aiScene& scene, const aiMaterial& m,
                                              const std::filesystem::path& mesh_file,
                                              std::vector<std::string>& warnings) {
  aiString name;
  if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS &&
      m.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS)
    return nullptr;
  const std::string file = name.C_Str();
  Expected<Texture> texture = make_error("");
  if (const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str())) {
    const std::string source = mesh_file.string() + " (embedded " + file + ")";
    if (embedded->mHeight == 0) {  // compressed: mWidth bytes of an image file
      texture = decode_texture(reinterpret_cast<const std::uint8_t*>(embedded->pcData),
                               embedded->mWidth, source);
    } else if (embedded->mWidth <= unsigned(kMaxTextureSide) &&
               embedded->mHeight <= unsigned(kMaxTextureSide)) {
      Texture raw{int(embedded->mWidth), int(embedded->mHeight), {}, source};
      for (std::size_t i = 0; i < std::size_t(embedded->mWidth) * embedded->mHeight; ++i) {
        const aiTexel& t = embedded->pcData[i];
        raw.rgba.insert(raw.rgba.end(), {t.r, t.g, t.b, t.a});
      }
      texture = std::move(raw);
    } else {
      texture = make_error(source + ": larger than " + std::to_string(kMaxTextureSide) +
                           " pixels a side");
    }
  } else {
    std::filesystem::path path(file);
    if (path.is_relative()) path = mesh_file.parent_path() / path;
    texture = load_texture(path);
  }
  if (!texture) {
    warnings.push_back(mesh_file.string() + ": material '" + m.GetName().C_Str() +
                       "': its texture is left out (" + texture.error().message +
                       "); drawn in its base colour");
    return nullptr;
  }
  return std::make_shared<const Texture>(std::move(*texture));
}

Material material_of(const aiMaterial& m) {
  Material out;
  aiColor4D colour(0.8f, 0.8f, 0.8f, 1.0f);
  const bool base = m.Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS;
  if (!base) m.Get(AI_MATKEY_COLOR_DIFFUSE, colour);
  out.color = glm::clamp(glm::vec3(colour.r, colour.g, colour.b), 0.0f, 1.0f);
  float opacity = 1.0f;
  if (m.Get(AI_MATKEY_OPACITY, opacity) != AI_SUCCESS) {
    aiString mode;  // glTF: the base colour's alpha is opacity where the mode is BLEND
    if (m.Get("$mat.gltf.alphaMode", 0, 0, mode) == AI_SUCCESS &&
        std::string(mode.C_Str()) == "BLEND")
      opacity = colour.a;
  }
  float transmission = 0.0f;
  if (m.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission) == AI_SUCCESS)
    opacity = std::min(opacity, 1.0f - transmission);
  out.opacity = std::isfinite(opacity) ? std::clamp(opacity, 0.0f, 1.0f) : 1.0f;
  return out;
}

// COLLADA's transparency (assimp 5.2 applies its opaque modes: A_ONE, the default, opacity =
// transparent.a x transparency; A_ZERO 1 - that; RGB_ONE and RGB_ZERO by the colour's luminance)
// and MTL's Tr (1 - d) are written inverted by many exporters: "transparency 0" or "Tr 1" for a
// material with no transparency, which the conventions read as fully see-through. A surface a
// file draws at opacity 0 would be invisible and cast no shadow, never what the file means, so
// these formats' opacity 0 is read as opaque, as the common viewers show such files, and said.
void read_no_transparency_as_opaque(const std::filesystem::path& file, FileMaterial& material,
                                    std::vector<std::string>& warnings) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if ((extension != ".dae" && extension != ".obj") || material.material.opacity != 0.0f) return;
  material.material.opacity = 1.0f;
  warnings.push_back(file.string() + ": material '" + material.name +
                     "' is fully transparent as the file is written (opacity 0: " +
                     (extension == ".dae" ? "COLLADA transparency 0 under A_ONE"
                                          : "MTL d 0 or Tr 1") +
                     "), which exporters write for no transparency; read as opaque");
}

// The materials the triangles use, where any is the file's own (not assimp's default); else
// none, and the triangles' indices are dropped.
void gather_materials(const aiScene& scene, const std::filesystem::path& file, LoadedMesh& out) {
  bool own = false;
  for (std::uint32_t index : out.triangle_material)
    if (index < scene.mNumMaterials &&
        std::string(scene.mMaterials[index]->GetName().C_Str()) != AI_DEFAULT_MATERIAL_NAME)
      own = true;
  if (!own) {
    out.triangle_material.clear();
    out.corner_uvs.clear();
    return;
  }
  // The materials in use, in the file's order, and each triangle's index among them.
  std::vector<std::uint32_t> slot(scene.mNumMaterials + 1, UINT32_MAX);
  for (std::uint32_t& index : out.triangle_material)
    slot[std::min<std::uint32_t>(index, scene.mNumMaterials)] = 0;
  for (unsigned i = 0; i < scene.mNumMaterials; ++i)
    if (slot[i] == 0) {
      slot[i] = static_cast<std::uint32_t>(out.materials.size());
      out.materials.push_back(
          {scene.mMaterials[i]->GetName().C_Str(), material_of(*scene.mMaterials[i])});
      read_no_transparency_as_opaque(file, out.materials.back(), out.warnings);
      out.materials.back().material.base_color_map =
          base_color_map(scene, *scene.mMaterials[i], file, out.warnings);
    }
  if (slot[scene.mNumMaterials] == 0) {  // an index past the file's materials: a default one
    slot[scene.mNumMaterials] = static_cast<std::uint32_t>(out.materials.size());
    out.materials.push_back({AI_DEFAULT_MATERIAL_NAME, Material{}});
  }
  for (std::uint32_t& index : out.triangle_material)
    index = slot[std::min<std::uint32_t>(index, scene.mNumMaterials)];
}

// `gltf`: assimp (5.2) reads glTF's cameras its own way: the horizontal field of view is the
// vertical one times the aspect (not by the tangents), and the camera's position is a copy of its
// node's translation, which the node's transform applies again.
void gather_cameras_and_lights(const aiScene& scene, const Gather& gather, bool gltf,
                               LoadedMesh& out) {
  for (unsigned i = 0; i < scene.mNumCameras; ++i) {
    const aiCamera& c = *scene.mCameras[i];
    if (!(c.mHorizontalFOV > 0.0f) || c.mOrthographicWidth > 0.0f) continue;  // perspective only
    const aiMatrix4x4 world = gather.world_of(c.mName);
    const aiMatrix3x3 turn(world);
    const bool copied = gltf && c.mPosition == gather.local_translation(c.mName);
    const aiVector3D position = copied ? aiVector3D() : c.mPosition;
    Camera camera;
    camera.position = to_vec3(world * position);
    camera.target = to_vec3(world * (position + c.mLookAt));
    camera.up = to_vec3(turn * c.mUp);
    // assimp's field of view is horizontal, the whole angle.
    const float aspect = c.mAspect > 0.0f ? c.mAspect : 1.0f;
    const float fov_y = gltf ? c.mHorizontalFOV / aspect
                             : 2.0f * std::atan(std::tan(c.mHorizontalFOV * 0.5f) / aspect);
    camera.fov_y_degrees = glm::degrees(fov_y);
    if (c.mClipPlaneNear > 0.0f) camera.near = c.mClipPlaneNear;
    if (!std::isfinite(camera.fov_y_degrees) || camera.fov_y_degrees <= 1.0f ||
        camera.fov_y_degrees >= 179.0f || glm::length(camera.target - camera.position) == 0.0f)
      continue;
    out.cameras.push_back({c.mName.C_Str(), camera});
  }
  for (unsigned i = 0; i < scene.mNumLights; ++i) {
    const aiLight& l = *scene.mLights[i];
    const aiMatrix4x4 world = gather.world_of(l.mName);
    SceneLight light;
    if (l.mType == aiLightSource_DIRECTIONAL) {
      const glm::vec3 towards = -to_vec3(aiMatrix3x3(world) * l.mDirection);  // to the light
      light.position = glm::vec4(towards, 0.0f);
    } else if (l.mType == aiLightSource_POINT || l.mType == aiLightSource_SPOT) {
      light.position = glm::vec4(to_vec3(world * l.mPosition), 1.0f);
    } else {
      continue;  // area and ambient lights cast no hard shadows
    }
    const glm::vec3 colour(l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b);
    const float top = std::max({colour.r, colour.g, colour.b});
    light.color = top > 0.0f && std::isfinite(top) ? colour / top : glm::vec3(1.0f);
    if (!check_light(light.position).ok()) continue;
    out.lights.push_back({l.mName.C_Str(), light});
  }
}

// The file's animations as clips of the hierarchy's nodes; an error names the animation and the
// node where a key is not a number.
Expected<void> gather_animations(const aiScene& scene, NodeHierarchy& hierarchy,
                                 const std::string& file, std::vector<std::string>& warnings) {
  std::map<std::string, int> node_index;
  for (std::size_t i = 0; i < hierarchy.nodes.size(); ++i)
    node_index.emplace(hierarchy.nodes[i].name, static_cast<int>(i));  // the first of a name
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    const aiAnimation& anim = *scene.mAnimations[a];
    Clip clip;
    clip.name = anim.mName.length > 0 ? anim.mName.C_Str() : "animation " + std::to_string(a);
    // Ticks to seconds; a file that gives no rate has assimp's customary 25 a second.
    const double per_second = anim.mTicksPerSecond > 0.0 ? anim.mTicksPerSecond : 25.0;
    for (unsigned c = 0; c < anim.mNumChannels; ++c) {
      const aiNodeAnim& channel = *anim.mChannels[c];
      const auto found = node_index.find(channel.mNodeName.C_Str());
      if (found == node_index.end()) {
        warnings.push_back(file + ": animation '" + clip.name + "' moves node '" +
                           channel.mNodeName.C_Str() + "', which the file does not have; left out");
        continue;
      }
      NodeChannels out;
      out.node = found->second;
      std::string bad;
      const auto keys = [&](auto& into, const auto* from, unsigned count, auto value) {
        std::vector<std::pair<double, decltype(value(from[0].mValue))>> sorted;
        for (unsigned k = 0; k < count; ++k)
          sorted.emplace_back(from[k].mTime / per_second, value(from[k].mValue));
        std::stable_sort(sorted.begin(), sorted.end(),
                         [](const auto& x, const auto& y) { return x.first < y.first; });
        for (const auto& [time, v] : sorted) {
          bool finite = std::isfinite(time);
          for (int i = 0; i < v.length(); ++i) finite = finite && std::isfinite(v[i]);
          if (!finite && bad.empty()) bad = "a key that is not a finite number";
          into.seconds.push_back(time);
          into.values.push_back(v);
          clip.duration = std::max(clip.duration, time);
        }
      };
      const auto vec3 = [](const aiVector3D& v) { return glm::dvec3(v.x, v.y, v.z); };
      keys(out.translation, channel.mPositionKeys, channel.mNumPositionKeys, vec3);
      keys(out.scale, channel.mScalingKeys, channel.mNumScalingKeys, vec3);
      keys(out.rotation, channel.mRotationKeys, channel.mNumRotationKeys,
           [&](const aiQuaternion& q) {
             const glm::dquat r(q.w, q.x, q.y, q.z);
             const double length = glm::length(r);
             if (length == 0.0 && bad.empty()) bad = "a rotation key of no length";
             return length > 0.0 ? r / length : r;
           });
      if (!bad.empty())
        return make_error(file + ": animation '" + clip.name + "' moves node '" +
                          channel.mNodeName.C_Str() + "' by " + bad);
      clip.channels.push_back(std::move(out));
    }
    hierarchy.clips.push_back(std::move(clip));
  }
  return {};
}

}  // namespace

Expected<LoadedMesh> load_mesh(const std::filesystem::path& path, const LoadProgress& progress) {
  const std::string name = path.string();
  if (auto ok = check_input_file(path, "mesh file"); !ok) return ok.error();
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (size == 0 && !ec) return make_error(name + ": the file is empty");
  if (auto fits = check_declared_size(path, size); !ec && !fits) return fits.error();

  Assimp::Importer importer;
  // Positions, normals, texture coordinates, faces, materials, textures, cameras, lights and
  // animations: ask assimp for nothing else.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS |
                                                          aiComponent_BONEWEIGHTS);
  if (progress) importer.SetProgressHandler(new ProgressForwarder(progress));
  const aiScene* scene = nullptr;
  try {
    scene =
        importer.ReadFile(name, aiProcess_Triangulate | aiProcess_SortByPType |
                                    aiProcess_RemoveComponent | aiProcess_ValidateDataStructure);
  } catch (const std::exception& e) {  // assimp catches most of its own; not all
    return make_error(name + ": cannot be read as a mesh (" + e.what() + ")");
  }
  if (scene == nullptr) {
    const std::string why = importer.GetErrorString();
    // A header that declares billions of elements makes the reader's first allocation fail.
    if (why.find("bad_alloc") != std::string::npos)
      return make_error(name + ": declares more data than fits in memory (a corrupt header?)");
    return make_error(name + ": cannot be read as a mesh (" +
                      (why.empty() ? std::string("unknown format") : explain_failure(path, why)) +
                      ")");
  }
  if (scene->mRootNode == nullptr)
    return make_error(name + ": the file has no scene hierarchy (no meshes placed in it)");

  LoadedMesh loaded;
  Gather gather{scene, &loaded, {}, {}, {}};
  gather.node(scene->mRootNode, aiMatrix4x4(), -1);
  if (!gather.error.empty()) return make_error(name + ": " + gather.error);
  if (auto ok = gather_animations(*scene, gather.hierarchy, name, loaded.warnings); !ok)
    return ok.error();
  if (gather.hierarchy.clips.empty())
    loaded.triangle_node.clear();
  else
    loaded.hierarchy = std::make_shared<const NodeHierarchy>(std::move(gather.hierarchy));
  gather_materials(*scene, path, loaded);
  // A map on triangles without texture coordinates has nothing to be sampled at.
  for (std::size_t t = 0; t < loaded.triangle_material.size() && !loaded.corner_uvs.empty(); ++t) {
    Material& material = loaded.materials[loaded.triangle_material[t]].material;
    if (material.base_color_map && std::isnan(loaded.corner_uvs[3 * t].x)) {
      material.base_color_map = nullptr;
      loaded.warnings.push_back(name + ": material '" +
                                loaded.materials[loaded.triangle_material[t]].name +
                                "': its texture is left out (its triangles have no texture "
                                "coordinates); drawn in its base colour");
    }
  }
  if (std::none_of(loaded.materials.begin(), loaded.materials.end(),
                   [](const FileMaterial& m) { return m.material.base_color_map != nullptr; }))
    loaded.corner_uvs.clear();
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  gather_cameras_and_lights(*scene, gather, extension == ".gltf" || extension == ".glb", loaded);
  if (loaded.points_ignored > 0)
    loaded.warnings.push_back(name + ": ignored " + std::to_string(loaded.points_ignored) +
                              " point primitives (points cast no shadow)");
  if (loaded.lines_ignored > 0)
    loaded.warnings.push_back(name + ": ignored " + std::to_string(loaded.lines_ignored) +
                              " line primitives (lines cast no shadow)");
  if (loaded.mesh.indices.empty())
    return make_error(name + ": the file has no triangles" +
                      (loaded.points_ignored + loaded.lines_ignored > 0
                           ? std::string(" (only points or lines)")
                           : std::string()));
  if (auto valid = validate_mesh(loaded.mesh, name); !valid) return valid.error();
  // The file's normals where it gives them, the crease angle's elsewhere.
  const bool all_given = std::none_of(loaded.corner_normals.begin(), loaded.corner_normals.end(),
                                      [](const glm::vec3& n) { return std::isnan(n.x); });
  if (!all_given) {
    const std::vector<glm::vec3> creased = crease_normals(loaded.mesh, kDefaultCreaseDegrees);
    for (std::size_t c = 0; c < creased.size(); ++c)
      if (std::isnan(loaded.corner_normals[c].x)) loaded.corner_normals[c] = creased[c];
  }
  return loaded;
}

}  // namespace shadowvol
