#pragma once

#include <cstdint>
#include <string>

namespace mpile {

/// Allocates `bytes` on the disk past the end of the file at `path`, so that what is written there
/// next cannot fail for want of space. HDF5 cuts a file back to what it holds when it closes it,
/// and a reader ignores bytes past that. A full file system or a file-size limit (ulimit -f) is a
/// std::runtime_error naming the file, with the system's reason, before anything of the file has
/// changed: HDF5 left a file it had half extended unreadable.
void reserve_space(const std::string& path, std::uintmax_t bytes);

} // namespace mpile
