#include "io/reserve_space.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mpile {

void reserve_space(const std::string& path, std::uintmax_t bytes) {
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (descriptor < 0) {
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  struct stat status {};
  int error = ::fstat(descriptor, &status) == 0 ? 0 : errno;
  if (error == 0 && bytes > 0) {
    // posix_fallocate returns the reason rather than setting errno.
    error = ::posix_fallocate(descriptor, status.st_size, static_cast<off_t>(bytes));
  }
  ::close(descriptor);
  if (error != 0) {
    throw NoRoomForOutput("cannot write " + path + ": " + std::strerror(error));
  }
}

} // namespace mpile
