#include "schemes/NewmarkEngine.h"

#include <cmath>

#include "plate/ModalPlate.h"
#include "plate/Spectrum.h"

namespace plate {

NewmarkEngine::NewmarkEngine(std::shared_ptr<const DiscretePlate> discrete,
                             std::unique_ptr<NewmarkContactStepper> stepper, double length, double width,
                             int vertexCount)
    : discrete_(std::move(discrete)),
      stepper_(std::move(stepper)),
      vertexCount_(vertexCount),
      corner1_(discrete_->probe(length, 0.0)),
      corner2_(discrete_->probe(length, width)),
      freeEdgeMid_(discrete_->probe(length, 0.5 * width)) {}

PlateOutputs NewmarkEngine::outputs(bool port) const {
    const NewmarkState& st = stepper_->state();
    PlateOutputs o;
    o.corner1 = st.z + corner1_(st.w);
    o.corner2 = st.z + corner2_(st.w);
    o.freeEdgeMid = st.z + freeEdgeMid_(st.w);
    if (energyStep_ != st.step) {
        energyCache_ = stepper_->energy();
        energyStep_ = st.step;
    }
    o.energy = energyCache_;
    o.energyDissipated = st.energyDissipated;
    o.energyInput = st.energyInput;
    o.energyDamped = st.energyDamped;
    o.contactVertices = st.contactVertices;
    o.maxKktResidual = st.maxKktResidual;
    o.qpIterationsTotal = double(st.qpIterationsTotal);
    o.qpIterationsMax = st.qpIterationsMax;
    o.impacts[0] = double(st.impactCount[0]);
    o.impacts[1] = double(st.impactCount[1]);
    if (port) portOutputs(o);
    return o;
}

void NewmarkEngine::portOutputs(PlateOutputs& o) const {
    // docs/theory.md §14, (T.14a, b): the step from t_n to t_{n+1} summed against the rigid motions 1 and X
    // (K·1 = K·X = 0) gives the clamp's force and moment on the plate at t_n; the plate exerts
    // their opposites on the clamp. Levels: w = w_{n+1}, wPrev = w_n, wPrev2 = w_{n−1}.
    const NewmarkState& st = stepper_->state();
    const ClampedPlate& plate = discrete_->clamped();
    const double dt = discrete_->dt(), beta = discrete_->beta(), dt2 = dt * dt;
    const Eigen::VectorXd& rotation = discrete_->rotationInertia();
    const double zAcc = (st.z - 2.0 * st.zPrev + st.zPrev2) / dt2;
    const double translationAcc = (st.baseCoupling - 2.0 * st.baseCouplingPrev + st.baseCouplingPrev2) / dt2;
    const double rotationAcc = (rotation.dot(st.w) - 2.0 * rotation.dot(st.wPrev) + rotation.dot(st.wPrev2)) / dt2;
    const double pBeta = beta * st.p + (1.0 - 2.0 * beta) * st.pPrev + beta * st.pPrev2;  // f^{nβ}
    const double contact = st.stepContactForce[0] + st.stepContactForce[1];
    o.clampForce = -(plate.totalMass * zAcc + translationAcc - pBeta * plate.loadResultant - contact);
    o.clampMoment = -(plate.totalMassMoment * zAcc + rotationAcc - pBeta * plate.loadMoment - st.stepContactMoment);
    // Velocities at t_{n+1} (second order, backward: the outputs' time), accelerations at t_n
    // (the scheme's own central difference, the level of the forces).
    const auto velocity = [dt](double now, double prev, double prev2) {
        return (3.0 * now - 4.0 * prev + prev2) / (2.0 * dt);
    };
    o.clampDisplacement = st.z;
    o.clampVelocity = velocity(st.z, st.zPrev, st.zPrev2);
    o.clampAcceleration = zAcc;
    const PointProbe* probes[3] = {&corner1_, &corner2_, &freeEdgeMid_};
    for (int k = 0; k < 3; ++k) {
        const double now = st.z + (*probes[k])(st.w), prev = st.zPrev + (*probes[k])(st.wPrev),
                     prev2 = st.zPrev2 + (*probes[k])(st.wPrev2);
        o.velocity[k] = velocity(now, prev, prev2);
        o.acceleration[k] = (now - 2.0 * prev + prev2) / dt2;
    }
    if (st.step == 0) {  // no step yet: the initial static state's reaction (§14)
        o.clampForce = initialForce_;
        o.clampMoment = initialMoment_;
    }
    for (int k = 0; k < 2; ++k) {
        o.contactForce[k] = st.stepContactForce[k];
        o.contactImpulse[k] = st.contactImpulseSum[k];
    }
}

std::vector<double> NewmarkEngine::vertexDisplacements() const {
    const NewmarkState& st = stepper_->state();
    const ClampedPlate& plate = discrete_->clamped();
    std::vector<double> u(static_cast<std::size_t>(vertexCount_), st.z);
    Eigen::VectorXd y;
    discrete_->gatherContact(st.w, y);
    for (std::size_t i = 0; i < plate.contactVertices.size(); ++i)
        u[plate.contactVertices[i]] += y[static_cast<Eigen::Index>(i)];
    return u;
}

void NewmarkEngine::restoreState(const std::vector<double>& data) {
    const NewmarkState& current = stepper_->state();
    stepper_->setState(deserialize(data, current.w.size(), current.contactState.size(), current.contactImpulse.size()));
    energyStep_ = -1;
}

std::string NewmarkEngine::name() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(discrete_.get());
    if (!modal) return "sparse";
    return modal->complete() ? "modal-complete" : "modal-" + std::to_string(modal->size());
}

double NewmarkEngine::firstFrequency() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(discrete_.get());
    double omega2;
    if (modal) {
        omega2 = modal->omega2()[0];
    } else {
        Eigen::MatrixXd phi;
        Eigen::VectorXd w2;
        lowestModes(discrete_->clamped(), 1, phi, w2);
        omega2 = w2[0];
    }
    return std::sqrt(omega2) / (2.0 * M_PI);
}

double NewmarkEngine::kappa() const {
    if (kappa_ < 0.0) {
        const auto* modal = dynamic_cast<const ModalPlate*>(discrete_.get());
        kappa_ = modal && modal->complete() ? modal->omega2().maxCoeff() : largestEigenvalue(discrete_->clamped());
    }
    return kappa_;
}

}  // namespace plate
