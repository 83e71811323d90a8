// The contact QP of one step: min ½ wᵀS w − wᵀb over lower ≤ C w ≤ upper, solved in the
// contact space by BoxQP. Checked on random problems against the KKT conditions in the FULL
// space (S w − b − Cᵀμ = 0, feasibility, sign, complementarity) and against brute force over
// all active sets on small ones.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "plate/BoxQP.h"

namespace {

struct Problem {
    Eigen::MatrixXd s;  // SPD n x n
    Eigen::VectorXd b;
    std::vector<int> constrained;  // C picks these entries of w
    Eigen::VectorXd lower, upper;
};

Problem randomProblem(std::mt19937& rng, int n, int m, bool twoSided) {
    std::normal_distribution<double> g;
    Problem p;
    Eigen::MatrixXd a(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) a(i, j) = g(rng);
    // Not an M-matrix: plenty of positive off-diagonal coupling in W, where PDAS may cycle.
    p.s = a * a.transpose() + 0.1 * n * Eigen::MatrixXd::Identity(n, n);
    p.b = Eigen::VectorXd::NullaryExpr(n, [&] { return 3.0 * g(rng); });
    std::vector<int> idx(n);
    for (int i = 0; i < n; ++i) idx[i] = i;
    std::shuffle(idx.begin(), idx.end(), rng);
    p.constrained.assign(idx.begin(), idx.begin() + m);
    p.lower.resize(m);
    p.upper.resize(m);
    for (int i = 0; i < m; ++i) {
        p.lower[i] = -0.2 - 0.3 * std::abs(g(rng));
        p.upper[i] = twoSided ? 0.2 + 0.3 * std::abs(g(rng)) : std::numeric_limits<double>::infinity();
    }
    return p;
}

// C picks the constrained entries of w: the contact operator of the full FE space.
plate::ContactColumns selectionColumns(const Problem& p, const Eigen::LLT<Eigen::MatrixXd>& llt) {
    const int n = static_cast<int>(p.s.rows()), m = static_cast<int>(p.constrained.size());
    return plate::ContactColumns(
        m,
        [&p, &llt, n](int j, Eigen::VectorXd& z) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
            e[p.constrained[j]] = 1.0;
            z = llt.solve(e);
        },
        [&p, m](const Eigen::VectorXd& z, Eigen::VectorXd& y) {
            y.resize(m);
            for (int i = 0; i < m; ++i) y[i] = z[p.constrained[i]];
        });
}

struct Solution {
    Eigen::VectorXd w, mu, y;
    plate::QPResult result;
};

Solution solveWithBoxQP(const Problem& p, int maxPdas) {
    const Eigen::LLT<Eigen::MatrixXd> llt(p.s);
    plate::ContactColumns columns = selectionColumns(p, llt);
    plate::BoxQP qp(columns, maxPdas);
    const int m = static_cast<int>(p.constrained.size());
    Solution s;
    s.w = llt.solve(p.b);
    Eigen::VectorXd yFree(m);
    for (int i = 0; i < m; ++i) yFree[i] = s.w[p.constrained[i]];
    std::vector<signed char> state(m, 0);
    s.mu = Eigen::VectorXd::Zero(m);
    s.result = qp.solve(yFree, p.lower, p.upper, state, s.mu, s.y);
    for (int i : qp.active()) s.w += s.mu[i] * columns.column(i);
    return s;
}

// Relative KKT residual of (w, μ) for the full-space problem.
double fullKkt(const Problem& p, const Solution& s) {
    const int m = static_cast<int>(p.constrained.size());
    Eigen::VectorXd ctmu = Eigen::VectorXd::Zero(p.s.rows());
    for (int i = 0; i < m; ++i) ctmu[p.constrained[i]] += s.mu[i];
    const double stationarity = (p.s * s.w - p.b - ctmu).norm() / (p.s.norm() * s.w.norm() + p.b.norm());
    double r = stationarity;
    const double scaleMu = std::max(1e-300, s.mu.cwiseAbs().maxCoeff());
    for (int i = 0; i < m; ++i) {
        const double y = s.w[p.constrained[i]];
        const double gap = std::isfinite(p.upper[i]) ? p.upper[i] - p.lower[i] : 1.0;
        r = std::max(r, std::max(p.lower[i] - y, y - p.upper[i]) / gap);  // feasibility
        if (s.mu[i] > 0) r = std::max(r, s.mu[i] * (y - p.lower[i]) / (scaleMu * gap));  // compl.
        if (s.mu[i] < 0) r = std::max(r, -s.mu[i] * (p.upper[i] - y) / (scaleMu * gap));
    }
    return r;
}

}  // namespace

