#include "engine/scene.hpp"

#include <stdexcept>

namespace mpile {

std::uint16_t Scene::add_material(std::unique_ptr<Material> material) {
  if (!particles.r.empty() && static_cast<int>(material->state_size()) > particles.state_stride) {
    throw std::logic_error("materials with state must be added before particles");
  }
  particles.state_stride =
      std::max(particles.state_stride, static_cast<int>(material->state_size()));
  materials.push_back(std::move(material));
  return static_cast<std::uint16_t>(materials.size() - 1);
}

std::uint16_t Scene::add_body(std::string name) {
  body_names.push_back(std::move(name));
  return static_cast<std::uint16_t>(body_names.size() - 1);
}

} // namespace mpile
