#include "plate/BoxQP.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plate {

ContactColumns::ContactColumns(int count, ColumnFn column, GatherFn gather)
    : count_(count), columnFn_(std::move(column)), gatherFn_(std::move(gather)), z_(count), w_(count) {}

void ContactColumns::ensure(int j) {
    if (z_[j].size() != 0) return;
    columnFn_(j, z_[j]);
    gatherFn_(z_[j], w_[j]);
}

BoxQP::BoxQP(ContactColumns& columns, int maxPdasIterations)
    : columns_(columns),
      maxPdasIterations_(maxPdasIterations),
      wss_(columns.count(), columns.count()),
      rhs_(columns.count()),
      residualOnActive_(columns.count()),
      yTrial_(columns.count()),
      current_(columns.count()) {
    active_.reserve(columns.count());
    factoredSet_.reserve(columns.count());
}

namespace {
inline double target(int i, signed char s, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
    return s < 0 ? lower[i] : upper[i];
}
// Below this a bound "violation" is roundoff of y = y_free + Wμ, not contact (1e-15 of the
// gap scale keeps the guaranteed penetration far under the 1e-12 m product limit).
inline double slack(double bound) { return 1e-15 * (1.0 + std::abs(bound)); }
}  // namespace

bool BoxQP::solveOnActive(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                          const std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y) {
    const int na = static_cast<int>(active_.size());
    y = yFree;
    if (na == 0) return true;
    // W_SS only changes with the set: in sustained contact it is factored once.
    if (factoredSet_ != active_) {
        for (int b = 0; b < na; ++b) {
            const auto col = columns_.contactColumn(active_[b]);
            for (int a = 0; a < na; ++a) wss_(a, b) = col[active_[a]];
        }
        Eigen::Ref<Eigen::MatrixXd> block = wss_.topLeftCorner(na, na);
        Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(block);  // in place: no allocation
        // A reduced (modal) plate has rank(W) ≤ modes: a set of more, or of dependent,
        // vertices gives a singular W_SS. Treat a pivot below 1e-12 of the largest as that.
        const auto d = block.diagonal().cwiseAbs2();
        if (llt.info() == Eigen::Success && d.minCoeff() > 1e-12 * d.maxCoeff())
            factoredSet_.assign(active_.begin(), active_.end());  // within reserved capacity
        else
            factoredSet_.clear();
    }
    if (factoredSet_ != active_) return false;  // singular on this set: the caller decides
    for (int a = 0; a < na; ++a) {
        const int i = active_[a];
        rhs_[a] = target(i, state[i], lower, upper) - yFree[i];
    }
    // wss_ holds the Cholesky factor in its lower triangle (in-place LLT above).
    auto l = wss_.topLeftCorner(na, na).triangularView<Eigen::Lower>();
    auto r = rhs_.head(na);
    l.solveInPlace(r);
    l.transpose().solveInPlace(r);
    for (int a = 0; a < na; ++a) {
        const int i = active_[a];
        mu[i] = r[a];
        const auto column = columns_.contactColumn(i);
        y.head(column.size()).noalias() += r[a] * column;
    }
    for (int a = 0; a < na; ++a) {
        const int i = active_[a];
        const double t = target(i, state[i], lower, upper);
        residualOnActive_[a] = y[i] - t;
        y[i] = t;  // on the obstacle exactly, not up to the roundoff of y_free + Wμ
    }
    return true;
}

QPResult BoxQP::solve(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                      std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y) {
    const int m = columns_.count();
    // mu is zero off the active set on return. The caller's vector may have been written by another
    // solver or restored from a snapshot since this one last ran, so clear it whole (O(m), as the
    // set scans below), not only this solver's last set.
    mu.setZero();
    QPResult result;
    for (int it = 1; it <= maxPdasIterations_; ++it) {
        active_.clear();
        for (int i = 0; i < m; ++i)
            if (state[i] != 0) active_.push_back(i);
        for (int i : active_) mu[i] = 0.0;
        if (!solveOnActive(yFree, lower, upper, state, mu, y)) break;  // dependent set: fallback
        bool changed = false;
        for (int i : active_) {
            if ((state[i] < 0 && mu[i] < 0.0) || (state[i] > 0 && mu[i] > 0.0)) {
                state[i] = 0;
                changed = true;
            }
        }
        for (int i = 0; i < m; ++i) {
            if (state[i] != 0) continue;
            // Only indices that were free in this iteration can enter.
            if (y[i] < lower[i] - slack(lower[i])) {
                state[i] = -1;
                changed = true;
            } else if (y[i] > upper[i] + slack(upper[i])) {
                state[i] = +1;
                changed = true;
            }
        }
        result.iterations = it;
        if (!changed) {
            result.converged = true;
            break;
        }
        for (int i : active_) mu[i] = 0.0;
    }
    if (!result.converged) {
        int extra = 0;
        result.converged = primalActiveSet(yFree, lower, upper, state, mu, y, extra);
        result.iterations += extra;
    }
    result.kktResidual = kktResidual(yFree, lower, upper, state, mu, y);
    return result;
}

