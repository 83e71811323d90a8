#include "StaticEquilibrium.h"

#include <sstream>

#include "BoxQP.h"
#include "PlateParameters.h"

namespace plate {

// The same contact-space QP as a time step, with S = K.
Eigen::VectorXd staticEquilibrium(const DiscretePlate& plate, const Obstacles& obstacles, double z0, double p0) {
    const DiscretePlate::Solver solveK = plate.stiffnessSolver();
    Eigen::VectorXd w;
    solveK(Eigen::VectorXd(p0 * plate.pressureLoad()), w);
    if (!obstacles.any()) return w;
    const int m = plate.contactCount();
    ContactColumns columns(
        m,
        [&](int j, Eigen::VectorXd& z) {
            Eigen::VectorXd c;
            plate.contactDirection(j, c);
            solveK(c, z);
        },
        [&plate](const Eigen::VectorXd& z, Eigen::VectorXd& y) { plate.gatherContact(z, y); });
    Eigen::VectorXd yFree, y, mu = Eigen::VectorXd::Zero(m);
    plate.gatherContact(w, yFree);
    const Eigen::VectorXd lower = Eigen::VectorXd::Constant(m, obstacles.lower - z0);
    const Eigen::VectorXd upper = Eigen::VectorXd::Constant(m, obstacles.upper - z0);
    std::vector<signed char> state(m, 0);
    BoxQP qp(columns);
    const QPResult r = qp.solve(yFree, lower, upper, state, mu, y);
    if (!r.converged || !(r.kktResidual <= 1e-10)) {
        std::ostringstream msg;
        msg << "invalid parameter initial_load = " << p0
            << ": the static contact problem for the initial state did not converge (relative KKT " << r.kktResidual
            << ")";
        throw ParameterError(msg.str());
    }
    for (int i : qp.active()) w.noalias() += mu[i] * columns.column(i);
    return w;
}

}  // namespace plate
