#pragma once
// The spectrum of the clamped plate K φ = ω² M φ: the lowest modes (the modal engines and the
// accuracy yardstick of a mesh) and the largest eigenvalue κ_h (the β < ¼ stability bound).
#include <Eigen/Core>

#include "fe/Assembly.h"

namespace plate {

// The m lowest modes, M-orthonormal, ascending (modes ≤ 0 or ≥ the dof count: all of them).
// Dense generalized eigensolver for small spaces, subspace iteration with the CHOLMOD factor
// of K for large ones. Throws std::runtime_error if it fails.
void lowestModes(const ClampedPlate& plate, int modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2);

// Every mode of the dense solution (what lowestModes solves for where it takes the dense path), so
// that the bases of several mode counts of one plate share one eigen solution: lowestModes given it
// slices its leading columns, bit for bit what it would have computed (DiscretizationCache).
struct DenseSpectrum {
    explicit DenseSpectrum(const ClampedPlate& plate);
    Eigen::MatrixXd phi;
    Eigen::VectorXd omega2;
};
// Does lowestModes(plate, modes) take the dense path (of a space of `dofs`)?
bool denseSpectrumServes(Eigen::Index dofs, int modes);
void lowestModes(const DenseSpectrum& dense, int modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2);

// κ_h = λ_max(M⁻¹K), s⁻² (docs/theory.md).
double largestEigenvalue(const ClampedPlate& plate);

}  // namespace plate