bool BoxQP::primalActiveSet(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                            std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y, int& iterations) {
    // Nocedal–Wright Alg. 16.3 for bounds, in y: from a feasible point, step towards the
    // minimizer with the working set fixed on its bounds; block on the first bound hit;
    // drop a bound whose multiplier has the wrong sign. Finite for SPD W.
    const int m = columns_.count();
    for (int i : active_) mu[i] = 0.0;
    y = yFree;
    // Start from w = 0 (y = 0) with an empty working set when it is feasible — it is in every
    // time step, the clamp lying between the obstacles. Then every iterate stays in the range
    // of C (y = C w) and a blocking bound is always independent of the working set, so W_SS
    // stays nonsingular even for a reduced plate where rank(W) < count.
    const bool zeroFeasible = (lower.head(m).array() <= 0.0).all() && (upper.head(m).array() >= 0.0).all();
    Eigen::VectorXd& current = current_;
    if (zeroFeasible)
        current.setZero();
    else
        current.head(m) = yFree.head(m).cwiseMax(lower.head(m)).cwiseMin(upper.head(m));
    for (int i = 0; i < m; ++i)
        state[i] = zeroFeasible ? 0 : (yFree[i] < lower[i] ? -1 : (yFree[i] > upper[i] ? +1 : 0));
    const int maxIterations = 10 * m + 100;
    for (iterations = 1; iterations <= maxIterations; ++iterations) {
        active_.clear();
        for (int i = 0; i < m; ++i)
            if (state[i] != 0) active_.push_back(i);
        for (int i = 0; i < m; ++i) mu[i] = 0.0;
        if (!solveOnActive(yFree, lower, upper, state, mu, yTrial_)) break;
        double alpha = 1.0;
        int blocking = -1;
        bool moved = false;
        for (int i = 0; i < m; ++i) {
            if (state[i] != 0) continue;
            const double p = yTrial_[i] - current[i];
            if (p != 0.0) moved = true;
            if (p < 0.0 && yTrial_[i] < lower[i]) {
                const double a = (lower[i] - current[i]) / p;
                if (a < alpha) alpha = a, blocking = i;
            } else if (p > 0.0 && yTrial_[i] > upper[i]) {
                const double a = (upper[i] - current[i]) / p;
                if (a < alpha) alpha = a, blocking = i;
            }
        }
        if (!moved || blocking < 0) {
            current.head(m) = yTrial_.head(m);
            // At the minimizer on the working set: drop the worst wrong-signed multiplier.
            int worst = -1;
            double worstValue = 0.0;
            for (int i : active_) {
                const double wrong = state[i] < 0 ? -mu[i] : mu[i];
                const double scaled = wrong / std::sqrt(columns_.contactColumn(i)[i]);
                if (scaled > worstValue) worstValue = scaled, worst = i;
            }
            if (worst < 0) {
                y.head(m) = current.head(m);
                return true;
            }
            state[worst] = 0;
            continue;
        }
        for (int i = 0; i < m; ++i)
            if (state[i] == 0) current[i] += alpha * (yTrial_[i] - current[i]);
        state[blocking] = yTrial_[blocking] < lower[blocking] ? -1 : +1;
        current[blocking] = target(blocking, state[blocking], lower, upper);
    }
    y.head(m) = current.head(m);
    return false;
}

double BoxQP::kktResidual(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                          const std::vector<signed char>& state, const Eigen::VectorXd& mu,
                          const Eigen::VectorXd& y) const {
    const int m = columns_.count();
    double scaleY = std::numeric_limits<double>::min();
    for (int i = 0; i < m; ++i) {
        scaleY = std::max(scaleY, std::abs(yFree[i]));
        if (std::isfinite(lower[i])) scaleY = std::max(scaleY, std::abs(lower[i]));
        if (std::isfinite(upper[i])) scaleY = std::max(scaleY, std::abs(upper[i]));
    }
    double scaleMu = std::numeric_limits<double>::min();
    for (int i : active_) scaleMu = std::max(scaleMu, std::abs(mu[i]));
    double r = 0.0;
    for (int i = 0; i < m; ++i) {
        // Primal feasibility.
        r = std::max(r, std::max(lower[i] - y[i], y[i] - upper[i]) / scaleY);
        // Complementarity off the set: μ_i must vanish.
        if (state[i] == 0) r = std::max(r, std::abs(mu[i]) / scaleMu);
    }
    for (std::size_t a = 0; a < active_.size(); ++a) {
        const int i = active_[a];
        // Stationarity y = y_free + Wμ on the set (before snapping to the bound).
        r = std::max(r, std::abs(residualOnActive_[a]) / scaleY);
        // Sign of the multiplier (complementarity on the set is exact: y_i is the bound).
        r = std::max(r, (state[i] < 0 ? -mu[i] : mu[i]) / scaleMu);
    }
    return r;
}

}  // namespace plate
