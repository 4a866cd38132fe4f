// The command line's output files: written whole or not at all, and checked before long work.
//
// A file is written to a temporary beside it, every write and the close checked, then renamed
// over the path, so that a full disk, a quota or a killed run never leaves a truncated picture
// under the name the user asked for. A path that names something other than a regular file (a
// device such as /dev/null or /dev/full, a pipe) is written in place, still checked. Errors name
// the path and the system's reason.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"

namespace shadowvol {

Expected<void> write_file(const std::string& path, std::string_view bytes);

// Before the work that makes them: every output's folder exists and can be written, no output is
// a folder or one of `inputs`, and no two outputs are the same file. Empty paths are skipped;
// "-" (standard output) is always fine.
Expected<void> check_outputs(const std::vector<std::string>& outputs,
                             const std::vector<std::string>& inputs = {});

}  // namespace shadowvol
