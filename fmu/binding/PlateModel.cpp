// The PlateImpact model binding: plate::PlateSimulation behind fmu::Model. The FMI layer
// (Instance.cpp) calls it; it knows the plate's variables (PlateVariables.cpp), builds the
// simulation from them, and feeds it the inputs each communication step. No numerics here.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "core/Model.h"
#include "binding/PlateAdvice.h"
#include "binding/PlateArrays.h"
#include "PlateImpactGuid.h"  // generated at build time: FMU_GUID
#include "binding/PlateVariables.h"

namespace plateimpact {

namespace {

const fmu::ModelInfo kInfo{
    "PlateImpact",
    "PlateImpact",
    "Kirchhoff plate clamped along x = 0 and free elsewhere, between two flat obstacles; C1 finite elements "
    "(Argyris or reduced FVS), Newmark scheme with exact per-step contact QP at a fixed time step dt",
    /*canInterpolateInputs=*/true,
    /*maxOutputDerivativeOrder=*/0,
    /*canGetAndSetFMUstate=*/true,
    /*defaultStopTime=*/0.2,
    /*defaultStepSize=*/0.001,
    R"(<h2>What it computes</h2>
<p>A Kirchhoff&ndash;Love plate [0, length] &times; [0, width], clamped along x = 0 and free elsewhere, between a flat
obstacle below (obstacle_lower) and one above (obstacle_upper). The master moves the clamped edge
(base_displacement) and may press on the plate (load, a uniform pressure). C1 finite elements (Argyris
triangles or reduced Fraeijs de Veubeke&ndash;Sander quadrilaterals), the Newmark scheme (gamma = 1/2, beta)
at the fixed internal step dt, and one exact contact QP per step keeping every mesh vertex between the
obstacles (Pozzolini, Renard &amp; Salaün 2013). Beyond the paper: a singular mass (mass = singular_p0)
whose impacts keep their energy as dt &rarr; 0, a restitution coefficient and Rayleigh damping.</p>
<h2>The default scene</h2>
<p>A 1.2 &times; 0.4 &times; 0.01 m steel plate (E = 210 GPa, &nu; = 0.3, &rho; = 7770 kg/m<sup>3</sup>),
14 &times; 5 cells (140 Argyris triangles), obstacles at &plusmn;0.1 m, dt = 1e-5 s; driven with
base_displacement = 0.09 sin(2&pi; 10 t) m it hits the obstacles from t &asymp; 0.05 s on.</p>
<h2>Using it</h2>
<ul>
<li>Any communication step up to a tenth of the plate's first period (T1/10: 0.0163 s for the default plate): the
scheme keeps its fixed grid of dt and interpolates the outputs between grid points; steps that are whole multiples
of dt (relative tolerance 1e-9) run exactly on the grid. A longer step over which an input changed is warned of
once: its samples cannot carry what the input does at the plate's frequencies.</li>
<li>Inputs: {fmi2:give their first and second derivatives (fmiXSetRealInputDerivatives) when you can; otherwise
}the FMU {fmi2:extrapolates}{fmi3:holds or extrapolates} the communicated values (base_input_mode, load_input_mode).</li>
<li>Switches (element, mass, base_drive, base_input_mode, load_input_mode) are Integers: the description of each
lists its items, e.g. base_drive = 2 drives the clamp by base_velocity.</li>
{fmi3:<li>Early return: a master that grants it at fmiXInstantiateCoSimulation gets every contact onset and
release as an event, exactly on the internal grid (lastSuccessfulTime), the impact in the outputs there.</li>
<li>The array output vertex_displacement holds the deflection at every mesh vertex
([vertex_output][vertices_x][vertices_y]); vertices_x = nx + 1 and vertices_y = ny + 1 are views of nx and ny;
vertex_output = 0 (before initialization) leaves the array empty.</li>
<li>Terminals (terminalsAndIcons/terminalsAndIcons.xml): <code>clamp</code> (kind
org.plateimpact.TranslationalFlange, matchingRule bus: base_displacement s, base_velocity v, base_acceleration a
in, clamp_force f out), <code>armature</code> (the same kind, plug: drive_force f in, clamp_displacement s,
clamp_velocity v, clamp_acceleration a out) and <code>line</code> (kind org.plateimpact.TransmissionLineEnd,
matchingRule org.plateimpact.crossed: tlm_wave_in wave_in, tlm_wave_out wave_out, tlm_impedance impedance; one
end's wave_out feeds the other's wave_in, the impedances are equal). A TranslationalFlange's members connect by
memberName, each output to the partner's input of the same memberName (all are signals: the connection is
causal).</li>
}<li>Outputs are absolute displacements; the energy ledger energy = E0 + energy_input &minus; energy_dissipated
&minus; energy_damped holds to roundoff.</li>
</ul>
<p>Reference experiments to validate this FMU on your platform and master (FMI-LS-REF):
<a href="fmi-ls-ref.html">fmi-ls-ref.html</a>.</p>
<h2>Limits: what the FMU refuses</h2>
<p>Each refusal returns fmiXError and logs what was wrong and the allowed range (category logStatusError).
Parameters outside the min/max of the table below (poisson_ratio and the obstacles' heights exclude their ends:
0 &lt; poisson_ratio &lt; 0.5, obstacle_lower &lt; 0 &lt; obstacle_upper); beta &lt; 0.25 beyond the stability
bound on dt; a singular mass with modes &gt; 0, beta &lt; 0.25 or without massless directions at every contact
vertex; an instance whose estimated memory exceeds memory_limit; inputs outside their min/max, NaN or Inf; a
clamp driven past an obstacle; a communication step shorter than 1e-9 dt; calls outside the states FMI
{fmi2:2.0}{fmi3:3.0} allows; FMU states of another build, of another CPU architecture (both platforms named) or damaged (XXH64 checksum); time_scheme = conserving
with mass = consistent or restitution &gt; 0. With the clamp carried (base_drive = force: an armature inside the
FMU; tlm: the end of a transmission line to a partner FMU): armature_mass &le; 0, tlm_impedance &le; 0, a singular
mass, a second input driving the clamp (a motion input with force or tlm, a drive_force with a motion drive),
communication steps that are not whole multiples of dt.</p>
)",
    /*stateMagic=*/"PLATEIMP",
};

