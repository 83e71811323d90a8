#pragma once
// The paper's scheme behind PlateSimulation: the Newmark–contact stepper (3.3)/(3.6) with its
// impact laws over a DiscretePlate (full space or modal), its outputs and the port (§14).
#include <memory>

#include "plate/DiscretePlate.h"
#include "schemes/NewmarkContactStepper.h"
#include "schemes/PlateEngine.h"

namespace plate {

class NewmarkEngine final : public PlateEngine {
public:
    // The probes are corner_1, corner_2 and free_edge_mid in the plate's coordinates.
    NewmarkEngine(std::shared_ptr<const DiscretePlate> discrete, std::unique_ptr<NewmarkContactStepper> stepper,
                  double length, double width, int vertexCount);

    void setLoadAtStart(double p0) override { stepper_->setLoadAtStart(p0); }
    void step(double zNext, double pNext) override { stepper_->step(zNext, pNext); }
    long long stepCount() const override { return stepper_->state().step; }
    double baseDisplacement() const override { return stepper_->state().z; }
    int contactVertices() const override { return stepper_->state().contactVertices; }
    PlateOutputs outputs(bool port) const override;
    std::vector<double> vertexDisplacements() const override;
    std::vector<double> saveState() const override { return serialize(stepper_->state()); }
    void restoreState(const std::vector<double>& state) override;
    std::string name() const override;
    double firstFrequency() const override;
    double kappa() const override;

    NewmarkContactStepper& stepper() { return *stepper_; }
    // The clamp's load at t = 0: the initial static state's reaction (force N, moment N·m).
    void setInitialReaction(double force, double moment) {
        initialForce_ = force;
        initialMoment_ = moment;
    }

private:
    void portOutputs(PlateOutputs& o) const;

    std::shared_ptr<const DiscretePlate> discrete_;
    std::unique_ptr<NewmarkContactStepper> stepper_;
    int vertexCount_;
    PointProbe corner1_, corner2_, freeEdgeMid_;
    double initialForce_ = 0.0, initialMoment_ = 0.0;
    mutable long long energyStep_ = -1;
    mutable double energyCache_ = 0.0, kappa_ = -1.0;
};

}  // namespace plate
