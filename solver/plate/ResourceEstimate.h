#pragma once
// What one PlateSimulation will allocate and spend, known before it is spent: memory, the time
// of its initialization and the cost of one time step (docs/performance.md, "Resources").
//
// Two stages, both before any matrix is assembled:
//   1. countEntries: counts from the finite element space alone, O(elements). The assembly's
//      triplets (Σ_e (dofs of e)² per matrix) are a certain lower bound of the peak: a mesh
//      whose assembly alone exceeds the budget is refused here, in well under a second.
//   2. analyzePattern: the pattern of A = M + βΔt²K on the free dofs, built from the element
//      dof lists (no values), and its symbolic Cholesky analysis with the ordering the
//      factorization uses: the exact nonzeros of L and the flops of the numeric factorization.
// estimateResources turns the counts into bytes with a model of what Assembly.cpp,
// SparseCholesky, FullOrderPlate, ModalPlate, Spectrum.cpp and StaticEquilibrium.cpp allocate,
// phase by phase; the peak is the largest phase. The constants of the time model are fitted
// to measurements on this project's 2-core machine (docs/performance.md).
#include <chrono>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "fe/Assembly.h"
#include "fe/FiniteElementSpace.h"
#include "plate/PlateParameters.h"

namespace plate {

// An instance whose estimated peak memory exceeds memory_limit: what() names the estimate,
// the limit and the parameter to raise.
class ResourceError : public ParameterError {
public:
    using ParameterError::ParameterError;
};

struct ProblemSize {
    long long fullDofs = 0;  // dofs of the space before the clamp
    long long dofs = 0;  // free dofs n
    long long contactVertices = 0;  // vertices carrying a contact bound
    long long elements = 0;
    long long elementEntries = 0;  // T = Σ_e (dofs of e)²: triplets of each assembled matrix
    long long fullNonZeros = 0;  // nnz of the assembled M and K (both triangles); 0 = not analyzed
    long long nonZeros = 0;  // nnz of the free M, K and A (one pattern, both triangles)
    long long factorNonZeros = 0;  // nnz(L) of A, diagonal included (symbolic analysis)
    double factorFlops = 0.0;  // flops of one numeric factorization of A
    bool predicted = false;  // stage 0: counts from fits, not from the space
};

// Stage 0: a prediction from nx, ny and the element alone (closed-form counts of the structured
// mesh, nnz(K) and nnz(L) from fits to the symbolic analyses of docs/performance.md), O(1):
// it refuses, before even the space is built, meshes predicted far beyond the budget.
ProblemSize predictFromMesh(const PlateParameters& p);
// Throws ResourceError if the stage 0 prediction exceeds memory_limit by more than the fits'
// margin (kPredictionMargin): what is within the margin is decided by the exact analysis.
void requireMeshWithinBudget(const PlateParameters& p);
constexpr double kPredictionMargin = 1.5;

// Stage 1: counts from the space alone.
ProblemSize countEntries(const FiniteElementSpace& space, const StopsAt& stopsAt = {});
// Stage 2: the free pattern (O(T) time, O(nnz) memory) and its symbolic factor.
void analyzePattern(const FiniteElementSpace& space, ProblemSize& size);

enum class EngineKind {
    Sparse,
    CompleteModal,
    ReducedModal,
    Condensed
};  // Condensed: time_scheme = conserving or flow

// Exact mode's choice between the sparse factor and the complete modal basis (docs/theory.md
// §7), from counts: n dofs, m contact vertices, nnz(K).
bool completeModalPays(long long n, long long m, long long stiffnessNonZeros);
// The engine PlateSimulation builds for these parameters and sizes (stage 2 counts).
EngineKind engineFor(const PlateParameters& p, const ProblemSize& size);

struct ResourceEstimate {
    ProblemSize size;  // the counts it was made from
    EngineKind engine = EngineKind::Sparse;
    bool complete = false;  // every phase estimated (stage 0 or 2; stage 1: a lower bound)
    double assemblyMB = 0.0;  // peak of the assembly (triplets and the assembled M, K)
    double matricesMB = 0.0;  // the clamped M and K and their row copies, kept for the run
    double factorsMB = 0.0;  // factors alive at once (A, and K for the static state)
    double engineMB = 0.0;  // dense modal basis and its contact products, eigen solver workspace
    double peakMB = 0.0;  // the largest total alive at once
    double assemblySeconds = 0.0, factorSeconds = 0.0, spectrumSeconds = 0.0, staticSeconds = 0.0;
    double initSeconds = 0.0;  // sum of the phases
    double stepSeconds = 0.0;  // one internal time step without contact
    std::string describe() const;  // one line for the log
};

ResourceEstimate estimateResources(const PlateParameters& p, const ProblemSize& size);

// Throws ResourceError if the estimate exceeds p.memoryLimit (MB; 0 = no limit).
void requireWithinBudget(const PlateParameters& p, const ResourceEstimate& estimate);

// What the estimate says the user should know before the time is spent, one line each (the FMU
// logs them at initialization): a setup of more than kLongSetupSeconds, and a run of more than
// kCostlyRunSeconds of CPU per simulated second, with what would make it cheaper.
inline constexpr double kLongSetupSeconds = 10.0;
inline constexpr double kCostlyRunSeconds = 60.0;
std::vector<std::string> costNotices(const PlateParameters& p, const ResourceEstimate& estimate);

// Messages of an instance's initialization (the FMU's log); empty: none. Called with a line, the
// estimate and the progress (the FMU's logInfo); warn() the cost notices, which a master that shows
// only warnings must show too (the FMU's status Warning; without a warning sink, the info one).
class ProgressLog {
public:
    using Sink = std::function<void(const std::string&)>;
    ProgressLog() = default;
    template <class Info, class = std::enable_if_t<std::is_constructible_v<Sink, Info>>>
    ProgressLog(Info info, Sink warning = {}) : info_(std::move(info)), warning_(std::move(warning)) {}
    explicit operator bool() const { return static_cast<bool>(info_); }
    void operator()(const std::string& line) const { info_(line); }
    void warn(const std::string& line) const { (warning_ ? warning_ : info_)(line); }

private:
    Sink info_, warning_;
};

// The initialization's phases as log lines: what is being done, its estimated time and how
// far the initialization is (elapsed against the estimate). Lines are written only when the
// estimate reaches `threshold` seconds (short initializations log the estimate and the end).
class InitProgress {
public:
    InitProgress(ProgressLog log, double estimatedSeconds, double threshold = 2.0);
    void phase(const std::string& what, double estimatedSeconds);
    void done(double peakEstimateMB);
    double elapsed() const;

private:
    ProgressLog log_;
    double estimated_, threshold_;
    std::chrono::steady_clock::time_point start_;
    int count_ = 0;
};

// Both stages for the parameters (logs the estimate, refuses beyond the budget); returns the
// stage 2 estimate.
ResourceEstimate planResources(const PlateParameters& p, const FiniteElementSpace& space, const ProgressLog& log);

}  // namespace plate
