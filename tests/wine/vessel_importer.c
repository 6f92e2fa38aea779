/* A small FMI 2 importer of the vessel-motion library (fmu/vessel/vessel_motion.c), built for
 * Windows by zig (run under wine) and for Linux by cc, by scripts/wine-vessel-check.sh: it
 * loads the library, instantiates it, sets the wave phase in initialization mode, steps to 3 s
 * in 1 ms steps with made-up reactions as inputs, and prints every Real output at 0, 0.5, ... 3 s
 * with 17 significant digits, so that the two platforms' libraries can be compared number by
 * number. Exit status 1 with a line on stderr when a call fails. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "../../fmu/vessel/fmi2_abi.h"

#ifdef _WIN32
#include <windows.h>
#define LOAD(path) ((void *)LoadLibraryA(path))
#define SYMBOL(lib, name) ((void *)GetProcAddress((HMODULE)(lib), name))
#else
#include <dlfcn.h>
#define LOAD(path) dlopen(path, RTLD_NOW | RTLD_LOCAL)
#define SYMBOL(lib, name) dlsym(lib, name)
#endif

typedef fmi2Component (*Instantiate)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions *,
                                     fmi2Boolean, fmi2Boolean);
typedef fmi2Status (*Setup)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*Plain)(fmi2Component);
typedef fmi2Status (*RealIO)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef void (*Free)(fmi2Component);

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env;
    fprintf(stderr, "vessel_importer: %s [%d %s] %s\n", instance, (int)status, category, message);
}

static void *need(void *lib, const char *name) {
    void *f = SYMBOL(lib, name);
    if (!f) {
        fprintf(stderr, "vessel_importer: the library has no %s\n", name);
        exit(1);
    }
    return f;
}

static void check(fmi2Status status, const char *what) {
    if (status != fmi2OK) {
        fprintf(stderr, "vessel_importer: %s returned %d\n", what, (int)status);
        exit(1);
    }
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: vessel_importer LIBRARY\n");
        return 2;
    }
    void *lib = LOAD(argv[1]);
    if (!lib) {
        fprintf(stderr, "vessel_importer: cannot load %s\n", argv[1]);
        return 1;
    }
    Instantiate instantiate = (Instantiate)need(lib, "fmi2Instantiate");
    Setup setup = (Setup)need(lib, "fmi2SetupExperiment");
    Plain enter = (Plain)need(lib, "fmi2EnterInitializationMode");
    Plain exit_init = (Plain)need(lib, "fmi2ExitInitializationMode");
    Plain terminate = (Plain)need(lib, "fmi2Terminate");
    RealIO get = (RealIO)need(lib, "fmi2GetReal");
    RealIO set = (RealIO)need(lib, "fmi2SetReal");
    DoStep step = (DoStep)need(lib, "fmi2DoStep");
    Free free_instance = (Free)need(lib, "fmi2FreeInstance");

    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = instantiate("vessel", fmi2CoSimulation, "{9e4f2a61-3b7d-4c85-a0d2-6f1c8e3b5a94}", "",
                                  &callbacks, fmi2False, fmi2False);
    if (!c) {
        fprintf(stderr, "vessel_importer: fmi2Instantiate returned NULL\n");
        return 1;
    }
    check(setup(c, fmi2False, 0.0, 0.0, fmi2True, 3.0), "fmi2SetupExperiment");
    check(enter(c), "fmi2EnterInitializationMode");
    const fmi2ValueReference phase_vr = 2; /* wave.phase */
    const fmi2Real phase = 1.0;
    check(set(c, &phase_vr, 1, (fmi2Real *)&phase), "fmi2SetReal");
    check(exit_init(c), "fmi2ExitInitializationMode");
    /* Outputs: value references 16..31 (wave.elevation .. deck.pitch_acceleration) and 32 (wave.length). */
    fmi2ValueReference outputs[17];
    for (int k = 0; k < 17; k++) outputs[k] = (fmi2ValueReference)(16 + k);
    const fmi2ValueReference inputs[3] = {13, 14, 15}; /* hinge_force, clamp_force, clamp_moment */
    const double h = 1e-3;
    for (int n = 0; n <= 3000; n++) {
        double t = n * h;
        fmi2Real reactions[3] = {1.0e5 + 10.0 * n, -2.0e5 + 5.0 * n, 3.0e4};
        check(set(c, inputs, 3, reactions), "fmi2SetReal");
        if (n % 500 == 0) {
            fmi2Real values[17];
            check(get(c, outputs, 17, values), "fmi2GetReal");
            for (int k = 0; k < 17; k++) printf("t=%.3f vr=%u %.17g\n", t, outputs[k], values[k]);
        }
        if (n < 3000) check(step(c, t, h, fmi2True), "fmi2DoStep");
    }
    check(terminate(c), "fmi2Terminate");
    free_instance(c);
    return 0;
}
