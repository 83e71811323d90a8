#pragma once
// The clamped plate with a singular mass, condensed (docs/theory.md §17): the massive space in
// mass-normalized modes with their static completion, the massless space static at every
// instant. What the condensed schemes (CondensedScheme: MidpointScheme, FlowScheme) step:
//
//   q̈ + Ω² q = p F_m − b_m z̈ + Gᵀλ,      y = G q + p c_p + z·𝟙 + D λ   (constraint rows),
//
// q the massive modal coordinates, y the absolute heights of the constraint rows (the contact
// vertices, then the output points that are not vertices), λ their contact forces and
// D = C Q0 S⁻¹ Q0ᵀ Cᵀ the massless Delassus operator (constant, SPD). Everything is computed once
// from the sparse factor of K: the massive flexibility T = Rᵀ K⁻¹ R (R the root of M_s,
// SingularMass.h) gives the massive stiffness T⁻¹ = Φ Ω² Φᵀ, the modes V = K⁻¹ R Φ Ω², and
// Q0 S⁻¹ Q0ᵀ = K⁻¹ − K⁻¹ R T⁻¹ Rᵀ K⁻¹ (§17). No dense matrix of the plate's size is formed.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

#include "fe/Assembly.h"
#include "plate/LinearRows.h"
#include "plate/Obstacles.h"

namespace plate {

struct CondensedPlate {
    // The retained massive modes (all of them, or the `modes` lowest), ascending.
    Eigen::VectorXd omega2;  // Ω²
    Eigen::MatrixXd rowModesT;  // Gᵀ = (C V)ᵀ: column i = the modes at constraint row i
    Eigen::MatrixXd delassus;  // D (rows × rows), symmetric positive definite
    Eigen::VectorXd rowLoad;  // c_p = C Q0 S⁻¹ Q0ᵀ F: the massless part's response to a unit pressure
    double loadFlexibility = 0.0;  // Fᵀ Q0 S⁻¹ Q0ᵀ F (its strain energy is ½ p² times this)
    Eigen::VectorXd modalLoad;  // F_m = Vᵀ F
    Eigen::VectorXd modalBaseInertia;  // b_m = Vᵀ (M_s·1)_free
    Eigen::VectorXd modalRotationInertia;  // Vᵀ (M_s·X)_free
    // Mass and first moment that move rigidly with the clamp: those of the discarded massive
    // modes (zero with every mode retained, §17).
    double clampMass = 0.0, clampMassMoment = 0.0;
    double totalMass = 0.0, totalMassMoment = 0.0, loadResultant = 0.0, loadMoment = 0.0;
    int massiveCount = 0;  // dimension of the massive space (retained: omega2.size())
    int contactRows = 0;  // the first rows: the contact vertices of ClampedPlate, in its order
    std::vector<double> rowAbscissae;  // x of each row (its lever arm about the clamp line)
    std::vector<unsigned char> rowStops;  // which obstacles hold each row (StopBits, docs/theory.md §25)
    double rowModeNormMax = 0.0;  // max_i ‖G_i‖₂ (the free-flight bound)
    // The recovery functionals L (probes, stress samples: docs/theory.md §23) of
    // w = V q + Q0 S⁻¹ Q0ᵀ (p F + Cᵀλ): L w = recoveryModes q + p recoveryLoad + recoveryRows λ.
    DenseRows recoveryModes, recoveryRows;  // L V (L × modes), L Q0 S⁻¹ Q0ᵀ Cᵀ (L × rows)
    Eigen::VectorXd recoveryLoad;  // L Q0 S⁻¹ Q0ᵀ F

    int rows() const { return static_cast<int>(rowLoad.size()); }
    int modes() const { return static_cast<int>(omega2.size()); }
};

// An output point as a constraint row: a point evaluation over the free dofs and its abscissa.
struct ConstraintRow {
    PointProbe functional;
    double x = 0.0;
    unsigned char stops = kUnderBoth;  // the obstacles whose stops cover the point (StopBits)
};

// How condense() finds the massive modes and the massless part: the complete dense eigen solution
// of the massive flexibility T (q × q, q the massive dimension: one per element with P0), or
// Lanczos for the kept modes and the massless flexibility on the sparse factors (CondensedSparse.h).
// Auto: dense where denseCondensationServes, so that coarse meshes and complete bases keep their
// results bit for bit; Sparse needs modes < q.
enum class Condensation { Auto, Dense, Sparse };
// Does the dense solution serve `modes` of a massive space of dimension q (Auto's choice)? Where
// most modes are kept, or q is small enough that T's dense eigen solution costs under a second.
bool denseCondensationServes(Eigen::Index massive, int modes);
inline constexpr Eigen::Index kDenseCondensationLimit = 1200;

// Builds the condensed plate. `root` is R over the free dofs (M_s = R Rᵀ), `extraRows` the output
// points added as constraint rows after the contact vertices, `modes` the massive modes kept
// (≤ 0 or ≥ the massive dimension: all). Throws ParameterError when the massless space cannot
// move every row independently (D not positive definite) or the massive flexibility is singular.
// `recovery`: functionals over the free dofs read through the same flexibilities (none by default).
CondensedPlate condense(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root,
                        const std::vector<ConstraintRow>& extraRows, int modes, const SparseRows& recovery = {},
                        Condensation method = Condensation::Auto);

}  // namespace plate
