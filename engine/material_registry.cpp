#include "engine/material_registry.hpp"

#include "engine/linear_elastic.hpp"
#include "engine/mohr_coulomb.hpp"

#include <stdexcept>

namespace mpile {

const std::vector<MaterialType>& material_types() {
  static const std::vector<MaterialType> types = {
      {"linear_elastic",
       "isotropic linear elasticity",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt},
        {"poisson_ratio", "-", "Poisson's ratio nu, in (-1, 0.5)", std::nullopt},
        {"density", "kg/m^3", "initial density", std::nullopt}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<LinearElastic>(p.at("young_modulus"), p.at("poisson_ratio"),
                                                p.at("density"));
       }},
      {"mohr_coulomb",
       "elastic-perfectly plastic Mohr-Coulomb with a tension cut-off, non-associated flow",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt},
        {"poisson_ratio", "-", "Poisson's ratio nu, in (-1, 0.5)", std::nullopt},
        {"density", "kg/m^3", "initial density", std::nullopt},
        {"cohesion", "Pa", "cohesion c, >= 0", std::nullopt},
        {"friction_angle", "degrees", "friction angle phi, in [0, 90)", std::nullopt},
        {"dilatancy_angle", "degrees", "dilatancy angle psi, in [0, phi]", 0.0},
        {"tension_limit", "Pa", "tension cut-off, >= 0, capped at c cot(phi)", 0.0}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<MohrCoulomb>(
             p.at("young_modulus"), p.at("poisson_ratio"), p.at("density"), p.at("cohesion"),
             p.at("friction_angle"), p.at("dilatancy_angle"), p.at("tension_limit"));
       }},
  };
  return types;
}

std::unique_ptr<Material> create_material(std::string_view type, MaterialParameters values) {
  const MaterialType* found = nullptr;
  std::string known;
  for (const MaterialType& t : material_types()) {
    known += (known.empty() ? "" : ", ") + t.name;
    if (t.name == type) {
      found = &t;
    }
  }
  if (found == nullptr) {
    throw std::invalid_argument("unknown material type '" + std::string(type) +
                                "' (known: " + known + ")");
  }
  for (const auto& [name, value] : values) {
    bool listed = false;
    for (const MaterialParameterSpec& spec : found->parameters) {
      listed = listed || spec.name == name;
    }
    if (!listed) {
      throw std::invalid_argument(found->name + ": unknown parameter '" + name + "'");
    }
  }
  for (const MaterialParameterSpec& spec : found->parameters) {
    if (values.find(spec.name) == values.end()) {
      if (!spec.default_value) {
        throw std::invalid_argument(found->name + ": missing parameter '" + spec.name + "' (" +
                                    spec.meaning + ", " + spec.unit + ")");
      }
      values.emplace(spec.name, *spec.default_value);
    }
  }
  try {
    return found->create(values);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(found->name + ": " + e.what());
  }
}

} // namespace mpile
