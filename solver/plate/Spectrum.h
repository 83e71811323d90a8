#pragma once
// The spectrum of the clamped plate K φ = ω² M φ: the lowest modes (the modal engines and the
// accuracy yardstick of a mesh) and the largest eigenvalue κ_h (the β < ¼ stability bound).
#include <Eigen/Core>

#include "fe/Assembly.h"

namespace plate {

// The m lowest modes, M-orthonormal, ascending (modes ≤ 0 or ≥ the dof count: all of them).
// Dense generalized eigensolver for small spaces, Spectra's shift-invert Lanczos with the CHOLMOD
// factor of K for a few modes of large ones. Throws std::runtime_error if it fails.
void lowestModes(const ClampedPlate& plate, int modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2);

// Does lowestModes(plate, modes) take the dense path (of a space of `dofs`)? There it solves for every
// mode and keeps the leading ones: a basis of any count is the leading columns of the complete one,
// bit for bit, so that the bases of one plate share one eigen solution (DiscretizationCache).
bool denseSolutionServes(Eigen::Index dofs, int modes);
// The leading `modes` of a complete dense solution (allPhi, allOmega2), as lowestModes would give them.
void leadingModes(const Eigen::MatrixXd& allPhi, const Eigen::VectorXd& allOmega2, int modes, Eigen::MatrixXd& phi,
                  Eigen::VectorXd& omega2);

// Entry i of start vector j of the iterative eigensolvers (Lanczos here and in CondensedSparse.cpp,
// power iteration): deterministic, bit for bit the same on every CPU.
double startEntry(Eigen::Index i, Eigen::Index j);

// κ_h = λ_max(M⁻¹K), s⁻² (docs/theory.md).
double largestEigenvalue(const ClampedPlate& plate);

}  // namespace plate
