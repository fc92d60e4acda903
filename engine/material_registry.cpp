#include "engine/material_registry.hpp"

#include "engine/hardening_soil.hpp"
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
      {"hardening_soil",
       "Hardening Soil (Schanz et al. 1999, PLAXIS form): stress-dependent stiffness, shear "
       "hardening with Mohr-Coulomb failure, cap from k0_nc and eoed_ref",
       {{"e50_ref", "Pa", "triaxial secant stiffness E50 at p_ref", std::nullopt},
        {"eoed_ref", "Pa", "oedometer tangent stiffness at sigma_1 = p_ref", std::nullopt},
        {"eur_ref", "Pa", "unloading/reloading stiffness at p_ref", std::nullopt},
        {"power", "-", "m, the stress dependency of stiffness, in [0, 1)", std::nullopt},
        {"poisson_ur", "-", "unloading/reloading Poisson ratio", 0.2},
        {"k0_nc", "-", "K0 of normally consolidated soil, in (0, 1)", std::nullopt},
        {"failure_ratio", "-", "Rf = qf / qa, in [0.001, 1)", 0.9},
        {"p_ref", "Pa", "reference stress of the stiffness laws", 100e3},
        {"friction_angle", "degrees", "friction angle phi", std::nullopt},
        {"dilatancy_angle", "degrees", "ultimate dilatancy angle psi, in [0, phi]", 0.0},
        {"cohesion", "Pa", "cohesion c", 0.0},
        {"tension_limit", "Pa", "tension cut-off", 0.0},
        {"stiffness_floor", "-", "lower bound of the stress ratio in the stiffness laws", 0.01},
        {"cap_floor", "Pa", "lower bound of the cap pressure p_p", 1e3},
        {"ocr", "-", "over-consolidation ratio of the initial state", 1.0},
        {"pop", "Pa", "pre-overburden pressure of the initial state", 0.0},
        {"density", "kg/m^3", "initial density", std::nullopt}},
       [](const MaterialParameters& p) -> std::unique_ptr<Material> {
         HardeningSoilParameters h;
         h.e50_ref = p.at("e50_ref");
         h.eoed_ref = p.at("eoed_ref");
         h.eur_ref = p.at("eur_ref");
         h.power = p.at("power");
         h.poisson_ur = p.at("poisson_ur");
         h.k0_nc = p.at("k0_nc");
         h.failure_ratio = p.at("failure_ratio");
         h.p_ref = p.at("p_ref");
         h.friction_angle = p.at("friction_angle");
         h.dilatancy_angle = p.at("dilatancy_angle");
         h.cohesion = p.at("cohesion");
         h.tension_limit = p.at("tension_limit");
         h.stiffness_floor = p.at("stiffness_floor");
         h.cap_floor = p.at("cap_floor");
         h.ocr = p.at("ocr");
         h.pop = p.at("pop");
         h.density = p.at("density");
         return std::make_unique<HardeningSoil>(h);
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
