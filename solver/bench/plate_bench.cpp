// Measures, in one run, the floor of an exact step (one solve with the factor of
// A = M + βΔt²K, docs/theory.md) and the average cost of a stepper step on a scene, and prints both
// as one JSON object. Usage:
//   plate_bench [key=value ...]   keys: element=argyris|fvs nx ny dt beta steps amplitude
//                                 frequency gap (both obstacles at ±gap; gap=0 disables them)
//                                 modes initial_load lower_only=0|1 damping_mass damping_stiffness
//                                 lower=H lower_x_min lower_x_max lower_y_min lower_y_max (a stop,
//                                 docs/theory.md §25; upper_x_min … the upper obstacle's)
//                                 mass=consistent|singular_p0|singular_p1dg
//                                 scheme=newmark|conserving|flow (time_scheme, docs/theory.md §17, §21)
//                                 substeps=N (contact_substeps of scheme=flow)
//                                 check=1 (discretization_check: the companion on the coarsened mesh)
//                                 tolerance=M max_substeps=N (scheme=flow: adaptive contact sub-steps)
//                                 rowspace=0 (scheme=flow: contact sub-steps in every row, the
//                                 baseline of docs/theory.md §24)
//                                 engine=auto|sparse|modal (how exact mode runs)
//                                 port=1 (read the port's outputs too, every communication step)
//                                 field=1 (read the probes and root_stress too; 2: also max_stress,
//                                 vertex_stress; with stress=1, and probes=N for N probes)
//                                 static_stress=P (the clamp's stress under a static pressure P: JSON)
//                                 series=FILE (CSV of the outputs every communication step;
//                                 its writing is outside the timed loop's cost only roughly)
//                                 comm=SECONDS (communication step, default 1e-4)
//                                 spectrum=1 (also print the first frequency and κ_h)
//                                 floor_repeats=N (solves per floor measurement, default 2000)
//                                 init_only=1 (build, print the resource estimate against the
//                                 measured peak RSS and initialization time, exit)
//                                 estimate_only=1 (the resource estimate alone: mesh and
//                                 symbolic analysis, nothing assembled; refusal as the FMU's)
//                                 memory_limit=MB (default 0 here: no limit)
//                                 export=DIR (write M, K, F, M·1 and the contact dofs of the
//                                 clamped plate as Matrix Market / text files, then exit)
// Besides the wall time of the stepping loop (step_s) it prints its process CPU time per step
// (step_cpu_s) and the floor timed with the CPU clock (floor_cpu_s, median of 20 batches of
// solves with a factor of A built here the same way): on a machine shared with other jobs the
// wall time includes the time the process waited for a core, the CPU time does not.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unsupported/Eigen/SparseExtra>

#include "fe/Assembly.h"
#include "fe/PointEvaluation.h"
#include "plate/SparseCholesky.h"
#include "CheckedPlate.h"

namespace {

// Peak resident set of this process image (VmHWM; getrusage's ru_maxrss would include the
// parent's peak before exec, e.g. the Python of scripts/resource_scaling.py).
double peakRssMB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;  // kB
    return 0.0;
}

// The resource estimate (ResourceEstimate.h) of a built simulation beside what was measured.
std::string resourceJson(const plate::PlateSimulation& sim, double initSeconds, double rssBeforeMB) {
    const plate::ResourceEstimate& e = sim.resources();
    char text[600];
    std::snprintf(text, sizeof text,
                  "\"nnz_k\": %lld, \"nnz_l\": %lld, \"factor_gflop\": %.4g, \"contact_vertices\": %lld, "
                  "\"est_peak_mb\": %.4g, \"rss_peak_mb\": %.4g, \"rss_before_mb\": %.4g, \"est_init_s\": %.4g, "
                  "\"init_s\": %.4g, \"est_step_s\": %.4g",
                  e.size.nonZeros, e.size.factorNonZeros, e.size.factorFlops * 1e-9, e.size.contactVertices, e.peakMB,
                  peakRssMB(), rssBeforeMB, e.initSeconds, initSeconds, e.stepSeconds);
    return text;
}

