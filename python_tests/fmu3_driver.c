/* A plain C master of the FMI 3.0 PlateImpact binary (no fmpy), for python_tests/test_aarch64.py
 * and python_tests/test_win64.py: the same program built for x86-64 Linux, for aarch64 (run under
 * qemu-aarch64) and for x86-64 Windows (run under Wine) prints the same events and values.
 *
 *   fmu3_driver <binaries/<platform>/PlateImpact.so|.dll> <instantiationToken>
 *
 * The life cycle: a wrong token refused; instantiate (early return and event mode granted);
 * initialize; the default scene for 0.1 s in communication steps of 1e-4 s (base 0.09 sin(2 pi 10 t)
 * m, value only), through every early return and event mode at the contact events; an FMU state
 * taken at t = 0.05 s, serialized, restored and the step after it repeated bit for bit; a bad call
 * answered with fmi3Error; terminate and free. Prints every output of every communication point
 * and event as C99 hex floats (%a) and exits 0 only if every check held. */
#if defined(_WIN32)
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) { return LoadLibraryA(path); }
static void* find_symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
static const char* library_error(void) { return "LoadLibrary failed"; }
static void close_library(Library lib) { FreeLibrary(lib); }
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* find_symbol(Library lib, const char* name) { return dlsym(lib, name); }
static const char* library_error(void) { return dlerror(); }
static void close_library(Library lib) { dlclose(lib); }
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"

#define VR_BASE 20u
#define VR_CORNER1 30u
#define VR_ENERGY 33u
#define VR_CONTACT 36u
#define VR_VERTICES 1003u
#define N_VERTICES 90u

static int failures = 0;

static void check(int ok, const char* what) {
    if (!ok) {
        fprintf(stderr, "fmu3_driver: FAILED: %s\n", what);
        ++failures;
    }
}

static void logger(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
    (void)env;
    fprintf(stderr, "[%d %s] %s\n", (int)status, category, message);
}

/* sin from + - * / and fmod only (each correctly rounded by IEEE 754): the base is the same
 * bits on every platform, whatever its libm. */
static double portableSin(double x) {
    const double twoPi = 6.283185307179586;
    double r = fmod(x, twoPi), term, sum;
    if (r > 3.141592653589793) r -= twoPi;
    if (r < -3.141592653589793) r += twoPi;
    term = r;
    sum = r;
    for (int k = 1; k < 30; ++k) {
        term *= -r * r / ((2.0 * k) * (2.0 * k + 1.0));
        sum += term;
    }
    return sum;
}

static double baseAt(double t) { return 0.09 * portableSin(2.0 * 3.141592653589793 * 10.0 * t); }

typedef struct {
    fmi3InstantiateCoSimulationTYPE* instantiate;
    fmi3FreeInstanceTYPE* freeInstance;
    fmi3EnterInitializationModeTYPE* enterInit;
    fmi3ExitInitializationModeTYPE* exitInit;
    fmi3EnterEventModeTYPE* enterEventMode;
    fmi3UpdateDiscreteStatesTYPE* updateDiscreteStates;
    fmi3EnterStepModeTYPE* enterStepMode;
    fmi3DoStepTYPE* doStep;
    fmi3GetFloat64TYPE* getFloat64;
    fmi3GetInt32TYPE* getInt32;
    fmi3SetFloat64TYPE* setFloat64;
    fmi3GetFMUStateTYPE* getState;
    fmi3SetFMUStateTYPE* setState;
    fmi3FreeFMUStateTYPE* freeState;
    fmi3SerializedFMUStateSizeTYPE* stateSize;
    fmi3SerializeFMUStateTYPE* serialize;
    fmi3DeserializeFMUStateTYPE* deserialize;
    fmi3TerminateTYPE* terminate;
} Api;

static void* symbol(Library lib, const char* name) {
    void* f = find_symbol(lib, name);
    if (!f) {
        fprintf(stderr, "fmu3_driver: %s not exported\n", name);
        exit(2);
    }
    return f;
}

static void load(Api* a, Library lib) {
    a->instantiate = (fmi3InstantiateCoSimulationTYPE*)symbol(lib, "fmi3InstantiateCoSimulation");
    a->freeInstance = (fmi3FreeInstanceTYPE*)symbol(lib, "fmi3FreeInstance");
    a->enterInit = (fmi3EnterInitializationModeTYPE*)symbol(lib, "fmi3EnterInitializationMode");
    a->exitInit = (fmi3ExitInitializationModeTYPE*)symbol(lib, "fmi3ExitInitializationMode");
    a->enterEventMode = (fmi3EnterEventModeTYPE*)symbol(lib, "fmi3EnterEventMode");
    a->updateDiscreteStates = (fmi3UpdateDiscreteStatesTYPE*)symbol(lib, "fmi3UpdateDiscreteStates");
    a->enterStepMode = (fmi3EnterStepModeTYPE*)symbol(lib, "fmi3EnterStepMode");
    a->doStep = (fmi3DoStepTYPE*)symbol(lib, "fmi3DoStep");
    a->getFloat64 = (fmi3GetFloat64TYPE*)symbol(lib, "fmi3GetFloat64");
    a->getInt32 = (fmi3GetInt32TYPE*)symbol(lib, "fmi3GetInt32");
    a->setFloat64 = (fmi3SetFloat64TYPE*)symbol(lib, "fmi3SetFloat64");
    a->getState = (fmi3GetFMUStateTYPE*)symbol(lib, "fmi3GetFMUState");
    a->setState = (fmi3SetFMUStateTYPE*)symbol(lib, "fmi3SetFMUState");
    a->freeState = (fmi3FreeFMUStateTYPE*)symbol(lib, "fmi3FreeFMUState");
    a->stateSize = (fmi3SerializedFMUStateSizeTYPE*)symbol(lib, "fmi3SerializedFMUStateSize");
    a->serialize = (fmi3SerializeFMUStateTYPE*)symbol(lib, "fmi3SerializeFMUState");
    a->deserialize = (fmi3DeserializeFMUStateTYPE*)symbol(lib, "fmi3DeserializeFMUState");
    a->terminate = (fmi3TerminateTYPE*)symbol(lib, "fmi3Terminate");
}

