// Builds the volume of a procedural torus through the installed headers and libraries.
#include <cstdio>
#include <vector>

#include <core/topology.h>
#include <core/volume.h>
#include <render/volume_builder.h>
#include <scene/shapes.h>

int main() {
  using namespace shadowvol;
  const Topology topo = build_topology(make_bumpy_torus(64, 32));
  VolumeBuffer volume;
  VolumeBuilder builder;
  const VolumeJob job{&topo, {0.5f, 0.2f, 3.0f, 1.0f}, {}, &volume};
  builder.build({&job, 1});
  std::printf("sides %zu light caps %zu dark caps %zu\n", volume.sides.size(),
              volume.light_caps.size(), volume.dark_caps.size());
  return volume.sides.size() > 0 ? 0 : 1;
}
