#include "fe/Assembly.h"

#include <algorithm>

#include "fe/StopBits.h"

namespace plate {

PlateMatrices assemble(const FiniteElementSpace& space, const MaterialParameters& material) {
    const double surfaceDensity = material.surfaceDensity(), bendingStiffness = material.bendingStiffness();
    const Eigen::Index n = space.dofCount();
    std::vector<Eigen::Triplet<double>> massTriplets, stiffnessTriplets;
    // Reserved at their final size: no reallocation doubles the peak (ResourceEstimate.h).
    std::size_t entries = 0;
    for (int e = 0; e < space.elementCount(); ++e) entries += space.elementDofs(e).size() * space.elementDofs(e).size();
    massTriplets.reserve(entries);
    stiffnessTriplets.reserve(entries);
    Eigen::VectorXd load = Eigen::VectorXd::Zero(n), momentLoad = Eigen::VectorXd::Zero(n);
    LocalBasis basis;
    const double nu = material.poissonRatio;
    for (int e = 0; e < space.elementCount(); ++e) {
        const auto& dofs = space.elementDofs(e);
        const int nl = static_cast<int>(dofs.size());
        Eigen::MatrixXd me = Eigen::MatrixXd::Zero(nl, nl), ke = Eigen::MatrixXd::Zero(nl, nl);
        Eigen::VectorXd fe = Eigen::VectorXd::Zero(nl), fxe = Eigen::VectorXd::Zero(nl);
        for (const auto& q : space.quadrature(e)) {
            space.evaluate(e, q.piece, q.point, basis);
            const double w = q.weight;
            me.noalias() += (w * surfaceDensity) * basis.value * basis.value.transpose();
            // a(u, v) = D ∫ (1−ν)(u_xx v_xx + 2 u_xy v_xy + u_yy v_yy) + ν Δu Δv  (§2.1)
            const Eigen::VectorXd laplacian = basis.dxx + basis.dyy;
            ke.noalias() += (w * bendingStiffness) *
                            ((1.0 - nu) * (basis.dxx * basis.dxx.transpose() + 2.0 * basis.dxy * basis.dxy.transpose() +
                                           basis.dyy * basis.dyy.transpose()) +
                             nu * laplacian * laplacian.transpose());
            fe += w * basis.value;
            fxe += (w * q.point.x()) * basis.value;
        }
        for (int a = 0; a < nl; ++a) {
            load[dofs[a]] += fe[a];
            momentLoad[dofs[a]] += fxe[a];
            for (int b = 0; b < nl; ++b) {
                massTriplets.emplace_back(dofs[a], dofs[b], me(a, b));
                stiffnessTriplets.emplace_back(dofs[a], dofs[b], ke(a, b));
            }
        }
    }
    PlateMatrices m;
    m.mass.resize(n, n);
    m.stiffness.resize(n, n);
    m.mass.setFromTriplets(massTriplets.begin(), massTriplets.end());
    m.stiffness.setFromTriplets(stiffnessTriplets.begin(), stiffnessTriplets.end());
    m.pressureLoad = load;
    m.momentLoad = momentLoad;
    m.massMoment = surfaceDensity * momentLoad;  // M X = ∫ ρt x ψ_i, x being in the space
    m.constant = Eigen::VectorXd::Zero(n);
    for (int v = 0; v < space.mesh().vertexCount(); ++v) m.constant[space.vertexValueDof(v)] = 1.0;
    return m;
}

namespace {

Eigen::SparseMatrix<double> restrict(const Eigen::SparseMatrix<double>& a, const std::vector<Eigen::Index>& freeIndex) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(a.nonZeros());
    Eigen::Index nFree = 0;
    for (auto i : freeIndex) nFree += (i >= 0);
    for (int k = 0; k < a.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
            const auto r = freeIndex[it.row()], c = freeIndex[it.col()];
            if (r >= 0 && c >= 0) t.emplace_back(r, c, it.value());
        }
    Eigen::SparseMatrix<double> out(nFree, nFree);
    out.setFromTriplets(t.begin(), t.end());
    return out;
}

}  // namespace

ClampedPlate clamp(const FiniteElementSpace& space, const PlateMatrices& matrices, const StopsAt& stopsAt) {
    const Eigen::Index n = space.dofCount();
    std::vector<Eigen::Index> freeIndex(n, 0);
    for (auto d : space.clampedDofs()) freeIndex[d] = -1;
    ClampedPlate p;
    for (Eigen::Index i = 0; i < n; ++i)
        if (freeIndex[i] >= 0) {
            freeIndex[i] = static_cast<Eigen::Index>(p.freeDofs.size());
            p.freeDofs.push_back(i);
        }
    p.mass = restrict(matrices.mass, freeIndex);
    p.stiffness = restrict(matrices.stiffness, freeIndex);
    const Eigen::VectorXd massTimesOne = matrices.mass * matrices.constant;
    p.totalMass = matrices.constant.dot(massTimesOne);
    p.pressureLoad.resize(p.freeDofs.size());
    p.baseInertia.resize(p.freeDofs.size());
    p.rotationInertia.resize(p.freeDofs.size());
    for (std::size_t k = 0; k < p.freeDofs.size(); ++k) {
        p.pressureLoad[k] = matrices.pressureLoad[p.freeDofs[k]];
        p.baseInertia[k] = massTimesOne[p.freeDofs[k]];
        p.rotationInertia[k] = matrices.massMoment[p.freeDofs[k]];
    }
    p.totalMassMoment = matrices.constant.dot(matrices.massMoment);
    p.loadResultant = matrices.constant.dot(matrices.pressureLoad);
    p.loadMoment = matrices.constant.dot(matrices.momentLoad);
    const Mesh& mesh = space.mesh();
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        const auto f = freeIndex[space.vertexValueDof(v)];
        if (f < 0) {
            p.clampedVertices.push_back(v);
            continue;
        }
        const unsigned char stops = stopsAt ? stopsAt(mesh.point(v)) : static_cast<unsigned char>(kUnderBoth);
        if (stops == 0) continue;
        p.contactVertices.push_back(v);
        p.contactStops.push_back(stops);
        p.contactDofs.push_back(f);
        p.contactAbscissae.push_back(mesh.point(v).x());
    }
    return p;
}

PointProbe ClampedPlate::probe(const FiniteElementSpace& space, double x, double y) const {
    const Eigen::Vector2d point(x, y);
    const int e = space.elementContaining(point);
    LocalBasis basis;
    space.evaluate(e, space.pieceContaining(e, point), point, basis);
    PointProbe probe;
    const auto& dofs = space.elementDofs(e);
    for (std::size_t a = 0; a < dofs.size(); ++a) {
        const auto it = std::lower_bound(freeDofs.begin(), freeDofs.end(), dofs[a]);
        if (it != freeDofs.end() && *it == dofs[a] && basis.value[a] != 0.0) {
            probe.dofs.push_back(it - freeDofs.begin());
            probe.coefficients.push_back(basis.value[a]);
        }
    }
    return probe;
}

}  // namespace plate
