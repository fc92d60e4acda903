#include "io/replace_file.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace mpile {

void replace_file(const std::string& temporary, const std::string& path) {
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + path + ": " + error.message());
  }
}

} // namespace mpile
