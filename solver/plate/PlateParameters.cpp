#include "plate/PlateParameters.h"

#include "plate/Stops.h"

#include <cmath>
#include <sstream>
#include <string>

namespace plate {

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

}  // namespace

double PlateParameters::firstFrequencyEstimate() const {
    return 1.8751 * 1.8751 / (2.0 * M_PI * mesh.length * mesh.length) *
           std::sqrt(material.bendingStiffness() / material.surfaceDensity());
}

namespace {

// Fewer than two steps per first period resolve nothing of the plate's motion (every output
// would be the static state or noise): refused, whatever the scheme. Finer than T1/20 for an
// accurate output: the FMU says so (fmu/binding/PlateWarnings.cpp).
void requireFirstPeriodResolved(const PlateParameters& p) {
    const double period = 1.0 / p.firstFrequencyEstimate();
    if (p.law.dt > 0.5 * period) {
        std::ostringstream allowed;
        allowed.precision(6);
        allowed << "dt <= " << 0.5 * period << " s, half the plate's first period T1 = " << period
                << " s (first mode about " << 1.0 / period << " Hz); dt <= T1/20 = " << period / 20.0
                << " s for accurate outputs";
        reject("dt", p.law.dt, allowed.str().c_str());
    }
}

// base_drive = force or tlm (docs/theory.md §18–19): the carrier's parameters, and the schemes and
// masses it is built on.
void validateCarrier(const PlateParameters& p) {
    using namespace ranges;
    if (p.carrier == PlateParameters::Carrier::Armature) {
        requireRange("armature_mass", p.armatureMass, kArmatureMass, "when base_drive = force");
        requireRange("armature_stiffness", p.armatureStiffness, kArmatureStiffness, "when base_drive = force");
        requireRange("armature_damping", p.armatureDamping, kArmatureDamping, "when base_drive = force");
    }
    if (p.carrier == PlateParameters::Carrier::Line)
        requireRange("tlm_impedance", p.tlmImpedance, kTlmImpedance, "when base_drive = tlm");
    if (p.carrier != PlateParameters::Carrier::None && p.law.condensed())
        reject("base_drive", p.carrier == PlateParameters::Carrier::Armature ? "force" : "tlm",
               "displacement, velocity or acceleration with time_scheme = conserving (the carried clamp is built on "
               "time_scheme = newmark)");
    if (p.carrier != PlateParameters::Carrier::None && p.law.singularMass())
        reject("mass", static_cast<int>(p.law.mass),
               "1 (consistent) when base_drive = force or tlm (a carried clamp with a singular mass is not "
               "implemented)");
}

// discretization_check (docs/theory.md §26): a companion on the mesh coarsened by two needs a mesh
// of at least two cells each way, and inputs it can be fed (a carried clamp moves with the plate).
void validateCheck(const PlateParameters& p) {
    if (!p.outputs.discretizationCheck) return;
    for (const auto& [name, cells] : {std::pair{"nx", p.mesh.nx}, std::pair{"ny", p.mesh.ny}})
        if (cells < 2)
            throw ParameterError(std::string("discretization_check needs a mesh it can coarsen: ") + name + " = " +
                                 std::to_string(cells) +
                                 " (allowed with the check: nx >= 2 and ny >= 2; the companion runs on ceil(nx/2) x "
                                 "ceil(ny/2) cells); refine the mesh or set discretization_check = false");
    if (p.carrier != PlateParameters::Carrier::None)
        reject("discretization_check", "true",
               "false with base_drive = force or tlm (the clamp is carried by this plate's own reaction, which the "
               "coarser companion does not share); drive the clamp by displacement, velocity or acceleration");
}

}  // namespace

