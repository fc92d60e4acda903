#pragma once

namespace mpile {

/// The commit this program was built from: git's short id, "-dirty" when files outside docs/
/// differed from it, "unknown" when built outside a git checkout. history.h5 records it, so that a
/// table of results can name the commit of the runs it comes from.
const char* source_commit();

} // namespace mpile
