#pragma once
// The singular (redistributed) mass of docs/theory.md §11, (T.3): M_s = ρt B C⁻¹ Bᵀ, with B the coupling
// ∫ ψ_i q_k of the plate space with a projection space Q of discontinuous polynomials (P0: one
// constant per element, P1dg: one linear per element) and C the mass ∫ q_k q_l of Q. M_s is the
// mass of the L² projection of the velocity on Q: the kinetic energy of ψ is that of its element
// means (P0) or element-wise linear parts (P1dg), and every ψ with Bᵀψ = 0 is massless.
//
// The semi-discrete problem is then well posed through impacts (Khenous, Laborde & Renard 2008;
// Renard 2010) provided every contact vertex can move along a massless direction, i.e. the
// vertex values C restricted to ker Bᵀ are onto (requireMasslessContact).
#include <Eigen/Sparse>

#include "fe/Assembly.h"
#include "fe/FiniteElementSpace.h"

namespace plate {

enum class MassProjection { P0, P1dg };

struct SingularMass {
    Eigen::SparseMatrix<double> mass;  // M_s over all dofs of the space
    Eigen::SparseMatrix<double> coupling;  // B: dofs x projection functions (geometric, ρt left out)
    Eigen::VectorXd massMoment;  // M_s X = ρt B C⁻¹ (∫ x q_k): the rotation's momentum (§14)
    // A square root of M_s: R = √(ρt) B L⁻ᵀ with C = L Lᵀ (element blocks), so M_s = R Rᵀ and Rᵀw are
    // coordinates of the velocity's projection in which the kinetic energy is ½|Rᵀẇ|² (§17).
    Eigen::SparseMatrix<double> root;
};

// Element by element: the local block ρt B_e C_e⁻¹ B_eᵀ (Q is discontinuous, so C is block
// diagonal and M_s assembles from element blocks with the sparsity of the consistent mass).
SingularMass assembleSingularMass(const FiniteElementSpace& space, double surfaceDensity, MassProjection projection);

// Rows of B at the free dofs of the clamped plate.
Eigen::SparseMatrix<double> freeRows(const Eigen::SparseMatrix<double>& coupling, const ClampedPlate& plate);

// Throws ParameterError unless rank [B Cᵀ] = rank B + (contact vertices): every contact vertex
// value can be moved along ker Bᵀ (no inertia), independently of the others.
void requireMasslessContact(const Eigen::SparseMatrix<double>& couplingFree, const ClampedPlate& plate,
                            const char* projectionName);

}  // namespace plate
