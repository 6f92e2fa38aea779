/* A minimal FMI 2 and FMI 3 co-simulation importer, built for Windows (zig cc -target
 * x86_64-windows-gnu) and run under wine64 against the win64 DLL, or built for Linux (cc ... -ldl)
 * against the Linux library: the same calls on both, so their printed values, serialized states and
 * MCAP logs can be compared byte for byte (scripts/wine-check.sh).
 *
 * Usage: importer LIBRARY RESOURCE_URI PREFIX [STOP_TIME [STEP]]
 * For FMI 2, then FMI 3: loads LIBRARY, instantiates BeamImpact (the paper scenario: every
 * parameter at its default) with log.path = PREFIX-fmiN.mcap (relative to the working directory),
 * initialises, steps to STOP_TIME (default 3 s) in STEP (default 1 ms). Halfway (1.5 s) it gets the
 * FMU state, serializes it (written to PREFIX-fmiN.state), frees it, deserializes it, sets it back
 * and checks that every output read is unchanged; it steps to the end, rolls back to the
 * deserialized state, steps to the end again and checks that every output is the same bit for bit
 * as the first time; then terminates and frees the instance (which completes the log).
 * Prints `fmiN.name value` lines (%.17g). Exit code 0 when every call returned OK and every
 * check held, 1 otherwise, 2 when the library cannot be used at all. */
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <windows.h>
typedef HMODULE lib_t;
static lib_t lib_open(const char *path) { return LoadLibraryA(path); }
static void *lib_sym(lib_t lib, const char *name) { return (void *)GetProcAddress(lib, name); }
static const char *lib_error(void) {
    static char text[64];
    snprintf(text, sizeof text, "Windows error %lu", (unsigned long)GetLastError());
    return text;
}
#else
#include <dlfcn.h>
typedef void *lib_t;
static lib_t lib_open(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(lib_t lib, const char *name) { return dlsym(lib, name); }
static const char *lib_error(void) { return dlerror(); }
#endif

/* The FMI 2.0 types this importer needs (fmi2TypesPlatform.h, fmi2FunctionTypes.h). */
typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef const char *fmi2String;
typedef double fmi2Real;
typedef int fmi2Boolean;
typedef char fmi2Byte;
typedef unsigned int fmi2ValueReference;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef struct {
    void (*logger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef const char *(*Fmi2GetVersion)(void);
typedef fmi2Component (*Fmi2Instantiate)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions *,
                                         fmi2Boolean, fmi2Boolean);
typedef fmi2Status (*Fmi2SetupExperiment)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*Fmi2Simple)(fmi2Component);
typedef fmi2Status (*Fmi2SetString)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2String *);
typedef fmi2Status (*Fmi2GetReal)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*Fmi2DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef void (*Fmi2FreeInstance)(fmi2Component);
typedef fmi2Status (*Fmi2GetFMUstate)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*Fmi2SetFMUstate)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*Fmi2FreeFMUstate)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*Fmi2SerializedFMUstateSize)(fmi2Component, fmi2FMUstate, size_t *);
typedef fmi2Status (*Fmi2SerializeFMUstate)(fmi2Component, fmi2FMUstate, fmi2Byte *, size_t);
typedef fmi2Status (*Fmi2DeSerializeFMUstate)(fmi2Component, const fmi2Byte *, size_t, fmi2FMUstate *);

/* The FMI 3.0 types this importer needs (fmi3PlatformTypes.h, fmi3FunctionTypes.h). */
typedef void *fmi3Instance;
typedef void *fmi3InstanceEnvironment;
typedef void *fmi3FMUState;
typedef const char *fmi3String;
typedef double fmi3Float64;
typedef bool fmi3Boolean;
typedef uint8_t fmi3Byte;
typedef uint32_t fmi3ValueReference;
typedef enum { fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal } fmi3Status;
typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String);
typedef void (*fmi3IntermediateUpdateCallback)(fmi3InstanceEnvironment, fmi3Float64, fmi3Boolean, fmi3Boolean,
                                               fmi3Boolean, fmi3Boolean, fmi3Boolean *, fmi3Float64 *);

typedef fmi3Instance (*Fmi3InstantiateCoSimulation)(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                                    fmi3Boolean, fmi3Boolean, const fmi3ValueReference *, size_t,
                                                    fmi3InstanceEnvironment, fmi3LogMessageCallback,
                                                    fmi3IntermediateUpdateCallback);
