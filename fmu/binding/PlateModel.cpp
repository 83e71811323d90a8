// The PlateImpact model binding: plate::PlateSimulation behind fmu::Model. The FMI layer
// (Instance.cpp) calls it; it knows the plate's variables (PlateVariables.cpp), builds the
// simulation from them, and feeds it the inputs each communication step. No numerics here.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <utility>

#include "core/Model.h"
#include "binding/BaseDrives.h"
#include "binding/PlateAdvice.h"
#include "binding/PlateArrays.h"
#include "binding/PlateWarnings.h"
#include "plate/Stops.h"
#include "PlateImpactGuid.h"  // generated at build time: FMU_GUID
#include "binding/PlateVariables.h"
#include "CheckedPlate.h"

namespace plateimpact {

namespace {

class PlateModel final : public fmu::Model {
public:
    const fmu::ModelInfo& info() const override { return plateInfo(); }
    const std::vector<fmu::Variable>& variables() const override { return plateVariables(); }

    double get(const fmu::Variable& v) const override {
        advisor_.onRead(v.vr, v.name, values_.parameters);
        return getValue(values_, v);
    }
    void set(const fmu::Variable& v, double x) override {
        setValue(values_, v, x);
        // Set while the simulation runs (not the start value of initialization mode): the drive is
        // driven, or another motion input is (terminate tells which).
        if (simulation_ && v.causality == fmu::Causality::Input) {
            if (values_.inputPort(v.vr) == &drivePort())
                driveSet_ = true;
            else if (isMotionInput(v.vr) && !otherMotionSet_)
                otherMotionSet_ = v.name;
        }
    }

