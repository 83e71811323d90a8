/* A plain C master that replays the FMU's reference experiments (FMI-LS-REF) on the FMI 3.0
 * binary of any platform, for python_tests/test_experiments_platforms.py: the same source built for
 * x86-64 Linux, for aarch64 (run under qemu-aarch64) and for x86-64 Windows (run under Wine). No
 * Python and no XML under emulation: the test writes each experiment as a plan of plain numbers.
 *
 *   experiment_driver <binaries/<platform>/PlateImpact.so|.dll> <instantiationToken> PLAN OUT [PLAN OUT ...]
 *
 * PLAN (whitespace-separated):
 *   start stop step nParameters nInputs nOutputs nRows stateBytes
 *   per parameter: kind (f Float64, i Int32, u UInt64, b Boolean) valueReference value
 *   the input value references, then the output value references (all Float64)
 *   per communication point k < nRows: the input values at start + k step
 *   stateBytes > 0: that many bytes of a serialized FMU state as two-digit hex, set right after
 *   instantiation instead of initializing (the parameters are the state's)
 * Numbers are read with strtod (exact for C99 hex floats). Per experiment: instantiate (no event
 * mode, no early return), the parameters and the inputs at start, initialize (or the state), then
 * nRows - 1 steps of `step` from start, the inputs of point k set before the step from it. OUT
 * gets one line per communication point: the time and the outputs as %a. Exit 0 when every call
 * succeeded, 1 with a message otherwise. */
#if defined(_WIN32)
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) { return LoadLibraryA(path); }
static void* find_symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* find_symbol(Library lib, const char* name) { return dlsym(lib, name); }
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"

static void logger(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
    (void)env;
    if (status >= fmi3Warning) fprintf(stderr, "[%d %s] %s\n", (int)status, category, message);
}

static char* read_file(const char* path) {
    FILE* f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char* text = malloc((size_t)n + 1);
    if (text && fread(text, 1, (size_t)n, f) != (size_t)n) {
        free(text);
        text = NULL;
    }
    if (text) text[n] = 0;
    fclose(f);
    return text;
}

static char* cursor;
static char* word(void) {
    while (*cursor == ' ' || *cursor == '\n' || *cursor == '\r' || *cursor == '\t') ++cursor;
    char* start = cursor;
    while (*cursor && *cursor != ' ' && *cursor != '\n' && *cursor != '\r' && *cursor != '\t') ++cursor;
    if (*cursor) *cursor++ = 0;
    return start;
}
static double number(void) { return strtod(word(), NULL); }

#define FN(name) name##TYPE* name
static struct {
    FN(fmi3InstantiateCoSimulation);
    FN(fmi3EnterInitializationMode);
    FN(fmi3ExitInitializationMode);
    FN(fmi3SetFloat64);
    FN(fmi3SetInt32);
    FN(fmi3SetUInt64);
    FN(fmi3SetBoolean);
    FN(fmi3GetFloat64);
    FN(fmi3DoStep);
    FN(fmi3DeserializeFMUState);
    FN(fmi3SetFMUState);
    FN(fmi3FreeFMUState);
    FN(fmi3Terminate);
    FN(fmi3FreeInstance);
} api;

