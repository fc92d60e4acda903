#include "engine/materials/material_registry.hpp"

#include "engine/materials/hardening_soil.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/materials/mohr_coulomb.hpp"
#include "engine/materials/undrained_soil.hpp"

#include <stdexcept>

namespace mpile {

namespace {

ParameterRange above(double x) {
  return {Bound{x, false}, std::nullopt};
}
ParameterRange at_least(double x) {
  return {Bound{x, true}, std::nullopt};
}
ParameterRange between(double low, bool low_inclusive, double high, bool high_inclusive) {
  return {Bound{low, low_inclusive}, Bound{high, high_inclusive}};
}

/// Hardening Soil's parameters, each declared once: its name, its member of
/// HardeningSoilParameters (whose initialiser is the default of an optional one), unit, range and
/// meaning. The cap's alpha and H are derived, never given (docs/hardening-soil.md).
MaterialType hardening_soil_type() {
  struct Field {
    const char* name;
    double HardeningSoilParameters::*member;
    bool optional;
    const char* unit;
    ParameterRange range;
    const char* meaning;
  };
  const Field fields[] = {
      {"e50_ref", &HardeningSoilParameters::e50_ref, false, "Pa", above(0.0),
       "triaxial secant stiffness E50 at p_ref"},
      {"eoed_ref", &HardeningSoilParameters::eoed_ref, false, "Pa", above(0.0),
       "oedometer tangent stiffness at sigma_1 = p_ref"},
      {"eur_ref", &HardeningSoilParameters::eur_ref, false, "Pa", above(0.0),
       "unloading/reloading stiffness at p_ref, above 2 E50 / (2 - Rf)"},
      {"power", &HardeningSoilParameters::power, false, "-", between(0.0, true, 1.0, false),
       "m, the stress dependency of stiffness"},
      {"poisson_ur", &HardeningSoilParameters::poisson_ur, true, "-",
       between(-1.0, false, 0.5, false), "unloading/reloading Poisson ratio"},
      {"k0_nc", &HardeningSoilParameters::k0_nc, false, "-", between(0.0, false, 1.0, false),
       "K0 of normally consolidated soil"},
      {"failure_ratio", &HardeningSoilParameters::failure_ratio, true, "-",
       between(1e-3, true, 1.0, false), "Rf = qf / qa"},
      {"p_ref", &HardeningSoilParameters::p_ref, true, "Pa", above(0.0),
       "reference stress of the stiffness laws"},
      {"friction_angle", &HardeningSoilParameters::friction_angle, false, "degrees",
       between(0.0, false, 90.0, false), "friction angle phi"},
      {"dilatancy_angle", &HardeningSoilParameters::dilatancy_angle, true, "degrees", at_least(0.0),
       "ultimate dilatancy angle psi, at most phi"},
      {"cohesion", &HardeningSoilParameters::cohesion, true, "Pa", at_least(0.0), "cohesion c"},
      {"tension_limit", &HardeningSoilParameters::tension_limit, true, "Pa", at_least(0.0),
       "tension cut-off"},
      {"stiffness_floor", &HardeningSoilParameters::stiffness_floor, true, "-",
       between(0.0, false, 1.0, true), "lower bound of the stress ratio in the stiffness laws"},
      {"cap_floor", &HardeningSoilParameters::cap_floor, true, "Pa", above(0.0),
       "lower bound of the cap pressure p_p"},
      {"ocr", &HardeningSoilParameters::ocr, true, "-", at_least(1.0),
       "over-consolidation ratio of the initial state"},
      {"pop", &HardeningSoilParameters::pop, true, "Pa", at_least(0.0),
       "pre-overburden pressure of the initial state"},
      {"density", &HardeningSoilParameters::density, false, "kg/m^3", above(0.0),
       "initial density"},
  };
  MaterialType type{"hardening_soil",
                    "Hardening Soil (Schanz et al. 1999, PLAXIS form): stress-dependent "
                    "stiffness, shear hardening with Mohr-Coulomb failure, cap from k0_nc and "
                    "eoed_ref",
                    {},
                    {}};
  const HardeningSoilParameters defaults;
  std::vector<std::pair<std::string, double HardeningSoilParameters::*>> members;
  for (const Field& f : fields) {
    type.parameters.push_back(
        {f.name, f.unit, f.meaning,
         f.optional ? std::optional<double>(defaults.*f.member) : std::nullopt, f.range});
    members.emplace_back(f.name, f.member);
  }
  type.create = [members](const MaterialParameters& p) -> std::unique_ptr<Material> {
    HardeningSoilParameters h;
    for (const auto& [name, member] : members) {
      h.*member = p.at(name);
    }
    return std::make_unique<HardeningSoil>(h);
  };
  return type;
}

} // namespace

const std::vector<MaterialType>& material_types() {
  static const std::vector<MaterialType> types = {
      {"linear_elastic",
       "isotropic linear elasticity",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt, above(0.0)},
        {"poisson_ratio", "-", "Poisson's ratio nu", std::nullopt,
         between(-1.0, false, 0.5, false)},
        {"density", "kg/m^3", "initial density", std::nullopt, above(0.0)}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<LinearElastic>(p.at("young_modulus"), p.at("poisson_ratio"),
                                                p.at("density"));
       }},
      {"mohr_coulomb",
       "elastic-perfectly plastic Mohr-Coulomb with a tension cut-off, non-associated flow",
       {{"young_modulus", "Pa", "Young's modulus E", std::nullopt, above(0.0)},
        {"poisson_ratio", "-", "Poisson's ratio nu", std::nullopt,
         between(-1.0, false, 0.5, false)},
        {"density", "kg/m^3", "initial density", std::nullopt, above(0.0)},
        {"cohesion", "Pa", "cohesion c", std::nullopt, at_least(0.0)},
        {"friction_angle", "degrees", "friction angle phi", std::nullopt,
         between(0.0, true, 90.0, false)},
        {"dilatancy_angle", "degrees", "dilatancy angle psi, at most phi", 0.0, at_least(0.0)},
        {"tension_limit", "Pa", "tension cut-off, capped at c cot(phi)", 0.0, at_least(0.0)}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         return std::make_unique<MohrCoulomb>(
             p.at("young_modulus"), p.at("poisson_ratio"), p.at("density"), p.at("cohesion"),
             p.at("friction_angle"), p.at("dilatancy_angle"), p.at("tension_limit"));
       }},
      hardening_soil_type(),
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
