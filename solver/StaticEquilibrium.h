#pragma once
// The initial state of §5.2: static equilibrium under a uniform pressure between the obstacles.
#include <Eigen/Core>

#include "DiscretePlate.h"
#include "Errors.h"
#include "Obstacles.h"

namespace plate {

// min ½ wᵀK w − p0 wᵀF over obstacle.lower − z0 ≤ C w ≤ obstacle.upper − z0 (the clamp at z0),
// in the plate's own coordinates. Throws ParameterError if the contact QP does not converge.
Eigen::VectorXd staticEquilibrium(const DiscretePlate& plate, const Obstacles& obstacles, double z0, double p0);

}  // namespace plate