typedef fmi3Status (*Fmi3EnterInitializationMode)(fmi3Instance, fmi3Boolean, fmi3Float64, fmi3Float64, fmi3Boolean,
                                                  fmi3Float64);
typedef fmi3Status (*Fmi3Simple)(fmi3Instance);
typedef fmi3Status (*Fmi3SetString)(fmi3Instance, const fmi3ValueReference *, size_t, const fmi3String *, size_t);
typedef fmi3Status (*Fmi3GetFloat64)(fmi3Instance, const fmi3ValueReference *, size_t, fmi3Float64 *, size_t);
typedef fmi3Status (*Fmi3DoStep)(fmi3Instance, fmi3Float64, fmi3Float64, fmi3Boolean, fmi3Boolean *, fmi3Boolean *,
                                 fmi3Boolean *, fmi3Float64 *);
typedef void (*Fmi3FreeInstance)(fmi3Instance);
typedef fmi3Status (*Fmi3GetFMUState)(fmi3Instance, fmi3FMUState *);
typedef fmi3Status (*Fmi3SetFMUState)(fmi3Instance, fmi3FMUState);
typedef fmi3Status (*Fmi3FreeFMUState)(fmi3Instance, fmi3FMUState *);
typedef fmi3Status (*Fmi3SerializedFMUStateSize)(fmi3Instance, fmi3FMUState, size_t *);
typedef fmi3Status (*Fmi3SerializeFMUState)(fmi3Instance, fmi3FMUState, fmi3Byte *, size_t);
typedef fmi3Status (*Fmi3DeserializeFMUState)(fmi3Instance, const fmi3Byte *, size_t, fmi3FMUState *);

static void logger2(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                    fmi2String message, ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s %d %s] ", instance ? instance : "?", (int)status, category ? category : "");
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
    (void)env;
    fprintf(stderr, "[fmi3 %d %s] %s\n", (int)status, category ? category : "", message ? message : "");
}

static int failures = 0;
static const char *version = "fmi2"; /* the run under way, for messages */
static void check(int status, const char *what) {
    if (status != 0) {
        fprintf(stderr, "importer: %s %s returned status %d\n", version, what, status);
        failures++;
    }
}

static void *need(lib_t lib, const char *name) {
    void *f = lib_sym(lib, name);
    if (!f) {
        fprintf(stderr, "importer: %s is not exported\n", name);
        exit(2);
    }
    return f;
}

/* From modelDescription.xml (FMI 2 guid = FMI 3 instantiationToken; the value references are the same). */
#define TOKEN "{26abd558-9fe5-a1f6-3774-e9c76ed4d7ed}"
#define VR_LOG_PATH 27
#define N_OUTPUTS 8
#define N_PEAKS 5 /* the first N_PEAKS outputs */
static const struct {
    const char *name;
    unsigned int vr;
} outputs[N_OUTPUTS] = {
    {"peak.lower.tip_deflection", 44},         {"peak.lower.clamp_bending_stress", 45},
    {"peak.lower.clamp_shear_stress", 46},     {"peak.upper.contact_bending_stress", 47},
    {"peak.contact.force", 48},                {"lower.tip_deflection", 30},
    {"contact.force", 37},                     {"energy.residual", 43},
};

/* One instance of either version, behind the few operations the scenario needs. */
typedef struct {
    int fmi3;
    void *c;
    Fmi2DoStep doStep2;
    Fmi2GetReal getReal;
    Fmi2GetFMUstate getState2;
    Fmi2SetFMUstate setState2;
    Fmi2FreeFMUstate freeState2;
    Fmi2SerializedFMUstateSize stateSize2;
    Fmi2SerializeFMUstate serialize2;
    Fmi2DeSerializeFMUstate deserialize2;
    Fmi2Simple terminate2;
    Fmi2FreeInstance free2;
    Fmi3DoStep doStep3;
    Fmi3GetFloat64 getFloat64;
    Fmi3GetFMUState getState3;
    Fmi3SetFMUState setState3;
    Fmi3FreeFMUState freeState3;
    Fmi3SerializedFMUStateSize stateSize3;
    Fmi3SerializeFMUState serialize3;
    Fmi3DeserializeFMUState deserialize3;
    Fmi3Simple terminate3;
    Fmi3FreeInstance free3;
} Fmu;

