#include "engine/scene.hpp"

#include "engine/materials/rigid_material.hpp"

#include <algorithm>
#include <stdexcept>

namespace mpile {

std::uint16_t Scene::add_material(std::unique_ptr<Material> material, std::string name) {
  if (!particles.r.empty() && static_cast<int>(material->state_size()) > particles.state_stride) {
    throw std::logic_error("materials with state must be added before particles");
  }
  particles.state_stride =
      std::max(particles.state_stride, static_cast<int>(material->state_size()));
  material_names.push_back(name.empty() ? "material " + std::to_string(materials.size())
                                        : std::move(name));
  materials.push_back(std::move(material));
  return static_cast<std::uint16_t>(materials.size() - 1);
}

std::vector<char> Scene::rigid_materials() const {
  std::vector<char> rigid;
  rigid.reserve(materials.size());
  for (const auto& material : materials) {
    rigid.push_back(material->is_rigid() ? 1 : 0);
  }
  return rigid;
}

std::uint16_t Scene::add_body(std::string name) {
  body_names.push_back(std::move(name));
  return static_cast<std::uint16_t>(body_names.size() - 1);
}

ContactPair& Scene::add_contact_structure(std::uint16_t body) {
  if (field_of_body.size() < body_names.size()) {
    field_of_body.resize(body_names.size(), 0);
  }
  if (field_of_body[body] != 0) {
    throw std::logic_error("body " + body_names[body] + " already has a field of its own");
  }
  const int field = grid.add_structure_field();
  if (field > 255) {
    throw std::invalid_argument("too many contact structures");
  }
  field_of_body[body] = static_cast<std::uint8_t>(field);
  ContactPair pair;
  pair.name = body_names[body];
  pair.structure_body = body;
  pair.field = field;
  contacts.push_back(std::move(pair));
  return contacts.back();
}

RigidBody& Scene::make_rigid(std::uint16_t body, double density, double mass, double inertia) {
  ContactPair* pair = nullptr;
  for (ContactPair& c : contacts) {
    if (c.structure_body == body) {
      pair = &c;
    }
  }
  if (pair == nullptr) {
    throw std::logic_error("a rigid body must be a contact structure: " + body_names[body]);
  }
  const std::uint16_t material =
      add_material(std::make_unique<RigidMaterial>(density), body_names[body] + " (rigid)");
  RigidBody rigid;
  rigid.name = body_names[body];
  rigid.body = body;
  rigid.field = pair->field;
  rigid.mode = mode;
  double m = 0.0, mr = 0.0, my = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.body[i] != body) {
      continue;
    }
    particles.material[i] = material;
    particles.mass[i] = density * particles.volume[i];
    m += particles.mass[i];
    mr += particles.mass[i] * particles.r[i];
    my += particles.mass[i] * particles.y[i];
  }
  if (m > 0.0) {
    rigid.centre = {mr / m, my / m};
  }
  double j = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.body[i] == body) {
      const double dr =
          mode == GeometryMode::axisymmetric ? particles.r[i] : particles.r[i] - rigid.centre[0];
      const double dy = mode == GeometryMode::axisymmetric ? 0.0 : particles.y[i] - rigid.centre[1];
      j += particles.mass[i] * (dr * dr + dy * dy);
    }
  }
  rigid.mass = mass > 0.0 ? mass : m;
  rigid.inertia = inertia > 0.0 ? inertia : j;
  pair->rigid_body = static_cast<int>(rigid_bodies.size());
  rigid_bodies.push_back(std::move(rigid));
  return rigid_bodies.back();
}

bool has_coupled_water(const Scene& scene) {
  for (const auto& material : scene.materials) {
    if (material->liquid_phase() != nullptr) {
      return true;
    }
  }
  return false;
}

bool has_pore_water(const Scene& scene) {
  return std::any_of(scene.materials.begin(), scene.materials.end(),
                     [](const auto& material) { return material->pore_pressure_index() >= 0; });
}

} // namespace mpile
