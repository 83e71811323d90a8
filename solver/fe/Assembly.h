#pragma once
// Assembly of the plate matrices of §3.1 — mass (3.4), stiffness (3.5), uniform-pressure
// load — from any FiniteElementSpace, and their reduction to the clamped (free) dofs.
#include <Eigen/Sparse>
#include <functional>
#include <vector>

#include "fe/FiniteElementSpace.h"

namespace plate {

struct PlateMatrices {
    Eigen::SparseMatrix<double> mass;  // ∫ ρ t ψ_i ψ_j
    Eigen::SparseMatrix<double> stiffness;  // ∫ D[(1−ν) ψ_i,αβ ψ_j,αβ + ν Δψ_i Δψ_j]
    Eigen::VectorXd pressureLoad;  // ∫ ψ_i (load of a unit uniform pressure)
    Eigen::VectorXd constant;  // the dof vector of the function 1 (K·1 = 0)
    // ∫ x ψ_i: the first moment about the clamp line x = 0 of each shape function; M·X for the
    // rotation X (the dof vector of the function x, K·X = 0) is ρt times it with the consistent
    // mass (docs/theory.md §14, the clamp moment).
    Eigen::VectorXd momentLoad;
    Eigen::VectorXd massMoment;  // M·X over all dofs (replaced with the singular mass's)
};

// The plate's material (PlateParameters' material part): what M and K are made of beside the space.
struct MaterialParameters {
    double thickness = 0.01;  // m
    double youngsModulus = 2.1e11;  // Pa
    double poissonRatio = 0.3;
    double density = 7770.0;  // kg/m^3
    double bendingStiffness() const {
        return youngsModulus * thickness * thickness * thickness / (12.0 * (1.0 - poissonRatio * poissonRatio));
    }
    double surfaceDensity() const { return density * thickness; }
};
PlateMatrices assemble(const FiniteElementSpace& space, const MaterialParameters& material);

// A point evaluation w(x) = Σ coefficient_k · w_free[dof_k] over the free dofs.
struct PointProbe {
    std::vector<Eigen::Index> dofs;
    std::vector<double> coefficients;
    double operator()(const Eigen::VectorXd& w) const {
        double value = 0.0;
        for (std::size_t k = 0; k < dofs.size(); ++k) value += coefficients[k] * w[dofs[k]];
        return value;
    }
};

// The plate with the clamp x = 0 applied: only the free dofs remain. The base motion z(t)
// enters through `baseInertia` = (M·1)_free (docs/theory.md: u = z·1 + w, w clamped).
struct ClampedPlate {
    Eigen::SparseMatrix<double> mass, stiffness;  // free x free
    Eigen::VectorXd pressureLoad;  // free
    Eigen::VectorXd baseInertia;  // (M·1)_free
    double totalMass = 0.0;  // 1ᵀ M 1 = ρ t |Ω|
    // The port (docs/theory.md §14): rigid motions 1 and X (rotation about x = 0) of the full space.
    Eigen::VectorXd rotationInertia;  // (M·X)_free
    double totalMassMoment = 0.0;  // Xᵀ M 1 = ∫ ρ t x
    double loadResultant = 0.0;  // 1ᵀ F = |Ω|: the force of a unit pressure
    double loadMoment = 0.0;  // Xᵀ F = ∫ x: its moment about the clamp line
    std::vector<double> contactAbscissae;  // x of each contact vertex (its lever arm)
    std::vector<Eigen::Index> freeDofs;  // full index of each free dof
    // The free mesh vertices under a stop (docs/theory.md §25): only they carry a contact bound.
    std::vector<int> contactVertices;
    std::vector<unsigned char> contactStops;  // which obstacles hold each (StopBits)
    std::vector<Eigen::Index> contactDofs;  // their vertex-value dof (free index)
    std::vector<int> clampedVertices;  // vertices on x = 0 (they move with z)

    PointProbe probe(const FiniteElementSpace& space, double x, double y) const;
};

// Which obstacles' stops cover a point (StopBits; 0: none, the vertex is no contact row).
using StopsAt = std::function<unsigned char(const Eigen::Vector2d&)>;

// Without `stopsAt`, every free vertex is a contact row under both obstacles (the whole plate).
ClampedPlate clamp(const FiniteElementSpace& space, const PlateMatrices& matrices, const StopsAt& stopsAt = {});

}  // namespace plate
