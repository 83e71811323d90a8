#pragma once
// One time scheme of the plate behind PlateSimulation (docs/architecture.md): Newmark with its
// impact laws (NewmarkScheme), the conserving midpoint rule (MidpointScheme, docs/theory.md §17)
// or the exact modal flow with contact sub-steps (FlowScheme, §21). PlateSimulation owns the
// communication grid, the inputs and the interpolation between grid points; a scheme owns its
// state, its outputs at the grid point it stands on, and that state's flat form. Schemes are
// made in one place: makeScheme (PlateSimulation.cpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "schemes/PlateOutputs.h"

namespace plate {

class Armature;

class Scheme {
public:
    virtual ~Scheme() = default;

    // The load input at t = 0, known only when the master starts stepping (before the first step).
    virtual void setLoadAtStart(double p0) = 0;
    // One internal step to t_{n+1} with the base at zNext and the pressure pNext there. Throws
    // StepError without changing the state if the step cannot be taken.
    virtual void step(double zNext, double pNext) = 0;

    virtual long long stepCount() const = 0;
    virtual double baseDisplacement() const = 0;  // z(t_n)
    virtual double clampHeight(int level) const = 0;  // z at the output level (0) or one of the two before it
    virtual int contactVertices() const = 0;  // points held by an obstacle at t_n
    // The outputs at t_n; `port` adds the port's fields (docs/theory.md §14).
    virtual PlateOutputs outputs(bool port) const = 0;
    // Absolute height of every mesh vertex at t_n.
    virtual std::vector<double> vertexDisplacements() const = 0;
    // The recovery functionals [first, first + out.size()) — the probes and stress samples
    // PlateSimulation gave the scheme at construction (docs/theory.md §23) — of the displacement
    // relative to the clamp at the output level (0) or one of the two before it (1, 2).
    virtual void recover(Eigen::Index first, int level, Eigen::Ref<Eigen::VectorXd> out) const = 0;

    virtual std::vector<double> saveState() const = 0;
    virtual void restoreState(const std::vector<double>& state) = 0;  // throws std::invalid_argument

    virtual std::string name() const = 0;  // "sparse", "modal-complete", "modal-<m>", "conserving-…"
    virtual double firstFrequency() const = 0;  // Hz, lowest mode of the plate as stepped
    virtual double kappa() const = 0;  // largest ω² of the plate as stepped, s⁻²

    // The clamp's carrier (docs/theory.md §18–19), where the scheme carries the clamp: none by default.
    virtual Armature* carrier() { return nullptr; }
    const Armature* carrier() const { return const_cast<Scheme*>(this)->carrier(); }
    virtual CarrierOutputs carrierOutputs() const { return {}; }  // zero without a carrier
};

}  // namespace plate