/* One line: time, corner_1, energy, contact_vertices, the sum of the vertex displacements. */
static void print(const Api* a, fmi3Instance s, double t, const char* tag) {
    const fmi3ValueReference reals[2] = {VR_CORNER1, VR_ENERGY}, contact = VR_CONTACT, vertices = VR_VERTICES;
    double x[2], w[N_VERTICES], sum = 0.0;
    fmi3Int32 c = 0;
    check(a->getFloat64(s, reals, 2, x, 2) == fmi3OK, "fmi3GetFloat64");
    check(a->getInt32(s, &contact, 1, &c, 1) == fmi3OK, "fmi3GetInt32");
    check(a->getFloat64(s, &vertices, 1, w, N_VERTICES) == fmi3OK, "fmi3GetFloat64 of the array");
    for (unsigned k = 0; k < N_VERTICES; ++k) sum += w[k];
    printf("%s %a %a %a %d %a\n", tag, t, x[0], x[1], (int)c, sum);
}

/* One communication step from *t toward `end`, through the early returns and event mode. */
static void stepTo(const Api* a, fmi3Instance s, double* t, double end) {
    const fmi3ValueReference base = VR_BASE;
    while (end - *t > 1e-12) {
        fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
        double reached = *t;
        const double value = baseAt(*t);
        check(a->setFloat64(s, &base, 1, &value, 1) == fmi3OK, "fmi3SetFloat64 of the base");
        check(a->doStep(s, *t, end - *t, fmi3True, &event, &terminate, &early, &reached) == fmi3OK, "fmi3DoStep");
        *t = early ? reached : end;
        if (event) {
            fmi3Boolean more, stop, nominals, values, defined;
            double next;
            print(a, s, *t, "event");
            check(a->enterEventMode(s) == fmi3OK, "fmi3EnterEventMode");
            check(a->updateDiscreteStates(s, &more, &stop, &nominals, &values, &defined, &next) == fmi3OK,
                  "fmi3UpdateDiscreteStates");
            check(a->enterStepMode(s) == fmi3OK, "fmi3EnterStepMode");
        }
    }
}

int main(int argc, char** argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s <PlateImpact.so> <instantiationToken>\n", argv[0]);
        return 2;
    }
    Library lib = open_library(argv[1]);
    if (!lib) {
        fprintf(stderr, "fmu3_driver: %s\n", library_error());
        return 2;
    }
    Api a;
    load(&a, lib);
    check(!a.instantiate("x", "{wrong}", "", 0, 0, 1, 1, NULL, 0, NULL, logger, NULL), "a wrong token is refused");
    fmi3Instance s = a.instantiate("plate", argv[2], "", 0, 0, 1, 1, NULL, 0, NULL, logger, NULL);
    check(s != NULL, "fmi3InstantiateCoSimulation");
    if (!s) return 1;
    check(a.enterInit(s, 0, 0.0, 0.0, 1, 0.1) == fmi3OK, "fmi3EnterInitializationMode");
    check(a.exitInit(s) == fmi3OK, "fmi3ExitInitializationMode");
    check(a.enterStepMode(s) == fmi3OK, "fmi3EnterStepMode after initialization");
    double t = 0.0;
    fmi3FMUState mid = NULL;
    print(&a, s, t, "point");
    for (int k = 1; k <= 1000; ++k) {
        stepTo(&a, s, &t, k * 1e-4);
        print(&a, s, t, "point");
        if (k == 500) check(a.getState(s, &mid) == fmi3OK, "fmi3GetFMUState");
    }
    /* The state at 0.05 s through its bytes: the step after it again, the same bits. */
    size_t size = 0;
    check(a.stateSize(s, mid, &size) == fmi3OK && size > 0, "fmi3SerializedFMUStateSize");
    unsigned char* bytes = malloc(size);
    fmi3FMUState copy = NULL;
    check(bytes && a.serialize(s, mid, bytes, size) == fmi3OK, "fmi3SerializeFMUState");
    check(bytes && a.deserialize(s, bytes, size, &copy) == fmi3OK, "fmi3DeserializeFMUState");
    check(a.setState(s, copy) == fmi3OK, "fmi3SetFMUState");
    t = 0.05;
    stepTo(&a, s, &t, 0.0501);
    print(&a, s, t, "again");
    const fmi3ValueReference unknown = 99999;
    double x;
    check(a.getFloat64(s, &unknown, 1, &x, 1) == fmi3Error, "an unknown value reference is an fmi3Error");
    free(bytes);
    a.freeState(s, &mid);
    a.freeState(s, &copy);
    a.freeInstance(s);
    close_library(lib);
    printf("failures %d\n", failures);
    return failures == 0 ? 0 : 1;
}
