#include "plate/StaticEquilibrium.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <memory>
#include <sstream>

#include "plate/BoxQP.h"
#include "plate/PlateParameters.h"

namespace plate {

namespace {

// The contact-space QP of a static problem (BoxQP.h with the given S): w ← w + S⁻¹Cᵀλ within
// the obstacles (clamp at z0); returns λ, one entry per contact vertex. `failure` opens the
// message of the ParameterError thrown if the QP does not converge.
Eigen::VectorXd solveStaticContact(ContactColumns& columns, const ContactColumns::GatherFn& gather,
                                   const Obstacles& obstacles, const std::vector<unsigned char>& stops, double z0,
                                   Eigen::VectorXd& w, const std::string& failure) {
    const int m = columns.count();
    Eigen::VectorXd yFree, y, mu = Eigen::VectorXd::Zero(m), lower, upper;
    gather(w, yFree);
    obstacles.rowBounds(stops, lower, upper);  // each row's obstacles (docs/theory.md §25)
    lower.array() -= z0;
    upper.array() -= z0;
    std::vector<signed char> state(m, 0);
    BoxQP qp(columns);
    const QPResult r = qp.solve(yFree, lower, upper, state, mu, y);
    if (!r.converged || !(r.kktResidual <= 1e-10)) {
        std::ostringstream msg;
        msg << failure << " did not converge (relative KKT " << r.kktResidual << ")";
        throw ParameterError(msg.str());
    }
    for (int i : qp.active()) w.noalias() += mu[i] * columns.column(i);
    return mu;
}

}  // namespace

// The same contact-space QP as a time step, with S = K.
Eigen::VectorXd staticEquilibrium(const DiscretePlate& plate, const Obstacles& obstacles, double z0, double p0,
                                  Eigen::VectorXd* contactForce) {
    const DiscretePlate::Solver solveK = plate.stiffnessSolver();
    Eigen::VectorXd w;
    solveK(Eigen::VectorXd(p0 * plate.pressureLoad()), w);
    if (contactForce) *contactForce = Eigen::VectorXd::Zero(obstacles.any() ? plate.contactCount() : 0);
    if (!obstacles.any()) return w;
    const int m = plate.contactCount();
    const ContactColumns::GatherFn gather = [&plate](const Eigen::VectorXd& z, Eigen::VectorXd& y) {
        plate.gatherContact(z, y);
    };
    ContactColumns columns(
        m,
        [&](int j, Eigen::VectorXd& z) {
            Eigen::VectorXd c;
            plate.contactDirection(j, c);
            solveK(c, z);
        },
        gather);
    std::ostringstream what;
    what << "invalid parameter initial_load = " << p0 << ": the static contact problem for the initial state";
    const Eigen::VectorXd mu =
        solveStaticContact(columns, gather, obstacles, plate.clamped().contactStops, z0, w, what.str());
    if (contactForce) *contactForce = mu;
    return w;
}

Eigen::VectorXd masslessEquilibrium(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& couplingFree,
                                    const Obstacles& obstacles, double z0, double p0, const Eigen::VectorXd& w0,
                                    Eigen::VectorXd& contactForce) {
    const Eigen::Index n = plate.stiffness.rows(), r = couplingFree.cols();
    const auto m = static_cast<int>(plate.contactDofs.size());
    // [K B; Bᵀ 0] [δ; η] = [rhs; 0]: δ is the K-orthogonal correction along ker Bᵀ.
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(plate.stiffness.nonZeros() + 2 * couplingFree.nonZeros());
    for (int c = 0; c < plate.stiffness.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(plate.stiffness, c); it; ++it)
            t.emplace_back(it.row(), it.col(), it.value());
    // B scaled to the size of K's entries (pivoting of the LU sees comparable numbers).
    const double scale = plate.stiffness.diagonal().cwiseAbs().maxCoeff() / couplingFree.coeffs().cwiseAbs().maxCoeff();
    for (int c = 0; c < couplingFree.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(couplingFree, c); it; ++it) {
            t.emplace_back(it.row(), n + it.col(), scale * it.value());
            t.emplace_back(n + it.col(), it.row(), scale * it.value());
        }
    Eigen::SparseMatrix<double> saddle(n + r, n + r);
    saddle.setFromTriplets(t.begin(), t.end());
    auto lu = std::make_shared<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>();
    lu->compute(saddle);
    if (lu->info() != Eigen::Success)
        throw ParameterError("the massless equilibrium of the initial state could not be computed (saddle-point LU)");
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + r);
    const auto correction = [&](const Eigen::VectorXd& force, Eigen::VectorXd& delta) {
        rhs.head(n) = force;
        rhs.tail(r).setZero();
        delta = lu->solve(rhs).head(n);
    };
    Eigen::VectorXd w;
    correction(Eigen::VectorXd(p0 * plate.pressureLoad - plate.stiffness * w0), w);
    w += w0;
    contactForce = Eigen::VectorXd::Zero(obstacles.any() ? m : 0);
    if (!obstacles.any()) return w;
    const ContactColumns::GatherFn gather = [&plate](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
        y.resize(static_cast<Eigen::Index>(plate.contactDofs.size()));
        for (std::size_t i = 0; i < plate.contactDofs.size(); ++i)
            y[static_cast<Eigen::Index>(i)] = v[plate.contactDofs[i]];
    };
    ContactColumns columns(
        m,
        [&](int j, Eigen::VectorXd& z) {
            Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
            c[plate.contactDofs[j]] = 1.0;
            correction(c, z);
        },
        gather);
    const Eigen::VectorXd mu = solveStaticContact(columns, gather, obstacles, plate.contactStops, z0, w,
                                                  "the contact problem of the singular mass's initial equilibrium");
    contactForce = mu;
    return w;
}

}  // namespace plate