/* Steps from step number `from` to `to` (time = i * h, every step from an exact multiple of h). */
static void step(Fmu *f, long from, long to, double h) {
    for (long i = from; i < to && failures == 0; i++) {
        if (f->fmi3) {
            fmi3Boolean event = false, terminate = false, early = false;
            fmi3Float64 last = 0;
            check(f->doStep3(f->c, (double)i * h, h, false, &event, &terminate, &early, &last), "fmi3DoStep");
            if (early || terminate) {
                fprintf(stderr, "importer: fmi3DoStep at step %ld returned early or asked to terminate\n", i);
                failures++;
            }
        } else {
            check(f->doStep2(f->c, (double)i * h, h, 0), "fmi2DoStep");
        }
    }
}

static void get_outputs(Fmu *f, double values[N_OUTPUTS]) {
    for (size_t i = 0; i < N_OUTPUTS; i++) {
        values[i] = 0;
        if (f->fmi3) {
            fmi3ValueReference vr = outputs[i].vr;
            check(f->getFloat64(f->c, &vr, 1, &values[i], 1), "fmi3GetFloat64");
        } else {
            fmi2ValueReference vr = outputs[i].vr;
            check(f->getReal(f->c, &vr, 1, &values[i]), "fmi2GetReal");
        }
    }
}

/* GetFMUState, serialize (into a malloc'd buffer, *size bytes), FreeFMUState. */
static unsigned char *save_state(Fmu *f, size_t *size) {
    void *state = NULL;
    unsigned char *bytes = NULL;
    *size = 0;
    if (f->fmi3) {
        check(f->getState3(f->c, &state), "fmi3GetFMUState");
        check(f->stateSize3(f->c, state, size), "fmi3SerializedFMUStateSize");
        bytes = malloc(*size ? *size : 1);
        check(f->serialize3(f->c, state, bytes, *size), "fmi3SerializeFMUState");
        check(f->freeState3(f->c, &state), "fmi3FreeFMUState");
    } else {
        check(f->getState2(f->c, &state), "fmi2GetFMUstate");
        check(f->stateSize2(f->c, state, size), "fmi2SerializedFMUstateSize");
        bytes = malloc(*size ? *size : 1);
        check(f->serialize2(f->c, state, (fmi2Byte *)bytes, *size), "fmi2SerializeFMUstate");
        check(f->freeState2(f->c, &state), "fmi2FreeFMUstate");
    }
    if (state != NULL) {
        fprintf(stderr, "importer: %s FreeFMUState left the state pointer set\n", version);
        failures++;
    }
    return bytes;
}

static void *deserialize(Fmu *f, const unsigned char *bytes, size_t size) {
    void *state = NULL;
    if (f->fmi3) {
        check(f->deserialize3(f->c, bytes, size, &state), "fmi3DeserializeFMUState");
    } else {
        check(f->deserialize2(f->c, (const fmi2Byte *)bytes, size, &state), "fmi2DeSerializeFMUstate");
    }
    return state;
}

static void set_state(Fmu *f, void *state) {
    if (f->fmi3) {
        check(f->setState3(f->c, state), "fmi3SetFMUState");
    } else {
        check(f->setState2(f->c, state), "fmi2SetFMUstate");
    }
}

static void free_state(Fmu *f, void *state) {
    if (f->fmi3) {
        check(f->freeState3(f->c, &state), "fmi3FreeFMUState");
    } else {
        check(f->freeState2(f->c, &state), "fmi2FreeFMUstate");
    }
}

/* Whether a and b hold the same bits; names the first output that differs. */
static int same_bits(const double a[N_OUTPUTS], const double b[N_OUTPUTS], const char *what) {
    for (size_t i = 0; i < N_OUTPUTS; i++) {
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0) {
            fprintf(stderr, "importer: %s %s: %s is %.17g, was %.17g\n", version, what, outputs[i].name, b[i], a[i]);
            failures++;
            return 0;
        }
    }
    return 1;
}

static void write_file(const char *path, const unsigned char *bytes, size_t size) {
    FILE *out = fopen(path, "wb");
    if (!out || fwrite(bytes, 1, size, out) != size || fclose(out) != 0) {
        fprintf(stderr, "importer: cannot write %s\n", path);
        failures++;
    }
}

/* The scenario on an instantiated, initialised instance: to halfway, save and restore the state,
 * to the end, roll back to the restored state, to the end again; prints the outputs. */