std::string format(const char* fmt, double a, double b, double c = 0.0) {
    char text[400];
    std::snprintf(text, sizeof text, fmt, a, b, c);
    return text;
}

class PlateModel final : public fmu::Model {
public:
    const fmu::ModelInfo& info() const override { return kInfo; }
    const std::vector<fmu::Variable>& variables() const override { return plateVariables(); }

    double get(const fmu::Variable& v) const override {
        adviseOnRead(v.vr, v.name);
        return getValue(values_, v);
    }
    void set(const fmu::Variable& v, double x) override {
        setValue(values_, v, x);
        // Set while the simulation runs (not the start value of initialization mode): the drive is driven.
        if (simulation_ && v.causality == fmu::Causality::Input && values_.inputPort(v.vr) == &drivePort())
            driveSet_ = true;
    }

    // FMI 3.0: the vertex displacements as an array, early return at contact onset and release.
    const std::vector<fmu::StructuralParameter>& structuralParameters() const override {
        return plateStructuralParameters();
    }
    const std::vector<fmu::ArrayOutput>& arrayOutputs() const override { return plateArrayOutputs(); }
    const std::vector<fmu::Terminal>& terminals() const override { return plateTerminals(); }
    void getArray(const fmu::ArrayOutput& a, double* out, std::size_t n) const override {
        if (!simulation_) throw fmu::ModelError("internal error: no simulation to read an array from");
        adviseOnRead(a.vr, a.name);
        getPlateArray(*simulation_, a, out, n);
    }
    // FMI 3.0 intermediate update with inputs: the clamp's height and the load, set by the master at
    // each internal grid point, are the values the step to that point takes (no reconstruction).
    bool takesIntermediateValue(const fmu::Variable& v) const override {
        return v.vr == kVrBaseDisplacement || v.vr == kVrLoad;
    }
    void setIntermediate(const fmu::Variable& v, double x) override {
        if (v.vr == kVrBaseDisplacement && values_.baseDrive != BaseDrive::Displacement)
            throw fmu::ModelError(
                std::string("base_displacement set in the intermediate update callback, but base_drive "
                            "= ") +
                driveName() + " drives the clamp: only the drive's own input moves it");
        (v.vr == kVrLoad ? sampledLoad_ : sampledBase_) = {true, x};
    }
    bool hasEvents() const override { return true; }
    bool providesIntermediateUpdate() const override { return true; }
    double fixedInternalStepSize() const override { return plate::PlateParameters{}.dt; }
    bool doStepUntilEvent(double t, double h) override {
        stopAtContactChange_ = true;
        endedAtEvent_ = false;
        try {
            doStep(t, h);
        } catch (...) {
            stopAtContactChange_ = false;
            throw;
        }
        stopAtContactChange_ = false;
        if (endedAtEvent_)
            trace(std::string(values_.outputs.contactVertices > 0 ? "contact onset" : "contact release") +
                  format(" at t = %.17g", simulation_->time(), 0.0));
        return endedAtEvent_;
    }

