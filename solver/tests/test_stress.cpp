// Stress recovery (docs/theory.md §23) against facts of the plate: at the clamp w_yy = w_xy = 0, so
// σ_yy = ν σ_xx and the root's von Mises stress is √(1 − ν + ν²) σ_xx; the root moment ∫ D w_xx dy of a
// static pressure converges to the exact clamp moment p W L²/2 (the refinement study up to 56×20 is
// tools/stress_convergence.py; here its two cheapest meshes); and the root stress amplitude of a
// harmonic base motion below the first resonance is the frequency-domain (all-mode modal) solution's.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cmath>
#include <complex>

#include "PlateSimulation.h"
#include "fe/Assembly.h"
#include "fe/PointEvaluation.h"
#include "plate/PlateParameters.h"

using namespace plate;

namespace {

struct StaticClamp {
    double moment = 0.0;  // ∫ D w_xx dy over x = 0
    double wxxMax = 0.0, offAxisMax = 0.0;  // max |w_xx|, max(|w_yy|, |w_xy|) at the root's samples
};

double apply(const PointFunctional& f, const Eigen::VectorXd& u) {
    double sum = 0.0;
    for (std::size_t k = 0; k < f.dofs.size(); ++k) sum += f.coefficients[k] * u[f.dofs[k]];
    return sum;
}

// The static shape under the pressure p (no obstacles) and its clamp; 5 Gauss points per element
// edge integrate the cubic (Argyris) or linear (FVS) w_xx on x = 0 exactly.
StaticClamp staticClamp(ElementType element, int nx, int ny, double p) {
    PlateParameters par;
    const Mesh mesh(par.mesh.length, par.mesh.width, nx, ny);
    const auto space = makeSpace(element, mesh);
    const PlateMatrices m = assemble(*space, par.material);
    const ClampedPlate c = clamp(*space, m);
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> k(c.stiffness);
    const Eigen::VectorXd w = k.solve(p * c.pressureLoad);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(space->dofCount());
    for (std::size_t i = 0; i < c.freeDofs.size(); ++i) u[c.freeDofs[i]] = w[Eigen::Index(i)];
    StaticClamp s;
    const double g[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    const double wt[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                          0.2369268850561891};
    for (int j = 0; j < ny; ++j) {
        const double y0 = j * mesh.hy(), y1 = (j + 1) * mesh.hy();
        PointLocation at = locate(*space, {0.0, 0.5 * (y0 + y1)});
        for (int q = 0; q < 5; ++q) {
            at.point = {0.0, 0.5 * (y0 + y1) + 0.5 * (y1 - y0) * g[q]};
            s.moment += 0.5 * (y1 - y0) * wt[q] * par.material.bendingStiffness() *
                        apply(pointFunctional(*space, at, PointQuantity::Dxx), u);
        }
    }
    for (const PointLocation& at : clampedEdgeSamples(*space)) {
        s.wxxMax = std::max(s.wxxMax, std::abs(apply(pointFunctional(*space, at, PointQuantity::Dxx), u)));
        s.offAxisMax = std::max({s.offAxisMax, std::abs(apply(pointFunctional(*space, at, PointQuantity::Dyy), u)),
                                 std::abs(apply(pointFunctional(*space, at, PointQuantity::Dxy), u))});
    }
    return s;
}

}  // namespace

// Outside the anonymous namespace: TEST_P's class derives from it (a unity build warns -Wsubobject-linkage).
class StaticStress : public ::testing::TestWithParam<ElementType> {};

TEST_P(StaticStress, RootMomentConvergesToTheClampMomentAndTheClampIsUniaxial) {
    const double p = 1000.0;
    const PlateParameters par;
    const double exact = 0.5 * p * par.mesh.width * par.mesh.length * par.mesh.length;  // p W L²/2, the clamp's moment
    const StaticClamp coarse = staticClamp(GetParam(), 7, 3, p), fine = staticClamp(GetParam(), 14, 5, p);
    const double e0 = std::abs(coarse.moment - exact) / exact, e1 = std::abs(fine.moment - exact) / exact;
    // Converging: halving h_x at least halves the error (observed: ×2.7 Argyris, ×4.0 FVS; the order
    // from 14×5 to 56×20 in docs/stress_convergence.json is 1.5 and 2.0), and 14×5 is within 0.5 %.
    EXPECT_LT(e1, 0.5 * e0) << coarse.moment << " " << fine.moment;
    EXPECT_LT(e1, 5e-3);
    // w = w_x = 0 along x = 0 makes w_yy and w_xy vanish there identically: only roundoff of the
    // shape functions' coefficients (cond of the local dof matrix × eps) is left.
    EXPECT_LT(fine.offAxisMax, 1e-8 * fine.wxxMax);
}

INSTANTIATE_TEST_SUITE_P(BothElements, StaticStress, ::testing::Values(ElementType::Argyris, ElementType::Fvs));

TEST(StaticStress, RootStressOutputIsTheUniaxialVonMisesOfTheLargestRootCurvature) {
    PlateParameters par;
    par.outputs.stressOutputs = true;
    par.initialLoad = 1000.0;
    par.obstacles.lowerEnabled = par.obstacles.upperEnabled = false;
    const PlateSimulation sim(par, 0.0, par.initialLoad);
    const StaticClamp s = staticClamp(ElementType::Argyris, par.mesh.nx, par.mesh.ny, par.initialLoad);
    const double nu = par.material.poissonRatio, t = par.material.thickness;
    const double expected = 6.0 * par.material.bendingStiffness() / (t * t) * s.wxxMax * std::sqrt(1.0 - nu + nu * nu);
    // Two solves of the same static problem (the modal engine's against a sparse LDLᵀ): roundoff
    // of cond(K) ≈ 1e8 times eps.
    EXPECT_NEAR(sim.outputs(false, FieldOutputs::Points).rootStress, expected, 1e-7 * expected);
    EXPECT_EQ(sim.outputs(false, FieldOutputs::Points).rootStressPeak,
              sim.outputs(false, FieldOutputs::Points).rootStress);  // t = 0 belongs to the peak
}

// Below the first resonance (f = f1/2) without obstacles, damped (C = aM on the relative motion,
// docs/theory.md §13: the start's transients decay like e^{−a t/2}), the root stress amplitude
// reached in the time domain against the steady state of the same discrete plate,
// (K − ω²M + iωaM) W = ω² Z M·1 (w = Im(W e^{iωt})), which is the modal solution with every mode.
TEST(HarmonicStress, RootStressAmplitudeIsTheModalSolution) {
    PlateParameters par;
    par.outputs.stressOutputs = true;
    par.obstacles.lowerEnabled = par.obstacles.upperEnabled = false;
    par.law.dt = 1e-4;
    par.law.dampingMass = 20.0;  // 1/s: ζ1 ≈ 0.27, the first mode's transient decays like e^{−10 t}
    const double amplitude = 1e-3;
    PlateSimulation sim(par, 0.0);
    const double f = 0.5 * sim.firstFrequency(), omega = 2.0 * M_PI * f, period = 1.0 / f;
    const double measureFrom = 1.0, end = measureFrom + 2.0 * period;
    double largest = 0.0;
    // Switched on smoothly over 0.3 s (a C² ramp): an abrupt start would ring the high modes, which
    // the scheme (γ = ½, no numerical dissipation) damps only by a/2 in the continuum's sense.
    const auto z = [&](double t) {
        const double r = std::min(1.0, t / 0.3), ramp = r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);
        return ramp * amplitude * std::sin(omega * t);
    };
    while (sim.time() < end) {
        sim.advance(1, InputSignal{z(sim.time() + par.law.dt)}, InputSignal{});  // the scheme sees z at t_{n+1}
        if (sim.time() >= measureFrom) largest = std::max(largest, sim.outputs(false, FieldOutputs::Points).rootStress);
    }
    // The frequency-domain solution and its root stress (the same samples as the FMU's).
    const Mesh mesh(par.mesh.length, par.mesh.width, par.mesh.nx, par.mesh.ny);
    const auto space = makeSpace(par.mesh.element, mesh);
    const PlateMatrices m = assemble(*space, par.material);
    const ClampedPlate c = clamp(*space, m);
    using Complex = std::complex<double>;
    const Eigen::SparseMatrix<Complex> a =
        c.stiffness.cast<Complex>() + Complex(-omega * omega, omega * par.law.dampingMass) * c.mass.cast<Complex>();
    Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(a);
    const Eigen::VectorXcd w = lu.solve((omega * omega * amplitude) * c.baseInertia.cast<Complex>());
    Eigen::VectorXcd u = Eigen::VectorXcd::Zero(space->dofCount());
    for (std::size_t i = 0; i < c.freeDofs.size(); ++i) u[c.freeDofs[i]] = w[Eigen::Index(i)];
    double wxx = 0.0;
    for (const PointLocation& at : clampedEdgeSamples(*space)) {
        const PointFunctional fxx = pointFunctional(*space, at, PointQuantity::Dxx);
        Complex sum = 0.0;
        for (std::size_t k = 0; k < fxx.dofs.size(); ++k) sum += fxx.coefficients[k] * u[fxx.dofs[k]];
        wxx = std::max(wxx, std::abs(sum));
    }
    const double nu = par.material.poissonRatio, t = par.material.thickness;
    const double modal = 6.0 * par.material.bendingStiffness() / (t * t) * wxx * std::sqrt(1.0 - nu + nu * nu);
    // Budget: the scheme's phase error (ωΔt)²/12 ≈ 3e-7 at f and ≈ 1e-6 at f1, the peak sampled every
    // Δt (cos(ωΔt/2) ≈ 1 − 4e-7), the smooth ramp's small transient times e^{−a·0.7 s/2} ≈ 9e-4:
    // 1e-3 bounds them, ten times inside the 1 % asked of it (measured: 1.2e-4).
    EXPECT_NEAR(largest / modal, 1.0, 1e-3) << "time domain " << largest << " Pa, modal " << modal << " Pa";
    std::printf("harmonic root stress: time domain %.9g Pa, modal %.9g Pa, ratio - 1 = %.3g\n", largest, modal,
                largest / modal - 1.0);
}