    // FMI 3.0: the vertex displacements as an array, early return at contact onset and release.
    const std::vector<fmu::StructuralParameter>& structuralParameters() const override {
        return plateStructuralParameters();
    }
    const std::vector<fmu::ArrayVariable>& arrayVariables() const override { return plateArrays(); }
    const std::vector<fmu::Terminal>& terminals() const override { return plateTerminals(); }
    void getArray(const fmu::ArrayVariable& a, double* out, std::size_t n) const override {
        advisor_.onRead(a.vr, a.name, values_.parameters);
        getPlateArray(values_, a, out, n);
    }
    void setArray(const fmu::ArrayVariable& a, const double* values, std::size_t n) override {
        setPlateArray(values_, a, values, n);
    }
    // FMI 3.0's probe_count is the probes' count itself (FMU states carry it: saveState).
    double ownStructuralValue(const fmu::StructuralParameter& s) const override {
        return s.vr == kVrProbeCountArrays ? double(values_.probes.count) : Model::ownStructuralValue(s);
    }
    void setOwnStructuralValue(const fmu::StructuralParameter& s, double x) override {
        if (s.vr != kVrProbeCountArrays) return Model::setOwnStructuralValue(s, x);
        values_.probes.setCount(std::size_t(x));
        values_.probes.placed = true;
    }
    // FMI 3.0: up to kMaxProbes probes, one to start with (an array's initial size is positive).
    void useVersion(int version) override {
        Model::useVersion(version);
        values_.probes.max = version == 3 ? kMaxProbes : kScalarProbes;
        values_.probes.setCount(version == 3 ? 1 : 0);
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
    std::string accuracyParameters() const override {
        return "the parameter dt (s, the internal step of a fixed grid) and, under time_scheme = flow, the parameter "
               "tolerance (m, a bound on the error of the reported points)";
    }
    double fixedInternalStepSize() const override { return plate::PlateParameters{}.law.dt; }
    bool doStepUntilEvent(double t, double h) override {
        endedAtEvent_ = false;
        step(t, h, /*untilEvent=*/true);
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
        // long initializations go to the user (category logInfo); a long setup or a costly run is
        // said at status Warning (costNotices), which masters show by default.
        std::string estimate = "no estimate was made";
        const plate::ProgressLog log(
            [this, &estimate](const std::string& line) {
                if (estimate == "no estimate was made") estimate = line;
                inform(line);
            },
            [this](const std::string& line) { warn(line); });
        requireOneDrive();
        try {
            simulation_ = std::make_unique<plate::CheckedPlate>(
                values_.solverParameters(), values_.baseDisplacement.signal.value, values_.load.signal.value, log);
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
        trace(format("simulation built (nx = %g, ny = %g, dt = %g s)", p.mesh.nx, p.mesh.ny, p.law.dt));
        for (const std::string& message : buildWarnings(values_, fmiVersion() == 3)) warn(message);
        driveSet_ = false;
        advisor_.onBuild(p);
        otherMotionSet_ = nullptr;
    }
    void terminate() override {
        // A drive the master never set: the clamp stayed where it started. A motion input of another
        // drive set instead is a mistake (base_drive not switched, or the wrong column): warned. None
        // set is a load-only scene (the paper's §5.2 release), as likely meant as not: told once, at
        // the info level (logInfo), for the user who looks for why the clamp did not move.
        if (driveSet_ || simulation_->stepCount() == 0 || carried()) return;
        if (otherMotionSet_)
            warn(std::string(otherMotionSet_) + " was set during this run, but base_drive = " + mode().item +
                 " moves the clamp by " + driveName() +
                 ", which was never set: the clamp stayed at its start value; set base_drive to the input you "
                 "drive (1 = base_displacement, 2 = base_velocity, 3 = base_acceleration)");
        else
            inform(std::string(driveName()) +
                   " (base_drive) was never set during this run: a load-only run, the clamp stayed at its start "
                   "value; if an input file or a connection should drive it, check the input's name");
    }
    bool built() const override { return simulation_ != nullptr; }
    void drop() override {
        simulation_.reset();
        refreshOutputs();
    }
    double time() const override { return simulation_ ? simulation_->time() : 0.0; }

    void doStep(double t, double h) override { step(t, h, false); }
    // A communication step; untilEvent: FMI 3.0 early return, up to the first contact onset or release.
    void step(double t, double h, bool untilEvent) {
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
                h, values_.parameters.law.dt));
        const double now = simulation_->time();
        advisor_.onStep(values_.parameters, plan, h, t, drivePort(), driveName(), values_.load);
        const std::optional<DriveSample> sample = driveSample(t);
        for (InputPort* port : ports()) {
            port->beginStep(now);
            port->reach = plan.offset + double(plan.steps) * values_.parameters.law.dt;  // the last grid point read
        }
        try {
            const plate::InputSignal base = clampSignal(now, plan.span);
            if (sample) advisor_.onDriveSample(*sample, base.value, h, values_.parameters.law.dt, driveName());
            const plate::InputSignal load = values_.load.stepSignal(now, plan.span, -plate::kMaxLoad, plate::kMaxLoad);
            advanceClamp(base, communicate(plan, base, load, untilEvent));
        } catch (const plate::StepError& e) {
            refreshOutputs();  // the simulation stays at its last good step (for debugging)
            // The failed internal step's time, from the scheme's clock onto the master's (NaN: refused before a step).
            const std::string at = std::isnan(e.time()) ? "" : format(" at t = %.17g", t + e.time() - now);
            throw fmu::ModelError(format("step from t = %.17g failed", t) + at + ": " + namingTheDrive(e.what()));
        }
        refreshOutputs();
        if (values_.baseDrive == BaseDrive::Acceleration)
            advisor_.onIntegratedClamp(t + h, simulation_->time(), clampPosition_ - simulationBase0_, clampVelocity_,
                                       values_.baseAcceleration.signal.value);
        advisor_.afterStep(values_.parameters, values_.outputs, simulation_->time(), simulation_->toleranceHorizon());
        if (const std::string said = simulation_->takeDiscretizationWarning(); !said.empty()) warn(said);
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
        values_.probes.appendTo(out);
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
        const double* count = take(1, "the probes' count");
        ProbePlaces probes = values_.probes;
        if (!probes.setCountFrom(*count)) throw fmu::ModelError("the probes' count is out of range");
        if (!probes.readPlaces(take(2 * probes.x.size(), "the probes' places")))
            throw fmu::ModelError("a probe's place is not finite");
        values_.probes = probes;
        const double* flags = take(2, "the simulation flag");
        if ((flags[0] != 0.0 && flags[0] != 1.0) || !std::isfinite(flags[1]))
            throw fmu::ModelError("simulation flag or initial base displacement out of range");
        // The parameters the instance was built with (the state's are set already): said when they differ.
        const std::vector<double> own = simulation_ ? builtWith_ : std::vector<double>{};
        if (flags[0] == 0.0) {
            if (in != end) throw fmu::ModelError("simulation state without a simulation");
            drop();
            warnOfReplacedParameters(own);
            return;
        }
        const std::vector<double> state(in, end);
        in = end;
        // Equal configurations (every parameter of the table, and the initial base) reuse the
        // discretization; another one is built for the state's parameters.
        if (!simulation_ || builtWith_ != configuration() || simulationBase0_ != flags[1]) {
            auto simulation = std::make_unique<plate::CheckedPlate>(values_.solverParameters(), flags[1]);
            simulation->restoreState(state);
            simulation_ = std::move(simulation);
            builtWith_ = configuration();
        } else {
            simulation_->restoreState(state);
        }
        simulationBase0_ = flags[1];
        refreshOutputs();
        warnOfReplacedParameters(own);
    }

private:
    // The values of every parameter, walking the table: two simulations built from equal
    // configurations (and the same initial base) are the same discretization.
    std::vector<double> configuration() const {
        std::vector<double> out;
        for (const fmu::Variable& v : plateVariables())
            if (v.causality == fmu::Causality::Parameter) out.push_back(getValue(values_, v));
        values_.probes.appendTo(out);
        return out;
    }
    // An FMU state carries the parameters it was taken with: set into an instance built with others, it
    // replaces them (the instance runs on as the state's), which the user may not expect (issue 71). Said,
    // naming each parameter that changed; `own` is empty when the instance had no simulation yet.
    void warnOfReplacedParameters(const std::vector<double>& own) {
        const std::vector<double> now = configuration();
        if (own.empty() || own == now) return;
        std::string changed;
        std::size_t k = 0, listed = 0;
        for (const fmu::Variable& v : plateVariables()) {
            if (v.causality != fmu::Causality::Parameter) continue;
            if (own[k] != now[k] && listed++ < 6)
                changed +=
                    (changed.empty() ? "" : ", ") + std::string(v.name) + format(" = %.6g (was %.6g)", now[k], own[k]);
            ++k;
        }
        if (!std::equal(own.begin() + std::ptrdiff_t(k), own.end(), now.begin() + std::ptrdiff_t(k), now.end()))
            changed += changed.empty() ? "the probes" : ", the probes";
        warn("the FMU state set was taken with other parameters than this instance's: " + changed +
             (listed > 6 ? format(" and %g more", double(listed - 6)) : std::string()) +
             "; the instance runs on with the state's parameters (the discretization rebuilt for them). To keep "
             "this instance's, set a state taken from an instance with the same parameters");
    }
    void refreshOutputs() {
        values_.outputs = simulation_ ? simulation_->outputs() : plate::PlateOutputs{};
        values_.simulation = simulation_.get();
        values_.forgetReads();
    }

