/* A plain C co-simulation master for PlateImpact.fmu, made to run under valgrind memcheck
 * (python_tests/test_valgrind.py) and as a ctest smoke test.
 *
 *     fmu_driver [--keep-loaded] UNZIPPED_FMU_DIR [STEPS]
 *     fmu_driver --scene OUT.csv UNZIPPED_FMU_DIR      (the default scene for 0.1 s, see below)
 *     fmu_driver --bad-step UNZIPPED_FMU_DIR           (h below the grid's resolution -> fmi2Error)
 *     fmu_driver --latency OUT.csv UNZIPPED_FMU_DIR STEPS DRIVEN [i:VR=VALUE | b:VR=VALUE | r:VR=VALUE]...
 *                                      (each fmi2DoStep of 1e-4 s timed, linux64: see run_latency)
 *
 * The same source builds for linux64 and, cross-compiled with mingw-w64, for win64 (run under
 * Wine by python_tests/test_win64.py): it loads UNZIPPED_FMU_DIR/binaries/linux64/PlateImpact.so
 * with dlopen (so the shipped libraries are the ones loaded, through RPATH=$ORIGIN) or
 * binaries/win64/PlateImpact.dll with LoadLibrary, reads the GUID from modelDescription.xml and
 * runs, for three small configurations (Argyris exact, FVS, reduced modal; 4 x 2 cells):
 * instantiate (logAll on) -> parameters -> initialize -> STEPS communication steps with input
 * derivatives -> get/set/serialize/deserialize/free FMU states (also into a second instance
 * that was never initialized) -> an illegal call (the error path and its log) -> reset ->
 * initialize again -> step -> terminate -> free. Every result is checked: runs after a state
 * restore or a reset must reproduce the first run bit for bit. Exit code 0 when all checks pass,
 * 1 (with a message on stderr) otherwise. All memory the driver allocates is freed, so every
 * leak valgrind reports belongs to the FMU. At the end the driver unloads the FMU (dlclose), as
 * fmpy does in freeInstance, so memory the library allocated when it was loaded and never frees
 * shows as lost; --keep-loaded skips the dlclose (the library stays loaded until exit, as in an
 * importer that keeps it for the whole session).
 */
#if defined(_WIN32)
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) { return LoadLibraryA(path); }
static void* symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
static int close_library(Library lib) { return FreeLibrary(lib) ? 0 : 1; }
static const char* library_error(void) { return "LoadLibrary/GetProcAddress failed"; }
#define PLATFORM_LIBRARY "binaries/win64/PlateImpact.dll"
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* symbol(Library lib, const char* name) { return dlsym(lib, name); }
static int close_library(Library lib) { return dlclose(lib); }
static const char* library_error(void) { return dlerror(); }
#define PLATFORM_LIBRARY "binaries/linux64/PlateImpact.so"
#endif
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

