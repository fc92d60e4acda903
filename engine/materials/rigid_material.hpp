#pragma once

#include "engine/materials/material.hpp"

namespace mpile {

/// The material of a rigid body's particles: they carry no stress and do not limit the time step
/// (constrained modulus 0); only their density counts, for the body's mass when the case does not
/// give it.
class RigidMaterial final : public Material {
public:
  explicit RigidMaterial(double density) : density_(density) {}

  std::string_view type() const override { return "rigid"; }
  double density() const override { return density_; }
  bool is_rigid() const override { return true; }
  void update_stress(const StressUpdateBatch& batch) const override {
    for (double& modulus : batch.constrained_modulus) {
      modulus = 0.0;
    }
  }
  double constrained_modulus(const Stress&, const double*) const override { return 0.0; }
  double shear_modulus(const Stress&, const double*) const override { return 0.0; }
  double elastic_energy_density(const Stress&, const double*) const override { return 0.0; }

private:
  double density_;
};

} // namespace mpile
