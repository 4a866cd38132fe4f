#include "scene/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <sstream>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>

#include "scene/declared_size.h"

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

struct Gather {
  const aiScene* scene;
  LoadedMesh* out;
  std::string error;  // the first problem found, empty if none

  void node(const aiNode* n, const aiMatrix4x4& parent) {
    const aiMatrix4x4 world = parent * n->mTransformation;
    for (unsigned i = 0; i < n->mNumMeshes; ++i) mesh(scene->mMeshes[n->mMeshes[i]], world);
    for (unsigned i = 0; i < n->mNumChildren; ++i) node(n->mChildren[i], world);
  }

  void mesh(const aiMesh* m, const aiMatrix4x4& world) {
    Mesh& dst = out->mesh;
    const std::size_t base = dst.positions.size();
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
      }
    }
  }
};

}  // namespace

Expected<LoadedMesh> load_mesh(const std::filesystem::path& path, const LoadProgress& progress) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return make_error(name + ": no such file");
  if (std::filesystem::is_directory(path, ec))
    return make_error(name + ": is a directory, not a mesh file");
  if (!std::ifstream(path, std::ios::binary).good())
    return make_error(name + ": cannot be opened for reading (check its permissions)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (size == 0 && !ec) return make_error(name + ": the file is empty");
  if (auto fits = check_declared_size(path, size); !ec && !fits) return fits.error();

  Assimp::Importer importer;
  // Only positions and faces matter to a shadow caster; ask assimp for nothing else.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS |
                                  aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                  aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS);
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
  Gather gather{scene, &loaded, {}};
  gather.node(scene->mRootNode, aiMatrix4x4());
  if (!gather.error.empty()) return make_error(name + ": " + gather.error);
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
  return loaded;
}

}  // namespace shadowvol
