#pragma once

#include <string>

namespace mpile {

/// Moves a finished temporary file over `path` in one step (readers see the old file or the new
/// one, never half of one). A failure is a std::runtime_error that names the file and gives the
/// system's reason ("cannot write out/particles.pvd: Is a directory").
void replace_file(const std::string& temporary, const std::string& path);

} // namespace mpile
