#include "output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace shadowvol {
namespace {

namespace fs = std::filesystem;

Error cannot_write(const std::string& path, int error) {
  return make_error(path + ": cannot be written (" + std::strerror(error) + ")");
}

// Writes all of `bytes` to `fd`; the errno of the first failure, else 0.
int write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? errno : ENOSPC;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return 0;
}

// Devices and pipes take the bytes as they come: nothing to rename, still every write checked.
Expected<void> write_in_place(const std::string& path, std::string_view bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return cannot_write(path, errno);
  int error = write_all(fd, bytes);
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) return cannot_write(path, error);
  return {};
}

fs::path folder_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// The same file, whether or not it exists yet.
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec) && !ec;
}

}  // namespace

Expected<void> write_file(const std::string& path, std::string_view bytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) return make_error(path + ": is a folder, not a file to write");
  if (fs::exists(status) && !fs::is_regular_file(status)) return write_in_place(path, bytes);
  // A link to a file: replace the file it names, not the link.
  const fs::path target = fs::exists(status) ? fs::canonical(path, ec) : fs::path(path);
  std::string hidden = target.filename().string();  // ".NAME.XXXXXX", beside it
  hidden.insert(hidden.begin(), '.');
  hidden.append(".XXXXXX");
  std::string temporary = folder_of(target) / hidden;
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) return cannot_write(path, errno);
  // mkstemp makes it private; give it what a file created by open() would have had.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  int error = ::fchmod(fd, 0666 & ~mask) == 0 ? 0 : errno;
  if (error == 0) error = write_all(fd, bytes);
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error == 0 && ::rename(temporary.c_str(), target.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temporary.c_str());
    return cannot_write(path, error);
  }
  return {};
}

Expected<void> check_outputs(const std::vector<std::string>& outputs,
                             const std::vector<std::string>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const std::string& path = outputs[i];
    if (path.empty() || path == "-") continue;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_directory(status)) return make_error(path + ": is a folder, not a file to write");
    if (fs::exists(status) && !fs::is_regular_file(status)) {  // a device or a pipe
      if (::access(path.c_str(), W_OK) != 0) return cannot_write(path, errno);
    } else {  // the temporary is made in the folder and renamed there
      const fs::path folder =
          folder_of(fs::exists(status) ? fs::canonical(path, ec) : fs::path(path));
      if (!fs::is_directory(folder, ec))
        return make_error(path + ": cannot be written (no folder " + folder.string() + ")");
      if (::access(folder.c_str(), W_OK) != 0) return cannot_write(path, errno);
    }
    for (const std::string& input : inputs)
      if (!input.empty() && same_file(path, input))
        return make_error(path + ": is the input " + (input == path ? "" : input + " ") +
                          "(read for this run); write the output elsewhere");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].empty() && outputs[j] != "-" && same_file(path, outputs[j]))
        return make_error(path + ": asked for twice" +
                          (outputs[j] == path ? std::string() : " (as " + outputs[j] + ")") +
                          "; give each output its own file");
  }
  return {};
}

}  // namespace shadowvol
