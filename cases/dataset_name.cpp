#include "cases/dataset_name.hpp"

#include <cctype>

namespace mpile {

std::string dataset_name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    out += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
  }
  return out;
}

std::optional<std::string> GroupNames::clash(const std::string& name, const std::string& where) {
  const std::string group = dataset_name(name);
  const auto [found, inserted] = taken_.emplace(group, Earlier{name, where});
  if (inserted) {
    return std::nullopt;
  }
  const Earlier& earlier = found->second;
  return "'" + name + "' and '" + earlier.name + "' (" + earlier.where + ") are both written to " +
         parent_ + "/" + group + " in the history: give this one another name";
}

} // namespace mpile
