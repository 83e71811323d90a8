#include "schemes/ConservingEngine.h"

#include <cmath>

namespace plate {

ConservingEngine::ConservingEngine(std::unique_ptr<ConservingStepper> stepper, std::array<int, 3> probeRows,
                                   std::vector<int> vertexRows)
    : stepper_(std::move(stepper)), probeRows_(probeRows), vertexRows_(std::move(vertexRows)) {}

PlateOutputs ConservingEngine::outputs(bool port) const {
    const ConservingStepper& stepper = *stepper_;
    const ConservingState& st = stepper.state();
    PlateOutputs o;
    o.corner1 = stepper.rowHeight(probeRows_[0]);
    o.corner2 = stepper.rowHeight(probeRows_[1]);
    o.freeEdgeMid = stepper.rowHeight(probeRows_[2]);
    o.energy = stepper.energy();
    o.energyDissipated = 0.0;  // the scheme loses nothing at impacts (T.17d)
    o.energyInput = st.energyInput;
    o.energyDamped = st.energyDamped;
    o.maxKktResidual = st.maxKktResidual;
    o.contactVertices = st.contactRows;
    o.qpIterationsTotal = double(st.lcpSolves);
    o.qpIterationsMax = st.gradientIterationsMax;
    o.impacts[0] = double(st.impactCount[0]);
    o.impacts[1] = double(st.impactCount[1]);
    if (!port) return o;
    // The port at t_{n−½} (§17): what the plate exerts on the clamp is the opposite of the clamp's
    // force on it. Velocities at t_n (second-order backward), accelerations at t_{n−1}.
    const double dt = stepper.dt(), dt2 = dt * dt;
    const auto velocity = [dt](double now, double prev, double prev2) {
        return (3.0 * now - 4.0 * prev + prev2) / (2.0 * dt);
    };
    o.clampForce = -st.clampForce;
    o.clampMoment = -st.clampMoment;
    if (st.step == 0) stepper.initialReaction(o.clampForce, o.clampMoment);  // no step yet (§17)
    o.clampDisplacement = st.z;
    o.clampVelocity = velocity(st.z, st.zPrev, st.zPrev2);
    o.clampAcceleration = (st.z - 2.0 * st.zPrev + st.zPrev2) / dt2;
    for (int k = 0; k < 3; ++k) {
        const double now = stepper.rowHeight(probeRows_[k], 0), prev = stepper.rowHeight(probeRows_[k], 1),
                     prev2 = stepper.rowHeight(probeRows_[k], 2);
        o.velocity[k] = velocity(now, prev, prev2);
        o.acceleration[k] = (now - 2.0 * prev + prev2) / dt2;
    }
    for (int k = 0; k < 2; ++k) {
        o.contactForce[k] = st.stepContactForce[k];
        o.contactImpulse[k] = st.contactImpulseSum[k];
    }
    return o;
}

std::vector<double> ConservingEngine::vertexDisplacements() const {
    std::vector<double> u(vertexRows_.size(), stepper_->state().z);
    for (std::size_t v = 0; v < vertexRows_.size(); ++v)
        if (vertexRows_[v] >= 0) u[v] = stepper_->rowHeight(vertexRows_[v]);
    return u;
}

std::string ConservingEngine::name() const {
    const CondensedPlate& c = stepper_->plate();
    return c.modes() == c.massiveCount ? "conserving-complete" : "conserving-" + std::to_string(c.modes());
}

double ConservingEngine::firstFrequency() const { return std::sqrt(stepper_->plate().omega2[0]) / (2.0 * M_PI); }

}  // namespace plate
