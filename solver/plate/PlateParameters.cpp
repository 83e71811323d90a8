#include "plate/PlateParameters.h"

#include "plate/Stops.h"

#include <cmath>
#include <sstream>
#include <string>
#include <tuple>

namespace plate {

using namespace ranges;

double PlateParameters::firstFrequencyEstimate() const {
    return 1.8751 * 1.8751 / (2.0 * M_PI * mesh.length * mesh.length) *
           std::sqrt(material.bendingStiffness() / material.surfaceDensity());
}

namespace {

template <class T>
[[noreturn]] void reject(const char* name, T value, const char* allowed) {
    std::ostringstream msg;
    msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
    msg << "invalid parameter " << name << " = " << value << " (allowed: " << allowed << ")";
    throw ParameterError(msg.str());
}

// "lo <= name <= hi" (with < at an open end), as the message states the range.
std::string rangeText(const char* name, const Range& r) {
    std::ostringstream text;
    text << r.min << (r.minOpen ? " < " : " <= ") << name << (r.maxOpen ? " < " : " <= ") << r.max;
    return text.str();
}

void requireRange(const char* name, double value, const Range& r, const char* why = nullptr) {
    if (!r.contains(value)) {
        const std::string allowed = rangeText(name, r) + (why ? std::string(" ") + why : "");
        reject(name, value, allowed.c_str());
    }
}

// Each part checks itself (validate below runs them part by part). The units are SI (issue 71: a
// modulus in GPa or a density in g/cm3 is refused or runs as another material); the refusals say
// so, with the conversion a user most likely needs.
void validate(const MeshParameters& mesh) {
    requireRange("length", mesh.length, kLength, "(m: the FMU takes SI units; 1200 mm is 1.2)");
    requireRange("width", mesh.width, kWidth, "(m: the FMU takes SI units; 400 mm is 0.4)");
    requireRange("nx", mesh.nx, kCells);
    requireRange("ny", mesh.ny, kCells);
}

void validate(const MaterialParameters& material) {
    requireRange("thickness", material.thickness, kThickness, "(m: the FMU takes SI units; 10 mm is 0.01)");
    requireRange("youngs_modulus", material.youngsModulus, kYoungsModulus,
                 "(Pa: the FMU takes SI units; steel is 2.1e11 Pa, not 210 GPa)");
    requireRange("poisson_ratio", material.poissonRatio, kPoissonRatio);
    requireRange("density", material.density, kDensity,
                 "(kg/m^3: the FMU takes SI units; steel is 7850 kg/m^3, not 7.85 g/cm^3)");
}

// Each present obstacle's height and its stop (docs/theory.md §25), which the mesh must meet.
void validate(const ObstacleParameters& obstacles, const MeshParameters& mesh) {
    if (obstacles.lowerEnabled)
        requireRange("obstacle_lower", obstacles.lower, kObstacleLower,
                     "when obstacle_lower_enabled (the plate starts at w = 0)");
    if (obstacles.upperEnabled)
        requireRange("obstacle_upper", obstacles.upper, kObstacleUpper,
                     "when obstacle_upper_enabled (the plate starts at w = 0)");
    validateStops(obstacles, mesh);
}

// The law; `period` the plate's first period (firstFrequencyEstimate). Fewer than two steps per
// first period resolve nothing of the plate's motion (every output would be the static state or
// noise): refused, whatever the scheme. Finer than T1/20 for an accurate output: the FMU says so
// (fmu/binding/PlateWarnings.cpp).
void validate(const LawParameters& law, double period) {
    requireRange("dt", law.dt, kDt);
    requireRange("beta", law.beta, kBeta);
    if (law.dt > 0.5 * period) {
        std::ostringstream allowed;
        allowed.precision(6);
        allowed << "dt <= " << 0.5 * period << " s, half the plate's first period T1 = " << period
                << " s (first mode about " << 1.0 / period << " Hz); dt <= T1/20 = " << period / 20.0
                << " s for accurate outputs";
        reject("dt", law.dt, allowed.str().c_str());
    }
    requireRange("modes", law.modes, kModes, "(0 = full space)");
    if (law.mass != MassModel::Consistent && law.mass != MassModel::SingularP0 && law.mass != MassModel::SingularP1dg)
        reject("mass", static_cast<int>(law.mass), "1 (consistent), 2 (singular_p0) or 3 (singular_p1dg)");
    if (law.timeScheme != TimeScheme::Newmark && law.timeScheme != TimeScheme::Conserving &&
        law.timeScheme != TimeScheme::Flow)
        reject("time_scheme", static_cast<int>(law.timeScheme), "1 (newmark), 2 (conserving) or 3 (flow)");
    const bool conserving = law.condensed();
    if (conserving && !law.singularMass())
        reject("mass", "consistent",
               "mass = singular_p0 (2) or singular_p1dg (3) with time_scheme = conserving or flow: the scheme steps "
               "the massive modes of a singular mass and keeps its massless part static");
    if (law.singularMass() && law.modes != 0 && !conserving)
        reject("modes", law.modes,
               "modes = 0 with a singular mass and time_scheme = newmark (the reduced singular model is "
               "time_scheme = conserving)");
    if (law.singularMass() && law.beta < 0.25 && !conserving)
        reject("beta", law.beta,
               "0.25 <= beta <= 0.5 with a singular mass (massless dofs have no explicit stability bound)");
    requireRange("restitution", law.restitution, kRestitution);
    // The condensed laws have neither the Newmark average beta nor an impact law to choose: both are
    // refused alike (issue 71: beta was ignored silently while restitution was refused), naming the
    // scheme the user set.
    if (conserving) {
        const std::string scheme =
            law.timeScheme == TimeScheme::Flow ? "time_scheme = flow" : "time_scheme = conserving";
        if (law.restitution != 0.0)
            reject("restitution", law.restitution,
                   ("restitution = 0 with " + scheme +
                    ": its impacts conserve energy by construction, there is no impact law to choose; for an "
                    "impact that loses energy use time_scheme = newmark (1) with restitution > 0")
                       .c_str());
        if (law.beta != LawParameters{}.beta)
            reject("beta", law.beta,
                   ("beta = 0.5, the default, with " + scheme +
                    ": beta weighs the Newmark scheme's average and this scheme steps by the midpoint rule, which "
                    "has no beta; leave beta at 0.5, or use time_scheme = newmark (1) for another beta")
                       .c_str());
    }
    requireRange("damping_mass", law.dampingMass, kDampingMass);
    requireRange("damping_stiffness", law.dampingStiffness, kDampingStiffness);
}

void validate(const ContactRefinement& refinement) {
    requireRange("contact_substeps", refinement.substeps, kContactSubsteps);
    requireRange("tolerance", refinement.tolerance, kTolerance);
    requireRange("max_contact_substeps", refinement.maxSubsteps, kMaxContactSubsteps);
    if ((refinement.maxSubsteps & (refinement.maxSubsteps - 1)) != 0)
        throw ParameterError("invalid parameter max_contact_substeps = " + std::to_string(refinement.maxSubsteps) +
                             " (allowed: a power of two from 2 to 1024)");
}

// The outputs on the plate of `mesh`. discretization_check (docs/theory.md §26): a companion on the
// mesh coarsened by two needs a mesh of at least two cells each way. The probes (§23): inside the
// plate, whose size the table's range cannot know; named as the FMI 2.0 FMU's scalars (probe_1_x) and
// the FMI 3.0 FMU's arrays (probe_x[0]) name them.
void validate(const OutputParameters& outputs, const MeshParameters& mesh) {
    for (const auto& [name, cells] : {std::pair{"nx", mesh.nx}, std::pair{"ny", mesh.ny}})
        if (outputs.discretizationCheck && cells < 2)
            throw ParameterError(std::string("discretization_check needs a mesh it can coarsen: ") + name + " = " +
                                 std::to_string(cells) +
                                 " (allowed with the check: nx >= 2 and ny >= 2; the companion runs on ceil(nx/2) x "
                                 "ceil(ny/2) cells); refine the mesh or set discretization_check = false");
    if (outputs.probeX.size() != outputs.probeY.size())
        throw ParameterError("invalid probes: " + std::to_string(outputs.probeX.size()) + " x coordinates and " +
                             std::to_string(outputs.probeY.size()) + " y coordinates (allowed: one of each per probe)");
    const Range along{0.0, mesh.length}, across{0.0, mesh.width};
    for (std::size_t i = 0; i < outputs.probeX.size(); ++i)
        for (const auto& [axis, x, range, edge] : {std::tuple{"x", outputs.probeX[i], along, "length"},
                                                   std::tuple{"y", outputs.probeY[i], across, "width"}}) {
            const std::string name = "probe_" + std::to_string(i + 1) + "_" + axis;
            if (!range.contains(x))
                reject(name.c_str(), x,
                       (rangeText(name.c_str(), range) + " = " + edge + ": a point of the plate; probe_" + axis + "[" +
                        std::to_string(i) + "] in FMI 3.0")
                           .c_str());
        }
}

// base_drive = force or tlm (docs/theory.md §18–19): the carrier's parameters, and the schemes, masses
// and outputs it is built on (the discretization check's companion does not share the clamp this
// plate's own reaction carries).
void validateCarrier(const PlateParameters& p) {
    if (p.carrier == PlateParameters::Carrier::Armature) {
        requireRange("armature_mass", p.armatureMass, kArmatureMass, "when base_drive = force");
        requireRange("armature_stiffness", p.armatureStiffness, kArmatureStiffness, "when base_drive = force");
        requireRange("armature_damping", p.armatureDamping, kArmatureDamping, "when base_drive = force");
    }
    if (p.carrier == PlateParameters::Carrier::Line)
        requireRange("tlm_impedance", p.tlmImpedance, kTlmImpedance, "when base_drive = tlm");
    if (p.carrier == PlateParameters::Carrier::None) return;
    if (p.law.condensed())
        reject("base_drive", p.carrier == PlateParameters::Carrier::Armature ? "force" : "tlm",
               "displacement, velocity or acceleration with time_scheme = conserving (the carried clamp is built on "
               "time_scheme = newmark)");
    if (p.law.singularMass())
        reject("mass", static_cast<int>(p.law.mass),
               "1 (consistent) when base_drive = force or tlm (a carried clamp with a singular mass is not "
               "implemented)");
    if (p.outputs.discretizationCheck)
        reject("discretization_check", "true",
               "false with base_drive = force or tlm (the clamp is carried by this plate's own reaction, which the "
               "coarser companion does not share); drive the clamp by displacement, velocity or acceleration");
}

}  // namespace

void validate(const PlateParameters& p) {
    validate(p.mesh);
    validate(p.material);
    validate(p.obstacles, p.mesh);
    validate(p.law, 1.0 / p.firstFrequencyEstimate());
    validate(p.refinement);
    requireRange("initial_load", p.initialLoad, kInitialLoad);
    requireRange("memory_limit", p.memoryLimit, kMemoryLimit);  // MB; 0 = no limit
    validate(p.outputs, p.mesh);
    validateCarrier(p);
}

}  // namespace plate