TEST(BoxQP, RandomProblemsSatisfyFullSpaceKkt) {
    std::mt19937 rng(7);
    int contactSolved = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Problem p = randomProblem(rng, 30, 12, trial % 2 == 0);
        for (int maxPdas : {30, 0}) {
            const Solution s = solveWithBoxQP(p, maxPdas);
            ASSERT_TRUE(s.result.converged) << "trial " << trial << " pdas " << maxPdas;
            EXPECT_LE(s.result.kktResidual, 1e-10) << "trial " << trial;
            EXPECT_LE(fullKkt(p, s), 1e-10) << "trial " << trial << " pdas " << maxPdas;
            contactSolved += (s.mu.cwiseAbs().maxCoeff() > 0);
        }
    }
    EXPECT_GT(contactSolved, 300);  // the bounds were active in most trials: not a vacuous check
}

TEST(BoxQP, BothPathsAgreeWithBruteForceOverAllActiveSets) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 60; ++trial) {
        const Problem p = randomProblem(rng, 8, 5, true);
        const int m = 5;
        // Brute force: the unique KKT point among all 3^m lower/free/upper assignments.
        Eigen::VectorXd best;
        int found = 0;
        int code[5];
        for (int c = 0; c < 243; ++c) {
            int t = c;
            for (int i = 0; i < m; ++i) code[i] = t % 3 - 1, t /= 3;
            // Solve S w − Cᵀμ = b with y_i fixed where code ≠ 0 and μ_i = 0 elsewhere.
            const int n = 8;
            Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + m, n + m);
            Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
            k.topLeftCorner(n, n) = p.s;
            rhs.head(n) = p.b;
            for (int i = 0; i < m; ++i) {
                if (code[i] != 0) {
                    k(p.constrained[i], n + i) = -1.0;
                    k(n + i, p.constrained[i]) = 1.0;
                    rhs[n + i] = code[i] < 0 ? p.lower[i] : p.upper[i];
                } else {
                    k(n + i, n + i) = 1.0;  // μ_i = 0
                }
            }
            const Eigen::VectorXd x = k.fullPivLu().solve(rhs);
            bool ok = true;
            for (int i = 0; i < m && ok; ++i) {
                const double y = x[p.constrained[i]], mu = x[n + i];
                ok = y >= p.lower[i] - 1e-12 && y <= p.upper[i] + 1e-12 && (code[i] >= 0 || mu >= -1e-12) &&
                     (code[i] <= 0 || mu <= 1e-12);
            }
            if (ok) {
                ++found;
                best = x.head(n);
            }
        }
        ASSERT_GE(found, 1);
        for (int maxPdas : {30, 0}) {
            const Solution s = solveWithBoxQP(p, maxPdas);
            EXPECT_LE((s.w - best).norm(), 1e-10 * (1.0 + best.norm())) << "trial " << trial;
        }
    }
}

namespace {

// A two-sided problem of 30 unknowns and 12 constraints with its solver, built in place (the
// solver keeps references to the problem and its factor), its free contact values and a cold start.
struct TwelveContacts {
    explicit TwelveContacts(unsigned seed)
        : rng(seed), p(randomProblem(rng, 30, m, true)), llt(p.s), columns(selectionColumns(p, llt)), qp(columns) {
        const Eigen::VectorXd w = llt.solve(p.b);
        for (int i = 0; i < m; ++i) yFree[i] = w[p.constrained[i]];
    }
    plate::QPResult solve() { return qp.solve(yFree, p.lower, p.upper, state, mu, y); }

    static constexpr int m = 12;
    std::mt19937 rng;
    Problem p;
    Eigen::LLT<Eigen::MatrixXd> llt;
    plate::ContactColumns columns;
    plate::BoxQP qp;
    Eigen::VectorXd yFree = Eigen::VectorXd(m), mu = Eigen::VectorXd::Zero(m), y;
    std::vector<signed char> state = std::vector<signed char>(m, 0);
};

}  // namespace

