// Node hierarchies that move: keys interpolated as glTF asks, transforms composed through the
// ancestors, clips repeating; values by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "scene/node_animation.h"

namespace shadowvol {
namespace {

glm::dquat y_turn(double degrees) {
  return glm::angleAxis(glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
}
// The angle about y by which a unit quaternion turns +x (to (cos a, 0, -sin a)).
double y_degrees(const glm::dquat& q) {
  const glm::dvec3 x = q * glm::dvec3(1.0, 0.0, 0.0);
  return glm::degrees(std::atan2(-x.z, x.x));
}

TEST(Keyframes, TranslationsAreLinearAndHeldBeyondTheKeys) {
  const Keyframes<glm::dvec3> keys{{1.0, 2.0, 4.0}, {{0, 0, 0}, {2, 0, 0}, {2, 4, 0}}};
  EXPECT_EQ(sample(keys, 0.0), glm::dvec3(0, 0, 0));  // before the first key: the first
  EXPECT_EQ(sample(keys, 1.5), glm::dvec3(1, 0, 0));
  EXPECT_EQ(sample(keys, 3.0), glm::dvec3(2, 2, 0));
  EXPECT_EQ(sample(keys, 4.0), glm::dvec3(2, 4, 0));
  EXPECT_EQ(sample(keys, 9.0), glm::dvec3(2, 4, 0));  // after the last: the last
  const Keyframes<glm::dvec3> one{{0.5}, {{7, 8, 9}}};
  EXPECT_EQ(sample(one, 0.0), glm::dvec3(7, 8, 9));
  EXPECT_EQ(sample(one, 3.0), glm::dvec3(7, 8, 9));
}

TEST(Keyframes, RotationsAreSphericalTheShorterWayRound) {
  const Keyframes<glm::dquat> keys{{0.0, 1.0}, {y_turn(0), y_turn(90)}};
  EXPECT_NEAR(y_degrees(sample(keys, 0.5)), 45.0, 1e-9);
  EXPECT_NEAR(y_degrees(sample(keys, 0.25)), 22.5, 1e-9);  // even in angle, not in chord
  // 350 degrees is -10: halfway from 0 is -5, not 175; and a key given as -q is the same turn.
  for (const glm::dquat& end : {y_turn(350), -y_turn(350)}) {
    const Keyframes<glm::dquat> wrap{{0.0, 1.0}, {y_turn(0), end}};
    EXPECT_NEAR(y_degrees(sample(wrap, 0.5)), -5.0, 1e-9);
    EXPECT_NEAR(glm::length(sample(wrap, 0.3)), 1.0, 1e-12);
  }
}

// A root turning a quarter about y in 1 s, a child 2 along x scaling from 1 to 3, and a still
// sibling.
std::shared_ptr<NodeHierarchy> two_level() {
  auto h = std::make_shared<NodeHierarchy>();
  const glm::dquat none(1.0, 0.0, 0.0, 0.0);
  const glm::dvec3 unit(1.0);
  h->nodes.push_back({"root", -1, glm::dmat4(1.0), glm::dvec3(0.0), none, unit});
  const glm::dmat4 two_along_x = glm::translate(glm::dmat4(1.0), glm::dvec3(2, 0, 0));
  h->nodes.push_back({"child", 0, two_along_x, {2, 0, 0}, none, unit});
  h->nodes.push_back({"still", -1, two_along_x, {2, 0, 0}, none, unit});
  Clip clip{"turn", 1.0, {}};
  NodeChannels root{0, {}, {{0.0, 1.0}, {y_turn(0), y_turn(90)}}, {}};
  NodeChannels child{1, {}, {}, {{0.0, 1.0}, {{1, 1, 1}, {3, 3, 3}}}};
  clip.channels = {root, child};
  h->clips.push_back(clip);
  return h;
}

TEST(NodeHierarchy, ChildrenMoveWithTheirParents) {
  const auto h = two_level();
  EXPECT_TRUE(h->moves(1, 0));  // by its parent and by itself
  EXPECT_FALSE(h->moves(2, 0));
  EXPECT_FALSE(h->moves(1, -1));  // at rest, nothing moves
  // At 1 s the child stands at (0, 0, -2), three times its size: its +x axis is 3 along -z.
  const glm::dmat4 w = h->world_at(1, 0, 1.0);
  const glm::dvec4 origin = w * glm::dvec4(0, 0, 0, 1);
  const glm::dvec4 x_axis = w * glm::dvec4(1, 0, 0, 0);
  EXPECT_NEAR(origin.x, 0.0, 1e-12);
  EXPECT_NEAR(origin.z, -2.0, 1e-12);
  EXPECT_NEAR(x_axis.z, -3.0, 1e-12);
  // The translation the clip leaves is the rest's; a node the clip leaves is exactly its rest.
  EXPECT_EQ(h->local_at(1, 0, 0.5)[3], glm::dvec4(2, 0, 0, 1));
  EXPECT_EQ(h->world_at(2, 0, 0.7), h->nodes[2].rest);
  EXPECT_EQ(h->world_at(1, -1, 0.7), h->nodes[1].rest);
}

TEST(NodeBinding, FramesAreSecondsAtItsPaceRepeatingTheClip) {
  NodeBinding b{two_level(), 1, 0, 30.0, glm::dmat4(1.0), glm::dmat4(1.0), 0};
  EXPECT_DOUBLE_EQ(b.seconds_at(15), 0.5);
  EXPECT_DOUBLE_EQ(b.seconds_at(30), 0.0);  // the clip's 1 s, begun again
  EXPECT_DOUBLE_EQ(b.seconds_at(45), 0.5);
  b.frames_per_second = 60.0;
  EXPECT_DOUBLE_EQ(b.seconds_at(15), 0.25);
  // The object's mesh at rest is where the node's rest puts it: from_rest undoes that, the
  // node's motion and the placement follow.
  b.from_rest = glm::inverse(b.hierarchy->world_at(1, -1, 0.0));
  b.placement = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 10, 0));
  const glm::vec4 rest_point(2.0f, 0.0f, 0.0f, 1.0f);  // the child's origin, at rest
  EXPECT_EQ(b.transform_at(0) * rest_point, glm::vec4(2, 10, 0, 1));
  const glm::vec4 at_half = b.transform_at(30) * rest_point;  // 0.5 s: 45 degrees
  EXPECT_NEAR(at_half.x, 2.0 * std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(at_half.y, 10.0, 1e-6);
  EXPECT_NEAR(at_half.z, -2.0 * std::sqrt(0.5), 1e-6);
}

}  // namespace
}  // namespace shadowvol