static void scenario(Fmu *f, const char *prefix, double stop, double h) {
    long steps = (long)(stop / h + 0.5), half = steps / 2;
    double at_save[N_OUTPUTS], restored[N_OUTPUTS], first[N_OUTPUTS], again[N_OUTPUTS];
    char path[1024];
    clock_t start = clock();

    step(f, 0, half, h);
    get_outputs(f, at_save);
    size_t size = 0;
    unsigned char *bytes = save_state(f, &size);
    snprintf(path, sizeof path, "%s-%s.state", prefix, version);
    write_file(path, bytes, size);
    void *state = deserialize(f, bytes, size);
    set_state(f, state);
    get_outputs(f, restored);
    int restore_ok = same_bits(at_save, restored, "after restoring the deserialized state");

    step(f, half, steps, h);
    get_outputs(f, first);
    set_state(f, state); /* roll back to halfway and run the second half again */
    get_outputs(f, restored);
    restore_ok &= same_bits(at_save, restored, "after rolling back to the deserialized state");
    step(f, half, steps, h);
    get_outputs(f, again);
    int repeat_ok = same_bits(first, again, "the second run of the second half");
    free_state(f, state);
    free(bytes);
    double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;

    printf("%s.steps %ld\n%s.do_step_calls %ld\n%s.state_saved_at %.17g\n%s.state_bytes %lu\n", version, steps,
           version, steps + (steps - half), version, (double)half * h, version, (unsigned long)size);
    for (size_t i = 0; i < N_OUTPUTS; i++) {
        printf("%s.%s %.17g\n", version, outputs[i].name, first[i]);
    }
    for (size_t i = 0; i < N_PEAKS; i++) {
        printf("%s.at_save.%s %.17g\n", version, outputs[i].name, at_save[i]);
    }
    printf("%s.restore %s\n%s.rerun %s\n", version, restore_ok ? "bit-identical" : "DIFFERS", version,
           repeat_ok ? "bit-identical" : "DIFFERS");
    fprintf(stderr, "importer: %s: %ld steps in %.2f s CPU\n", version, steps + (steps - half), seconds);
}

static void run_fmi2(lib_t lib, const char *uri, const char *prefix, double stop, double h) {
    Fmi2GetVersion getVersion = (Fmi2GetVersion)need(lib, "fmi2GetVersion");
    Fmi2GetVersion getTypesPlatform = (Fmi2GetVersion)need(lib, "fmi2GetTypesPlatform");
    Fmi2Instantiate instantiate = (Fmi2Instantiate)need(lib, "fmi2Instantiate");
    Fmi2SetupExperiment setup = (Fmi2SetupExperiment)need(lib, "fmi2SetupExperiment");
    Fmi2Simple enterInit = (Fmi2Simple)need(lib, "fmi2EnterInitializationMode");
    Fmi2Simple exitInit = (Fmi2Simple)need(lib, "fmi2ExitInitializationMode");
    Fmi2SetString setString = (Fmi2SetString)need(lib, "fmi2SetString");
    Fmu f = {0};
    f.doStep2 = (Fmi2DoStep)need(lib, "fmi2DoStep");
    f.getReal = (Fmi2GetReal)need(lib, "fmi2GetReal");
    f.getState2 = (Fmi2GetFMUstate)need(lib, "fmi2GetFMUstate");
    f.setState2 = (Fmi2SetFMUstate)need(lib, "fmi2SetFMUstate");
    f.freeState2 = (Fmi2FreeFMUstate)need(lib, "fmi2FreeFMUstate");
    f.stateSize2 = (Fmi2SerializedFMUstateSize)need(lib, "fmi2SerializedFMUstateSize");
    f.serialize2 = (Fmi2SerializeFMUstate)need(lib, "fmi2SerializeFMUstate");
    f.deserialize2 = (Fmi2DeSerializeFMUstate)need(lib, "fmi2DeSerializeFMUstate");
    f.terminate2 = (Fmi2Simple)need(lib, "fmi2Terminate");
    f.free2 = (Fmi2FreeInstance)need(lib, "fmi2FreeInstance");

    version = "fmi2";
    printf("fmi2.GetVersion %s\nfmi2.GetTypesPlatform %s\n", getVersion(), getTypesPlatform());
    fmi2CallbackFunctions callbacks = {logger2, calloc, free, NULL, NULL};
    f.c = instantiate("wine", fmi2CoSimulation, TOKEN, uri, &callbacks, 0, 0);
    if (!f.c) {
        fprintf(stderr, "importer: fmi2Instantiate returned NULL\n");
        failures++;
        return;
    }
    char log[1024];
    snprintf(log, sizeof log, "%s-fmi2.mcap", prefix);
    fmi2String value = log;
    fmi2ValueReference vr = VR_LOG_PATH;
    check(setup(f.c, 0, 0.0, 0.0, 1, stop), "fmi2SetupExperiment");
    check(setString(f.c, &vr, 1, &value), "fmi2SetString(log.path)");
    check(enterInit(f.c), "fmi2EnterInitializationMode");
    check(exitInit(f.c), "fmi2ExitInitializationMode");
    if (failures == 0) {
        scenario(&f, prefix, stop, h);
    }
    check(f.terminate2(f.c), "fmi2Terminate");
    f.free2(f.c);
}

