#pragma once
// The conserving scheme behind PlateSimulation (time_scheme = conserving, docs/theory.md §17):
// the condensed singular plate stepped by ConservingStepper. The output points are constraint
// rows (the corners and a vertex free_edge_mid among the contact vertices, a free_edge_mid
// between vertices as a row of its own), so every reported height is within the obstacles.
#include <array>
#include <memory>

#include "schemes/ConservingStepper.h"
#include "schemes/PlateEngine.h"

namespace plate {

class ConservingEngine final : public PlateEngine {
public:
    // probeRows: the rows of corner_1, corner_2 and free_edge_mid; vertexRows: the row of each mesh
    // vertex (−1 for a clamped vertex).
    ConservingEngine(std::unique_ptr<ConservingStepper> stepper, std::array<int, 3> probeRows,
                     std::vector<int> vertexRows);

    void setLoadAtStart(double p0) override { stepper_->setLoadAtStart(p0); }
    void step(double zNext, double pNext) override { stepper_->step(zNext, pNext); }
    long long stepCount() const override { return stepper_->state().step; }
    double baseDisplacement() const override { return stepper_->state().z; }
    int contactVertices() const override { return stepper_->state().contactRows; }
    PlateOutputs outputs(bool port) const override;
    std::vector<double> vertexDisplacements() const override;
    std::vector<double> saveState() const override { return stepper_->serialize(); }
    void restoreState(const std::vector<double>& state) override { stepper_->setState(stepper_->deserialize(state)); }
    std::string name() const override;
    double firstFrequency() const override;
    double kappa() const override { return stepper_->plate().omega2.maxCoeff(); }

    const ConservingStepper& stepper() const { return *stepper_; }

private:
    std::unique_ptr<ConservingStepper> stepper_;
    std::array<int, 3> probeRows_;
    std::vector<int> vertexRows_;
};

}  // namespace plate
