#include "schemes/FieldRecovery.h"

#include <algorithm>
#include <cmath>

#include "schemes/Scheme.h"

namespace plate {

namespace {

// Appends a functional over the global dofs as a row over the free dofs (clamped dofs are zero).
void addRow(const PointFunctional& f, const ClampedPlate& clamped, Eigen::Index row,
            std::vector<Eigen::Triplet<double>>& entries) {
    for (std::size_t k = 0; k < f.dofs.size(); ++k) {
        const auto it = std::lower_bound(clamped.freeDofs.begin(), clamped.freeDofs.end(), f.dofs[k]);
        if (it != clamped.freeDofs.end() && *it == f.dofs[k])
            entries.emplace_back(row, Eigen::Index(it - clamped.freeDofs.begin()), f.coefficients[k]);
    }
}

}  // namespace

FieldRecovery::FieldRecovery(const FiniteElementSpace& space, const ClampedPlate& clamped, const PlateParameters& p)
    : moment_(6.0 * p.material.bendingStiffness() / (p.material.thickness * p.material.thickness)),
      nu_(p.material.poissonRatio),
      rootFactor_(moment_ * std::sqrt(1.0 - nu_ + nu_ * nu_)),
      stress_(p.outputs.stressOutputs),
      probeCount_(Eigen::Index(p.outputs.probeCount())),
      vertexCount_(space.mesh().vertexCount()) {
    // The stresses' functionals only where they are asked for: three per vertex sample, more rows than
    // the contact vertices' (the condensed plate's setup solves for them: 112x40, 0.5 GB).
    if (stress_) {
        rootSamples_ = clampedEdgeSamples(space);
        fieldSamples_ = vertexSamples(space, fieldVertex_);
    }
    const std::vector<PointLocation>& root = rootSamples_;
    rootFirst_ = probeCount_;
    fieldFirst_ = rootFirst_ + Eigen::Index(root.size());
    valueFirst_ = fieldFirst_ + 3 * Eigen::Index(fieldSamples_.size());
    const Mesh& mesh = space.mesh();
    std::vector<bool> isRow(std::size_t(mesh.vertexCount()), false);
    for (int v : clamped.contactVertices) isRow[std::size_t(v)] = true;
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if (!mesh.isClamped(v) && !isRow[std::size_t(v)]) valueVertex_.push_back(v);
    const Eigen::Index rows = valueFirst_ + Eigen::Index(valueVertex_.size());
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index k = 0; k < probeCount_; ++k)
        addRow(
            pointFunctional(space, locate(space, {p.outputs.probeX[std::size_t(k)], p.outputs.probeY[std::size_t(k)]}),
                            PointQuantity::Value),
            clamped, k, entries);
    for (std::size_t i = 0; i < root.size(); ++i)
        addRow(pointFunctional(space, root[i], PointQuantity::Dxx), clamped, rootFirst_ + Eigen::Index(i), entries);
    const PointQuantity curvatures[3] = {PointQuantity::Dxx, PointQuantity::Dyy, PointQuantity::Dxy};
    for (std::size_t i = 0; i < fieldSamples_.size(); ++i)
        for (int c = 0; c < 3; ++c)
            addRow(pointFunctional(space, fieldSamples_[i], curvatures[c]), clamped,
                   fieldFirst_ + 3 * Eigen::Index(i) + c, entries);
    for (std::size_t k = 0; k < valueVertex_.size(); ++k) {
        const Eigen::Vector2d x = mesh.point(valueVertex_[k]);
        addRow(pointFunctional(space, locate(space, x), PointQuantity::Value), clamped, valueFirst_ + Eigen::Index(k),
               entries);
    }
    functionals_.resize(rows, Eigen::Index(clamped.freeDofs.size()));
    functionals_.setFromTriplets(entries.begin(), entries.end());
    root_.resize(Eigen::Index(root.size()));
    heights_.resize(probeCount_, 3);
    field_.resize(3 * Eigen::Index(fieldSamples_.size()));
    values_.resize(Eigen::Index(valueVertex_.size()));
}

