// FMI 3.0 terminals over the plate's table of variables (PlateVariables.h, plateTerminals): the
// members name rows of the table; the description writer checks that each exists.
#include "binding/PlateVariables.h"

namespace plateimpact {

// The terminal kinds (documented on the model's page, PlateInfo.cpp):
//   org.plateimpact.TranslationalFlange  a vertical translational flange: s [m], v [m/s],
//       a [m/s2] the flange's motion, f [N] the force on it; members of equal memberName
//       connect (a causal connection: one side's output feeds the other's input).
//   org.plateimpact.TransmissionLineEnd  one end of a transmission line (TLM): wave_out feeds
//       the partner's wave_in and the other way round (matchingRule org.plateimpact.crossed),
//       impedance is equal at both ends.
const std::vector<fmu::Terminal>& plateTerminals() {
    static const std::vector<fmu::Terminal> terminals = {
        {"clamp",
         "bus",
         "org.plateimpact.TranslationalFlange",
         "The clamped edge moved by a partner (base_drive = displacement, velocity or acceleration: the partner "
         "gives the one the drive uses) and the force the plate exerts on it",
         {{"base_displacement", "s", "signal"},
          {"base_velocity", "v", "signal"},
          {"base_acceleration", "a", "signal"},
          {"clamp_force", "f", "signal"}}},
        {"armature",
         "plug",
         "org.plateimpact.TranslationalFlange",
         "The clamp carried by the armature inside the FMU (base_drive = force): the partner's force in, the "
         "clamp's motion out",
         {{"drive_force", "f", "signal"},
          {"clamp_displacement", "s", "signal"},
          {"clamp_velocity", "v", "signal"},
          {"clamp_acceleration", "a", "signal"}}},
        {"line",
         "org.plateimpact.crossed",
         "org.plateimpact.TransmissionLineEnd",
         "The clamp as the end of a transmission line to a partner (base_drive = tlm)",
         {{"tlm_wave_in", "wave_in", "signal"},
          {"tlm_wave_out", "wave_out", "signal"},
          {"tlm_impedance", "impedance", "signal"}}},
    };
    return terminals;
}

}  // namespace plateimpact
