#pragma once
// The initial state of §5.2: static equilibrium under a uniform pressure between the obstacles;
// with a singular mass, the equilibrium of its massless part (docs/theory.md §11).
#include <Eigen/Core>
#include <Eigen/Sparse>

#include "fe/Assembly.h"

#include "plate/DiscretePlate.h"
#include "base/Errors.h"
#include "plate/Obstacles.h"

namespace plate {

// min ½ wᵀK w − p0 wᵀF over obstacle.lower − z0 ≤ C w ≤ obstacle.upper − z0 (the clamp at z0),
// in the plate's own coordinates. Throws ParameterError if the contact QP does not converge.
// contactForce (if given) receives λ, K w = p0 F + Cᵀλ (one entry per contact vertex).
Eigen::VectorXd staticEquilibrium(const DiscretePlate& plate, const Obstacles& obstacles, double z0, double p0,
                                  Eigen::VectorXd* contactForce = nullptr);

// The massless part of w0 brought to equilibrium under the pressure p0 (§11): w = w0 + δ with
// Bᵀδ = 0 (the part the singular mass sees is kept) and K w − p0 F − Cᵀλ in the range of B (no
// massless direction unbalanced), obstacles respected, λ complementary. One sparse LU of the
// saddle-point matrix [K B; Bᵀ 0]. contactForce receives λ. Throws ParameterError if the contact
// problem does not converge.
Eigen::VectorXd masslessEquilibrium(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& couplingFree,
                                    const Obstacles& obstacles, double z0, double p0, const Eigen::VectorXd& w0,
                                    Eigen::VectorXd& contactForce);

}  // namespace plate
