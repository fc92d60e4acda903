#pragma once

// The names of HDF5 groups in a history: what a body, surface, monitor or boundary condition is
// called there, and the check that two names do not end up as one group.

#include <map>
#include <optional>
#include <string>

namespace mpile {

/// A dataset-safe name: letters, digits and underscores (every other character becomes '_').
std::string dataset_name(const std::string& name);

/// The names given to the groups under one parent (/bodies, /boundaries, a structure's
/// /reactions/<body>): two names that differ but become the same group ("top cap", "top_cap")
/// would write their rows into one.
class GroupNames {
public:
  explicit GroupNames(std::string parent) : parent_(std::move(parent)) {}

  /// Takes `name` (found at `where`, a "file:line" or a description); when an earlier name
  /// becomes the same group, returns a message that names both and the group.
  std::optional<std::string> clash(const std::string& name, const std::string& where);

private:
  struct Earlier {
    std::string name;
    std::string where;
  };
  std::string parent_;
  std::map<std::string, Earlier> taken_; // by dataset name
};

} // namespace mpile
