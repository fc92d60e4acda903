#include "engine/materials/material_registry.hpp"

#include "engine/materials/hardening_soil.hpp"
#include "engine/materials/hypoplastic.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/materials/mohr_coulomb.hpp"
#include "engine/materials/undrained_soil.hpp"

#include <span>
#include <stdexcept>

namespace mpile {

namespace {

/// A model whose parameters are declared once as fields (key, member, optional, unit, range,
/// meaning) as a material type: its keys from the declaration, and its constructor fed from them.
template <class Model, class Parameters, class Field>
MaterialType declared_type(std::string name, std::string description,
                           std::span<const Field> fields) {
  MaterialType type{std::move(name), std::move(description), {}, {}};
  const Parameters defaults;
  std::vector<std::pair<std::string, double Parameters::*>> members;
  for (const Field& f : fields) {
    type.parameters.push_back(
        {f.name, f.unit, f.meaning,
         f.optional ? std::optional<double>(defaults.*f.member) : std::nullopt, f.range});
    members.emplace_back(f.name, f.member);
  }
  type.create = [members](const MaterialParameters& p) -> std::unique_ptr<Material> {
    Parameters h;
    for (const auto& [key, member] : members) {
      h.*member = p.at(key);
    }
    return std::make_unique<Model>(h);
  };
  return type;
}

/// Hardening Soil as a material type, from its parameters' declaration (hardening_soil.cpp).
MaterialType hardening_soil_type() {
  return declared_type<HardeningSoil, HardeningSoilParameters>(
      "hardening_soil",
      "Hardening Soil (Schanz et al. 1999, PLAXIS form): stress-dependent stiffness, shear "
      "hardening with Mohr-Coulomb failure, cap from k0_nc and eoed_ref",
      hardening_soil_fields());
}

/// Hypoplasticity with intergranular strain, from its parameters' declaration (hypoplastic.cpp).
MaterialType hypoplastic_type() {
  return declared_type<Hypoplastic, HypoplasticParameters>(
      "hypoplastic",
      "hypoplasticity (von Wolffersdorff 1996) with Bauer's limit void ratios and the "
      "intergranular strain of Niemunis and Herle (1997): the void ratio as state, cyclic "
      "accumulation of strain and pore pressure",
      hypoplastic_fields());
}

} // namespace

const std::vector<MaterialType>& material_types() {
  static const std::vector<MaterialType> types = {
      {"linear_elastic",
       "isotropic linear elasticity",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt, young_modulus_range},
        {"poisson_ratio", "-", "Poisson's ratio nu", std::nullopt, poisson_ratio_range},
        {"density", "kg/m^3", "initial density", std::nullopt, density_range}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<LinearElastic>(p.at("young_modulus"), p.at("poisson_ratio"),
                                                p.at("density"));
       }},
      {"mohr_coulomb",
       "elastic-perfectly plastic Mohr-Coulomb with a tension cut-off, non-associated flow",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt, young_modulus_range},
        {"poisson_ratio", "-", "Poisson's ratio nu", std::nullopt, poisson_ratio_range},
        {"density", "kg/m^3", "initial density", std::nullopt, density_range},
        {"cohesion", "Pa", "cohesion c", std::nullopt, cohesion_range},
        {"friction_angle", "degrees", "friction angle phi", std::nullopt,
         mohr_coulomb_friction_range},
        {"dilatancy_angle", "degrees", "dilatancy angle psi, at most phi", 0.0, at_least(0.0)},
        {"tension_limit", "Pa", "tension cut-off, capped at c cot(phi)", 0.0, tension_limit_range}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<MohrCoulomb>(
             p.at("young_modulus"), p.at("poisson_ratio"), p.at("density"), p.at("cohesion"),
             p.at("friction_angle"), p.at("dilatancy_angle"), p.at("tension_limit"));
       }},
      hardening_soil_type(),
      hypoplastic_type(),
  };
  return types;
}

std::unique_ptr<Material> create_material(std::string_view type, MaterialParameters values,
                                          const PoreWater& water) {
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
    const double x = values.at(spec.name);
    if (!spec.range.contains(x)) {
      throw std::invalid_argument(found->name + ": " + spec.name + " " + spec.range.requirement() +
                                  (spec.unit == "-" ? "" : " " + spec.unit) + ", got " +
                                  format_bound(x));
    }
  }
  try {
    std::unique_ptr<Material> skeleton = found->create(values);
    if (water.drainage == Drainage::drained) {
      return skeleton;
    }
    return std::make_unique<UndrainedSoil>(std::move(skeleton), water);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(found->name + ": " + e.what());
  }
}

} // namespace mpile