#define CALL(call)                                                                       \
    if ((call) > fmi3Warning) {                                                          \
        fprintf(stderr, "experiment_driver: %s: %s failed at t = %g\n", plan, #call, t); \
        return 1;                                                                        \
    }

static int replay(const char* token, const char* plan, const char* out_path) {
    char* text = read_file(plan);
    if (!text) {
        fprintf(stderr, "experiment_driver: cannot read %s\n", plan);
        return 1;
    }
    cursor = text;
    double t = number();
    const double start = t, stop = number(), step = number();
    const int n_par = atoi(word()), n_in = atoi(word()), n_out = atoi(word()), n_rows = atoi(word());
    const long state_bytes = atol(word());
    (void)stop;
    fmi3Instance c = api.fmi3InstantiateCoSimulation("replay", token, NULL, fmi3False, fmi3False, fmi3False, fmi3False,
                                                     NULL, 0, NULL, logger, NULL);
    if (!c) {
        fprintf(stderr, "experiment_driver: %s: instantiation failed\n", plan);
        return 1;
    }
    for (int p = 0; p < n_par; ++p) {
        const char* kind = word();
        const fmi3ValueReference vr = (fmi3ValueReference)strtoul(word(), NULL, 10);
        const char* value = word();
        if (state_bytes > 0) continue;
        if (kind[0] == 'f') {
            const fmi3Float64 v = strtod(value, NULL);
            CALL(api.fmi3SetFloat64(c, &vr, 1, &v, 1))
        } else if (kind[0] == 'i') {
            const fmi3Int32 v = (fmi3Int32)strtol(value, NULL, 10);
            CALL(api.fmi3SetInt32(c, &vr, 1, &v, 1))
        } else if (kind[0] == 'u') {
            const fmi3UInt64 v = (fmi3UInt64)strtoull(value, NULL, 10);
            CALL(api.fmi3SetUInt64(c, &vr, 1, &v, 1))
        } else {
            const fmi3Boolean v = value[0] == '1' || value[0] == 't';
            CALL(api.fmi3SetBoolean(c, &vr, 1, &v, 1))
        }
    }
    fmi3ValueReference* in = calloc((size_t)n_in + 1, sizeof *in);
    fmi3ValueReference* outv = calloc((size_t)n_out + 1, sizeof *outv);
    fmi3Float64* in_values = calloc((size_t)n_in * (size_t)n_rows + 1, sizeof *in_values);
    fmi3Float64* values = calloc((size_t)n_out + 1, sizeof *values);
    for (int i = 0; i < n_in; ++i) in[i] = (fmi3ValueReference)strtoul(word(), NULL, 10);
    for (int i = 0; i < n_out; ++i) outv[i] = (fmi3ValueReference)strtoul(word(), NULL, 10);
    for (long i = 0; i < (long)n_in * n_rows; ++i) in_values[i] = number();
    if (state_bytes > 0) {
        const char* hex = word();
        unsigned char* bytes = malloc((size_t)state_bytes);
        for (long i = 0; i < state_bytes; ++i) {
            unsigned int b;
            sscanf(hex + 2 * i, "%2x", &b);
            bytes[i] = (unsigned char)b;
        }
        fmi3FMUState state = NULL;
        CALL(api.fmi3DeserializeFMUState(c, bytes, (size_t)state_bytes, &state))
        CALL(api.fmi3SetFMUState(c, state))
        CALL(api.fmi3FreeFMUState(c, &state))
        free(bytes);
        if (n_in) CALL(api.fmi3SetFloat64(c, in, (size_t)n_in, in_values, (size_t)n_in))
    } else {
        if (n_in) CALL(api.fmi3SetFloat64(c, in, (size_t)n_in, in_values, (size_t)n_in))
        CALL(api.fmi3EnterInitializationMode(c, fmi3False, 0.0, start, fmi3False, 0.0))
        CALL(api.fmi3ExitInitializationMode(c))
    }
    FILE* out = fopen(out_path, "w");
    if (!out) {
        fprintf(stderr, "experiment_driver: cannot write %s\n", out_path);
        return 1;
    }
    for (int k = 0; k < n_rows; ++k) {
        t = start + k * step;
        CALL(api.fmi3GetFloat64(c, outv, (size_t)n_out, values, (size_t)n_out))
        fprintf(out, "%a", t);
        for (int i = 0; i < n_out; ++i) fprintf(out, " %a", values[i]);
        fprintf(out, "\n");
        if (k + 1 == n_rows) break;
        if (n_in) CALL(api.fmi3SetFloat64(c, in, (size_t)n_in, in_values + (size_t)k * n_in, (size_t)n_in))
        fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
        fmi3Float64 last = t;
        CALL(api.fmi3DoStep(c, t, step, fmi3True, &event, &terminate, &early, &last))
    }
    fclose(out);
    CALL(api.fmi3Terminate(c))
    api.fmi3FreeInstance(c);
    free(in);
    free(outv);
    free(in_values);
    free(values);
    free(text);
    return 0;
}

#define LOAD(name)                                                                     \
    api.name = (name##TYPE*)find_symbol(lib, #name);                                   \
    if (!api.name) {                                                                   \
        fprintf(stderr, "experiment_driver: %s not exported by %s\n", #name, argv[1]); \
        return 1;                                                                      \
    }

int main(int argc, char** argv) {
    if (argc < 5 || argc % 2 == 0) {
        fprintf(stderr, "usage: experiment_driver LIBRARY TOKEN PLAN OUT [PLAN OUT ...]\n");
        return 2;
    }
    Library lib = open_library(argv[1]);
    if (!lib) {
        fprintf(stderr, "experiment_driver: cannot load %s\n", argv[1]);
        return 1;
    }
    LOAD(fmi3InstantiateCoSimulation)
    LOAD(fmi3EnterInitializationMode)
    LOAD(fmi3ExitInitializationMode)
    LOAD(fmi3SetFloat64)
    LOAD(fmi3SetInt32)
    LOAD(fmi3SetUInt64)
    LOAD(fmi3SetBoolean)
    LOAD(fmi3GetFloat64)
    LOAD(fmi3DoStep)
    LOAD(fmi3DeserializeFMUState)
    LOAD(fmi3SetFMUState)
    LOAD(fmi3FreeFMUState)
    LOAD(fmi3Terminate)
    LOAD(fmi3FreeInstance)
    for (int i = 3; i + 1 < argc; i += 2)
        if (replay(argv[2], argv[i], argv[i + 1]) != 0) return 1;
    return 0;
}
