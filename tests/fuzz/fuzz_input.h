// What the fuzz targets share: an input written to a file of its own, for the loaders that read
// files (as the tool does), named per process so that parallel jobs do not meet.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace shadowvol::fuzz {

inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size,
                                         const std::string& extension) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("shadowvol_fuzz_" + std::to_string(getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace shadowvol::fuzz
