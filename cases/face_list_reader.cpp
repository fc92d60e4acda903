#include "cases/face_list_reader.hpp"

#include <algorithm>
#include <iterator>

namespace mpile {

std::vector<GridFace> read_face_list(TomlTable& table, const std::string& key,
                                     const std::string& axis_refusal) {
  const TomlValue& list = table.raw(key);
  const char* names[] = {"r_min", "r_max", "y_min", "y_max"};
  const std::string expected =
      "must be a list of grid faces, each \"r_min\", \"r_max\", \"y_min\" or \"y_max\" once";
  if (!list.is_array() || list.as_array().empty()) {
    table.fail(key, expected);
  }
  std::vector<GridFace> faces;
  for (const TomlValue& entry : list.as_array()) {
    if (!entry.is_string()) {
      table.fail(key, expected);
    }
    const std::string name = entry.as_string();
    const auto found = std::find(std::begin(names), std::end(names), name);
    if (found == std::end(names)) {
      table.fail(key, expected + ", got \"" + name + "\"");
    }
    const auto face = static_cast<GridFace>(found - std::begin(names));
    if (std::find(faces.begin(), faces.end(), face) != faces.end()) {
      table.fail(key, "lists \"" + name + "\" twice");
    }
    if (face == GridFace::r_min && !axis_refusal.empty()) {
      table.fail(key, "\"r_min\" is the axis here, " + axis_refusal);
    }
    faces.push_back(face);
  }
  return faces;
}

} // namespace mpile
