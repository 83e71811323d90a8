#include "fe/SingularMass.h"

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>
#include <cmath>
#include <sstream>

#include "base/Errors.h"

namespace plate {

SingularMass assembleSingularMass(const FiniteElementSpace& space, double surfaceDensity, MassProjection projection) {
    const int perElement = projection == MassProjection::P0 ? 1 : 3;
    const Eigen::Index n = space.dofCount();
    std::vector<Eigen::Triplet<double>> massTriplets, couplingTriplets, rootTriplets;
    LocalBasis basis;
    SingularMass s;
    s.massMoment = Eigen::VectorXd::Zero(n);
    for (int e = 0; e < space.elementCount(); ++e) {
        const auto& dofs = space.elementDofs(e);
        const int nl = static_cast<int>(dofs.size());
        const auto nodes = space.quadrature(e);
        // Q on this element: 1 (P0), or 1, (x − x_c)/s, (y − y_c)/s (P1dg) about the centroid,
        // scaled by the element size s so that C_e stays well conditioned on any mesh.
        Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
        double area = 0.0;
        for (const auto& q : nodes) {
            centroid += q.weight * q.point;
            area += q.weight;
        }
        centroid /= area;
        const double size = std::sqrt(area);
        Eigen::MatrixXd be = Eigen::MatrixXd::Zero(nl, perElement);  // ∫ ψ_a q_k
        Eigen::MatrixXd ce = Eigen::MatrixXd::Zero(perElement, perElement);  // ∫ q_k q_l
        Eigen::VectorXd qv(perElement), xq = Eigen::VectorXd::Zero(perElement);  // ∫ x q_k
        for (const auto& q : nodes) {
            space.evaluate(e, q.piece, q.point, basis);
            qv[0] = 1.0;
            if (perElement == 3) qv.tail<2>() = (q.point - centroid) / size;
            be.noalias() += q.weight * basis.value * qv.transpose();
            ce.noalias() += q.weight * qv * qv.transpose();
            xq += (q.weight * q.point.x()) * qv;
        }
        // The rules integrate ψ q (degree ≤ p + 1) and q q exactly (they are exact to degree 2p).
        const Eigen::LLT<Eigen::MatrixXd> projection(ce);
        const Eigen::MatrixXd me = surfaceDensity * be * projection.solve(be.transpose());
        const Eigen::VectorXd mx = surfaceDensity * be * projection.solve(xq);
        // R_e = √(ρt) B_e L_e⁻ᵀ: R_e R_eᵀ = ρt B_e C_e⁻¹ B_eᵀ = the element's M_s block.
        const Eigen::MatrixXd re = std::sqrt(surfaceDensity) * projection.matrixU().solve<Eigen::OnTheRight>(be);
        for (int a = 0; a < nl; ++a) {
            for (int k = 0; k < perElement; ++k) {
                couplingTriplets.emplace_back(dofs[a], perElement * e + k, be(a, k));
                rootTriplets.emplace_back(dofs[a], perElement * e + k, re(a, k));
            }
            for (int b = 0; b < nl; ++b) massTriplets.emplace_back(dofs[a], dofs[b], me(a, b));
            s.massMoment[dofs[a]] += mx[a];
        }
    }
    s.mass.resize(n, n);
    s.mass.setFromTriplets(massTriplets.begin(), massTriplets.end());
    s.coupling.resize(n, static_cast<Eigen::Index>(perElement) * space.elementCount());
    s.coupling.setFromTriplets(couplingTriplets.begin(), couplingTriplets.end());
    s.root.resize(n, s.coupling.cols());
    s.root.setFromTriplets(rootTriplets.begin(), rootTriplets.end());
    return s;
}

Eigen::SparseMatrix<double> freeRows(const Eigen::SparseMatrix<double>& coupling, const ClampedPlate& plate) {
    std::vector<Eigen::Index> freeIndex(coupling.rows(), -1);
    for (std::size_t k = 0; k < plate.freeDofs.size(); ++k) freeIndex[plate.freeDofs[k]] = static_cast<Eigen::Index>(k);
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < coupling.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(coupling, c); it; ++it)
            if (freeIndex[it.row()] >= 0) t.emplace_back(freeIndex[it.row()], it.col(), it.value());
    Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(plate.freeDofs.size()), coupling.cols());
    out.setFromTriplets(t.begin(), t.end());
    return out;
}

namespace {

Eigen::Index numericalRank(const Eigen::SparseMatrix<double>& a) {
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
    qr.setPivotThreshold(1e-10 * a.norm());
    qr.compute(a);
    if (qr.info() != Eigen::Success) throw ParameterError("the rank check of the singular mass failed (sparse QR)");
    return qr.rank();
}

// Full column rank of A shown cheaply: A's columns of unit norm, the sparse Cholesky factor of AᵀA
// (= RᵀR, R of A's QR in the same column order) with every pivot |R_kk| ≥ 1e-6: 100× numericalRank's
// threshold (1e-10 ‖A‖_F, ‖A‖_F below 1e3 up to 1e6 columns), and R_kk² ≥ 1e-12 100× the Gram
// matrix's roundoff (ε ‖A‖₂², ‖A‖₂² at most 1 + the ~60 columns one column meets). So the QR would
// decide the same, at its cost: the 56x20 plate with singular_p0 0.1 s against 24 s; singular_p1dg,
// whose smallest pivot falls like h³ (2.8e-4 on 14x5, 3.3e-5 on 28x10: under 1e-4, the bound before),
// 28x20 0.3 s against 24 s. Where it does not show it, the QR decides.
bool clearlyFullColumnRank(const Eigen::SparseMatrix<double>& a) {
    const Eigen::SparseMatrix<double> gram = a.transpose() * a;
    const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(gram);
    return llt.info() == Eigen::Success &&
           Eigen::VectorXd(llt.matrixL().nestedExpression().diagonal()).minCoeff() >= 1e-6;
}

}  // namespace

void requireMasslessContact(const Eigen::SparseMatrix<double>& couplingFree, const ClampedPlate& plate,
                            const char* projectionName) {
    const Eigen::Index n = couplingFree.rows(), r = couplingFree.cols();
    const auto m = static_cast<Eigen::Index>(plate.contactDofs.size());
    // [B Cᵀ], with the columns scaled to unit norm (B's entries are areas, Cᵀ's are ones).
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index c = 0; c < r; ++c) {
        const double norm = couplingFree.col(c).norm();
        for (Eigen::SparseMatrix<double>::InnerIterator it(couplingFree, c); it; ++it)
            t.emplace_back(it.row(), c, it.value() / (norm > 0.0 ? norm : 1.0));
    }
    for (Eigen::Index j = 0; j < m; ++j) t.emplace_back(plate.contactDofs[j], r + j, 1.0);
    Eigen::SparseMatrix<double> bc(n, r + m), b(n, r);
    bc.setFromTriplets(t.begin(), t.end());
    if (clearlyFullColumnRank(bc)) return;  // rank [B Cᵀ] = r + m, rank B = r
    b = bc.leftCols(r);
    const Eigen::Index rankB = numericalRank(b), rankBC = numericalRank(bc);
    if (rankBC - rankB < m) {
        std::ostringstream msg;
        msg << "invalid parameter mass = " << projectionName << " for this element and mesh: its massless directions "
            << "reach only " << (rankBC - rankB) << " of the " << m
            << " contact vertices independently (the projection space has " << r << " functions for " << n
            << " free dofs; allowed: a mass whose massless directions move every contact vertex, e.g. "
            << "singular_p0, or mass = consistent)";
        throw ParameterError(msg.str());
    }
}

}  // namespace plate