void FieldRecovery::addFreeVertices(const Scheme& scheme, std::vector<double>& heights) const {
    if (valueVertex_.empty()) return;
    scheme.recover(valueFirst_, 0, values_);
    for (std::size_t k = 0; k < valueVertex_.size(); ++k)
        heights[std::size_t(valueVertex_[k])] += values_[Eigen::Index(k)];
}

double FieldRecovery::vonMises(double wxx, double wyy, double wxy) const {
    const double a = wxx + nu_ * wyy, b = wyy + nu_ * wxx, c = (1.0 - nu_) * wxy;
    return moment_ * std::sqrt(a * a - a * b + b * b + 3.0 * c * c);
}

double FieldRecovery::rootCurvature(const Scheme& scheme) const {
    if (root_.size() == 0) return 0.0;
    scheme.recover(rootFirst_, 0, root_);
    return root_.cwiseAbs().maxCoeff();
}

void FieldRecovery::fieldValues(const Scheme& scheme) const { scheme.recover(fieldFirst_, 0, field_); }

void FieldRecovery::fill(const Scheme& scheme, PlateOutputs& o, bool plate) const {
    // What is off reads 0 and is not computed (NaN would say it better, but masters and checks take a
    // NaN output for a failed run: measured with fmpy's, libcosim's and this suite's own).
    constexpr double off = 0.0;
    if (!stress_) {
        o.rootStress = o.maxStress = o.maxStressX = o.maxStressY = off;
        return;
    }
    scheme.recover(rootFirst_, 0, root_);
    o.rootStress = rootStress(root_.size() > 0 ? root_.cwiseAbs().maxCoeff() : 0.0);
    if (!plate) return;
    // The largest over the vertices and the root's samples (its middles are no vertices, and the
    // largest stress is often there).
    fieldValues(scheme);
    double largest = -1.0;
    for (Eigen::Index i = 0; i < root_.size(); ++i) {
        const double s = rootStress(std::abs(root_[i]));
        if (s > largest) {
            largest = s;
            o.maxStress = s;
            o.maxStressX = 0.0;
            o.maxStressY = rootSamples_[std::size_t(i)].point.y();
        }
    }
    for (std::size_t i = 0; i < fieldSamples_.size(); ++i) {
        const Eigen::Index r = 3 * Eigen::Index(i);
        const double s = vonMises(field_[r], field_[r + 1], field_[r + 2]);
        if (s > largest) {
            largest = s;
            o.maxStress = s;
            o.maxStressX = fieldSamples_[i].point.x();
            o.maxStressY = fieldSamples_[i].point.y();
        }
    }
}

void FieldRecovery::fillProbes(const Scheme& scheme, double dt, ProbeOutputs& o) const {
    if (o.displacement.size() != probeCount_) o.resize(probeCount_);
    if (probeCount_ == 0) return;
    // The probes' absolute heights at the three levels; velocity and acceleration as the corners'.
    // One row at a time: a product over several dense rows rounds a row differently with their
    // number (Eigen's kernels block the rows), and a probe's value must not depend on how many
    // others are asked for.
    for (int level = 0; level < 3; ++level) {
        for (Eigen::Index k = 0; k < probeCount_; ++k) scheme.recover(k, level, heights_.col(level).segment(k, 1));
        heights_.col(level).array() += scheme.clampHeight(level);
    }
    const double dt2 = dt * dt;
    for (Eigen::Index k = 0; k < probeCount_; ++k) {
        const double now = heights_(k, 0), prev = heights_(k, 1), prev2 = heights_(k, 2);
        o.displacement[k] = now;
        o.velocity[k] = backwardVelocity(now, prev, prev2, dt);
        o.acceleration[k] = centralAcceleration(now, prev, prev2, dt2);
    }
}

std::vector<double> FieldRecovery::vertexStress(const Scheme& scheme) const {
    if (!stress_) return std::vector<double>(std::size_t(vertexCount_), 0.0);
    fieldValues(scheme);
    std::vector<double> s(std::size_t(vertexCount_), 0.0);
    for (std::size_t i = 0; i < fieldSamples_.size(); ++i) {
        const Eigen::Index r = 3 * Eigen::Index(i);
        double& v = s[std::size_t(fieldVertex_[i])];
        v = std::max(v, vonMises(field_[r], field_[r + 1], field_[r + 2]));
    }
    return s;
}

}  // namespace plate
