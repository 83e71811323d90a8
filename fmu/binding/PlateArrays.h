#pragma once
// FMI 3.0 only (FMI 2.0 has no arrays): the plate's arrays — the absolute displacement and the
// stress at every mesh vertex, the probes' places and motion — and the UInt64 structural parameters
// that size them: vertex_output (the vertex arrays' switch, 1 or 0: a value of its own), views of
// the table's nx and ny (vertices_x = nx + 1, vertices_y = ny + 1), and probe_count (the probes'
// count, PlateValues::probes, set in Configuration Mode).
#include <cstddef>
#include <vector>

#include "binding/PlateVariables.h"
#include "core/Model.h"

namespace plateimpact {

// Value references of the FMI 3.0 interface only (time is 1000, fmu/fmi3/Fmi3Interface.h).
enum PlateArrayVr : fmu::ValueReference {
    kVrVerticesX = 1001,
    kVrVerticesY = 1002,
    kVrVertexDisplacement = 1003,
    kVrVertexOutput = 1004,
    kVrVertexStress = 1005,
    kVrProbeCountArrays = 1006,  // probe_count (FMI 2.0's Integer probe_count is vr 218)
    kVrProbeX = 1007,
    kVrProbeY = 1008,
    kVrProbe = 1009,
    kVrProbeVelocity = 1010,
    kVrProbeAcceleration = 1011,
};

const std::vector<fmu::StructuralParameter>& plateStructuralParameters();
const std::vector<fmu::ArrayVariable>& plateArrays();
// The n values of array `a`: a vertex array (vertex (i, j) at index i (ny + 1) + j: x slowest; the
// simulation built), the probes' places or their motion; throws fmu::ModelError if n is not its size.
void getPlateArray(const PlateValues& values, const fmu::ArrayVariable& a, double* out, std::size_t n);
// The probes' places (probe_x, probe_y; n = probe_count, checked by the caller).
void setPlateArray(PlateValues& values, const fmu::ArrayVariable& a, const double* in, std::size_t n);

}  // namespace plateimpact
