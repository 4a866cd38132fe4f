#include "input_file.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace shadowvol {

namespace fs = std::filesystem;

Expected<void> check_input_file(const fs::path& path, std::string_view kind) {
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    if (ec == std::errc::too_many_symbolic_link_levels)
      return make_error(name +
                        ": too many levels of symbolic links (a link that leads to itself?)");
    if (ec == std::errc::filename_too_long)
      return make_error(name + ": the path is too long for the system (" +
                        std::to_string(name.size()) + " characters)");
    return make_error(name + ": cannot be looked at (" + ec.message() + ")");
  }
  if (!fs::exists(status)) return make_error(name + ": no such file");
  if (fs::is_directory(status))
    return make_error(name + ": is a folder, not a " + std::string(kind));
  if (!fs::is_regular_file(status))
    return make_error(name + ": is not a regular file (a device or a pipe), not a " +
                      std::string(kind));
  if (::access(path.c_str(), R_OK) != 0)
    return make_error(name + ": cannot be opened for reading (" + std::strerror(errno) + ")");
  return {};
}

bool names_a_path(const fs::path& name) {
  if (name.has_parent_path() || name.has_extension()) return true;
  std::error_code ec;
  (void)fs::symlink_status(name, ec);
  return !ec || ec != std::errc::no_such_file_or_directory;
}

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace shadowvol
