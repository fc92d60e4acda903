#include "io/output_directory.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace mpile {

OutputLock::OutputLock(const std::string& directory) {
  const std::string path = directory + "/.mpile.lock";
  descriptor_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0) {
    throw std::runtime_error("cannot make the lock file " + path + ": " + std::strerror(errno));
  }
  if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    ::close(descriptor_);
    descriptor_ = -1;
    if (reason == EWOULDBLOCK) {
      throw OutputBusy("another run is writing to " + directory + " (it holds " + path +
                       "); give this run another output directory (--out)");
    }
    throw std::runtime_error("cannot lock " + path + ": " + std::strerror(reason));
  }
}

OutputLock::~OutputLock() {
  if (descriptor_ >= 0) {
    ::close(descriptor_); // releases the lock
  }
}

namespace {

/// The file names a ParaView collection lists (its DataSet elements' file attributes). A plain
/// search, not a regular expression: libstdc++'s matcher recurses once per character and a
/// foreign index with a 30 000-character name overflowed the stack.
std::vector<std::string> listed_files(const std::filesystem::path& collection) {
  std::ifstream in(collection);
  std::stringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  const std::string attribute = "file=\"";
  std::vector<std::string> files;
  for (std::size_t at = content.find(attribute); at != std::string::npos;
       at = content.find(attribute, at)) {
    at += attribute.size();
    const std::size_t end = content.find('"', at);
    if (end == std::string::npos) {
      break;
    }
    if (end > at) {
      files.push_back(content.substr(at, end - at));
    }
    at = end + 1;
  }
  return files;
}

void remove_file(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::remove(path, error);
  if (error) {
    throw std::runtime_error("cannot remove the earlier run's " + path.string() + ": " +
                             error.message());
  }
}

} // namespace

void remove_earlier_outputs(const std::string& directory) {
  const std::filesystem::path dir(directory);
  for (const char* index : {"particles.pvd", "grid.pvd"}) {
    const auto collection = dir / index;
    if (!std::filesystem::is_regular_file(collection)) {
      continue;
    }
    for (const std::string& name : listed_files(collection)) {
      // Only a plain name in this directory: an index edited to point elsewhere deletes nothing
      // outside it, and a name longer than a file name can be is none this program wrote.
      const std::filesystem::path file(name);
      if (file.has_parent_path() || name == "." || name == ".." || name.size() > 255) {
        continue;
      }
      std::error_code error;
      if (std::filesystem::is_regular_file(dir / file, error)) {
        remove_file(dir / file);
      }
    }
    remove_file(collection);
  }
  for (const char* name : {"history.h5", "checkpoint.h5", "run.log"}) {
    if (std::filesystem::is_regular_file(dir / name)) {
      remove_file(dir / name);
    }
  }
}

} // namespace mpile