    void setInputDerivative(const fmu::Variable& v, int order, double x) override {
        InputPort& port = *values_.inputPort(v.vr);
        (order == 1 ? port.signal.d1 : port.signal.d2) = x;
        port.derivativesGiven = true;
    }

    void build() override {
        // A plate::ParameterError names the parameter, its value and the allowed range; a
        // plate::ResourceError the estimate and memory_limit. The estimate and the progress of
        // long initializations go to the user (category logInfo).
        std::string estimate = "no estimate was made";
        const plate::ProgressLog log = [this, &estimate](const std::string& line) {
            if (estimate == "no estimate was made") estimate = line;
            inform(line);
        };
        requireOneDrive();
        try {
            simulation_ = std::make_unique<plate::PlateSimulation>(
                values_.parameters, values_.baseDisplacement.signal.value, values_.load.signal.value, log);
        } catch (const std::bad_alloc&) {
            // The estimate is an estimate: what fails anyway is reported, never an abort.
            throw fmu::ModelError("out of memory while building the simulation (std::bad_alloc) after " + estimate +
                                  "; lower memory_limit below what this machine can give, or use a coarser mesh");
        }
        builtWith_ = configuration();
        simulationBase0_ = values_.baseDisplacement.signal.value;
        clampPosition_ = simulationBase0_;
        clampVelocity_ = 0.0;
        refreshOutputs();
        const plate::PlateParameters& p = values_.parameters;
        trace(format("simulation built (nx = %g, ny = %g, dt = %g s)", p.nx, p.ny, p.dt));
        warnOfCoarseStep();
        driveSet_ = interpolationWarned_ = errorWarned_ = cappedWarned_ = stressReadWarned_ = longStepWarned_ = false;
        warnOfUnusedTolerance();
        say(capAdvice(p));
        warnOfProbes();
    }
    void terminate() override {
        // A drive the master never set: the clamp stayed where it started (a CSV column missing or
        // misspelled runs to the end without an error otherwise).
        if (!driveSet_ && simulation_->stepCount() > 0 && !carried())
            warn(std::string(driveName()) +
                 " (base_drive) was never set during this run: the clamp stayed at its start value, so only the "
                 "load moved the plate; if an input file or a connection should drive it, check the input's name");
    }
    bool built() const override { return simulation_ != nullptr; }
    void drop() override {
        simulation_.reset();
        refreshOutputs();
    }
    double time() const override { return simulation_ ? simulation_->time() : 0.0; }

