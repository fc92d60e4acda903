#pragma once

#include "engine/materials/material.hpp"
#include "engine/materials/pore_water.hpp"
#include "engine/parameter_range.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpile {

using MaterialParameters = std::map<std::string, double, std::less<>>;

struct MaterialParameterSpec {
  std::string name;
  std::string unit;
  std::string meaning;
  std::optional<double> default_value; // empty: required
  ParameterRange range;                // the values the model accepts on their own
};

/// A material type as the case layer sees it: its name, its parameters, and how to build it.
struct MaterialType {
  std::string name;
  std::string description;
  std::vector<MaterialParameterSpec> parameters;
  std::function<std::unique_ptr<Material>(const MaterialParameters&)> create;
};

/// Every registered material type. A new model registers itself in material_registry.cpp.
const std::vector<MaterialType>& material_types();

/// Builds a material by type name, with its pore water drained (no water state, the model as it
/// is) or undrained (UndrainedSoil over the model). Unknown types, unknown or missing parameters
/// and invalid values throw std::invalid_argument naming the type, the parameter and what is wrong.
std::unique_ptr<Material> create_material(std::string_view type, MaterialParameters values,
                                          const PoreWater& water = {});

} // namespace mpile
