#pragma once
// The one place a scheme is made (docs/architecture.md): `time_scheme` chooses the class, the
// resource estimate's engine (decided once, ResourceEstimate::engine) the coordinates of Newmark's
// plate, and each scheme starts from its initial static state here.
#include <Eigen/Sparse>
#include <memory>

#include "plate/DiscretizationCache.h"
#include "plate/Obstacles.h"
#include "plate/PlateParameters.h"
#include "plate/ResourceEstimate.h"

namespace plate {

class Scheme;
class FieldRecovery;
class FiniteElementSpace;
struct ClampedPlate;

// What a scheme is made from: the parameters and what PlateSimulation assembled before it.
struct SchemeSetup {
    const PlateParameters& parameters;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    const FieldRecovery& recovery;
    const ResourceEstimate& resources;
    const Eigen::SparseMatrix<double>& couplingFree;  // B of the singular mass (free rows), or empty
    const Eigen::SparseMatrix<double>& rootFree;  // R of the singular mass (free rows), or empty
    Obstacles obstacles;
    double baseDisplacement0, loadAtStart;
    CacheUse& cache;  // what the modal basis, the condensed plate and κ_h came from (DiscretizationCache.h)
};

// The scheme at t = 0 in its initial static state. Throws ParameterError (an unstable Δt for
// β < ¼, a contact problem that does not converge).
std::unique_ptr<Scheme> makeScheme(const SchemeSetup& setup, InitProgress& progress);

}  // namespace plate