    void doStep(double t, double h) override {
        if (!simulation_) throw fmu::ModelError("internal error: no simulation in state stepComplete");
        plate::StepPlan plan;
        try {
            plan = simulation_->plan(h);  // any h the grid resolves (docs/theory.md §15)
        } catch (const plate::StepError& e) {
            throw fmu::ModelError(e.what());
        }
        // The values the master set since the last step extend the histories (a step it set
        // nothing for continues the reconstruction); a master that set no derivatives gets the
        // inputs reconstructed from them (docs/theory.md §8). The history's times are the
        // model's own: a master's roundoff in t does not reach the divided differences.
        requireOneDrive();
        if (carried() && (!plan.endsOnGrid || plan.offset != 0.0))
            throw fmu::ModelError(format(
                "communicationStepSize h = %.17g is not a whole multiple of dt = %g: with base_drive = force or tlm "
                "the clamp is carried inside the FMU, which takes communication steps on the grid of dt only",
                h, values_.parameters.dt));
        const double now = simulation_->time();
        if (!plan.endsOnGrid && plan.steps < 2 && !interpolationWarned_) {
            interpolationWarned_ = true;
            warn(
                format("communicationStepSize h = %.17g is shorter than two internal steps of dt = %g: the outputs "
                       "are interpolated between the grid points around t (docs/theory.md §15); for the scheme's own "
                       "values take h a whole multiple of dt, or a smaller dt",
                       h, values_.parameters.dt));
        }
        adviseOnStep(h, t);
        for (InputPort* port : ports()) {
            port->beginStep(now);
            port->reach = plan.offset + double(plan.steps) * values_.parameters.dt;  // the last grid point read
        }
        try {
            const plate::InputSignal base = clampSignal(now, plan.span);
            const plate::InputSignal load = values_.load.stepSignal(now, plan.span, -plate::kMaxLoad, plate::kMaxLoad);
            advanceClamp(base, communicate(plan, base, load));
        } catch (const plate::StepError& e) {
            refreshOutputs();  // the simulation stays at its last good step (for debugging)
            throw fmu::ModelError(
                format("step from t = %.17g failed at t = %.17g: ", t, t + simulation_->time() - now) + e.what());
        }
        refreshOutputs();
        warnOfErrorEstimate();
        trace(format("t = %.17g, h = %.17g, %g steps", t, h, double(plan.steps)));
    }

    // The model's part of an FMU state: per input the derivatives, whether they were given,
    // whether the value was set since the last step, the time its signal starts and the history; then whether a simulation exists, the base it was built with and its state.
    void saveState(std::vector<double>& out) const override {
        for (const InputPort* port : const_cast<PlateModel*>(this)->ports()) {
            out.insert(out.end(), {port->signal.d1, port->signal.d2, port->derivativesGiven ? 1.0 : 0.0,
                                   port->fresh ? 1.0 : 0.0, port->signalTime});
            port->history.serialize(out);
        }
        out.insert(out.end(), {clampPosition_, clampVelocity_});
        out.push_back(simulation_ ? 1.0 : 0.0);
        out.push_back(simulationBase0_);
        if (simulation_) {
            const std::vector<double> state = simulation_->saveState();
            out.insert(out.end(), state.begin(), state.end());
        }
    }

    void restoreState(const double*& in, const double* end) override {
        const auto take = [&](std::size_t n, const char* what) {
            if (end - in < static_cast<std::ptrdiff_t>(n))
                throw fmu::ModelError(std::string("data end before ") + what);
            const double* at = in;
            in += n;
            return at;
        };
        for (InputPort* port : ports()) {
            const double* x = take(5 + plate::InputHistory::kSerializedSize, "an input's derivatives and history");
            if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || (x[2] != 0.0 && x[2] != 1.0) ||
                (x[3] != 0.0 && x[3] != 1.0) || !std::isfinite(x[4]))
                throw fmu::ModelError("an input's derivatives, set flags or time are not finite or out of range");
            port->signal.d1 = x[0];
            port->signal.d2 = x[1];
            port->derivativesGiven = x[2] == 1.0;
            port->fresh = x[3] == 1.0;
            port->signalTime = x[4];
            try {
                port->history = plate::InputHistory::deserialize(x + 5);
            } catch (const std::invalid_argument& e) {
                throw fmu::ModelError(e.what());
            }
        }
        const double* clamp = take(2, "the clamp's motion");
        if (!std::isfinite(clamp[0]) || !std::isfinite(clamp[1]))
            throw fmu::ModelError("the clamp's motion is not finite");
        clampPosition_ = clamp[0];
        clampVelocity_ = clamp[1];
        const double* flags = take(2, "the simulation flag");
        if ((flags[0] != 0.0 && flags[0] != 1.0) || !std::isfinite(flags[1]))
            throw fmu::ModelError("simulation flag or initial base displacement out of range");
        if (flags[0] == 0.0) {
            if (in != end) throw fmu::ModelError("simulation state without a simulation");
            drop();
            return;
        }
        const std::vector<double> state(in, end);
        in = end;
        // Equal configurations (every parameter of the table, and the initial base) reuse the
        // discretization; another one is built for the state's parameters.
        if (!simulation_ || builtWith_ != configuration() || simulationBase0_ != flags[1]) {
            auto simulation = std::make_unique<plate::PlateSimulation>(values_.parameters, flags[1]);
            simulation->restoreState(state);
            simulation_ = std::move(simulation);
            builtWith_ = configuration();
        } else {
            simulation_->restoreState(state);
        }
        simulationBase0_ = flags[1];
        refreshOutputs();
    }