TEST(BoxQP, WarmStartFromTheSolutionTakesOneIteration) {
    TwelveContacts c(3);
    const auto cold = c.solve();
    const auto warm = c.solve();
    EXPECT_TRUE(cold.converged);
    EXPECT_EQ(warm.iterations, 1);  // the previous step's set is the answer: verified, not searched
}

// A reduced (modal) plate: more contact vertices than coordinates, so W = G S⁻¹ Gᵀ is
// singular. The solution must still satisfy the full KKT conditions exactly.
TEST(BoxQP, RankDeficientContactOperatorOfAReducedPlate) {
    std::mt19937 rng(5);
    std::normal_distribution<double> g;
    int withContact = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const int n = 6, m = 15;
        Eigen::MatrixXd a(n, n), gm(m, n);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) a(i, j) = g(rng);
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < n; ++j) gm(i, j) = g(rng);
        const Eigen::MatrixXd s = a * a.transpose() + Eigen::MatrixXd::Identity(n, n);
        const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(n, [&] { return 4.0 * g(rng); });
        const Eigen::VectorXd lower = Eigen::VectorXd::Constant(m, -0.5);
        const Eigen::VectorXd upper =
            trial % 2 ? Eigen::VectorXd::Constant(m, 0.7) : Eigen::VectorXd::Constant(m, INFINITY);
        const Eigen::LLT<Eigen::MatrixXd> llt(s);
        plate::ContactColumns columns(
            m, [&](int j, Eigen::VectorXd& z) { z = llt.solve(Eigen::VectorXd(gm.row(j).transpose())); },
            [&](const Eigen::VectorXd& z, Eigen::VectorXd& y) { y = gm * z; });
        plate::BoxQP qp(columns);
        Eigen::VectorXd w = llt.solve(b), yFree = gm * w, mu = Eigen::VectorXd::Zero(m), y;
        std::vector<signed char> state(m, 0);
        const auto r = qp.solve(yFree, lower, upper, state, mu, y);
        ASSERT_TRUE(r.converged) << "trial " << trial;
        for (int i : qp.active()) w += mu[i] * columns.column(i);
        const Eigen::VectorXd gw = gm * w;
        const double scale = s.norm() * w.norm() + b.norm();
        EXPECT_LE((s * w - b - gm.transpose() * mu).norm(), 1e-10 * scale) << "trial " << trial;
        const double muScale = std::max(1e-300, mu.cwiseAbs().maxCoeff());
        for (int i = 0; i < m; ++i) {
            EXPECT_GE(gw[i], lower[i] - 1e-10);
            EXPECT_LE(gw[i], upper[i] + 1e-10);
            if (mu[i] > 0) EXPECT_NEAR(gw[i], lower[i], 1e-10) << "trial " << trial;
            if (mu[i] < 0) EXPECT_NEAR(gw[i], upper[i], 1e-10) << "trial " << trial;
            if (state[i] == 0) EXPECT_EQ(mu[i], 0.0);
            if (state[i] < 0) EXPECT_GE(mu[i], -1e-12 * muScale);
            if (state[i] > 0) EXPECT_LE(mu[i], 1e-12 * muScale);
        }
        withContact += !qp.active().empty();
        EXPECT_LE(static_cast<int>(qp.active().size()), n);  // independent working set
    }
    EXPECT_GT(withContact, 100);
}

// The multipliers' vector is the caller's: between two solves of one solver it may have been
// written by another solver (the flow law's sub-step levels share one) or restored from a snapshot.
// A solve must not trust it to be zero off its own last set (issue 55's regression: stale entries
// read as a violated complementarity, "contact solve did not converge ... KKT residual 1.47").
TEST(BoxQP, MultipliersWrittenElsewhereDoNotLeakIntoTheSolution) {
    TwelveContacts c(11);
    ASSERT_TRUE(c.solve().converged);
    const std::vector<signed char> solution = c.state;
    c.mu.setConstant(123.0);  // another solver's multipliers, or a snapshot's
    const auto again = c.solve();
    EXPECT_TRUE(again.converged);
    EXPECT_LE(again.kktResidual, 1e-10);
    for (int i = 0; i < TwelveContacts::m; ++i)
        if (solution[std::size_t(i)] == 0) EXPECT_EQ(c.mu[i], 0.0) << "row " << i;
}
