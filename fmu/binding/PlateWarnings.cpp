// The plate's plausibility warnings at build (PlateModel::build): a result that is computed but likely
// not what the user meant, each a message naming the cause and the fix.
#include "binding/PlateWarnings.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace plateimpact {

std::string format(const char* fmt, double a, double b, double c, double d) {
    char text[600];
    std::snprintf(text, sizeof text, fmt, a, b, c, d);
    return text;
}

namespace {

// dt against the plate's first period (plate::PlateParameters::firstFrequencyEstimate; dt above
// T1/2 is refused by the solver): fewer than 20 steps per period give visibly wrong amplitudes
// and phases.
void warnOfCoarseStep(const PlateValues& values, std::vector<std::string>& out) {
    const plate::PlateParameters& p = values.parameters;
    const double period = 1.0 / p.firstFrequencyEstimate();
    if (p.law.dt <= period / 20.0) return;
    out.push_back(
        format("dt = %g s is %.3g of the plate's first period T1 = %.4g s", p.law.dt, p.law.dt / period, period) +
        " (fewer than 20 steps per period): the outputs resolve the first mode only roughly; take dt <= " +
        format("%.4g s (T1/20) for accurate results", period / 20.0, 0.0));
}
// Units (issue 71): a geometry in millimetres runs as a plate a thousand times larger, silently. Said:
// a thickness above a tenth of the smaller side (outside the thin-plate range of the Kirchhoff model the
// elements discretize), a side over 100 m, a density or a modulus no structural material has (off by
// 1e3 or 1e6: g/cm3, kg/mm3, MPa, GPa in place of SI).
void warnOfUnits(const PlateValues& values, std::vector<std::string>& out) {
    const plate::PlateParameters& p = values.parameters;
    const double side = std::min(p.mesh.length, p.mesh.width);
    if (p.material.thickness > 0.1 * side)
        out.push_back(
            format("thickness = %g m is %.3g of the plate's smaller side (%g m): outside the thin-plate "
                   "range of the Kirchhoff model this FMU solves (thickness <= a tenth of the smaller side), "
                   "its results are not those of so thick a plate; the FMU takes SI units: lengths in m",
                   p.material.thickness, p.material.thickness / side, side));
    if (std::max(p.mesh.length, p.mesh.width) > 100.0)
        out.push_back(
            format("length = %g m, width = %g m: a plate over 100 m; the FMU takes SI units (lengths, "
                   "thickness and obstacle heights in m: 1200 mm is 1.2)",
                   p.mesh.length, p.mesh.width));
    if (p.material.density < 100.0 || p.material.density > 3e4)
        out.push_back(
            format("density = %g kg/m3 is no structural material's (steel 7850, aluminium 2700 kg/m3): the "
                   "FMU takes SI units (kg/m3; 7.85 g/cm3 is 7850)",
                   p.material.density));
    if (p.material.youngsModulus < 1e7 || p.material.youngsModulus > 2e12)
        out.push_back(
            format("youngs_modulus = %g Pa is no structural material's (steel 2.1e11, aluminium 7e10 Pa): "
                   "the FMU takes SI units (Pa; 210 GPa is 2.1e11, 210000 MPa too)",
                   p.material.youngsModulus));
}
// modes above what the plate has (issue 71): the engine keeps every mode there is, the full model of
// modes = 0, at the full model's cost. Said with the count where the engine states it: the free dofs
// under newmark; under the condensed laws the massive modes, whose count the engine keeps to itself.
void warnOfModesBeyondModel(const PlateValues& values, std::vector<std::string>& out) {
    const plate::PlateParameters& p = values.parameters;
    if (p.law.modes <= 0 || !values.simulation) return;
    const std::string engine = values.simulation->engine();
    const bool complete = engine.size() >= 9 && engine.compare(engine.size() - 9, 9, "-complete") == 0;
    if (!complete) return;
    if (!p.law.condensed()) {
        const double dofs = double(values.simulation->dofCount());
        if (p.law.modes <= dofs) return;  // modes = dofs: every mode, as asked
        out.push_back(
            format("modes = %g is more than the plate's %g free dofs (nx = %g, ny = %g): there are no more "
                   "modes than dofs, so this run keeps all of them, the full model of modes = 0, at its "
                   "cost; take modes < the dofs for a reduced model",
                   double(p.law.modes), dofs, double(p.mesh.nx), double(p.mesh.ny)));
    } else {
        out.push_back(
            format("modes = %g is at least the count of the singular mass's massive modes on this mesh "
                   "(nx = %g, ny = %g): this run keeps all of them, the full model of modes = 0, at its "
                   "cost; take fewer modes for a reduced model",
                   double(p.law.modes), double(p.mesh.nx), double(p.mesh.ny)));
    }
}
// A tolerance or sub-step count only the flow law uses (docs/theory.md §21–22), set for another
// scheme: said at build.
void warnOfUnusedTolerance(const PlateValues& values, std::vector<std::string>& out) {
    const plate::PlateParameters& p = values.parameters;
    if (p.law.timeScheme == plate::TimeScheme::Flow) return;
    if (p.refinement.tolerance > 0.0)
        out.push_back(
            format("tolerance = %g m is used by time_scheme = flow only (3): this run's scheme ignores it, and "
                   "error_estimate stays 0",
                   p.refinement.tolerance, 0.0));
    const plate::PlateParameters defaults;
    if (p.refinement.substeps != defaults.refinement.substeps)
        out.push_back(
            format("contact_substeps = %g is used by time_scheme = flow only (3): this run's scheme ignores it",
                   double(p.refinement.substeps), 0.0));
    if (p.refinement.maxSubsteps != defaults.refinement.maxSubsteps)
        out.push_back(
            format("max_contact_substeps = %g is used by time_scheme = flow with a tolerance only: this run's "
                   "scheme ignores it",
                   double(p.refinement.maxSubsteps), 0.0));
}
// Probes (docs/theory.md §23) that are not what they seem, among those the importer placed or
// counted: an FMI 2.0 probe placed but not counted (it reads 0), one counted but on the clamped
// edge x = 0 (unplaced: the default (0, 0)), which moves with the clamp.
void warnOfProbes(const PlateValues& values, bool arrays, std::vector<std::string>& out) {
    const ProbePlaces& probes = values.probes;
    if (!probes.placed) return;
    for (std::size_t k = 0; k < probes.x.size(); ++k) {
        const double x = probes.x[k], y = probes.y[k];
        const std::string index = std::to_string(k + 1), at = "[" + std::to_string(k) + "]";
        const std::string name = arrays ? "probe" + at : "probe_" + index;
        const std::string placeX = arrays ? "probe_x" + at : name + "_x";
        if (k >= probes.count && !arrays && (x != 0.0 || y != 0.0))
            out.push_back(name + format(" is placed at (%g, %g) m", x, y) +
                          format(" but probe_count = %g leaves it off: it reads 0; set probe_count >= %g to compute it",
                                 double(probes.count), double(k + 1)));
        if (k < probes.count && x == 0.0)
            out.push_back(name +
                          format(" at (%g, %g) m is counted (probe_count = %g) but lies on the clamped edge x = 0", x,
                                 y, double(probes.count)) +
                          ": it reads the clamp's motion; place it with " + placeX + " > 0 (" +
                          (y == 0.0 ? placeX + " and its y were never set)" : placeX + " is 0)"));
    }
}

}  // namespace

std::vector<std::string> buildWarnings(const PlateValues& values, bool arrays) {
    std::vector<std::string> out;
    warnOfUnits(values, out);
    warnOfCoarseStep(values, out);
    warnOfModesBeyondModel(values, out);
    warnOfUnusedTolerance(values, out);
    warnOfProbes(values, arrays, out);
    return out;
}

}  // namespace plateimpact