private:
    // The values of every parameter, walking the table: two simulations built from equal
    // configurations (and the same initial base) are the same discretization.
    std::vector<double> configuration() const {
        std::vector<double> out;
        for (const fmu::Variable& v : plateVariables())
            if (v.causality == fmu::Causality::Parameter) out.push_back(getValue(values_, v));
        return out;
    }
    void refreshOutputs() {
        values_.outputs = simulation_ ? simulation_->outputs() : plate::PlateOutputs{};
        values_.simulation = simulation_.get();
        values_.portValid = false;
        values_.fieldValid = false;
        values_.plateFieldValid = false;
    }

    std::array<InputPort*, 6> ports() {
        return {&values_.baseDisplacement, &values_.baseVelocity, &values_.baseAcceleration, &values_.load,
                &values_.driveForce,       &values_.tlmWaveIn};
    }
    bool carried() const { return values_.baseDrive == BaseDrive::Force || values_.baseDrive == BaseDrive::Tlm; }
    // The motion input base_drive chooses (carried clamps: their drive).
    InputPort& drivePort() {
        switch (values_.baseDrive) {
            case BaseDrive::Velocity: return values_.baseVelocity;
            case BaseDrive::Acceleration: return values_.baseAcceleration;
            case BaseDrive::Force: return values_.driveForce;
            case BaseDrive::Tlm: return values_.tlmWaveIn;
            case BaseDrive::Displacement: break;
        }
        return values_.baseDisplacement;
    }
    const char* driveName() const {
        static const char* const names[] = {
            "", "base_displacement", "base_velocity", "base_acceleration", "drive_force", "tlm_wave_in"};
        return names[static_cast<int>(values_.baseDrive)];
    }
    // dt against the plate's first period (plate::PlateParameters::firstFrequencyEstimate; dt above
    // T1/2 is refused by the solver): fewer than 20 steps per period give visibly wrong amplitudes
    // and phases. Once per build.
    void warnOfCoarseStep() {
        const plate::PlateParameters& p = values_.parameters;
        const double period = 1.0 / p.firstFrequencyEstimate();
        if (p.dt <= period / 20.0) return;
        warn(format("dt = %g s is %.3g of the plate's first period T1 = %.4g s", p.dt, p.dt / period, period) +
             " (fewer than 20 steps per period): the outputs resolve the first mode only roughly; take dt <= " +
             format("%.4g s (T1/20) for accurate results", period / 20.0, 0.0));
    }
    // The checks of PlateAdvice.h, each said once per build.
    void say(const std::string& advice) const {
        if (!advice.empty()) warn(advice);
    }
    void adviseOnRead(fmu::ValueReference vr, const char* name) const {
        if (stressReadWarned_ || !isStressOutput(vr)) return;
        stressReadWarned_ = !values_.parameters.stressOutputs;
        say(stressReadAdvice(name, values_.parameters));
    }
    void adviseOnStep(double h, double t) {
        if (longStepWarned_ || h <= longestCommunicationStep(values_.parameters)) return;
        InputPort& drive = drivePort();
        const char* input = inputChanged(drive) ? driveName() : inputChanged(values_.load) ? "load" : nullptr;
        if (!input) return;
        longStepWarned_ = true;
        say(longStepAdvice(values_.parameters, h, t, input));
    }
    // A tolerance or sub-step count only the flow law uses (docs/theory.md §21–22), set for another
    // scheme: said at build.
    void warnOfUnusedTolerance() {
        const plate::PlateParameters& p = values_.parameters;
        if (p.timeScheme == plate::TimeScheme::Flow) return;
        if (p.tolerance > 0.0)
            warn(
                format("tolerance = %g m is used by time_scheme = flow only (3): this run's scheme ignores it, and "
                       "error_estimate stays 0",
                       p.tolerance, 0.0));
        const plate::PlateParameters defaults;
        if (p.contactSubsteps != defaults.contactSubsteps)
            warn(format("contact_substeps = %g is used by time_scheme = flow only (3): this run's scheme ignores it",
                        double(p.contactSubsteps), 0.0));
        if (p.maxContactSubsteps != defaults.maxContactSubsteps)
            warn(
                format("max_contact_substeps = %g is used by time_scheme = flow with a tolerance only: this run's "
                       "scheme ignores it",
                       double(p.maxContactSubsteps), 0.0));
    }
    // Probes (docs/theory.md §23) that are not what they seem: one placed but not counted (it reads 0),
    // one counted but on the clamped edge x = 0 (unplaced: the default (0, 0)), which moves with the clamp.
    void warnOfProbes() {
        const plate::PlateParameters& p = values_.parameters;
        for (int k = 0; k < plate::kProbeCount; ++k) {
            const double x = p.probeX[std::size_t(k)], y = p.probeY[std::size_t(k)];
            const std::string name = "probe_" + std::to_string(k + 1);
            if (k >= p.probeCount && (x != 0.0 || y != 0.0))
                warn(name + format(" is placed at (%g, %g) m", x, y) +
                     format(" but probe_count = %g leaves it off: it reads 0; set probe_count >= %g to compute it",
                            double(p.probeCount), double(k + 1)));
            if (k < p.probeCount && x == 0.0)
                warn(name +
                     format(" at (%g, %g) m is counted (probe_count = %g) but lies on the clamped edge x = 0", x, y,
                            double(p.probeCount)) +
                     ": it reads the clamp's motion; place it with " + name + "_x > 0 (" + name +
                     (y == 0.0 ? "_x and _y were never set)" : "_x is 0)"));
        }
    }
    // tolerance > 0 (docs/theory.md §22): the contact steps' accumulated error estimate passing the
    // tolerance, and a contact step the cap bounded, are each said once per build.
    void warnOfErrorEstimate() {
        const plate::PlateParameters& p = values_.parameters;
        const plate::PlateOutputs& o = values_.outputs;
        if (p.tolerance <= 0.0 || p.timeScheme != plate::TimeScheme::Flow) return;
        if (!errorWarned_ && o.errorEstimate > p.tolerance) {
            errorWarned_ = true;
            warn(format("error_estimate = %.3g m passed tolerance = %.3g m at t = %.17g", o.errorEstimate, p.tolerance,
                        simulation_->time()) +
                 ": the contact phases so far add up to more than the tolerance (it bounds what about 3 ms of "
                 "contact adds); later outputs are this much less certain (docs/performance.md)");
        }
        if (!cappedWarned_ && o.cappedSteps > 0) {
            cappedWarned_ = true;
            warn(format("a contact step before t = %.17g needed more than max_contact_substeps = %g sub-steps for "
                        "its target",
                        simulation_->time(), double(p.maxContactSubsteps)) +
                 "; raise max_contact_substeps (capped_steps counts such steps; error_estimate includes them)");
        }
    }
    // A clamp moved by one input only (docs/theory.md §16–18): a force-driven or line-carried clamp
    // whose motion inputs are set as well, or a motion-driven one given a force, is refused.
    void requireOneDrive() const {
        const double base0 = simulation_ ? simulationBase0_ : values_.baseDisplacement.signal.value;
        const struct {
            const char* name;
            double value;
            bool used;
        } inputs[] = {
            {"base_displacement", values_.baseDisplacement.signal.value - base0,
             values_.baseDrive == BaseDrive::Displacement},
            {"base_velocity", values_.baseVelocity.signal.value, values_.baseDrive == BaseDrive::Velocity},
            {"base_acceleration", values_.baseAcceleration.signal.value, values_.baseDrive == BaseDrive::Acceleration},
            {"drive_force", values_.driveForce.signal.value, values_.baseDrive == BaseDrive::Force},
            {"tlm_wave_in", values_.tlmWaveIn.signal.value, values_.baseDrive == BaseDrive::Tlm},
        };
        const bool motion = !carried();
        for (const auto& input : inputs) {
            if (input.used || input.value == 0.0) continue;
            const bool inputIsMotion = input.name[0] == 'b';
            if (motion && inputIsMotion) continue;  // the motion drives ignore each other's inputs (§16)
            static const char* const drives[] = {"", "displacement", "velocity", "acceleration", "force", "tlm"};
            throw fmu::ModelError(
                std::string("invalid parameter base_drive = ") + drives[static_cast<int>(values_.baseDrive)] +
                " with " + input.name + " set (" + format("%.17g", input.value, 0.0) +
                (input.name == std::string("base_displacement") ? " from the initial position" : "") +
                "): the clamp is driven by one input only; a clamp carried by the armature (force) or by the line "
                "(tlm) is not also moved by a motion input, nor a motion-driven clamp by a force (allowed: set "
                "base_drive to the input you drive, leave the others at 0)");
        }
    }

    // The clamp's path over a step of length span from the communication time `now` (docs/theory.md
    // §16): the displacement input as it comes, or the exact integral of the velocity (once) or
    // the acceleration (twice) input from the clamp's position and velocity there. A
    // reconstructed clamp stays between the obstacles the master's values respect.
    plate::InputSignal clampSignal(double now, double span) {
        const plate::PlateParameters& p = simulation_->parameters();
        const double lower = p.obstacleLowerEnabled ? p.obstacleLower : -plate::kMaxDisplacement;
        const double upper = p.obstacleUpperEnabled ? p.obstacleUpper : plate::kMaxDisplacement;
        switch (values_.baseDrive) {
            case BaseDrive::Velocity:
                return values_.baseVelocity.stepSignal(now, span, -kMaxBaseVelocity, kMaxBaseVelocity)
                    .integral(clampPosition_);
            case BaseDrive::Acceleration:
                return values_.baseAcceleration.stepSignal(now, span, -kMaxBaseAcceleration, kMaxBaseAcceleration)
                    .integral(clampVelocity_)
                    .integral(clampPosition_);
            case BaseDrive::Force:  // the drive force on the armature (§18)
                return values_.driveForce.stepSignal(now, span, -plate::kMaxCarrierForce, plate::kMaxCarrierForce);
            case BaseDrive::Tlm:  // the wave, held: what the partner launched is what arrives (§19)
                values_.tlmWaveIn.history.reached(values_.tlmWaveIn.signal.value);
                return plate::InputSignal{values_.tlmWaveIn.signal.value, 0.0, 0.0};
            case BaseDrive::Displacement:
            default: return values_.baseDisplacement.stepSignal(now, span, lower, upper);
        }
    }
    // simulation_->communicate, or with stopAtContactChange_ (FMI 3.0 early return) up to the
    // first contact onset or release on the grid. Returns the span of the step as taken; after
    // an early end, every input ends the step where its signal stands then.
    double communicate(const plate::StepPlan& plan, const plate::InputSignal& base, const plate::InputSignal& load) {
        // FMI 3.0 intermediate update: the outputs at every grid point inside the step, and the
        // master's wish to end the step early (honoured where early return is granted).
        plate::PlateSimulation::GridPointObserver observer;
        returnRequested_ = false;
        if (intermediateUpdate) {
            returnAt_ = HUGE_VAL;
            observer = [this] {
                refreshOutputs();
                const double t = simulation_->time();
                returnAt_ = std::min(returnAt_, intermediateUpdate(t));
                returnRequested_ = t >= returnAt_ - 1e-9 * values_.parameters.dt;
                return returnRequested_;
            };
        }
        // FMI 3.0 intermediate update with inputs: the master's values at each grid point, where it set them.
        plate::PlateSimulation::InputSampler sampler;
        if (intermediateInputs) {
            const double now = simulation_->time();
            sampler = [this, now](double s, double& z, double& p) {
                sampledBase_ = sampledLoad_ = {false, 0.0};
                intermediateInputs(now + s);
                if (sampledBase_.first) z = sampledBase_.second;
                if (sampledLoad_.first) p = sampledLoad_.second;
            };
        }
        simulation_->setInputSampler(std::move(sampler));
        if (!stopAtContactChange_ || carried()) {  // a carried clamp: no early return (§18)
            simulation_->communicate(plan, base, load, observer);
            return plan.span;
        }
        const double start = simulation_->time();
        const bool endedEarly = simulation_->communicateUntilContactChange(plan, base, load, observer);
        endedAtEvent_ = endedEarly && !returnRequested_;
        if (!endedEarly) return plan.span;
        const double span = simulation_->time() - start;
        if (simulation_->time() == plan.end) return plan.span;  // at the end anyway
        values_.load.history.reached(load.at(span));
        switch (values_.baseDrive) {  // the drive's own signal inside the clamp's (clampSignal)
            case BaseDrive::Velocity:
                values_.baseVelocity.history.reached(plate::InputSignal{base.d1, base.d2, base.d3, base.d4}.at(span));
                break;
            case BaseDrive::Acceleration:
                values_.baseAcceleration.history.reached(plate::InputSignal{base.d2, base.d3, base.d4}.at(span));
                break;
            case BaseDrive::Displacement:
            default: values_.baseDisplacement.history.reached(base.at(span));
        }
        return span;
    }
    void advanceClamp(const plate::InputSignal& base, double span) {
        if (values_.baseDrive == BaseDrive::Displacement || carried()) return;
        clampPosition_ = base.at(span);
        clampVelocity_ = base.d1 + span * (base.d2 + span * (0.5 * base.d3 + span * base.d4 / 6.0));
    }

    PlateValues values_;
    std::unique_ptr<plate::PlateSimulation> simulation_;
    std::vector<double> builtWith_;  // configuration() when simulation_ was built
    double simulationBase0_ = 0.0;  // base displacement the simulation was built with
    // The clamp at the communication time when a velocity or an acceleration drives it.
    double clampPosition_ = 0.0, clampVelocity_ = 0.0;
    bool driveSet_ = false;  // the drive input was set during the run (warned at terminate otherwise)
    bool interpolationWarned_ = false;  // the warning of steps shorter than two grid steps, once
    bool errorWarned_ = false;  // the warning of the error estimate past the tolerance, once
    bool cappedWarned_ = false;  // the warning of a contact step the sub-step cap bounded, once
    mutable bool stressReadWarned_ = false;  // a stress output read while stress_outputs = false, once
    bool longStepWarned_ = false;  // a communication step too long for the plate and the inputs, once
    bool stopAtContactChange_ = false;  // inside doStepUntilEvent
    bool endedAtEvent_ = false;  // the last step of doStepUntilEvent ended at a contact change
    bool returnRequested_ = false;  // ... or where the master's intermediate update asked
    double returnAt_ = HUGE_VAL;  // the earliest early return time the master asked for in this step
    // Inputs the master set in the intermediate update callback for the grid point ahead (set, value).
    std::pair<bool, double> sampledBase_{false, 0.0}, sampledLoad_{false, 0.0};
};

}  // namespace

}  // namespace plateimpact

namespace fmu {
std::unique_ptr<Model> createModel() { return std::make_unique<plateimpact::PlateModel>(); }
const char* modelGuid() { return FMU_GUID; }
}  // namespace fmu
