#pragma once
// The clamp carried by a body inside the plate's step (docs/theory.md §18): an armature (mass,
// suspension spring and damper, a drive force) or the end of a transmission line (no mass, no
// spring, the line's impedance as the damper, the line's incoming wave as the force). The
// carrier's position is the clamp position z, one more unknown of the Newmark step coupled to the
// plate through the rigid column b = (M·1)_free:
//
//   [ A   b ] [ d ]   [ r_w + Cᵀμ ]          d = w⁺ − 2w + w⁻,  e = z⁺ − 2z + z⁻,
//   [ bᵀ  α ] [ e ] = [ r_z + 1ᵀμ ],         α = M_a + m + βΔt²k_a + Δt c_a/2           (T.18)
//
// solved by the Schur complement s = α − bᵀg with the one precomputed g = A⁻¹b: the free step
// costs one dot and one axpy beyond the plate's solve, and the contact columns of the bordered
// matrix are the plate's minus a multiple of g (a rank-one change of W, (T.19)).
#include <Eigen/Core>
#include <iterator>
#include <memory>
#include <vector>

#include "plate/BoxQP.h"
#include "plate/DiscretePlate.h"
#include "base/FieldTable.h"
#include "schemes/NewmarkState.h"

namespace plate {

struct CarrierOptions {
    bool line = false;  // a TLM line end (docs/theory.md §19) instead of an armature
    double mass = 0.0, stiffness = 0.0, damping = 0.0;  // kg, N/m, N·s/m (line: 0, 0, impedance)
    double restPosition = 0.0;  // m, where the suspension spring is relaxed (the clamp at t = 0)
};

// The carrier's part of the state: the drive force history and its energy ledger (cumulative,
// J), and for a line end the wave it launches (docs/theory.md §19).
struct CarrierState {
    double force = 0.0, forcePrev = 0.0;  // drive force at t_n and t_{n−1} (0 for t ≤ 0)
    double driveWork = 0.0;  // Σ F^{nβ}(z⁺ − z⁻)/2
    double damperWork = 0.0;  // Σ c (z⁺ − z⁻)²/(4Δt) ≥ 0
    double portWork = 0.0;  // Σ f_n (z⁺ − z⁻)/2: the plate's work on the carrier (f_n = clamp force)
    double waveSum = 0.0, waveSquares = 0.0;  // Σ a_n Δt, Σ a_n² Δt over the running communication step
    double waveOut = 0.0;  // mean outgoing wave of the last communication step, N
    double transit = 0.0;  // h ā²/(4Z): the energy the line carries to the partner, J
    double lineLoss = 0.0;  // Σ (Σ a_n²Δt − h ā²)/(4Z) ≥ 0: what the mean wave cannot carry, J
    double clampForce = 0.0;  // f_n of the last step, N
};

// Every field of CarrierState once (checked below), in the order of the FMU states
// (PlateSimulation::saveState): a new field is one row here.
// clang-format off
inline constexpr NamedField<CarrierState> kCarrierFields[] = {
    {"force",       fieldOf<&CarrierState::force>},
    {"forcePrev",   fieldOf<&CarrierState::forcePrev>},
    {"driveWork",   fieldOf<&CarrierState::driveWork>},
    {"damperWork",  fieldOf<&CarrierState::damperWork>},
    {"portWork",    fieldOf<&CarrierState::portWork>},
    {"waveSum",     fieldOf<&CarrierState::waveSum>},
    {"waveSquares", fieldOf<&CarrierState::waveSquares>},
    {"waveOut",     fieldOf<&CarrierState::waveOut>},
    {"transit",     fieldOf<&CarrierState::transit>},
    {"lineLoss",    fieldOf<&CarrierState::lineLoss>},
    {"clampForce",  fieldOf<&CarrierState::clampForce>},
};
// clang-format on
constexpr std::size_t kCarrierStateSize = std::size(kCarrierFields);
static_assert(coversEachFieldOnce<CarrierState>(kCarrierFields),
              "kCarrierFields must list every double of CarrierState exactly once");

class Armature {
public:
    Armature(const DiscretePlate& plate, const CarrierOptions& options);

    const CarrierOptions& options() const { return options_; }
    // F^{nβ} for the step to the force fNext at t_{n+1} (a line end holds its wave: F^{nβ} = fNext,
    // docs/theory.md §19).
    double forceBeta(double fNext) const;
    // The free step of (T.18): d holds A⁻¹ r_w on entry and d − g e on return; returns e.
    double solveFree(const NewmarkState& s, double forceBeta, double pBeta, Eigen::VectorXd& d) const;
    // Contact columns of the bordered matrix (T.19), n + 1 entries: the plate's part, then z's.
    void column(int j, Eigen::VectorXd& x) const;
    void gather(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;  // y = C x_w + x_z
    std::unique_ptr<ContactColumns> contactColumns() const;  // of column() and gather()
    // w⁺ += Σ μ_j x_j over the active set; returns the change of z⁺ and removes it from y.
    double correct(ContactColumns& columns, const std::vector<int>& active, const Eigen::VectorXd& mu,
                   Eigen::VectorXd& wNext, Eigen::VectorXd& y) const;
    // The ledger of the step from s (before its commit) to zNext (docs/theory.md §18).
    void commit(const NewmarkState& s, double zNext, double fNext, double fBeta);
    // The carrier's discrete energy ½ M_a v² + Φ(z⁺, z) at the state s (after the commit).
    double energy(const NewmarkState& s) const;
    void beginCommunication();
    void endCommunication(long long steps);

    const CarrierState& state() const { return state_; }
    void setState(const CarrierState& s) { state_ = s; }
    void reset() { state_ = CarrierState{}; }

private:
    const DiscretePlate& plate_;
    CarrierOptions options_;
    double alpha_ = 0.0, schur_ = 0.0;
    Eigen::VectorXd g_;  // A⁻¹ b
    Eigen::VectorXd h_;  // 1 − C g per contact vertex
    CarrierState state_;
};

}  // namespace plate
