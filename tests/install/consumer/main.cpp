// Uses the installed headers and libraries the way README.md shows: a mesh from a file, its
// topology, one volume on the calling thread and one through the threaded builder.
#include <cstdio>
#include <iostream>

#include <core/topology.h>
#include <core/volume.h>
#include <render/volume_builder.h>
#include <scene/mesh_io.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  auto loaded = shadowvol::load_mesh(argv[1]);  // Expected<>: check, never throws
  if (!loaded) {
    std::cerr << loaded.error().message;
    return 1;
  }
  const shadowvol::Topology topo = shadowvol::build_topology(loaded->mesh);
  shadowvol::VolumeBuffer volume;    // yours, reused every frame
  shadowvol::VolumeScratch scratch;  // yours, reused every frame
  shadowvol::build_volume(topo, {2, 5, 3, 1} /* point light, mesh space */,
                          {shadowvol::Generator::automatic, /*caps=*/true}, scratch, volume);

  shadowvol::VolumeBuffer threaded;
  shadowvol::VolumeBuilder builder;
  const shadowvol::VolumeJob job{&topo, {2, 5, 3, 1}, {}, &threaded};
  builder.build({&job, 1});
  std::printf("sides %zu light caps %zu dark caps %zu\n", volume.sides.size(),
              volume.light_caps.size(), volume.dark_caps.size());
  return volume.sides.size() > 0 && threaded.sides.weights == volume.sides.weights ? 0 : 1;
}
