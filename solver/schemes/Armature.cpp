#include "schemes/Armature.h"

#include <cmath>
#include <sstream>

#include "schemes/NewmarkScheme.h"
#include "plate/PlateParameters.h"

namespace plate {

Armature::Armature(const DiscretePlate& plate, const CarrierOptions& options) : plate_(plate), options_(options) {
    const double dt = plate_.dt(), beta = plate_.beta();
    // (T.18): the carrier's row. Its own mass, spring and damper as the scheme takes them (the
    // spring β-averaged, the damper centred, as the plate's stiffness and Rayleigh damping), plus
    // the plate's rigid mass m = 1ᵀM1, which the relative coordinates w leave to the clamp.
    alpha_ = options_.mass + plate_.totalMass() + beta * dt * dt * options_.stiffness + 0.5 * dt * options_.damping;
    plate_.solveStepMatrix(plate_.baseInertia(), g_);
    schur_ = alpha_ - plate_.baseInertia().dot(g_);  // > 0: the bordered matrix is SPD
    if (plate_.contactCount() > 0) {
        plate_.gatherContact(g_, h_);
        h_ = Eigen::VectorXd::Ones(h_.size()) - h_;
    }
}

double Armature::forceBeta(double fNext) const {
    if (options_.line) return fNext;  // the wave is held over the communication step (§19)
    const double beta = plate_.beta();
    return beta * fNext + (1.0 - 2.0 * beta) * state_.force + beta * state_.forcePrev;
}

// (T.18) by the Schur complement: e = (r_z − bᵀA⁻¹r_w)/s, d = A⁻¹r_w − g e, with
// r_z = Δt²(F^{nβ} + p^{nβ}|Ω| − k_a(z − z_r)) − Δt c_a (z − z⁻) (the plate's load acts on the rigid
// translation too: 1ᵀF p = p|Ω|).
double Armature::solveFree(const NewmarkState& s, double forceBeta, double pBeta, Eigen::VectorXd& d) const {
    const double dt = plate_.dt(), dt2 = dt * dt;
    const double rz = dt2 * (forceBeta + pBeta * plate_.clamped().loadResultant -
                             options_.stiffness * (s.z - options_.restPosition)) -
                      dt * options_.damping * (s.z - s.zPrev);
    const double e = (rz - plate_.baseInertia().dot(d)) / schur_;
    d.noalias() -= e * g_;
    return e;
}

// Column j of the bordered inverse applied to (C_jᵀ, 1) (the constraint on u_j = (C w)_j + z):
// x_z = (1 − (Cg)_j)/s, x_w = A⁻¹C_jᵀ − g x_z; in contact space W + h hᵀ/s (T.19).
void Armature::column(int j, Eigen::VectorXd& x) const {
    const Eigen::Index n = plate_.size();
    Eigen::VectorXd plateColumn;
    plate_.stepMatrixContactColumn(j, plateColumn);
    x.resize(n + 1);
    x[n] = h_[j] / schur_;
    x.head(n) = plateColumn - x[n] * g_;
}

void Armature::gather(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    const Eigen::Index n = plate_.size();
    plate_.gatherContact(x.head(n).eval(), y);
    y.array() += x[n];
}

std::unique_ptr<ContactColumns> Armature::contactColumns() const {
    return std::make_unique<ContactColumns>(
        plate_.contactCount(), [this](int j, Eigen::VectorXd& x) { column(j, x); },
        [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) { gather(x, y); });
}

double Armature::correct(ContactColumns& columns, const std::vector<int>& active, const Eigen::VectorXd& mu,
                         Eigen::VectorXd& wNext, Eigen::VectorXd& y) const {
    const Eigen::Index n = plate_.size();
    double dz = 0.0;
    for (int i : active) {
        const Eigen::VectorXd& x = columns.column(i);
        wNext.noalias() += mu[i] * x.head(n);
        dz += mu[i] * x[n];
    }
    y.array() -= dz;  // the QP's y is u − z_free; the law wants C w⁺ with the final z⁺
    return dz;
}

// The carrier's equation times (z⁺ − z⁻)/2 (docs/theory.md §18): with f_n the force of the plate on
// the carrier at t_n, M_a e + Δt c_a (z⁺ − z⁻)/2 + Δt² k_a (z^β − z_r) = Δt²(F^{nβ} + f_n), so
// ΔE_a = F^{nβ}(z⁺ − z⁻)/2 + f_n (z⁺ − z⁻)/2 − c_a (z⁺ − z⁻)²/(4Δt) exactly.
void Armature::commit(const NewmarkState& s, double zNext, double fNext, double fBeta) {
    const double dt = plate_.dt(), dt2 = dt * dt, beta = plate_.beta();
    const double e = zNext - 2.0 * s.z + s.zPrev, travel = zNext - s.zPrev;
    const double spring = s.z + beta * e - options_.restPosition;  // z^β − z_r
    const double f =
        (options_.mass * e + 0.5 * dt * options_.damping * travel) / dt2 + options_.stiffness * spring - fBeta;
    CarrierState& c = state_;
    c.clampForce = f;
    c.driveWork += 0.5 * fBeta * travel;
    c.damperWork += options_.damping * travel * travel / (4.0 * dt);
    c.portWork += 0.5 * f * travel;
    if (options_.line) {
        // The outgoing wave a_n = F^{nβ} − 2Z v_n, v_n = (z⁺ − z⁻)/(2Δt): the step's power into the line is
        // (a_n² − F^{nβ}²)/(4Z) (§19).
        const double a = fBeta - options_.damping * travel / dt;
        c.waveSum += a * dt;
        c.waveSquares += a * a * dt;
    }
    c.forcePrev = c.force;
    c.force = fNext;
}

double Armature::energy(const NewmarkState& s) const {
    const double dt = plate_.dt(), beta = plate_.beta();
    const double v = (s.z - s.zPrev) / dt, a = s.z - options_.restPosition, b = s.zPrev - options_.restPosition;
    return 0.5 * options_.mass * v * v +
           0.5 * options_.stiffness * (beta * (a * a + b * b) + (1.0 - 2.0 * beta) * a * b);
}

void Armature::beginCommunication() {
    state_.waveSum = 0.0;
    state_.waveSquares = 0.0;
}

void Armature::endCommunication(long long steps) {
    if (!options_.line || steps <= 0) return;
    CarrierState& c = state_;
    const double h = double(steps) * plate_.dt(), z = options_.damping;
    c.waveOut = c.waveSum / h;
    c.transit = h * c.waveOut * c.waveOut / (4.0 * z);
    c.lineLoss += (c.waveSquares - h * c.waveOut * c.waveOut) / (4.0 * z);
}

// ---------------------------------------------------------------------------------------------
// NewmarkScheme::step with the clamp carried (docs/theory.md §18): the plate's step with the
// carrier's row bordered on, the same contact QP on the bordered columns, the plate's ledger as
// always (its base is the carrier's z⁺) and the carrier's own.

void NewmarkScheme::stepCarried(double fNext, double pNext) {
    const NewmarkState& s = state_;
    if (!std::isfinite(fNext) || !std::isfinite(pNext) || !(std::fabs(fNext) <= kMaxCarrierForce) ||
        !(std::fabs(pNext) <= kMaxLoad)) {
        std::ostringstream msg;
        msg << "input out of range at t = " << (s.step + 1) * dt() << ": "
            << (armature_->options().line ? "tlm_wave_in = " : "drive_force = ") << fNext << ", load = " << pNext
            << " (allowed: finite, |force| <= " << kMaxCarrierForce << " N, |load| <= " << kMaxLoad << " Pa)";
        throw StepError(msg.str(), double(s.step + 1) * dt());
    }
    const double fBeta = armature_->forceBeta(fNext);
    const double pBeta = beta() * pNext + (1.0 - 2.0 * beta()) * s.p + beta() * s.pPrev;  // f^{nβ}
    assembleRightHandSide(0.0, pBeta);  // the base term b e moves into the bordered row
    plate_->solveStepMatrix(rhs_, d_);
    const double e = armature_->solveFree(s, fBeta, pBeta, d_);
    double zNext = 2.0 * s.z - s.zPrev + e;
    wNext_.noalias() = 2.0 * s.w - s.wPrev + d_;
    ContactWork contact;
    int iterations = 0, contactCount = 0;
    double kkt = 0.0;
    carrierShift_ = 0.0;
    if (law_) contact = resolveContact(zNext, iterations, kkt, contactCount);
    zNext += carrierShift_;
    if (!std::isfinite(zNext) || zNext < obstacles_.clampLower() || zNext > obstacles_.clampUpper()) {
        std::ostringstream msg;
        msg.precision(15);
        msg << "the carried clamp reached z = " << zNext << " at t = " << (s.step + 1) * dt()
            << ", past an obstacle (allowed: obstacle_lower <= z <= obstacle_upper): the drive is too strong for "
               "this gap";
        throw StepError(msg.str(), double(s.step + 1) * dt());
    }
    const auto [damped, sNext, tNext] = finishSolve();
    const double baseJump = zNext - 2.0 * s.z + s.zPrev;
    const double work = inputWork(zNext, baseJump, pBeta, sNext, tNext, contact);
    armature_->commit(s, zNext, fNext, fBeta);
    commit(zNext, pNext, sNext, tNext, contact, damped, work, iterations, kkt, contactCount);
}

}  // namespace plate
