#include "io/source_commit.hpp"

#include "mpile_source_commit.hpp" // generated at build time

namespace mpile {

const char* source_commit() {
  return MPILE_SOURCE_COMMIT;
}

} // namespace mpile
