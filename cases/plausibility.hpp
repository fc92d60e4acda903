#pragma once

#include "cases/case_spec.hpp"
#include "engine/scene.hpp"

#include <optional>
#include <string>

namespace mpile {

/// The most steps a run may need at its first stable step: about a day at the engine's speed on
/// a small scene. Past it, the case is almost surely mistyped (a modulus or density off by powers
/// of ten) and would step for ever.
inline constexpr double max_run_steps = 1e9;

/// The largest initial stress a particle may start at: a terapascal, hundreds of times the
/// strongest steel's and past any soil's, yet far below 1e154, past which the models' invariants
/// (squares of stress) overflow.
inline constexpr double max_initial_stress = 1e12;

/// The most snapshots a run may write: each is a file of every particle, and a ParaView series of
/// more is past use; an interval that asks for more is almost surely mistyped (a step for an
/// interval) and would fill the disk.
inline constexpr double max_snapshots = 1e5;

/// Refuses (CaseError) a run that cannot be carried out as written, from its first stable step:
/// more than max_run_steps steps for the phases' durations (at the first stable step, or at a
/// shorter snapshot interval, on whose times steps land), more than max_snapshots snapshots, or
/// one step longer than the whole run (waves that cannot cross a cell in the run). The message
/// names the material, the particle and the cell that set the step, and the keys to check. Needs
/// the particles located in their cells. First refuses, through refuse_inadmissible_states, a start
/// no material admits.
void refuse_implausible_run(const CaseSpec& spec, const Scene& scene, double first_step);

/// A particle whose stress and state its material does not admit: the parameter's location in the
/// case with why ("file:line: materials.sand.void_ratio: ..."), and the particle ("particle 12 of
/// body 'sand' at (r, y) = (...)").
struct InadmissibleParticle {
  std::string key_and_reason;
  std::string particle;
};

/// The first particle of the case's materials (a rigid body's left out) in a state its material
/// does not admit, or at an initial stress past max_initial_stress, if any.
std::optional<InadmissibleParticle> first_inadmissible_particle(const CaseSpec& spec,
                                                                const Scene& scene);

/// Refuses (CaseError) particles whose initial stress and state their material does not admit
/// (a hypoplastic sand looser than its loosest state at its pressure: a void ratio or a stress off
/// by a unit), naming the parameter where it was written, the first such particle and why.
void refuse_inadmissible_states(const CaseSpec& spec, const Scene& scene);

} // namespace mpile
