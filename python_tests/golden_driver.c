/* The golden run without Python: a plain C FMI 2.0 master for python_tests/test_golden_emulated.py,
 * made to run under qemu-x86_64 with another CPU model (a Python or numpy build may execute
 * instructions the emulated CPU lacks at import and die with SIGILL before the FMU is loaded).
 *
 *     golden_driver UNZIPPED_FMU_DIR GUID STEPS H BASE_VR LOAD_VR REAL_VRS INT_VRS < inputs
 *
 * Loads UNZIPPED_FMU_DIR/binaries/linux64/PlateImpact.so, instantiates, initializes with the start
 * values (the inputs BASE_VR and LOAD_VR, base_displacement and load, at 0), then per communication step k < STEPS reads one line
 * "z z' z''" (decimal or hex floats, read exactly by strtod) from stdin, sets base_displacement and its first and second derivatives, steps by H from t (t += H, as
 * plateimpact.PlateImpactFMU does), and prints "t v1 v2 ..." with the real outputs of REAL_VRS
 * (comma-separated value references) as hex floats (%a: exact) and then the integer outputs of
 * INT_VRS. The first line is t = 0 before any step. Exit 1 with a message on any FMI error. */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env;
    if (status < fmi2Error) return;
    va_list args;
    va_start(args, message);
    fprintf(stderr, "[%s %s] ", instance ? instance : "?", category ? category : "");
    vfprintf(stderr, message, args);
    fprintf(stderr, "\n");
    va_end(args);
}

static size_t parse_vrs(const char* text, fmi2ValueReference* out, size_t max) {
    size_t n = 0;
    const char* p = text;
    while (*p && n < max) {
        char* end;
        unsigned long v = strtoul(p, &end, 10);
        if (end == p) break;
        out[n++] = (fmi2ValueReference)v;
        p = *end == ',' ? end + 1 : end;
    }
    return n;
}

#define LOAD(name)                                                                 \
    name##TYPE* name = (name##TYPE*)dlsym(lib, #name);                             \
    if (!name) {                                                                   \
        fprintf(stderr, "golden_driver: %s not exported: %s\n", #name, dlerror()); \
        return 1;                                                                  \
    }
#define CHECK(call)                                                        \
    if ((call) > fmi2Warning) {                                            \
        fprintf(stderr, "golden_driver: %s failed at t = %g\n", #call, t); \
        return 1;                                                          \
    }

int main(int argc, char** argv) {
    if (argc != 9) {
        fprintf(stderr,
                "usage: golden_driver UNZIPPED_FMU_DIR GUID STEPS H BASE_VR LOAD_VR REAL_VRS INT_VRS < inputs\n");
        return 2;
    }
    char so[4096], resources[4096];
    snprintf(so, sizeof so, "%s/binaries/linux64/PlateImpact.so", argv[1]);
    snprintf(resources, sizeof resources, "file://%s/resources", argv[1]);
    const int steps = atoi(argv[3]);
    const double h = strtod(argv[4], NULL);
    fmi2ValueReference reals[256], ints[256];
    const size_t n_real = parse_vrs(argv[7], reals, 256), n_int = parse_vrs(argv[8], ints, 256);
    void* lib = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "golden_driver: loading %s: %s\n", so, dlerror());
        return 1;
    }
    LOAD(fmi2Instantiate)
    LOAD(fmi2SetupExperiment)
    LOAD(fmi2EnterInitializationMode)
    LOAD(fmi2ExitInitializationMode)
    LOAD(fmi2SetReal)
    LOAD(fmi2GetReal)
    LOAD(fmi2GetInteger)
    LOAD(fmi2SetRealInputDerivatives)
    LOAD(fmi2DoStep)
    LOAD(fmi2FreeInstance)
    const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = fmi2Instantiate("golden", fmi2CoSimulation, argv[2], resources, &callbacks, fmi2False, fmi2False);
    if (!c) {
        fprintf(stderr, "golden_driver: fmi2Instantiate failed\n");
        return 1;
    }
    double t = 0.0;
    const fmi2ValueReference base = (fmi2ValueReference)atoi(argv[5]),
                             inputs[2] = {base, (fmi2ValueReference)atoi(argv[6])};
    const fmi2Real zero[2] = {0.0, 0.0};
    CHECK(fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0))
    CHECK(fmi2EnterInitializationMode(c))
    CHECK(fmi2SetReal(c, inputs, 2, zero))
    CHECK(fmi2ExitInitializationMode(c))
    fmi2Real values[256];
    fmi2Integer counts[256];
    for (int k = 0;; ++k) {
        CHECK(fmi2GetReal(c, reals, n_real, values))
        CHECK(fmi2GetInteger(c, ints, n_int, counts))
        printf("%a", t);
        for (size_t j = 0; j < n_real; ++j) printf(" %a", values[j]);
        for (size_t j = 0; j < n_int; ++j) printf(" %d", (int)counts[j]);
        printf("\n");
        if (k == steps) break;
        double z[3];
        if (scanf("%lf %lf %lf", &z[0], &z[1], &z[2]) != 3) {
            fprintf(stderr, "golden_driver: no input for step %d\n", k);
            return 1;
        }
        const fmi2ValueReference refs[2] = {base, base};
        const fmi2Integer orders[2] = {1, 2};
        CHECK(fmi2SetReal(c, &base, 1, &z[0]))
        CHECK(fmi2SetRealInputDerivatives(c, refs, 2, orders, &z[1]))
        CHECK(fmi2DoStep(c, t, h, fmi2True))
        t += h;
    }
    fmi2FreeInstance(c);
    return 0;
}
