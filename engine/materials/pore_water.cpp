#include "engine/materials/pore_water.hpp"

#include <stdexcept>

namespace mpile {

const std::vector<std::string>& drainage_names() {
  static const std::vector<std::string> names{"drained", "undrained"};
  return names;
}

Drainage drainage_from_name(std::string_view name) {
  const auto& names = drainage_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) {
      return static_cast<Drainage>(i);
    }
  }
  throw std::invalid_argument("unknown drainage '" + std::string(name) + "'");
}

const std::vector<PoreWaterParameter>& pore_water_parameters() {
  // Water is never in tension large enough to matter here, nor lighter than a gas: the ranges
  // refuse only what no pore water is.
  static const std::vector<PoreWaterParameter> parameters{
      {"water_density",
       "kg/m^3",
       "density of the pore water rho_w",
       &PoreWater::density,
       {Bound{0.0, false}, std::nullopt}},
      {"water_bulk_modulus",
       "Pa",
       "bulk modulus K_w of the pore water; a smaller one softens the undrained response "
       "(Skempton's "
       "B below 1), and `mpile check` prints what it implies",
       &PoreWater::bulk_modulus,
       {Bound{0.0, false}, std::nullopt}},
      {"grain_density",
       "kg/m^3",
       "density rho_s of the grains; with the dry density it gives the porosity n = 1 - rho_d / "
       "rho_s",
       &PoreWater::grain_density,
       {Bound{0.0, false}, std::nullopt}},
  };
  return parameters;
}

double porosity(double dry_density, const PoreWater& water) {
  return 1.0 - dry_density / water.grain_density;
}

UndrainedResponse undrained_response(double drained_bulk, double shear, double water_stiffness) {
  const double bulk = drained_bulk + water_stiffness;
  return {bulk, water_stiffness / bulk, (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear))};
}

} // namespace mpile