    std::array<InputPort*, 6> ports() {
        return {&values_.baseDisplacement, &values_.baseVelocity, &values_.baseAcceleration, &values_.load,
                &values_.driveForce,       &values_.tlmWaveIn};
    }
    // The row of base_drive's mode (BaseDrives.h): its input, whether it carries the clamp, its path.
    const DriveMode& mode() const { return driveMode(values_.baseDrive); }
    bool carried() const { return mode().carried; }
    InputPort& drivePort() { return values_.*mode().port; }  // the input base_drive chooses
    const char* driveName() const { return mode().input; }
    bool isMotionInput(fmu::ValueReference vr) {
        for (int k = 0; k < kDriveModeCount; ++k)
            if (!driveModes()[k].carried && &(values_.*driveModes()[k].port) == values_.inputPort(vr)) return true;
        return false;
    }
    // A clamp moved by one input only (docs/theory.md §16–18): a force-driven or line-carried clamp
    // whose motion inputs are set as well, or a motion-driven one given a force, is refused.
    void requireOneDrive() const {
        const double base0 = simulation_ ? simulationBase0_ : values_.baseDisplacement.signal.value;
        for (int k = 0; k < kDriveModeCount; ++k) {
            const DriveMode& input = driveModes()[k];
            const bool displacement = input.drive == BaseDrive::Displacement;
            const double value = (values_.*input.port).signal.value - (displacement ? base0 : 0.0);
            if (input.drive == values_.baseDrive || value == 0.0) continue;
            if (!carried() && !input.carried) continue;  // the motion drives ignore each other's inputs (§16)
            throw fmu::ModelError(
                std::string("invalid parameter base_drive = ") + mode().item + " with " + input.input + " set (" +
                format("%.17g", value, 0.0) + (displacement ? " from the initial position" : "") +
                "): the clamp is driven by one input only; a clamp carried by the armature (force) or by the line "
                "(tlm) is not also moved by a motion input, nor a motion-driven clamp by a force (allowed: set "
                "base_drive to the input you drive, leave the others at 0)");
        }
    }

