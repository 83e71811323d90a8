#pragma once
// The state of the Newmark–contact scheme and its flat serialization (FMU states).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace plate {

// The full mutable state of the scheme: two time levels plus the bookkeeping that makes the
// energy ledger and the warm start exact. Saving and restoring it continues bit-identically.
struct NewmarkState {
    Eigen::VectorXd w, wPrev, wPrev2;  // w_n, w_{n−1}, w_{n−2} (the last: the port's level, §14)
    Eigen::VectorXd kw, kwPrev;  // K w_n, K w_{n−1} (reused by the next step and the energy)
    double z = 0, zPrev = 0, zPrev2 = 0;  // base z_n, z_{n−1}, z_{n−2}
    double p = 0, pPrev = 0, pPrev2 = 0;  // pressure p_n, p_{n−1}, p_{n−2}
    double pressureWork = 0, pressureWorkPrev = 0;  // Fᵀw_n, Fᵀw_{n−1} (work of the pressure)
    double baseCoupling = 0, baseCouplingPrev = 0, baseCouplingPrev2 = 0;  // (M·1)ᵀw: base–plate inertia
    long long step = 0;
    double energyInput = 0, energyDissipated = 0;
    double energyDamped = 0;  // cumulative work of the Rayleigh damping (docs/theory.md §13)
    double maxKktResidual = 0;
    long long qpIterationsTotal = 0;
    int qpIterationsMax = 0, qpIterationsLast = 0;
    int contactVertices = 0;
    std::vector<signed char> contactState;  // −1 on lower, +1 on upper, 0 free (warm start)
    // Singular mass only (empty otherwise): the contact impulses μ_n, μ_{n−1} of the last two
    // steps, which keep the massless part in equilibrium (docs/theory.md §11).
    Eigen::VectorXd contactImpulse, contactImpulsePrev;
    // The port (docs/theory.md §14), per obstacle (0 lower, 1 upper): the contact force of the
    // last step (the whole impulse τ/Δt² of the step's equation, N), its moment about the clamp
    // line (both obstacles, N·m), the cumulative impulse (N·s) and the contact onsets so far.
    double stepContactForce[2] = {0, 0}, stepContactMoment = 0;
    double contactImpulseSum[2] = {0, 0};
    long long impactCount[2] = {0, 0};
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
