#pragma once
// The state of the Newmark–contact scheme and its flat serialization (FMU states).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "schemes/Scheme.h"

namespace plate {

// The full mutable state of the scheme: the base's share (SchemeState: the inputs' levels, the
// ledger, the port's sums) and the plate's levels with what makes the ledger and the warm start
// exact. Saving and restoring it continues bit-identically.
struct NewmarkState : SchemeState {
    Eigen::VectorXd w, wPrev, wPrev2;  // w_n, w_{n−1}, w_{n−2} (the last: the port's level, §14)
    Eigen::VectorXd kw, kwPrev;  // K w_n, K w_{n−1} (reused by the next step and the energy)
    double pressureWork = 0, pressureWorkPrev = 0;  // Fᵀw_n, Fᵀw_{n−1} (work of the pressure)
    double baseCoupling = 0, baseCouplingPrev = 0, baseCouplingPrev2 = 0;  // (M·1)ᵀw: base–plate inertia
    std::vector<signed char> contactState;  // −1 on lower, +1 on upper, 0 free (warm start)
    // Singular mass only (empty otherwise): the contact impulses μ_n, μ_{n−1} of the last two
    // steps, which keep the massless part in equilibrium (docs/theory.md §11).
    Eigen::VectorXd contactImpulse, contactImpulsePrev;
};

// Flat form (base/StateArchive.h): format version, sizes, then the members in the order of their one
// description (NewmarkState.cpp, members): the five vectors, the scalars, the contact set, the impulses.
std::vector<double> serialize(const NewmarkState& state);
// Throws std::invalid_argument if the data does not fit a plate with n coordinates, m contact
// vertices and `impulses` stored impulses per level (0, or m with a singular mass), or is corrupt
// (non-finite displacements, an impossible contact state).
NewmarkState deserialize(const std::vector<double>& data, Eigen::Index n, std::size_t m, std::size_t impulses);
// Where each member starts after the 4-value header (the tests that damage a state on purpose).
std::vector<std::pair<std::string, std::size_t>> stateLayout(Eigen::Index n, std::size_t m, std::size_t impulses);

}  // namespace plate
