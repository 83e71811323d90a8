/* A C master that loads copies of the FMU's library from different folders one after the other,
 * as fmpy's simulate_fmu does (fmu/core/PrimaryCopy.h): each run opens a library, runs one
 * instance of a small plate (4 x 2 cells, pressed against the upper obstacle: impacts within the
 * first steps), frees it and closes the library. The first run's copy becomes the process's
 * primary; every later copy forwards to it, so its plate is shared from the cache and its outputs
 * are the first run's, bit for bit. Exits 0 when so (test_primary_copy.py runs it under valgrind
 * on Linux and under Wine with the win64 DLL).
 *
 *   copies_driver GUID LIBRARY...     (each LIBRARY a path; the same path twice loads it anew) */
#if defined(_WIN32)
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) { return LoadLibraryA(path); }
static void* symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
static int close_library(Library lib) { return FreeLibrary(lib) ? 0 : 1; }
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* symbol(Library lib, const char* name) { return dlsym(lib, name); }
static int close_library(Library lib) { return dlclose(lib); }
#endif
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#define CHECK(cond)                                                                                 \
    do {                                                                                            \
        if (!(cond)) {                                                                              \
            fprintf(stderr, "copies_driver: %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            exit(1);                                                                                \
        }                                                                                           \
    } while (0)
#define OK(call) CHECK((call) == fmi2OK)
#define LOAD(name) name##TYPE* name = (name##TYPE*)symbol(lib, #name)

static const fmi2ValueReference REAL_OUT[] = {30, 31, 32, 33, 34, 35, 37};
#define N_REAL (sizeof REAL_OUT / sizeof REAL_OUT[0])

static int shared = -1, parts = -1; /* from the instance's log line */

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env, (void)instance, (void)status, (void)category;
    char text[2048];
    va_list args;
    va_start(args, message);
    vsnprintf(text, sizeof text, message, args);
    va_end(args);
    const char* at = strstr(text, "discretization: ");
    if (at) CHECK(sscanf(at, "discretization: %d of %d parts shared", &shared, &parts) == 2);
}

/* One run of `path`'s library: its outputs after three steps into out. */
static void run(const char* path, const char* guid, fmi2Real out[N_REAL]) {
    Library lib = open_library(path);
    CHECK(lib);
    LOAD(fmi2Instantiate);
    LOAD(fmi2FreeInstance);
    LOAD(fmi2SetupExperiment);
    LOAD(fmi2EnterInitializationMode);
    LOAD(fmi2ExitInitializationMode);
    LOAD(fmi2SetInteger);
    LOAD(fmi2SetReal);
    LOAD(fmi2GetReal);
    LOAD(fmi2DoStep);
    LOAD(fmi2Terminate);
    CHECK(fmi2Instantiate && fmi2FreeInstance && fmi2SetupExperiment && fmi2EnterInitializationMode &&
          fmi2ExitInitializationMode && fmi2SetInteger && fmi2SetReal && fmi2GetReal && fmi2DoStep && fmi2Terminate);
    const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = fmi2Instantiate("copy", fmi2CoSimulation, guid, "", &callbacks, fmi2False, fmi2True);
    CHECK(c);
    const fmi2ValueReference ivr[] = {6, 7}; /* nx, ny */
    const fmi2Integer ival[] = {4, 2};
    const fmi2ValueReference rvr[] = {13, 15}; /* dt, initial_load */
    const fmi2Real rval[] = {1e-4, 8600.0};
    shared = parts = -1;
    OK(fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(fmi2EnterInitializationMode(c));
    OK(fmi2SetInteger(c, ivr, 2, ival));
    OK(fmi2SetReal(c, rvr, 2, rval));
    OK(fmi2ExitInitializationMode(c));
    for (int k = 0; k < 3; ++k) OK(fmi2DoStep(c, k * 1e-3, 1e-3, fmi2True));
    OK(fmi2GetReal(c, REAL_OUT, N_REAL, out));
    OK(fmi2Terminate(c));
    fmi2FreeInstance(c);
    CHECK(close_library(lib) == 0);
}

int main(int argc, char** argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: copies_driver GUID LIBRARY LIBRARY...\n");
        return 2;
    }
    fmi2Real first[N_REAL], out[N_REAL];
    for (int k = 2; k < argc; ++k) {
        run(argv[k], argv[1], k == 2 ? first : out);
        printf("run %d: %s: %d of %d parts shared\n", k - 1, argv[k], shared, parts);
        CHECK(parts > 0 && shared == (k == 2 ? 0 : parts));
        if (k > 2) CHECK(memcmp(first, out, sizeof out) == 0);
    }
    printf("copies_driver: all checks passed\n");
    return 0;
}