double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double wallSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The floor of an exact step: one solve with the sparse CHOLMOD factor of A = M + βΔt²K of the
// clamped plate, whatever coordinates the stepper runs in (docs/theory.md).
struct Floor {
    explicit Floor(const plate::ClampedPlate& clamped, double scale)
        : factor(Eigen::SparseMatrix<double>(clamped.mass + scale * clamped.stiffness)), load(clamped.pressureLoad) {}
    plate::SparseCholesky factor;
    Eigen::VectorXd load;
};
std::unique_ptr<Floor> makeFloor(const plate::PlateParameters& p) {
    const auto space = plate::makeSpace(p.mesh);
    const auto matrices = plate::assemble(*space, p.material);
    return std::make_unique<Floor>(plate::clamp(*space, matrices), p.law.beta * p.law.dt * p.law.dt);
}
// One solve's time by `clock` (wall or process CPU): the median over 20 batches after a warm-up batch.
double floorSeconds(const Floor& floor, int repeats, double (*clock)()) {
    Eigen::VectorXd b = floor.load, x(b.size());
    const int perBatch = std::max(1, repeats / 20);
    std::vector<double> batches;
    for (int batch = 0; batch < 21; ++batch) {
        const double c0 = clock();
        for (int r = 0; r < perBatch; ++r) {
            floor.factor.solve(b, x);
            b[0] += 1e-300 * x[0];  // keep the solves dependent so none is optimized away
        }
        if (batch > 0) batches.push_back((clock() - c0) / perBatch);
    }
    std::nth_element(batches.begin(), batches.begin() + batches.size() / 2, batches.end());
    return batches[batches.size() / 2];
}

// static_stress=P (docs/theory.md §23, tools/stress_convergence.py): the static shape under a uniform
// pressure P without obstacles, and the stress at the clamp x = 0 its curvatures give: σ_xx = 6D w_xx/t²
// at mid-edge (0, W/2) and at the corner (0, 0) (w_yy = w_xy = 0 on the clamp), the root moment
// ∫ D w_xx dy over x = 0 (5 Gauss points per element edge: exact for the cubic w_xx of Argyris and the
// linear one of FVS) against the exact clamp moment P W L²/2, and the FMU's root_stress of that state.
int staticStress(plate::PlateParameters p, double pressure) {
    const auto space = plate::makeSpace(p.mesh);
    const auto matrices = plate::assemble(*space, p.material);
    const auto clamped = plate::clamp(*space, matrices);
    const plate::SparseCholesky stiffness(clamped.stiffness);
    Eigen::VectorXd b = pressure * clamped.pressureLoad, w(b.size());
    stiffness.solve(b, w);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(space->dofCount());  // clamped dofs stay 0
    for (Eigen::Index i = 0; i < w.size(); ++i) u[clamped.freeDofs[std::size_t(i)]] = w[i];
    const auto curvature = [&](const plate::PointLocation& at) {
        const plate::PointFunctional f = plate::pointFunctional(*space, at, plate::PointQuantity::Dxx);
        double sum = 0.0;
        for (std::size_t k = 0; k < f.dofs.size(); ++k) sum += f.coefficients[k] * u[f.dofs[k]];
        return sum;
    };
    const double D = p.material.bendingStiffness(), t = p.material.thickness;
    // The samples nearest the middle and the corner of the clamped edge: the edge's own elements.
    plate::PointLocation middle = plate::locate(*space, {0.0, 0.5 * p.mesh.width - 1e-9 * p.mesh.width});
    middle.point = {0.0, 0.5 * p.mesh.width};
    plate::PointLocation corner = plate::locate(*space, {0.0, 1e-9 * p.mesh.width});
    corner.point = {0.0, 0.0};
    const double gauss[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                              0.2369268850561891};
    double moment = 0.0;
    for (int j = 0; j < p.mesh.ny; ++j) {
        const double y0 = j * space->mesh().hy(), y1 = (j + 1) * space->mesh().hy();
        plate::PointLocation at = plate::locate(*space, {0.0, 0.5 * (y0 + y1)});
        for (int g = 0; g < 5; ++g) {
            at.point = {0.0, 0.5 * (y0 + y1) + 0.5 * (y1 - y0) * gauss[g]};
            moment += 0.5 * (y1 - y0) * weight[g] * D * curvature(at);
        }
    }
    p.initialLoad = pressure;
    p.obstacles.lowerEnabled = p.obstacles.upperEnabled = false;
    p.memoryLimit = 0.0;
    p.outputs.stressOutputs = true;
    const plate::PlateSimulation sim(p, 0.0, pressure);
    const double strip = 3.0 * pressure * p.mesh.length * p.mesh.length / (t * t);  // 6 M/t², M = p L²/2
    std::printf(
        "{\"element\": \"%s\", \"nx\": %d, \"ny\": %d, \"dofs\": %ld, \"pressure\": %.17g, "
        "\"sigma_xx_mid\": %.17g, \"sigma_xx_corner\": %.17g, \"sigma_strip\": %.17g, \"root_moment\": %.17g, "
        "\"clamp_moment\": %.17g, \"root_stress\": %.17g, \"poisson_ratio\": %.17g}\n",
        p.mesh.element == plate::ElementType::Fvs ? "fvs" : "argyris", p.mesh.nx, p.mesh.ny,
        static_cast<long>(w.size()), pressure, 6.0 * D * curvature(middle) / (t * t),
        6.0 * D * curvature(corner) / (t * t), strip, moment,
        0.5 * pressure * p.mesh.width * p.mesh.length * p.mesh.length,
        sim.outputs(false, plate::FieldOutputs::Points).rootStress, p.material.poissonRatio);
    return 0;
}

