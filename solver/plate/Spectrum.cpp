#include "plate/Spectrum.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "plate/DenseEigenproblem.h"
#include "plate/SparseCholesky.h"

namespace plate {

// The Weyl sequence frac(a (i + 1) + b (j + 1)) − 1/2 has no structure that a mode could be
// orthogonal to, in exact arithmetic but for one rounding per operation — the same bits on every
// CPU (the C library's sine, used before, is not).
double startEntry(Eigen::Index i, Eigen::Index j) {
    const double x = 0.6180339887498949 * double(i + 1) + 0.4142135623730951 * double(j + 1);
    return (x - std::floor(x)) - 0.5;
}

namespace {

// Dense generalized eigensolver: fine up to a few thousand dofs (O(n³) once at start).
constexpr Eigen::Index kDenseLimit = 3000;

void denseModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::MatrixXd k = Eigen::MatrixXd(plate.stiffness);
    const Eigen::MatrixXd m = Eigen::MatrixXd(plate.mass);
    if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success) {
        // A singular mass (docs/theory.md §11): M φ = (1/ω²) K φ with K SPD; the massless
        // directions are the zero eigenvalues (ω = ∞) and are left out.
        Eigen::VectorXd mu;
        Eigen::MatrixXd vectors;  // Φᵀ K Φ = I, ascending
        if (!solveDenseEigenproblem(m, k, mu, vectors)) throw std::runtime_error("modal analysis failed");
        const double cut = 1e-12 * mu.maxCoeff();
        Eigen::Index massive = 0;
        while (massive < mu.size() && mu[mu.size() - 1 - massive] > cut) ++massive;
        const Eigen::Index count = std::min(modes, massive);
        phi.resize(m.rows(), count);
        omega2.resize(count);
        for (Eigen::Index j = 0; j < count; ++j) {
            const Eigen::Index c = mu.size() - 1 - j;  // largest 1/ω² first
            omega2[j] = 1.0 / mu[c];
            phi.col(j) = vectors.col(c) * std::sqrt(omega2[j]);  // Φᵀ M Φ = I
        }
        return;
    }
    // Eigen normalizes the eigenvectors to Φᵀ M Φ = I and sorts the eigenvalues ascending.
    Eigen::VectorXd values;
    if (!solveDenseEigenproblem(k, m, values, phi)) throw std::runtime_error("modal analysis failed");
    phi.conservativeResize(Eigen::NoChange, modes);
    omega2 = values.head(modes);
}

// Subspace iteration X ← K⁻¹ M X with Rayleigh–Ritz, p = m + guard vectors: converges like
// (ω_m / ω_{p+1})^{2k}; stop when the m Ritz values settle to 1e-12.
void subspaceModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    const Eigen::Index p = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * modes, modes + 16));
    const SparseCholesky kFactor(plate.stiffness);
    Eigen::MatrixXd x(n, p);
    for (Eigen::Index j = 0; j < p; ++j)
        for (Eigen::Index i = 0; i < n; ++i) x(i, j) = startEntry(i, j);
    Eigen::VectorXd previous = Eigen::VectorXd::Zero(modes), col, ritzValues;
    Eigen::MatrixXd ritzVectors;
    for (int it = 0; it < 300; ++it) {
        const Eigen::MatrixXd mx = plate.mass * x;
        for (Eigen::Index j = 0; j < p; ++j) {
            kFactor.solve(mx.col(j), col);
            x.col(j) = col;
        }
        const Eigen::MatrixXd kr = x.transpose() * (plate.stiffness * x);
        const Eigen::MatrixXd mr = x.transpose() * (plate.mass * x);
        if (!solveDenseEigenproblem(0.5 * (kr + kr.transpose()), 0.5 * (mr + mr.transpose()), ritzValues, ritzVectors))
            throw std::runtime_error("modal analysis failed (Rayleigh-Ritz)");
        x = x * ritzVectors;  // M-orthonormal Ritz vectors, ascending
        omega2 = ritzValues.head(modes);
        if (it > 2 && ((omega2 - previous).cwiseAbs().array() <= 1e-12 * omega2.array()).all()) break;
        previous = omega2;
    }
    phi = x.leftCols(modes);
}

}  // namespace

// A few modes of a large space: subspace iteration (~2m solves per iteration); the dense O(n³)
// solution where it is cheap or where most modes are wanted. Measured, m = 40: Argyris 28x10 (2727
// dofs) 11 s against 64 s dense; FVS 40x14 (1800) 1.8 s against 5–13 s; Argyris 14x5 (734) dense 0.5 s
// against 1.2 s.
bool denseSolutionServes(Eigen::Index n, int modes) {
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    return !(m < n && 4 * m <= n && n > 1200) && n <= kDenseLimit;
}

// The dense solution's columns are each computed whole, in ascending order (largest 1/ω² first with a
// singular mass), whatever the count asked: its leading m are denseModes(plate, m)'s, bit for bit.
void leadingModes(const Eigen::MatrixXd& allPhi, const Eigen::VectorXd& allOmega2, int modes, Eigen::MatrixXd& phi,
                  Eigen::VectorXd& omega2) {
    const Eigen::Index n = allPhi.cols();
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    phi = allPhi.leftCols(m);
    omega2 = allOmega2.head(m);
}

void lowestModes(const ClampedPlate& plate, int modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    if (denseSolutionServes(n, modes))
        denseModes(plate, m, phi, omega2);
    else if (m < n)
        subspaceModes(plate, m, phi, omega2);
    else
        throw std::runtime_error("a complete modal basis needs a space of at most 3000 dofs");
}

// Largest eigenvalue of M⁻¹K by power iteration with the Rayleigh quotient. The top of the FE
// spectrum is clustered, so the quotient is within a fraction of a percent after a few hundred
// iterations even where the eigenvector converges slowly.
double largestEigenvalue(const ClampedPlate& plate) {
    const SparseCholesky massFactor(plate.mass);
    Eigen::VectorXd x = Eigen::VectorXd::Ones(plate.mass.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.74 * startEntry(i, 0);
    Eigen::VectorXd kx, y, mx;
    double lambda = 0.0;
    for (int it = 0; it < 2000; ++it) {
        kx = plate.stiffness * x;
        massFactor.solve(kx, y);
        mx = plate.mass * y;
        const double next = y.dot(plate.stiffness * y) / y.dot(mx);
        x = y / std::sqrt(y.dot(mx));
        if (it > 50 && std::abs(next - lambda) <= 1e-7 * next) {
            lambda = next;
            break;
        }
        lambda = next;
    }
    return lambda;
}

}  // namespace plate