// Declares `name` as the FMU's function of that name (used as a statement: LOAD(x);).
#define LOAD(name)                                      \
    name##TYPE* name = (name##TYPE*)symbol(lib, #name); \
    if (!name) return missing(#name)

static int missing(const char* name) {
    fprintf(stderr, "fmu_driver: %s not exported: %s\n", name, library_error());
    return 1;
}

#define CHECK(cond)                                                                              \
    do {                                                                                         \
        if (!(cond)) {                                                                           \
            fprintf(stderr, "fmu_driver: %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            exit(1);                                                                             \
        }                                                                                        \
    } while (0)

#define OK(call) CHECK((call) == fmi2OK)

enum {
    VR_NX = 6,
    VR_NY = 7,
    VR_ELEMENT = 8,
    VR_DT = 13,
    VR_INITIAL_LOAD = 15,
    VR_MODES = 16,
    VR_OBSTACLE_LOWER = 9,
    VR_OBSTACLE_UPPER = 10,
    VR_BASE = 20,
    VR_LOAD = 21
};
static const fmi2ValueReference REAL_OUT[] = {30, 31, 32, 33, 34, 35, 37};
static const fmi2ValueReference INT_OUT[] = {36, 38, 39};
#define N_REAL (sizeof REAL_OUT / sizeof REAL_OUT[0])
#define N_INT (sizeof INT_OUT / sizeof INT_OUT[0])
#define H 1e-3 /* communication step: 10 internal steps of dt = 1e-4 */

typedef struct {
    fmi2Real r[N_REAL];
    fmi2Integer i[N_INT];
} Outputs;

static unsigned long log_messages = 0;
static char last_error[2048] = ""; /* the last message logged with fmi2Error or worse */

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env;
    char text[2048];
    va_list args;
    va_start(args, message);
    vsnprintf(text, sizeof text, message, args);
    va_end(args);
    ++log_messages;
    if (status >= fmi2Error) snprintf(last_error, sizeof last_error, "%s", text);
    if (status >= fmi2Error && getenv("FMU_DRIVER_VERBOSE"))
        fprintf(stderr, "[%s %s %d] %s\n", instance ? instance : "?", category, (int)status, text);
}

/* The FMI functions, resolved once. */
static struct {
    fmi2InstantiateTYPE* instantiate;
    fmi2FreeInstanceTYPE* freeInstance;
    fmi2SetDebugLoggingTYPE* setDebugLogging;
    fmi2SetupExperimentTYPE* setupExperiment;
    fmi2EnterInitializationModeTYPE* enterInit;
    fmi2ExitInitializationModeTYPE* exitInit;
    fmi2TerminateTYPE* terminate;
    fmi2ResetTYPE* reset;
    fmi2GetRealTYPE* getReal;
    fmi2GetIntegerTYPE* getInteger;
    fmi2SetRealTYPE* setReal;
    fmi2SetIntegerTYPE* setInteger;
    fmi2SetBooleanTYPE* setBoolean;
    fmi2SetRealInputDerivativesTYPE* setRealInputDerivatives;
    fmi2DoStepTYPE* doStep;
    fmi2GetFMUstateTYPE* getFMUstate;
    fmi2SetFMUstateTYPE* setFMUstate;
    fmi2FreeFMUstateTYPE* freeFMUstate;
    fmi2SerializedFMUstateSizeTYPE* serializedSize;
    fmi2SerializeFMUstateTYPE* serialize;
    fmi2DeSerializeFMUstateTYPE* deSerialize;
    fmi2GetRealStatusTYPE* getRealStatus;
} F;

typedef struct {
    const char* name;
    int element; /* 1 argyris, 2 fvs */
    int modes;
} Config;

static Outputs outputs(fmi2Component c) {
    Outputs o;
    OK(F.getReal(c, REAL_OUT, N_REAL, o.r));
    OK(F.getInteger(c, INT_OUT, N_INT, o.i));
    for (size_t k = 0; k < N_REAL; ++k) CHECK(isfinite(o.r[k]));
    return o;
}

/* bit for bit (memcmp of the arrays, not of the struct: its padding is never written) */
static int same(const Outputs* a, const Outputs* b) {
    return memcmp(a->r, b->r, sizeof a->r) == 0 && memcmp(a->i, b->i, sizeof a->i) == 0;
}

static void initialize(fmi2Component c, const Config* cfg) {
    const fmi2ValueReference ivr[] = {VR_NX, VR_NY, VR_ELEMENT, VR_MODES};
    const fmi2Integer ival[] = {4, 2, cfg->element, cfg->modes};
    /* pressed against the upper obstacle at the start: impacts within the first steps */
    const fmi2ValueReference rvr[] = {VR_DT, VR_INITIAL_LOAD, VR_OBSTACLE_LOWER, VR_OBSTACLE_UPPER};
    const fmi2Real rval[] = {1e-4, 8600.0, -0.05, 0.05};
    OK(F.setupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.enterInit(c));
    OK(F.setInteger(c, ivr, 4, ival));
    OK(F.setReal(c, rvr, 4, rval));
    OK(F.exitInit(c));
}

/* Communication steps k0..k1-1 with base motion and load and their derivatives; the outputs
 * after each step into trace[k - k0] (if trace). */
static void drive(fmi2Component c, int k0, int k1, Outputs* trace) {
    const double w = 2 * M_PI * 20.0, f = 2 * M_PI * 7.0;
    for (int k = k0; k < k1; ++k) {
        const double t = k * H;
        const fmi2ValueReference vr[] = {VR_BASE, VR_LOAD};
        const fmi2Real value[] = {0.005 * sin(w * t), 200.0 * cos(f * t)};
        const fmi2ValueReference dvr[] = {VR_BASE, VR_BASE, VR_LOAD, VR_LOAD};
        const fmi2Integer order[] = {1, 2, 1, 2};
        const fmi2Real deriv[] = {0.005 * w * cos(w * t), -0.005 * w * w * sin(w * t), -200.0 * f * sin(f * t),
                                  -200.0 * f * f * cos(f * t)};
        OK(F.setReal(c, vr, 2, value));
        OK(F.setRealInputDerivatives(c, dvr, 4, order, deriv));
        OK(F.doStep(c, t, H, fmi2True));
        if (trace) trace[k - k0] = outputs(c);
    }
}

static void run_config(const Config* cfg, const char* guid, const char* resources, int steps,
                       const fmi2CallbackFunctions* callbacks) {
    const int half = steps / 2;
    Outputs* first = calloc((size_t)steps, sizeof *first);
    Outputs* again = calloc((size_t)steps, sizeof *again);
    CHECK(first && again);

    fmi2Component c = F.instantiate(cfg->name, fmi2CoSimulation, guid, resources, callbacks, fmi2False, fmi2True);
    CHECK(c != NULL);
    const fmi2String all[] = {"logAll"};
    OK(F.setDebugLogging(c, fmi2True, 1, all));
    initialize(c, cfg);
    const Outputs start = outputs(c);
    drive(c, 0, half, first);

    /* FMU state at half time: get, run on, set back, run again */
    fmi2FMUstate state = NULL;
    OK(F.getFMUstate(c, &state));
    CHECK(state != NULL);
    drive(c, half, steps, first + half);
    OK(F.setFMUstate(c, state));
    drive(c, half, steps, again + half);
    for (int k = half; k < steps; ++k) CHECK(same(&first[k], &again[k]));

    /* serialize, free, deserialize, restore */
    size_t size = 0;
    OK(F.serializedSize(c, state, &size));
    CHECK(size > 0);
    fmi2Byte* blob = malloc(size);
    CHECK(blob != NULL);
    OK(F.serialize(c, state, blob, size));
    OK(F.freeFMUstate(c, &state));
    CHECK(state == NULL);
    fmi2FMUstate restored = NULL;
    OK(F.deSerialize(c, blob, size, &restored));
    OK(F.setFMUstate(c, restored));
    OK(F.freeFMUstate(c, &restored));
    drive(c, half, steps, again + half);
    for (int k = half; k < steps; ++k) CHECK(same(&first[k], &again[k]));

    /* a second instance, never initialized, continues from the serialized state; overwriting
     * an existing FMU state with fmi2GetFMUstate reuses it */
    fmi2Component other = F.instantiate("other", fmi2CoSimulation, guid, resources, callbacks, fmi2False, fmi2False);
    CHECK(other != NULL);
    OK(F.deSerialize(other, blob, size, &restored));
    OK(F.setFMUstate(other, restored));
    drive(other, half, half + 1, NULL);
    OK(F.getFMUstate(other, &restored)); /* overwrite the existing state */
    OK(F.freeFMUstate(other, &restored));
    free(blob);
    F.freeInstance(other); /* freed without fmi2Terminate */

    /* the error path: a step at the wrong communication point, logged; then reset */
    CHECK(F.doStep(c, 123.0, H, fmi2True) == fmi2Error);
    CHECK(F.doStep(c, steps * H, H, fmi2True) == fmi2Error); /* illegal in state error */
    OK(F.reset(c));

    /* initialize again: the same run as a fresh instance */
    initialize(c, cfg);
    const Outputs start2 = outputs(c);
    CHECK(same(&start, &start2));
    drive(c, 0, steps, again);
    for (int k = 0; k < steps; ++k) CHECK(same(&first[k], &again[k]));
    fmi2Real last = 0.0;
    OK(F.getRealStatus(c, fmi2LastSuccessfulTime, &last));
    CHECK(fabs(last - steps * H) < 1e-12);
    OK(F.terminate(c));
    OK(F.reset(c)); /* a reset after terminate, then free from state instantiated */
    F.freeInstance(c);

    printf("%s: %d steps, energy %.12g J, dissipated %.6g J, contact vertices %d, QP iterations %d\n", cfg->name, steps,
           first[steps - 1].r[3], first[steps - 1].r[4], first[steps - 1].i[0], first[steps - 1].i[1]);
    free(first);
    free(again);
}

/* The value of guid="..." in modelDescription.xml (malloc'ed). */
static char* read_guid(const char* dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    FILE* file = fopen(path, "rb");
    if (!file) return NULL;
    char* text = calloc(1, 1 << 20);
    size_t n = text ? fread(text, 1, (1 << 20) - 1, file) : 0;
    fclose(file);
    char* guid = NULL;
    const char* at = n ? strstr(text, "guid=\"") : NULL;
    if (at) {
        at += 6;
        const char* end = strchr(at, '"');
        if (end) {
            guid = calloc(1, (size_t)(end - at) + 1);
            memcpy(guid, at, (size_t)(end - at));
        }
    }
    free(text);
    return guid;
}

/* sin and cos from + - * / and fmod only (each correctly rounded by IEEE 754), so that the
 * linux64 and the win64 driver feed the FMU the same bits: glibc's and mingw-w64's sin differ in
 * the last bit for some arguments (at t = 0.05 s of the default scene, 2 pi 10 t = pi), which
 * would make the two runs differ from the first impact on for a reason outside the FMU. */
static void portable_sincos(double x, double* s, double* c) {
    const double two_pi = 6.283185307179586, pi = 3.141592653589793;
    double r = fmod(x, two_pi);
    if (r > pi) r -= two_pi;
    if (r < -pi) r += two_pi;
    const double r2 = r * r;
    double ps = 0.0, pc = 0.0;
    for (int k = 14; k >= 1; --k) { /* Horner: sin = r (1 - r²/(2·3) (1 - r²/(4·5) (...))) */
        ps = 1.0 - r2 / ((2.0 * k) * (2.0 * k + 1.0)) * ps;
        pc = 1.0 - r2 / ((2.0 * k - 1.0) * (2.0 * k)) * pc;
    }
    *s = r * ps;
    *c = pc;
}

/* The default scene's base at t, 0.09 sin(2 pi 10 t) m, with its first two derivatives. */
static void set_default_base(fmi2Component c, double t) {
    const double w = 2.0 * 3.14159265358979323846 * 10.0, a = 0.09;
    const fmi2ValueReference base = VR_BASE;
    const fmi2ValueReference vr2[] = {VR_BASE, VR_BASE};
    const fmi2Integer orders[] = {1, 2};
    double sn, cs;
    portable_sincos(w * t, &sn, &cs);
    const fmi2Real z = a * sn, rates[] = {a * w * cs, -a * w * w * sn};
    OK(F.setReal(c, &base, 1, &z));
    OK(F.setRealInputDerivatives(c, vr2, 2, orders, rates));
}

/* The default scene (14 x 5 Argyris, dt = 1e-5 s, obstacles at +-0.1 m, base 0.09 sin(2 pi 10 t)
 * given with its derivatives every h = 1e-4 s) for 0.1 s: one CSV row per communication point,
 * every Real output with 17 digits. */
static void run_scene(const char* out, const char* guid, const char* resources, const fmi2CallbackFunctions* cb) {
    FILE* f = fopen(out, "wb"); /* "\n" line ends on every platform */
    CHECK(f != NULL);
    fmi2Component c = F.instantiate("scene", fmi2CoSimulation, guid, resources, cb, fmi2False, fmi2False);
    CHECK(c != NULL);
    OK(F.setupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.enterInit(c));
    OK(F.exitInit(c));
    const double h = 1e-4;
    fprintf(f, "time,corner_1,corner_2,free_edge_mid,energy,energy_dissipated,energy_input,qp_kkt_residual_max\n");
    for (int k = 0; k <= 1000; ++k) {
        const double t = k * h;
        fmi2Real r[N_REAL];
        OK(F.getReal(c, REAL_OUT, N_REAL, r));
        fprintf(f, "%.17g", t);
        for (size_t j = 0; j < N_REAL; ++j) fprintf(f, ",%.17g", r[j]);
        fprintf(f, "\n");
        if (k == 1000) break;
        set_default_base(c, t);
        OK(F.doStep(c, t, h, fmi2True));
    }
    OK(F.terminate(c));
    F.freeInstance(c);
    fclose(f);
    printf("fmu_driver: wrote %s\n", out);
}

#if !defined(_WIN32)
#include <time.h>
static double clock_us(clockid_t clock) {
    struct timespec t;
    clock_gettime(clock, &t);
    return 1e6 * (double)t.tv_sec + 1e-3 * (double)t.tv_nsec;
}

/* The worst step a real-time master meets (tools/step_latency.py): the parameters given as
 * i:VR=VALUE (Integer), b:VR=VALUE (Boolean, 0 or 1) and r:VR=VALUE (Real), then STEPS communication steps of 1e-4 s, the base
 * driven as in run_scene (DRIVEN = 1) or left at rest (0). Each fmi2DoStep alone is timed, by the
 * wall clock and the thread's CPU clock; one CSV row per step (µs). */
static void run_latency(const char* out, const char* guid, const char* resources, const fmi2CallbackFunctions* cb,
                        int steps, int driven, int argc, char** argv) {
    fmi2Component c = F.instantiate("latency", fmi2CoSimulation, guid, resources, cb, fmi2False, fmi2False);
    CHECK(c != NULL);
    for (int k = 0; k < argc; ++k) {
        unsigned vr = 0;
        double value = 0.0;
        CHECK(sscanf(argv[k] + 2, "%u=%lf", &vr, &value) == 2);
        const fmi2ValueReference ref = vr;
        if (argv[k][0] == 'i') {
            const fmi2Integer i = (fmi2Integer)value;
            OK(F.setInteger(c, &ref, 1, &i));
        } else if (argv[k][0] == 'b') {
            const fmi2Boolean b = value != 0.0 ? fmi2True : fmi2False;
            OK(F.setBoolean(c, &ref, 1, &b));
        } else {
            CHECK(argv[k][0] == 'r');
            OK(F.setReal(c, &ref, 1, &value));
        }
    }
    OK(F.setupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.enterInit(c));
    OK(F.exitInit(c));
    double* times = malloc(2 * sizeof(double) * (size_t)steps);
    CHECK(times != NULL);
    const double h = 1e-4;
    for (int k = 0; k < steps; ++k) {
        const double t = k * h;
        if (driven) set_default_base(c, t);
        const double wall = clock_us(CLOCK_MONOTONIC), cpu = clock_us(CLOCK_THREAD_CPUTIME_ID);
        OK(F.doStep(c, t, h, fmi2True));
        times[2 * k + 1] = clock_us(CLOCK_THREAD_CPUTIME_ID) - cpu;
        times[2 * k] = clock_us(CLOCK_MONOTONIC) - wall;
    }
    OK(F.terminate(c));
    F.freeInstance(c);
    FILE* f = fopen(out, "wb");
    CHECK(f != NULL);
    fprintf(f, "wall_us,cpu_us\n");
    for (int k = 0; k < steps; ++k) fprintf(f, "%.3f,%.3f\n", times[2 * k], times[2 * k + 1]);
    fclose(f);
    free(times);
}
#endif

/* A communication step shorter than the grid resolves (1e-9 dt): fmi2Error, and the logged
 * message says so (printed for the caller to check); the instance is then reset and freed. */
static void run_bad_step(const char* guid, const char* resources, const fmi2CallbackFunctions* cb) {
    fmi2Component c = F.instantiate("bad", fmi2CoSimulation, guid, resources, cb, fmi2False, fmi2True);
    CHECK(c != NULL);
    OK(F.setupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.enterInit(c));
    OK(F.exitInit(c));
    CHECK(F.doStep(c, 0.0, 5e-15, fmi2True) == fmi2Error);
    printf("fmu_driver: fmi2DoStep(h = 5e-15) -> fmi2Error: %s\n", last_error);
    OK(F.reset(c));
    F.freeInstance(c);
}

int main(int argc, char** argv) {
    const char* scene_out = NULL;
    int bad_step = 0;
    const char* latency_out = NULL;
    int latency_steps = 0, latency_driven = 0, latency_argc = 0;
    char** latency_argv = NULL;
    if (argc > 5 && strcmp(argv[1], "--latency") == 0) {
#if defined(_WIN32)
        fprintf(stderr, "fmu_driver: --latency is linux64 only\n");
        return 2;
#endif
        latency_out = argv[2];
        latency_steps = atoi(argv[4]);
        latency_driven = atoi(argv[5]);
        latency_argc = argc - 6;
        latency_argv = argv + 6;
        CHECK(latency_steps > 0);
        argv += 2; /* argv[1] is the FMU's folder */
        argc = 2;
    } else if (argc > 2 && strcmp(argv[1], "--scene") == 0) {
        scene_out = argv[2];
        argv += 2;
        argc -= 2;
    } else if (argc > 1 && strcmp(argv[1], "--bad-step") == 0) {
        bad_step = 1;
        argv += 1;
        argc -= 1;
    }
    const int keep_loaded = argc > 1 && strcmp(argv[1], "--keep-loaded") == 0;
    argv += keep_loaded;
    argc -= keep_loaded;
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: fmu_driver [--keep-loaded] UNZIPPED_FMU_DIR [STEPS]\n");
        return 2;
    }
    const char* dir = argv[1];
    const int steps = argc == 3 ? atoi(argv[2]) : 6;
    if (steps < 2) {
        fprintf(stderr, "fmu_driver: STEPS must be >= 2\n");
        return 2;
    }
    char* guid = read_guid(dir);
    if (!guid) {
        fprintf(stderr, "fmu_driver: no guid in %s/modelDescription.xml\n", dir);
        return 1;
    }
    char so[4096], resources[4200];
    snprintf(so, sizeof so, "%s/" PLATFORM_LIBRARY, dir);
    snprintf(resources, sizeof resources, "file://%s/resources", dir);
    Library lib = open_library(so);
    if (!lib) {
        fprintf(stderr, "fmu_driver: loading %s: %s\n", so, library_error());
        free(guid);
        return 1;
    }
    {
        LOAD(fmi2Instantiate);
        LOAD(fmi2FreeInstance);
        LOAD(fmi2SetDebugLogging);
        LOAD(fmi2SetupExperiment);
        LOAD(fmi2EnterInitializationMode);
        LOAD(fmi2ExitInitializationMode);
        LOAD(fmi2Terminate);
        LOAD(fmi2Reset);
        LOAD(fmi2GetReal);
        LOAD(fmi2GetInteger);
        LOAD(fmi2SetReal);
        LOAD(fmi2SetInteger);
        LOAD(fmi2SetBoolean);
        LOAD(fmi2SetRealInputDerivatives);
        LOAD(fmi2DoStep);
        LOAD(fmi2GetFMUstate);
        LOAD(fmi2SetFMUstate);
        LOAD(fmi2FreeFMUstate);
        LOAD(fmi2SerializedFMUstateSize);
        LOAD(fmi2SerializeFMUstate);
        LOAD(fmi2DeSerializeFMUstate);
        LOAD(fmi2GetRealStatus);
        F.instantiate = fmi2Instantiate;
        F.freeInstance = fmi2FreeInstance;
        F.setDebugLogging = fmi2SetDebugLogging;
        F.setupExperiment = fmi2SetupExperiment;
        F.enterInit = fmi2EnterInitializationMode;
        F.exitInit = fmi2ExitInitializationMode;
        F.terminate = fmi2Terminate;
        F.reset = fmi2Reset;
        F.getReal = fmi2GetReal;
        F.getInteger = fmi2GetInteger;
        F.setReal = fmi2SetReal;
        F.setInteger = fmi2SetInteger;
        F.setBoolean = fmi2SetBoolean;
        F.setRealInputDerivatives = fmi2SetRealInputDerivatives;
        F.doStep = fmi2DoStep;
        F.getFMUstate = fmi2GetFMUstate;
        F.setFMUstate = fmi2SetFMUstate;
        F.freeFMUstate = fmi2FreeFMUstate;
        F.serializedSize = fmi2SerializedFMUstateSize;
        F.serialize = fmi2SerializeFMUstate;
        F.deSerialize = fmi2DeSerializeFMUstate;
        F.getRealStatus = fmi2GetRealStatus;
    }

    const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    if (scene_out || bad_step || latency_out) {
#if !defined(_WIN32)
        if (latency_out)
            run_latency(latency_out, guid, resources, &callbacks, latency_steps, latency_driven, latency_argc,
                        latency_argv);
#else
        (void)latency_steps, (void)latency_driven, (void)latency_argc, (void)latency_argv;
#endif
        if (scene_out) run_scene(scene_out, guid, resources, &callbacks);
        if (bad_step) run_bad_step(guid, resources, &callbacks);
        free(guid);
        CHECK(close_library(lib) == 0);
        return 0;
    }
    const Config configs[] = {{"argyris", 1, 0}, {"fvs", 2, 0}, {"modal", 1, 6}};
    for (size_t k = 0; k < sizeof configs / sizeof configs[0]; ++k)
        run_config(&configs[k], guid, resources, steps, &callbacks);
    CHECK(log_messages > 0);
    printf("fmu_driver: all checks passed (%lu log messages)\n", log_messages);

    free(guid);
    /* Unloading the FMU is part of the check: its static destructors run here. */
    if (!keep_loaded) CHECK(close_library(lib) == 0);
    return 0;
}
