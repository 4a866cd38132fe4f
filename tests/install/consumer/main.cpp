// Uses the installed headers and libraries the way README.md shows: a frame of a mesh file on its
// default stage; then the mesh's topology, one volume on the calling thread and one through the
// threaded builder.
#include <cstdio>
#include <iostream>

#include <backend/backend.h>
#include <core/topology.h>
#include <core/volume.h>
#include <render/volume_builder.h>
#include <scene/mesh_io.h>
#include <scene/scene_io.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  auto scene = shadowvol::load_scene(argv[1]);
  if (!scene) {
    std::cerr << scene.error().message;
    return 1;
  }
  const shadowvol::RenderOptions options{64, 36, shadowvol::Method::automatic};
  if (auto ok = shadowvol::check_frame(scene->scene, options); !ok) return 1;
  auto made = shadowvol::make_renderer(shadowvol::Backend::soft, {}, options);
  if (!made) return 1;
  shadowvol::Frame frame;
  made->renderer->render(scene->scene, options, frame);
  if (frame.image.rgba.size() != 64u * 36u * 4u ||
      frame.shadowed.size() != scene->scene.lights.size())
    return 1;

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