// The clamped plate's matrices for independent checks and the plain Python/SciPy baseline.
int exportMatrices(const plate::PlateParameters& p, const std::string& dir) {
    const auto space = plate::makeSpace(p.mesh);
    const auto matrices = plate::assemble(*space, p.material);
    const auto clamped = plate::clamp(*space, matrices);
    Eigen::saveMarket(clamped.mass, dir + "/mass.mtx");
    Eigen::saveMarket(clamped.stiffness, dir + "/stiffness.mtx");
    std::ofstream vectors(dir + "/vectors.txt");
    vectors.precision(17);
    vectors << "# pressure_load base_inertia (free dofs); total_mass " << clamped.totalMass << "\n";
    for (Eigen::Index i = 0; i < clamped.pressureLoad.size(); ++i)
        vectors << clamped.pressureLoad[i] << " " << clamped.baseInertia[i] << "\n";
    std::ofstream contact(dir + "/contact_dofs.txt");
    for (auto d : clamped.contactDofs) contact << d << "\n";
    std::ofstream probes(dir + "/probes.txt");
    probes.precision(17);
    for (const auto& xy : {std::pair{p.mesh.length, 0.0}, std::pair{p.mesh.length, p.mesh.width},
                           std::pair{p.mesh.length, 0.5 * p.mesh.width}}) {
        const auto probe = clamped.probe(*space, xy.first, xy.second);
        for (std::size_t k = 0; k < probe.dofs.size(); ++k)
            probes << probe.dofs[k] << ":" << probe.coefficients[k] << " ";
        probes << "\n";
    }
    std::printf("{\"exported\": \"%s\", \"dofs\": %ld, \"total_mass\": %.17g}\n", dir.c_str(),
                static_cast<long>(clamped.mass.rows()), clamped.totalMass);
    return 0;
}

