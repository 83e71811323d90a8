#pragma once
// The condensed plate of a fine mesh (CondensedPlate.h) at the cost of the modes kept: the pieces
// condense() takes from the sparse factors instead of the dense massive flexibility T = Rᵀ K⁻¹ R
// (q × q, q one per element) and its complete eigen solution (docs/theory.md §17):
//
// - the lowest `kept` massive modes by Lanczos (Spectra's SymEigsSolver) on T applied through the
//   factor of K,
//   y = Rᵀ K⁻¹ R x: T's largest eigenvalues are 1/ω² of the lowest modes;
// - the massless flexibility Q0 S⁻¹ Q0ᵀ v (the static response to v with Rᵀw = 0) by the augmented
//   Lagrangian iteration on the factor of K + ρ M_s (M_s = R Rᵀ): w ← (K + ρM_s)⁻¹(v − Rλ),
//   λ ← λ + ρRᵀw, converging by 1/(1 + ρ/ω²) per iteration in each massive mode, so in a few
//   iterations once ρ is well above the highest massive ω² — only for the constraint rows'
//   directions Cᵀ and the load: D = C Q0 S⁻¹ Q0ᵀ Cᵀ with every massive mode, no matrix of the
//   plate's size.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

#include "plate/CondensedPlate.h"

namespace plate {

// C as sparse rows over the free dofs: the contact vertices' values, then the extra functionals.
SparseRows constraintRows(const ClampedPlate& plate, const std::vector<ConstraintRow>& extraRows);

// Fills c's modal and massless parts (omega2, rowModesT, delassus, rowLoad, loadFlexibility,
// modalLoad, modalBaseInertia, modalRotationInertia, the recovery parts) with `kept` < q modes.
// Throws std::runtime_error when Lanczos or the massless iteration does not converge.
void condenseSparse(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root, const SparseRows& rows,
                    Eigen::Index kept, const SparseRows& recovery, CondensedPlate& c);

}  // namespace plate