    // The clamp's displacement as the master set it for the step from t, against where the FMU's model
    // of it over the last step ended (PlateAdvisor::onDriveSample); none when it drives no displacement,
    // was not set since, or no step was taken yet.
    std::optional<DriveSample> driveSample(double t) {
        const InputPort& port = values_.baseDisplacement;
        if (values_.baseDrive != BaseDrive::Displacement || !port.fresh || !port.history.hasReached()) return {};
        DriveSample s{t, port.signal.value, port.history.reachedValue()};
        static constexpr const char* kModels[] = {"held: base_input_mode = hold",
                                                  "the line through its last two values: base_input_mode = linear",
                                                  ("the parabola through its last three values: "
                                                   "base_input_mode = quadratic")};
        if (port.derivativesGiven) {
            s.order = port.signal.d2 != 0.0 ? 2 : 1;
            s.model = "the value and derivatives the master set";
        } else {
            s.order = static_cast<int>(port.mode) - 1;
            s.model = kModels[s.order];
        }
        s.continuous = !port.derivativesGiven && port.mode != plate::InputMode::Hold;
        return s;
    }
    // A refusal of the clamp's position while a velocity or an acceleration drives it: the solver names it
    // base_displacement, which the user never set (issue 71). Said as the clamp integrated from the input
    // driven, with where it went and why a clamp integrated from rest drifts.
    std::string namingTheDrive(std::string refusal) const {
        const BaseDrive d = values_.baseDrive;
        if ((d != BaseDrive::Velocity && d != BaseDrive::Acceleration) ||
            refusal.find("base_displacement") == std::string::npos)
            return refusal;
        const std::string clamp = std::string("the clamp's position (integrated from ") + driveName() + ")";
        for (std::size_t at = refusal.find("base_displacement"); at != std::string::npos;
             at = refusal.find("base_displacement", at + clamp.size()))
            refusal.replace(at, std::string("base_displacement").size(), clamp);
        refusal += std::string(" (") + driveName() + ", which base_drive = " + mode().item +
                   " drives, moves the clamp from rest at its start position" +
                   format(" (%.6g m): it had moved by %.3g m", simulationBase0_, clampPosition_ - simulationBase0_) +
                   " at the last communication point. " +
                   (d == BaseDrive::Velocity
                        ? "A velocity that does not average to zero moves the clamp by its mean times t; drive "
                          "base_displacement instead, or give the velocity a zero mean)"
                        : "An acceleration whose integral does not average to zero, such as the acceleration of a "
                          "sine, -A w^2 sin(w t), whose velocity from rest is A w (cos(w t) - 1), drifts the clamp "
                          "by that mean velocity times t; drive base_velocity (its first value is the clamp's start "
                          "velocity) or base_displacement instead, or give the acceleration a velocity of zero "
                          "mean)");
        return refusal;
    }
    // The clamp's path over a step of length span from the communication time `now` (docs/theory.md
    // §16): the displacement input as it comes, or the exact integral of the velocity (once) or
    // the acceleration (twice) input from the clamp's position and velocity there. A
    // reconstructed clamp stays between the obstacles the master's values respect.
    plate::InputSignal clampSignal(double now, double span) {
        const plate::PlateParameters& p = simulation_->parameters();
        const plate::Obstacles obstacles = plate::obstaclesOf(p.obstacles);  // those whose stops reach the clamp
        const double lower = std::max(obstacles.clampLower(), -plate::kMaxDisplacement);
        const double upper = std::min(obstacles.clampUpper(), plate::kMaxDisplacement);
        return mode().path(values_, {clampPosition_, clampVelocity_}, now, span, lower, upper);
    }
    // simulation_->communicate, or untilEvent (FMI 3.0 early return) up to the first contact onset or
    // release on the grid. Returns the span of the step as taken; after an early end, every input ends
    // the step where its signal stands then.
    double communicate(const plate::StepPlan& plan, const plate::InputSignal& base, const plate::InputSignal& load,
                       bool untilEvent) {
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
                returnRequested_ = t >= returnAt_ - 1e-9 * values_.parameters.law.dt;
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
        if (!untilEvent || carried()) {  // a carried clamp: no early return (§18)
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
        (values_.*mode().port).history.reached(mode().inputAt(base, span));  // the drive's own, inside the clamp's
        return span;
    }
    void advanceClamp(const plate::InputSignal& base, double span) {
        if (values_.baseDrive == BaseDrive::Displacement || carried()) return;
        clampPosition_ = base.at(span);
        clampVelocity_ = base.d1 + span * (base.d2 + span * (0.5 * base.d3 + span * base.d4 / 6.0));
    }

    PlateValues values_;
    std::unique_ptr<plate::CheckedPlate> simulation_;
    std::vector<double> builtWith_;  // configuration() when simulation_ was built
    double simulationBase0_ = 0.0;  // base displacement the simulation was built with
    // The clamp at the communication time when a velocity or an acceleration drives it.
    double clampPosition_ = 0.0, clampVelocity_ = 0.0;
    bool driveSet_ = false;  // the drive input was set during the run (terminate tells otherwise)
    const char* otherMotionSet_ = nullptr;  // the first motion input of another drive set during the run
    // The advice said once per build (PlateAdvice.h); mutable: a read may say it.
    mutable PlateAdvisor advisor_{warn};
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
