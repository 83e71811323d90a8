// The named items of the plate's Integer switches (fmu::EnumerationType, core/Model.h): the one
// place each switch's items are written; the table of variables (PlateVariables.cpp) declares them.
// Each made on first use (the table is made in another file's static initialization).
#include "binding/PlateSwitches.h"

namespace plateimpact {

const fmu::EnumerationType& elementType() {
    static const fmu::EnumerationType items{
        "ElementType",
        "C1 plate element",
        {{"argyris", 1, "Argyris triangle (P5, 21 dofs); each cell split into two triangles"},
         {"fvs", 2, "Reduced Fraeijs de Veubeke-Sander quadrilateral (12 dofs); one per cell"}}};
    return items;
}

const fmu::EnumerationType& inputMode() {
    static const fmu::EnumerationType items{
        "InputMode",
        "How an input is continued inside a communication step from its communicated values",
        {{"hold", 1, "Held constant over the step"},
         {"linear", 2, "Extrapolated along the line through the last two communicated values"},
         {"quadratic", 3, "Extrapolated along the parabola through the last three communicated values"}}};
    return items;
}

const fmu::EnumerationType& massModel() {
    static const fmu::EnumerationType items{
        "MassModel",
        "Mass matrix of the plate",
        {{"consistent", 1, "Consistent mass of the finite element space (the paper's scheme)"},
         {"singular_p0", 2,
          "Singular mass projected on element-wise constants: no inertia at the contact vertices, energy-consistent "
          "impacts as dt -> 0"},
         {"singular_p1dg", 3, "Singular mass projected on element-wise linear functions (Argyris only)"}}};
    return items;
}

const fmu::EnumerationType& timeScheme() {
    static const fmu::EnumerationType items{
        "TimeScheme",
        "Time scheme",
        {{"newmark", 1, "The paper's three-level Newmark scheme with the impact law set by mass and restitution"},
         {"conserving", 2,
          "Condensed singular plate (needs mass = singular_p0 or singular_p1dg): massive modes stepped by the midpoint "
          "rule, the massless boundary static, impacts through a discrete gradient; conserves energy through impacts "
          "at any dt"},
         {"flow", 3,
          "The conserving scheme with every massive mode advanced by its exact flow between contacts (no phase error "
          "in free flight) and each step with a constraint row active taken as contact_substeps discrete-gradient "
          "sub-steps; conserves energy through impacts at any dt"}}};
    return items;
}

const fmu::EnumerationType& baseDrive() {
    static const fmu::EnumerationType items{
        "BaseDrive",
        "Which input moves the clamped edge",
        {{"displacement", 1, "base_displacement (the clamp position)"},
         {"velocity", 2,
          "base_velocity, integrated exactly over each communication step from the position at its start"},
         {"acceleration", 3, "base_acceleration, integrated twice exactly over each communication step"},
         {"force", 4,
          "drive_force on an armature that carries the clamp inside the FMU (armature_mass, _stiffness, _damping)"},
         {"tlm", 5,
          "tlm_wave_in: the clamp is the end of a transmission line of impedance tlm_impedance to a partner FMU"}}};
    return items;
}

}  // namespace plateimpact
