// libFuzzer target: any bytes as a mesh in memory (a vertex count, positions, then indices), then
// its topology and its shadow volume for a light also taken from the bytes. validate_mesh must
// refuse what the topology builder cannot take; what it accepts must build, with every count the
// report gives consistent, and a volume built with every generator the report allows.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/mesh.h"
#include "core/topology.h"
#include "core/volume.h"

namespace {

template <class T>
bool take(const std::uint8_t*& data, std::size_t& size, T& out) {
  if (size < sizeof(T)) return false;
  std::memcpy(&out, data, sizeof(T));
  data += sizeof(T), size -= sizeof(T);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowvol;
  glm::vec4 light;
  std::uint16_t vertices = 0;
  if (!take(data, size, light) || !take(data, size, vertices)) return 0;
  Mesh mesh;
  for (std::uint16_t v = 0; v < vertices; ++v) {
    glm::vec3 p;
    if (!take(data, size, p)) return 0;
    mesh.positions.push_back(p);
  }
  for (std::uint16_t i; take(data, size, i);) mesh.indices.push_back(i);
  mesh.indices.resize(mesh.indices.size() / 3 * 3);
  if (!validate_mesh(mesh, "fuzz").ok()) return 0;
  const Topology topo = build_topology(mesh);
  const TopologyReport& r = topo.report;
  if (r.triangles != mesh.triangle_count() || r.vertices > mesh.positions.size()) __builtin_trap();
  if (!check_light(light).ok()) return 0;
  for (Generator g : {Generator::standard, Generator::robust, Generator::multiplicity}) {
    if (!check_generator(g, r, "fuzz").ok()) continue;
    VolumeScratch scratch;
    VolumeBuffer volume;
    build_volume(topo, light, VolumeOptions{g}, scratch, volume);
  }
  return 0;
}