// The estimate PlateSimulation makes before it assembles anything, as JSON (refused: on stderr).
int printEstimate(const plate::PlateParameters& p) {
    try {
        plate::validate(p);
        const auto t0 = std::chrono::steady_clock::now();
        plate::requireMeshWithinBudget(p);
        const auto space = plate::makeSpace(p.mesh);
        const plate::ResourceEstimate e = plate::planResources(p, *space, {});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const char* engine = e.engine == plate::EngineKind::Sparse          ? "sparse"
                             : e.engine == plate::EngineKind::CompleteModal ? "modal-complete"
                             : e.engine == plate::EngineKind::Condensed     ? "conserving"
                                                                            : "modal-reduced";
        std::printf(
            "{\"element\": \"%s\", \"nx\": %d, \"ny\": %d, \"engine\": \"%s\", \"dofs\": %lld, \"nnz_k\": %lld, "
            "\"nnz_l\": %lld, \"factor_gflop\": %.4g, \"est_peak_mb\": %.4g, \"est_init_s\": %.4g, \"est_step_s\": "
            "%.4g, \"estimate_s\": %.4g}\n",
            p.mesh.element == plate::ElementType::Fvs ? "fvs" : "argyris", p.mesh.nx, p.mesh.ny, engine, e.size.dofs,
            e.size.nonZeros, e.size.factorNonZeros, e.size.factorFlops * 1e-9, e.peakMB, e.initSeconds, e.stepSeconds,
            seconds);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "plate_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::map<std::string, std::string> args;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto eq = a.find('=');
        if (eq == std::string::npos) {
            std::fprintf(stderr, "argument '%s' is not key=value\n", argv[i]);
            return 2;
        }
        args[a.substr(0, eq)] = a.substr(eq + 1);
    }
    auto num = [&](const char* key, double fallback) {
        const auto it = args.find(key);
        return it == args.end() ? fallback : std::atof(it->second.c_str());
    };
    plate::PlateParameters p;
    p.mesh.element =
        args.count("element") && args["element"] == "fvs" ? plate::ElementType::Fvs : plate::ElementType::Argyris;
    p.mesh.nx = static_cast<int>(num("nx", p.mesh.nx));
    p.mesh.ny = static_cast<int>(num("ny", p.mesh.ny));
    p.law.dt = num("dt", p.law.dt);
    p.law.beta = num("beta", p.law.beta);
    p.law.modes = static_cast<int>(num("modes", 0));
    p.initialLoad = num("initial_load", 0.0);
    const double gap = num("gap", 0.1);
    p.obstacles.lowerEnabled = p.obstacles.upperEnabled = gap > 0.0;
    if (gap > 0.0) p.obstacles.lower = -gap, p.obstacles.upper = gap;
    if (num("lower_only", 0) != 0) p.obstacles.upperEnabled = false;
    // A stop (docs/theory.md §25): lower=H the lower obstacle's height; lower_x_min, lower_x_max,
    // lower_y_min, lower_y_max its rectangle (the upper_… keys the upper one's).
    p.obstacles.lower = num("lower", p.obstacles.lower);
    p.obstacles.lowerStop = {num("lower_x_min", 0.0), num("lower_x_max", 1e4), num("lower_y_min", 0.0),
                             num("lower_y_max", 1e4)};
    p.obstacles.upperStop = {num("upper_x_min", 0.0), num("upper_x_max", 1e4), num("upper_y_min", 0.0),
                             num("upper_y_max", 1e4)};
    if (args.count("engine")) {
        const std::string e = args["engine"];
        p.law.engine = e == "sparse"  ? plate::LawParameters::Engine::SparseFactor
                       : e == "modal" ? plate::LawParameters::Engine::CompleteModal
                                      : plate::LawParameters::Engine::Auto;
    }
    if (args.count("mass"))
        p.law.mass = args["mass"] == "singular_p0"     ? plate::MassModel::SingularP0
                     : args["mass"] == "singular_p1dg" ? plate::MassModel::SingularP1dg
                                                       : plate::MassModel::Consistent;
    if (args.count("scheme") && args["scheme"] == "conserving") p.law.timeScheme = plate::TimeScheme::Conserving;
    if (args.count("scheme") && args["scheme"] == "flow") p.law.timeScheme = plate::TimeScheme::Flow;
    p.refinement.substeps = static_cast<int>(num("substeps", p.refinement.substeps));
    p.refinement.tolerance = num("tolerance", p.refinement.tolerance);
    p.refinement.maxSubsteps = static_cast<int>(num("max_substeps", p.refinement.maxSubsteps));
    p.refinement.rowSpace = num("rowspace", 1.0) != 0.0;
    p.memoryLimit = num("memory_limit", 0.0);
    p.law.dampingMass = num("damping_mass", 0.0);
    p.law.dampingStiffness = num("damping_stiffness", 0.0);
    // stress=1 (stress_outputs: the root's peak tracked every step), probes=N (N probes, all at
    // corner_1's point: their cost does not depend on where they are)
    p.outputs.stressOutputs = num("stress", 0.0) != 0.0;
    p.outputs.discretizationCheck = num("check", 0.0) != 0.0;  // discretization_check (docs/theory.md §26)
    p.outputs.probeX.assign(static_cast<std::size_t>(num("probes", 0.0)), p.mesh.length);
    p.outputs.probeY.assign(p.outputs.probeX.size(), 0.0);
    if (args.count("export")) return exportMatrices(p, args["export"]);
    if (num("estimate_only", 0) != 0) return printEstimate(p);
    if (args.count("static_stress")) return staticStress(p, num("static_stress", 1000.0));
    const long long steps = static_cast<long long>(num("steps", 100000));
    const double amplitude = num("amplitude", 0.09), frequency = num("frequency", 10.0);
    try {
        const double rssBefore = peakRssMB();
        const double cpu0 = processCpuSeconds();
        const auto t0 = std::chrono::steady_clock::now();
        const plate::ProgressLog log = [&args](const std::string& line) {
            if (args.count("verbose")) std::fprintf(stderr, "[peak RSS %.1f MB] %s\n", peakRssMB(), line.c_str());
        };
        plate::CheckedPlate sim(p, 0.0, 0.0, log);
        const auto t1 = std::chrono::steady_clock::now();
        const double cpu1 = processCpuSeconds();
        const std::string resources = resourceJson(sim, std::chrono::duration<double>(t1 - t0).count(), rssBefore);
        if (num("init_only", 0) != 0) {
            std::printf("{\"element\": \"%s\", \"nx\": %d, \"ny\": %d, \"engine\": \"%s\", \"dofs\": %ld, %s}\n",
                        p.mesh.element == plate::ElementType::Fvs ? "fvs" : "argyris", p.mesh.nx, p.mesh.ny,
                        sim.engine().c_str(), static_cast<long>(sim.dofCount()), resources.c_str());
            return 0;
        }
        const int floorRepeats = std::max(20, static_cast<int>(num("floor_repeats", 2000)));
        const auto floorFactor = makeFloor(p);
        const double floorBefore = floorSeconds(*floorFactor, floorRepeats, wallSeconds);
        // Communication step 1e-4 s (or dt if larger), input derivatives as the FMU gets them.
        const long long perComm = std::max(1LL, std::llround(num("comm", 1e-4) / p.law.dt));
        const bool readPort = num("port", 0.0) != 0.0;
        // field=1: read the probes and the root's stress too, every communication step; field=2 also
        // the plate's largest stress and vertex_stress (docs/theory.md §23).
        const int fieldLevel = static_cast<int>(num("field", 0.0));
        const plate::FieldOutputs readField = fieldLevel >= 2   ? plate::FieldOutputs::Plate
                                              : fieldLevel == 1 ? plate::FieldOutputs::Points
                                                                : plate::FieldOutputs::None;
        std::FILE* series = args.count("series") ? std::fopen(args["series"].c_str(), "w") : nullptr;
        if (series)
            std::fprintf(series,
                         "time,base,corner_1,corner_2,free_edge_mid,energy,energy_input,"
                         "energy_dissipated,contact_vertices,error_estimate\n");
        auto record = [&](double base) {
            if (!series) return;
            const auto o = sim.outputs();
            std::fprintf(series, "%.10g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.0f,%.6g\n", sim.time(), base,
                         o.corner1, o.corner2, o.freeEdgeMid, o.energy, o.energyInput, o.energyDissipated,
                         o.contactVertices, o.errorEstimate);
        };
        record(0.0);
        const double omega = 2.0 * M_PI * frequency;
        double energySum = 0.0;
        const auto t2 = std::chrono::steady_clock::now();
        const double cpu2 = processCpuSeconds();
        for (long long done = 0; done < steps; done += perComm) {
            const double t = sim.time();
            const plate::InputSignal base{amplitude * std::sin(omega * t), amplitude * omega * std::cos(omega * t),
                                          -amplitude * omega * omega * std::sin(omega * t)};
            sim.advance(std::min(perComm, steps - done), base, plate::InputSignal{});
            // Outputs are read every communication step; port=1 reads the port's too (§14).
            energySum += sim.outputs(readPort, readField).energy;
            if (fieldLevel >= 1 && !p.outputs.probeX.empty()) energySum += 1e-300 * sim.probes().displacement[0];
            if (fieldLevel >= 2) energySum += 1e-300 * sim.vertexStress()[0];  // the FMI 3.0 array as well
            record(amplitude * std::sin(omega * sim.time()));
        }
        if (series) std::fclose(series);
        const double cpu3 = processCpuSeconds();
        const auto t3 = std::chrono::steady_clock::now();
        const double floorAfter = floorSeconds(*floorFactor, floorRepeats, wallSeconds);
        const double floor = std::min(floorBefore, floorAfter);
        const double floorCpu = floorSeconds(*floorFactor, floorRepeats, processCpuSeconds);
        const double perStep = std::chrono::duration<double>(t3 - t2).count() / steps;
        const auto o = sim.outputs();
        // spectrum=1: the lowest frequency and κ_h = λ_max(M⁻¹K) (outside the timed loop).
        std::string spectrum;
        if (num("spectrum", 0) != 0) {
            char buffer[128];
            std::snprintf(buffer, sizeof buffer, ", \"first_frequency_hz\": %.10g, \"kappa\": %.6g",
                          sim.firstFrequency(), sim.kappa());
            spectrum = buffer;
        }
        std::printf(
            "{\"element\": \"%s\", \"nx\": %d, \"ny\": %d, \"dt\": %g, \"beta\": %g, \"modes\": %d, "
            "\"engine\": \"%s\", \"dofs\": %ld, \"steps\": %lld, \"setup_s\": %.6g, \"setup_cpu_s\": %.6g, \"wall_s\": "
            "%.6g, \"step_s\": "
            "%.6g, "
            "\"step_cpu_s\": %.6g, \"floor_cpu_s\": %.6g, "
            "\"floor_solve_s\": %.6g, \"step_over_floor\": %.4g, \"qp_iterations_total\": %.0f, "
            "\"energy_dissipated\": %.10g, \"contact_onsets_lower\": %.0f, \"contact_onsets_upper\": %.0f, "
            "\"checksum\": %.10g, "
            "\"error_estimate\": %.6g, \"discretization_error\": %.6g, \"capped_steps\": %.0f, %s%s}\n",
            p.mesh.element == plate::ElementType::Fvs ? "fvs" : "argyris", p.mesh.nx, p.mesh.ny, p.law.dt, p.law.beta,
            p.law.modes, sim.engine().c_str(), static_cast<long>(sim.dofCount()), steps,
            std::chrono::duration<double>(t1 - t0).count(), cpu1 - cpu0, std::chrono::duration<double>(t3 - t2).count(),
            perStep, (cpu3 - cpu2) / steps, floorCpu, floor, perStep / floor, o.contactSolves, o.energyDissipated,
            o.contactOnsets[0], o.contactOnsets[1], energySum, o.errorEstimate, o.discretizationError, o.cappedSteps,
            resources.c_str(), spectrum.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "plate_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
