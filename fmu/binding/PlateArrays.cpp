#include "binding/PlateArrays.h"

#include <string>

namespace plateimpact {

const std::vector<fmu::StructuralParameter>& plateStructuralParameters() {
    static const std::vector<fmu::StructuralParameter> table = {
        {kVrVerticesX, "vertices_x",
         "Mesh vertices along x, nx + 1: the second extent of vertex_displacement (setting it sets nx)", kVrNx, 1},
        {kVrVerticesY, "vertices_y",
         "Mesh vertices along y, ny + 1: the third extent of vertex_displacement (setting it sets ny)", kVrNy, 1},
        {kVrVertexOutput, "vertex_output",
         "Switch of the array output: 1 = vertex_displacement holds the mesh ([1][vertices_x][vertices_y]), 0 = it is "
         "empty (for a master that records every output); the first extent of vertex_displacement",
         fmu::kOwnValue, 1, 0, 1},
        // Start 1: an array's initial size is positive (FMI 3.0); the one probe sits at the clamp's
        // corner (0, 0) until placed.
        {kVrProbeCountArrays, "probe_count",
         "Number of probes: the extent of probe_x, probe_y and of the outputs probe, probe_velocity, "
         "probe_acceleration (set it in Configuration Mode; 0 computes none)",
         fmu::kOwnValue, 1, 0, int(kMaxProbes), /*configurationOnly=*/true},
    };
    return table;
}

const std::vector<fmu::ArrayVariable>& plateArrays() {
    using fmu::Causality;
    const double coordinateMax = plate::ranges::kProbeCoordinate.max;
    static const std::vector<fmu::ArrayVariable> table = {
        {kVrVertexDisplacement,
         "vertex_displacement",
         "Absolute displacement w at every mesh vertex, [vertex_output][vertices_x][vertices_y]: vertex (i, j) at "
         "(i length/nx, j width/ny); a vertex on an obstacle sits at its height; empty when vertex_output = 0",
         "m",
         {kVrVertexOutput, kVrVerticesX, kVrVerticesY}},
        {kVrVertexStress,
         "vertex_stress",
         "Von Mises surface bending stress at every mesh vertex (fvs: its curvatures jump between elements, the "
         "value is that of one element holding it, the one above and right of it where there is one), as "
         "vertex_displacement: "
         "[vertex_output][vertices_x][vertices_y]; 0 unless stress_outputs = true",
         "Pa",
         {kVrVertexOutput, kVrVerticesX, kVrVerticesY}},
        {kVrProbeX,
         "probe_x",
         "x of each probe (0 <= probe_x[k] <= length; outputs probe[k], probe_velocity[k], probe_acceleration[k])",
         "m",
         {kVrProbeCountArrays},
         Causality::Parameter,
         0.0,
         coordinateMax},
        {kVrProbeY,
         "probe_y",
         "y of each probe (0 <= probe_y[k] <= width)",
         "m",
         {kVrProbeCountArrays},
         Causality::Parameter,
         0.0,
         coordinateMax},
        {kVrProbe,
         "probe",
         "Absolute displacement w at each probe (probe_x[k], probe_y[k]), from the element's shape functions",
         "m",
         {kVrProbeCountArrays}},
        {kVrProbeVelocity,
         "probe_velocity",
         "Absolute velocity at each probe (second-order backward difference, as corner_1_velocity)",
         "m/s",
         {kVrProbeCountArrays}},
        {kVrProbeAcceleration,
         "probe_acceleration",
         "Absolute acceleration at each probe at t - dt (the scheme's central difference, as corner_1_acceleration)",
         "m/s2",
         {kVrProbeCountArrays}},
    };
    return table;
}

namespace {

void requireLength(const fmu::ArrayVariable& a, std::size_t n, std::size_t size, const char* what) {
    if (n != size)
        throw fmu::ModelError(std::string(a.name) + ": nValues gives " + std::to_string(n) + " values, " + what + " " +
                              std::to_string(size));
}

}  // namespace

void getPlateArray(const PlateValues& values, const fmu::ArrayVariable& a, double* out, std::size_t n) {
    const ProbePlaces& probes = values.probes;
    if (a.vr == kVrProbeX || a.vr == kVrProbeY) {
        requireLength(a, n, probes.count, "probe_count is");
        const std::vector<double>& place = a.vr == kVrProbeX ? probes.x : probes.y;
        for (std::size_t k = 0; k < n; ++k) out[k] = place[k];
        return;
    }
    if (a.vr == kVrProbe || a.vr == kVrProbeVelocity || a.vr == kVrProbeAcceleration) {
        requireLength(a, n, probes.count, "probe_count is");
        Eigen::VectorXd plate::ProbeOutputs::*quantity = a.vr == kVrProbe ? &plate::ProbeOutputs::displacement
                                                         : a.vr == kVrProbeVelocity
                                                             ? &plate::ProbeOutputs::velocity
                                                             : &plate::ProbeOutputs::acceleration;
        for (std::size_t k = 0; k < n; ++k) out[k] = values.probe(quantity, k);
        return;
    }
    if ((a.vr != kVrVertexDisplacement && a.vr != kVrVertexStress) || !values.simulation)
        throw fmu::ModelError(std::string(a.name) + " is not an array of the plate");
    const std::vector<double> u =
        a.vr == kVrVertexStress ? values.simulation->vertexStress() : values.simulation->vertexDisplacements();
    if (u.size() != n)
        throw fmu::ModelError(std::string(a.name) + ": nValues gives " + std::to_string(n) + " values, the mesh has " +
                              std::to_string(u.size()) + " vertices");
    for (std::size_t k = 0; k < n; ++k) out[k] = u[k];
}

void setPlateArray(PlateValues& values, const fmu::ArrayVariable& a, const double* in, std::size_t n) {
    if (a.vr != kVrProbeX && a.vr != kVrProbeY) throw fmu::ModelError(std::string(a.name) + " cannot be set");
    ProbePlaces& probes = values.probes;
    requireLength(a, n, probes.count, "probe_count is");
    std::vector<double>& place = a.vr == kVrProbeX ? probes.x : probes.y;
    for (std::size_t k = 0; k < n; ++k) place[k] = in[k];
    probes.placed = true;
}

}  // namespace plateimpact
