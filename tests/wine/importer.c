/* A minimal FMI 2 co-simulation importer, built for Windows (zig cc -target x86_64-windows-gnu)
 * and run under wine64 against the win64 DLL, or built for Linux (cc ... -ldl) against the
 * Linux library: the same calls on both, so their printed peaks can be compared digit for digit.
 *
 * Usage: importer LIBRARY RESOURCE_URI [STOP_TIME [STEP]]
 * Loads LIBRARY, instantiates BeamImpact (the paper scenario, log.path "" = no log), steps to
 * STOP_TIME (default 3 s) in STEP (default 1 ms) and prints `name value` lines (%.17g). Exit
 * code 0 when every call returned fmi2OK, 1 otherwise. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _WIN32
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
typedef const char *fmi2String;
typedef double fmi2Real;
typedef int fmi2Boolean;
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

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s %d %s] ", instance ? instance : "?", (int)status, category ? category : "");
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static int failures = 0;
static void check(fmi2Status status, const char *what) {
    if (status != fmi2OK) {
        fprintf(stderr, "importer: %s returned status %d\n", what, (int)status);
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

/* From modelDescription.xml (FMI 2). */
#define GUID "{762728c4-54e4-7377-27e2-8de970f325dd}"
#define VR_LOG_PATH 27
static const struct {
    const char *name;
    fmi2ValueReference vr;
} outputs[] = {
    {"peak.lower.tip_deflection", 44},     {"peak.lower.clamp_bending_stress", 45},
    {"peak.lower.clamp_shear_stress", 46}, {"peak.upper.contact_bending_stress", 47},
    {"peak.contact.force", 48},
};

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: importer LIBRARY RESOURCE_URI [STOP_TIME [STEP]]\n");
        return 2;
    }
    double stop = argc > 3 ? atof(argv[3]) : 3.0, h = argc > 4 ? atof(argv[4]) : 1e-3;
    lib_t lib = lib_open(argv[1]);
    if (!lib) {
        fprintf(stderr, "importer: cannot load %s: %s\n", argv[1], lib_error());
        return 2;
    }
    Fmi2GetVersion getVersion = (Fmi2GetVersion)need(lib, "fmi2GetVersion");
    Fmi2GetVersion getTypesPlatform = (Fmi2GetVersion)need(lib, "fmi2GetTypesPlatform");
    Fmi2Instantiate instantiate = (Fmi2Instantiate)need(lib, "fmi2Instantiate");
    Fmi2SetupExperiment setup = (Fmi2SetupExperiment)need(lib, "fmi2SetupExperiment");
    Fmi2Simple enterInit = (Fmi2Simple)need(lib, "fmi2EnterInitializationMode");
    Fmi2Simple exitInit = (Fmi2Simple)need(lib, "fmi2ExitInitializationMode");
    Fmi2Simple terminate = (Fmi2Simple)need(lib, "fmi2Terminate");
    Fmi2SetString setString = (Fmi2SetString)need(lib, "fmi2SetString");
    Fmi2GetReal getReal = (Fmi2GetReal)need(lib, "fmi2GetReal");
    Fmi2DoStep doStep = (Fmi2DoStep)need(lib, "fmi2DoStep");
    Fmi2FreeInstance freeInstance = (Fmi2FreeInstance)need(lib, "fmi2FreeInstance");

    printf("fmi2GetVersion %s\nfmi2GetTypesPlatform %s\n", getVersion(), getTypesPlatform());
    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = instantiate("wine", fmi2CoSimulation, GUID, argv[2], &callbacks, 0, 0);
    if (!c) {
        fprintf(stderr, "importer: fmi2Instantiate returned NULL\n");
        return 1;
    }
    check(setup(c, 0, 0.0, 0.0, 1, stop), "fmi2SetupExperiment");
    fmi2ValueReference vr = VR_LOG_PATH;
    fmi2String empty = "";
    check(setString(c, &vr, 1, &empty), "fmi2SetString(log.path)");
    check(enterInit(c), "fmi2EnterInitializationMode");
    check(exitInit(c), "fmi2ExitInitializationMode");
    long steps = (long)(stop / h + 0.5);
    clock_t start = clock();
    for (long i = 0; i < steps && failures == 0; i++) {
        check(doStep(c, (double)i * h, h, 1), "fmi2DoStep");
    }
    double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    printf("steps %ld\n", steps);
    for (size_t i = 0; i < sizeof outputs / sizeof outputs[0]; i++) {
        fmi2Real value = 0;
        check(getReal(c, &outputs[i].vr, 1, &value), "fmi2GetReal");
        printf("%s %.17g\n", outputs[i].name, value);
    }
    check(terminate(c), "fmi2Terminate");
    freeInstance(c);
    fprintf(stderr, "importer: %ld steps in %.2f s CPU, %d failures\n", steps, seconds, failures);
    return failures ? 1 : 0;
}
