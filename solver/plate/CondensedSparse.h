#pragma once
// The condensed plate of a fine mesh (CondensedPlate.h) at the cost of the modes kept: the pieces
// condense() takes from the sparse factors instead of the dense massive flexibility T = Rᵀ K⁻¹ R
// (q × q, q one per element) and its complete eigen solution (docs/theory.md §17):
//
// - the lowest `kept` massive modes by Lanczos (Spectra's SymEigsSolver) on T applied through the
//   factor of K,
//   y = Rᵀ K⁻¹ R x: T's largest eigenvalues are 1/ω² of the lowest modes;
// - the massless flexibility Q0 S⁻¹ Q0ᵀ v (the static response to v with Rᵀw = 0) as the
//   displacement part of the saddle-point problem [[K, R], [Rᵀ, 0]] [w; μ] = [v; 0], one solve
//   with its L D Lᵀ factor per right-hand side — only for the constraint rows' directions Cᵀ and
//   the load: D = C Q0 S⁻¹ Q0ᵀ Cᵀ with every massive mode, no matrix of the plate's size.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

#include "plate/CondensedPlate.h"

namespace plate {

// C as sparse rows over the free dofs: the contact vertices' values, then the extra functionals.
SparseRows constraintRows(const ClampedPlate& plate, const std::vector<ConstraintRow>& extraRows);

// Fills c's modal and massless parts (omega2, rowModesT, delassus, rowLoad, loadFlexibility,
// modalLoad, modalBaseInertia, modalRotationInertia, the recovery parts) with `kept` < q modes.
// Throws std::runtime_error when Lanczos does not converge or the saddle-point factor meets a zero pivot.
void condenseSparse(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root, const SparseRows& rows,
                    Eigen::Index kept, const SparseRows& recovery, CondensedPlate& c);

}  // namespace plate
