#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace mpile {

/// A file the disk has no room for: an output error, never a sign that the input is wrong.
class NoRoomForOutput : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Allocates `bytes` on the disk past the end of the file at `path`, so that what is written there
/// next cannot fail for want of space. HDF5 cuts a file back to what it holds when it closes it,
/// and a reader ignores bytes past that. A full file system or a file-size limit (ulimit -f) is a
/// NoRoomForOutput naming the file, with the system's reason, before anything of the file has
/// changed: HDF5 left a file it had half extended unreadable.
void reserve_space(const std::string& path, std::uintmax_t bytes);

} // namespace mpile
