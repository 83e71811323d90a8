#pragma once
// Stress and probes recovered from the discrete field (docs/theory.md §23): the functionals the
// schemes evaluate — w at the probes, w_xx at the clamped edge's samples, the three curvatures at
// every vertex's samples — and what PlateSimulation makes of their values: von Mises surface
// stresses, their largest values and where, the probes' absolute motion. Built once; reading
// allocates nothing but the vertex field it returns.
#include <Eigen/Core>
#include <vector>

#include "fe/Assembly.h"
#include "fe/PointEvaluation.h"
#include "plate/LinearRows.h"
#include "plate/PlateParameters.h"
#include "schemes/PlateOutputs.h"

namespace plate {

class Scheme;

class FieldRecovery {
public:
    FieldRecovery(const FiniteElementSpace& space, const ClampedPlate& clamped, const PlateParameters& p);

    // Every functional over the free dofs: the probes, with stress_outputs the root's samples and 3 per
    // vertex sample, then w at the vertices that are no contact row.
    const SparseRows& functionals() const { return functionals_; }

    // The largest |w_xx| over the clamped edge's samples at the output level: the root's peak, tracked
    // every step with stress_outputs (PlateSimulation) (one product of 2 ny + 1 rows, 2 ny with FVS; no allocation).
    double rootCurvature(const Scheme& scheme) const;
    // The root's von Mises stress of the curvature w_xx: on x = 0 the clamp makes w and w_x vanish
    // identically, so w_yy = w_xy = 0 there and σ_vm = 6D/t² |w_xx| √(1 − ν + ν²) (§23).
    double rootStress(double curvature) const { return rootFactor_ * curvature; }
    // The root's stress now and the largest von Mises stress over the plate's samples (vertices, the
    // root's) with its position. `plate`: the largest over the plate too (rows at every vertex), else
    // the root's only.
    void fill(const Scheme& scheme, PlateOutputs& o, bool plate) const;
    // The probes (absolute w, velocity, acceleration as the port's points: setPortKinematics) into
    // `o`, sized to the probes (no allocation when it already is).
    void fillProbes(const Scheme& scheme, double dt, ProbeOutputs& o) const;
    Eigen::Index probeCount() const { return probeCount_; }
    // The von Mises stress at every mesh vertex (the largest over its samples).
    std::vector<double> vertexStress(const Scheme& scheme) const;
    // The vertices no stop covers carry no contact row (docs/theory.md §25): the scheme reports them
    // at the clamp's height; this adds their w (the heights of every vertex, vertex_output).
    void addFreeVertices(const Scheme& scheme, std::vector<double>& heights) const;

    // σ_vm = 6D/t² · √(a² − ab + b² + 3c²), a = w_xx + ν w_yy, b = w_yy + ν w_xx, c = (1 − ν) w_xy (§23).
    double vonMises(double wxx, double wyy, double wxy) const;

private:
    void fieldValues(const Scheme& scheme) const;  // the vertex samples' curvatures into field_

    double moment_ = 0.0, nu_ = 0.0, rootFactor_ = 0.0;  // 6D/t², ν, 6D/t² √(1 − ν + ν²)
    bool stress_ = false;  // stress_outputs: else the stresses read 0 (not computed)
    Eigen::Index probeCount_ = 0;  // the probes' rows come first
    Eigen::Index rootFirst_ = 0, fieldFirst_ = 0, valueFirst_ = 0;
    std::vector<PointLocation> rootSamples_, fieldSamples_;
    std::vector<int> fieldVertex_;
    std::vector<int> valueVertex_;  // the free vertices that are no contact row (w at each, last)
    int vertexCount_ = 0;
    SparseRows functionals_;
    mutable Eigen::VectorXd root_, field_, values_;  // scratch of the reads
    mutable Eigen::MatrixXd heights_;  // the probes' absolute heights at the three levels (a column each)
};

}  // namespace plate