static void run_fmi3(lib_t lib, const char *uri, const char *prefix, double stop, double h) {
    Fmi2GetVersion getVersion = (Fmi2GetVersion)need(lib, "fmi3GetVersion");
    Fmi3InstantiateCoSimulation instantiate = (Fmi3InstantiateCoSimulation)need(lib, "fmi3InstantiateCoSimulation");
    Fmi3EnterInitializationMode enterInit = (Fmi3EnterInitializationMode)need(lib, "fmi3EnterInitializationMode");
    Fmi3Simple exitInit = (Fmi3Simple)need(lib, "fmi3ExitInitializationMode");
    Fmi3SetString setString = (Fmi3SetString)need(lib, "fmi3SetString");
    Fmu f = {0};
    f.fmi3 = 1;
    f.doStep3 = (Fmi3DoStep)need(lib, "fmi3DoStep");
    f.getFloat64 = (Fmi3GetFloat64)need(lib, "fmi3GetFloat64");
    f.getState3 = (Fmi3GetFMUState)need(lib, "fmi3GetFMUState");
    f.setState3 = (Fmi3SetFMUState)need(lib, "fmi3SetFMUState");
    f.freeState3 = (Fmi3FreeFMUState)need(lib, "fmi3FreeFMUState");
    f.stateSize3 = (Fmi3SerializedFMUStateSize)need(lib, "fmi3SerializedFMUStateSize");
    f.serialize3 = (Fmi3SerializeFMUState)need(lib, "fmi3SerializeFMUState");
    f.deserialize3 = (Fmi3DeserializeFMUState)need(lib, "fmi3DeserializeFMUState");
    f.terminate3 = (Fmi3Simple)need(lib, "fmi3Terminate");
    f.free3 = (Fmi3FreeInstance)need(lib, "fmi3FreeInstance");

    version = "fmi3";
    printf("fmi3.GetVersion %s\n", getVersion());
    f.c = instantiate("wine", TOKEN, uri, false, false, false, false, NULL, 0, NULL, logger3, NULL);
    if (!f.c) {
        fprintf(stderr, "importer: fmi3InstantiateCoSimulation returned NULL\n");
        failures++;
        return;
    }
    char log[1024];
    snprintf(log, sizeof log, "%s-fmi3.mcap", prefix);
    fmi3String value = log;
    fmi3ValueReference vr = VR_LOG_PATH;
    check(setString(f.c, &vr, 1, &value, 1), "fmi3SetString(log.path)");
    check(enterInit(f.c, false, 0.0, 0.0, true, stop), "fmi3EnterInitializationMode");
    check(exitInit(f.c), "fmi3ExitInitializationMode");
    if (failures == 0) {
        scenario(&f, prefix, stop, h);
    }
    check(f.terminate3(f.c), "fmi3Terminate");
    f.free3(f.c);
}

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: importer LIBRARY RESOURCE_URI PREFIX [STOP_TIME [STEP]]\n");
        return 2;
    }
    double stop = argc > 4 ? atof(argv[4]) : 3.0, h = argc > 5 ? atof(argv[5]) : 1e-3;
#ifdef _WIN32
    _setmode(_fileno(stdout), _O_BINARY); /* "\n", not "\r\n": the same bytes as on Linux */
#endif
    lib_t lib = lib_open(argv[1]);
    if (!lib) {
        fprintf(stderr, "importer: cannot load %s: %s\n", argv[1], lib_error());
        return 2;
    }
    run_fmi2(lib, argv[2], argv[3], stop, h);
    int after2 = failures;
    run_fmi3(lib, argv[2], argv[3], stop, h);
    fprintf(stderr, "importer: %d failures (FMI 2: %d, FMI 3: %d)\n", failures, after2, failures - after2);
    return failures ? 1 : 0;
}
