// shadowvol scene: a mesh file's header checked against the file's size, before a reader
// allocates what the header declares.
//
// Owns: PLY (ASCII and binary) and OFF headers. Both declare their element counts up front, and
// readers allocate them before reading a byte of data: a header of a few bytes that declares 10^9
// faces takes gigabytes and minutes before anything fails. Every element needs some least number
// of bytes (binary: its fixed-size properties and list counts; ASCII: a character and a separator
// per value), so a header that declares more than the rest of the file can hold is refused at
// once, whatever memory the machine has. Other formats pass unchecked.
#pragma once

#include <cstdint>
#include <filesystem>

#include "core/expected.h"

namespace shadowvol {

// `file_size`: the file's size in bytes. Reads at most the header; an unreadable or unrecognised
// header passes (the reader says what is wrong with it). A PLY header without its end_header line
// is refused too: assimp's reader would search for it forever.
Expected<void> check_declared_size(const std::filesystem::path& path, std::uintmax_t file_size);

}  // namespace shadowvol