void validate(const PlateParameters& p) {
    using namespace ranges;
    const LawParameters& law = p.law;
    // The units are SI (issue 71: a modulus in GPa or a density in g/cm3 is refused or runs as another
    // material); the refusals say so, with the conversion a user most likely needs.
    requireRange("length", p.mesh.length, kLength, "(m: the FMU takes SI units; 1200 mm is 1.2)");
    requireRange("width", p.mesh.width, kWidth, "(m: the FMU takes SI units; 400 mm is 0.4)");
    requireRange("thickness", p.material.thickness, kThickness, "(m: the FMU takes SI units; 10 mm is 0.01)");
    requireRange("youngs_modulus", p.material.youngsModulus, kYoungsModulus,
                 "(Pa: the FMU takes SI units; steel is 2.1e11 Pa, not 210 GPa)");
    requireRange("poisson_ratio", p.material.poissonRatio, kPoissonRatio);
    requireRange("density", p.material.density, kDensity,
                 "(kg/m^3: the FMU takes SI units; steel is 7850 kg/m^3, not 7.85 g/cm^3)");
    requireRange("nx", p.mesh.nx, kCells);
    requireRange("ny", p.mesh.ny, kCells);
    if (p.obstacles.lowerEnabled)
        requireRange("obstacle_lower", p.obstacles.lower, kObstacleLower,
                     "when obstacle_lower_enabled (the plate starts at w = 0)");
    if (p.obstacles.upperEnabled)
        requireRange("obstacle_upper", p.obstacles.upper, kObstacleUpper,
                     "when obstacle_upper_enabled (the plate starts at w = 0)");
    requireRange("dt", law.dt, kDt);
    requireRange("beta", law.beta, kBeta);
    requireFirstPeriodResolved(p);
    requireRange("initial_load", p.initialLoad, kInitialLoad);
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
    requireRange("contact_substeps", p.refinement.substeps, kContactSubsteps);
    requireRange("tolerance", p.refinement.tolerance, kTolerance);
    requireRange("max_contact_substeps", p.refinement.maxSubsteps, kMaxContactSubsteps);
    if ((p.refinement.maxSubsteps & (p.refinement.maxSubsteps - 1)) != 0)
        throw ParameterError("invalid parameter max_contact_substeps = " + std::to_string(p.refinement.maxSubsteps) +
                             " (allowed: a power of two from 2 to 1024)");
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
        const char* scheme = law.timeScheme == TimeScheme::Flow ? "time_scheme = flow" : "time_scheme = conserving";
        const PlateParameters defaults;
        if (law.restitution != 0.0)
            reject("restitution", law.restitution,
                   (std::string("restitution = 0 with ") + scheme +
                    ": its impacts conserve energy by construction, there is no impact law to choose; for an "
                    "impact that loses energy use time_scheme = newmark (1) with restitution > 0")
                       .c_str());
        if (law.beta != defaults.law.beta)
            reject("beta", law.beta,
                   (std::string("beta = 0.5, the default, with ") + scheme +
                    ": beta weighs the Newmark scheme's average and this scheme steps by the midpoint rule, which "
                    "has no beta; leave beta at 0.5, or use time_scheme = newmark (1) for another beta")
                       .c_str());
    }
    requireRange("damping_mass", law.dampingMass, kDampingMass);
    requireRange("damping_stiffness", law.dampingStiffness, kDampingStiffness);
    requireRange("memory_limit", p.memoryLimit, kMemoryLimit);  // MB; 0 = no limit
    validateCarrier(p);
    validateCheck(p);
    validateStops(p.obstacles, p.mesh);  // each obstacle's stop (docs/theory.md §25)
    // The probes (docs/theory.md §23): inside the plate, whose size the table's range cannot know.
    // Named as the FMI 2.0 FMU's scalars (probe_1_x) and the FMI 3.0 FMU's arrays (probe_x[0]) name them.
    if (p.outputs.probeX.size() != p.outputs.probeY.size())
        throw ParameterError("invalid probes: " + std::to_string(p.outputs.probeX.size()) + " x coordinates and " +
                             std::to_string(p.outputs.probeY.size()) +
                             " y coordinates (allowed: one of each per probe)");
    const Range along{0.0, p.mesh.length}, across{0.0, p.mesh.width};
    for (std::size_t i = 0; i < p.outputs.probeX.size(); ++i) {
        const std::string k = std::to_string(i + 1), at = "[" + std::to_string(i) + "]";
        const std::string x = "probe_" + k + "_x", y = "probe_" + k + "_y";
        if (!along.contains(p.outputs.probeX[i]))
            reject(x.c_str(), p.outputs.probeX[i],
                   (rangeText(x.c_str(), along) + " = length: a point of the plate; probe_x" + at + " in FMI 3.0")
                       .c_str());
        if (!across.contains(p.outputs.probeY[i]))
            reject(y.c_str(), p.outputs.probeY[i],
                   (rangeText(y.c_str(), across) + " = width: a point of the plate; probe_y" + at + " in FMI 3.0")
                       .c_str());
    }
}

}  // namespace plate
