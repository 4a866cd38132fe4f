// shadowvol scene: node hierarchies that move (glTF's, COLLADA's, FBX's, through assimp's
// animation channels): a node's transform at a time, from keyframes of its translation,
// rotation and scale, composed through its ancestors; and the binding that moves an object by
// its node from frame to frame.
//
// Owns: the hierarchy, its clips and their evaluation (glTF 2.0 §3.11: linear interpolation of
// translation and scale, spherical linear of rotation; before a channel's first key its first
// value, after its last its last). No I/O: mesh_io fills it from a file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace shadowvol {

// Frames of `scene_at_frame` a second of a file's animation, where the scene does not say.
inline constexpr double kDefaultFramesPerSecond = 30.0;

template <class T>
struct Keyframes {
  std::vector<double> seconds;  // increasing
  std::vector<T> values;        // one per time

  bool empty() const { return seconds.empty(); }
};

// What one clip does to one node: a component without keys keeps the node's rest value.
struct NodeChannels {
  int node = -1;
  Keyframes<glm::dvec3> translation;
  Keyframes<glm::dquat> rotation;  // unit quaternions
  Keyframes<glm::dvec3> scale;
};

struct Clip {
  std::string name;
  double duration = 0.0;  // seconds: the last key of any channel; the clip repeats after it
  std::vector<NodeChannels> channels;
};

struct HierarchyNode {
  std::string name;
  int parent = -1;                   // an earlier node, or -1 for a root
  glm::dmat4 rest{1.0};              // local transform where no channel moves it
  glm::dvec3 rest_translation{0.0};  // `rest` decomposed, for the components a clip leaves
  glm::dquat rest_rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 rest_scale{1.0};
};

struct NodeHierarchy {
  std::vector<HierarchyNode> nodes;  // parents before their children
  std::vector<Clip> clips;

  // The node's transform in its parent's space at `seconds` of clip `clip` (-1: at rest).
  glm::dmat4 local_at(int node, int clip, double seconds) const;
  // The node's transform in the file's root space: its ancestors' local transforms and its own.
  glm::dmat4 world_at(int node, int clip, double seconds) const;
  // Whether the clip moves the node or any of its ancestors.
  bool moves(int node, int clip) const;
};

// Interpolation of one channel at a time (exposed for tests).
glm::dvec3 sample(const Keyframes<glm::dvec3>& keys, double seconds);
glm::dquat sample(const Keyframes<glm::dquat>& keys, double seconds);

// An object placed by a node of a moving hierarchy. Its mesh is in the file's root space at rest
// (as mesh_io gathers it), so at a frame its transform is placement * world_at(node) *
// inverse(world at rest): the node's motion since rest, then the scene's placement of the file.
struct NodeBinding {
  std::shared_ptr<const NodeHierarchy> hierarchy;  // null: the object is not bound
  int node = -1;
  int clip = 0;
  double frames_per_second = kDefaultFramesPerSecond;
  glm::dmat4 placement{1.0};  // the file's root space -> world
  glm::dmat4 from_rest{1.0};  // inverse of the node's world transform at rest
  int frame = 0;              // the frame the object stands at (scene_at_frame moves it on)

  bool bound() const { return hierarchy != nullptr; }
  // Seconds into the clip at `frame`: frame / frames_per_second, repeating after its duration.
  double seconds_at(int frame) const;
  glm::mat4 transform_at(int frame) const;
};

}  // namespace shadowvol
