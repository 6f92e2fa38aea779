/* SpringDamper: a linear spring-damper as an FMI 2.0 co-simulation FMU, the second FMU of the
 * coupled example in tests/python/test_coupled.py (which builds it with gcc and zips it with
 * SpringDamper.xml as its modelDescription.xml).
 *
 *   F = -k (x - x0) - c v        [N, up positive: the force the buffer exerts on the tip]
 *
 * inputs x (m) and v (m/s), parameters k (N/m), c (N s/m), x0 (m, unstretched position), output F.
 * The output is algebraic in the inputs (direct feedthrough, declared in the modelDescription);
 * the FMU has no state, so a step only advances its time.
 *
 * The FMI 2 headers come from fmpy's c-code folder at build time (-I .../fmpy/c-code); nothing of
 * the standard is copied here. Every one of the 25 common and 9 co-simulation functions exists
 * (fmpy looks them all up when it loads the library); the unsupported ones log why and return
 * fmi2Error. The logger is always called with "%s" as its format.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#define GUID "{5c0b3d52-6f3e-4c1a-9a57-2d1e8b4f7a10}"

enum { VR_X, VR_V, VR_K, VR_C, VR_X0, VR_F, N_VR };

typedef enum { INSTANTIATED, INITIALIZATION, STEP_COMPLETE, TERMINATED, FAILED } Phase;

typedef struct {
    char *name;
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment env;
    fmi2Boolean logging_on;
    Phase phase;
    fmi2Real time;
    fmi2Real values[N_VR];
} Instance;

static const fmi2Real START[N_VR] = {0.0, 0.0, 2.0e5, 2.0e4, 0.0, 0.0};

static void log_message(const Instance *s, fmi2Status status, const char *category, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static void log_message(const Instance *s, fmi2Status status, const char *category, const char *fmt, ...) {
    char message[512];
    va_list args;
    if (s == NULL || s->logger == NULL) return;
    /* Errors and warnings always reach the importer; anything else only with debug logging on. */
    if (status == fmi2OK && !s->logging_on) return;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    s->logger(s->env, s->name, status, category, "%s", message);
}

static fmi2Status fail(Instance *s, const char *function, const char *why) {
    log_message(s, fmi2Error, "logStatusError", "%s: %s", function, why);
    return fmi2Error;
}

static fmi2Status unsupported(fmi2Component c, const char *function) {
    return fail((Instance *)c, function, "not supported by this FMU");
}

static fmi2Real force(const Instance *s) {
    return -s->values[VR_K] * (s->values[VR_X] - s->values[VR_X0]) - s->values[VR_C] * s->values[VR_V];
}

/* ---- inquire version numbers, logging -------------------------------------------------------- */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (nCategories > 0 && categories == NULL) return fail(s, "fmi2SetDebugLogging", "categories is NULL");
    s->logging_on = loggingOn;
    return fmi2OK;
}

/* ---- creation and destruction ---------------------------------------------------------------- */

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    Instance *s;
    Instance probe;
    (void)fmuResourceLocation;
    (void)visible;
    memset(&probe, 0, sizeof probe);
    probe.name = (char *)(instanceName ? instanceName : "SpringDamper");
    probe.logger = functions ? functions->logger : NULL;
    probe.env = functions ? functions->componentEnvironment : NULL;
    if (instanceName == NULL || instanceName[0] == '\0') {
        fail(&probe, "fmi2Instantiate", "missing instance name");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        fail(&probe, "fmi2Instantiate", "only co-simulation (fmi2CoSimulation) is supported");
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, GUID) != 0) {
        fail(&probe, "fmi2Instantiate", "GUID does not match this binary's " GUID);
        return NULL;
    }
    /* canNotUseMemoryManagementFunctions="true": plain calloc, the callbacks may be NULL. */
    s = (Instance *)calloc(1, sizeof *s);
    if (s == NULL || (s->name = (char *)malloc(strlen(instanceName) + 1)) == NULL) {
        free(s);
        fail(&probe, "fmi2Instantiate", "out of memory");
        return NULL;
    }
    strcpy(s->name, instanceName);
    s->logger = probe.logger;
    s->env = probe.env;
    s->logging_on = loggingOn;
    s->phase = INSTANTIATED;
    s->time = 0.0;
    memcpy(s->values, START, sizeof START);
    log_message(s, fmi2OK, "logAll", "instantiated (k = %g N/m, c = %g N s/m by default)", START[VR_K], START[VR_C]);
    return s;
}

void fmi2FreeInstance(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return;
    free(s->name);
    free(s);
}

/* ---- initialization, termination, reset ------------------------------------------------------ */

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    Instance *s = (Instance *)c;
    (void)toleranceDefined;
    (void)tolerance;
    if (s == NULL) return fmi2Error;
    if (s->phase != INSTANTIATED) return fail(s, "fmi2SetupExperiment", "only allowed after fmi2Instantiate");
    if (!isfinite(startTime)) return fail(s, "fmi2SetupExperiment", "startTime is not finite");
    if (stopTimeDefined && !(stopTime >= startTime))
        return fail(s, "fmi2SetupExperiment", "stopTime is before startTime");
    s->time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (s->phase != INSTANTIATED) return fail(s, "fmi2EnterInitializationMode", "only allowed after fmi2Instantiate");
    s->phase = INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Instance *s = (Instance *)c;
    char why[160];
    if (s == NULL) return fmi2Error;
    if (s->phase != INITIALIZATION) return fail(s, "fmi2ExitInitializationMode", "not in initialization mode");
    if (!(s->values[VR_K] >= 0.0) || !isfinite(s->values[VR_K])) {
        snprintf(why, sizeof why, "k must be finite and >= 0 N/m, got %g", s->values[VR_K]);
        s->phase = FAILED;
        return fail(s, "fmi2ExitInitializationMode", why);
    }
    if (!(s->values[VR_C] >= 0.0) || !isfinite(s->values[VR_C])) {
        snprintf(why, sizeof why, "c must be finite and >= 0 N s/m, got %g", s->values[VR_C]);
        s->phase = FAILED;
        return fail(s, "fmi2ExitInitializationMode", why);
    }
    if (!isfinite(s->values[VR_X0])) {
        s->phase = FAILED;
        return fail(s, "fmi2ExitInitializationMode", "x0 is not finite");
    }
    s->phase = STEP_COMPLETE;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (s->phase != STEP_COMPLETE) return fail(s, "fmi2Terminate", "only allowed after initialization");
    s->phase = TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    s->phase = INSTANTIATED;
    s->time = 0.0;
    memcpy(s->values, START, sizeof START);
    return fmi2OK;
}

/* ---- getting and setting values -------------------------------------------------------------- */

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2GetReal", "vr or value is NULL");
    if (s->phase == INSTANTIATED || s->phase == FAILED)
        return fail(s, "fmi2GetReal", "not allowed before initialization mode or after an error");
    for (i = 0; i < nvr; i++) {
        if (vr[i] >= N_VR) {
            char why[80];
            snprintf(why, sizeof why, "unknown value reference %u", vr[i]);
            return fail(s, "fmi2GetReal", why);
        }
        value[i] = vr[i] == VR_F ? force(s) : s->values[vr[i]];
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    char why[120];
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2SetReal", "vr or value is NULL");
    if (s->phase == TERMINATED || s->phase == FAILED) return fail(s, "fmi2SetReal", "not allowed after termination or an error");
    for (i = 0; i < nvr; i++) {
        fmi2ValueReference r = vr[i];
        if (r == VR_F || r >= N_VR) {
            snprintf(why, sizeof why, "value reference %u is not an input or parameter", r);
            return fail(s, "fmi2SetReal", why);
        }
        if ((r == VR_K || r == VR_C || r == VR_X0) && s->phase == STEP_COMPLETE) {
            snprintf(why, sizeof why, "parameter %u is fixed: set it before fmi2ExitInitializationMode", r);
            return fail(s, "fmi2SetReal", why);
        }
        if (!isfinite(value[i])) {
            snprintf(why, sizeof why, "value reference %u: value is not finite", r);
            return fail(s, "fmi2SetReal", why);
        }
    }
    for (i = 0; i < nvr; i++) s->values[vr[i]] = value[i];
    return fmi2OK;
}

/* No Integer, Boolean or String variables: empty requests succeed, anything else is an error. */
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2GetInteger", "this FMU has no Integer variables");
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2GetBoolean", "this FMU has no Boolean variables");
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2GetString", "this FMU has no String variables");
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2SetInteger", "this FMU has no Integer variables");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2SetBoolean", "this FMU has no Boolean variables");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
    (void)vr;
    (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2SetString", "this FMU has no String variables");
}

/* ---- FMU state, directional derivatives: not supported (canGetAndSetFMUstate="false") ---------- */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    (void)FMUstate;
    return unsupported(c, "fmi2GetFMUstate");
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    (void)FMUstate;
    return unsupported(c, "fmi2SetFMUstate");
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    /* Freeing a null state is ignored (FMI 2.0.4); no state can ever be handed out. */
    if (FMUstate == NULL || *FMUstate == NULL) return fmi2OK;
    return unsupported(c, "fmi2FreeFMUstate");
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size) {
    (void)FMUstate;
    (void)size;
    return unsupported(c, "fmi2SerializedFMUstateSize");
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
    (void)FMUstate;
    (void)serializedState;
    (void)size;
    return unsupported(c, "fmi2SerializeFMUstate");
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate) {
    (void)serializedState;
    (void)size;
    (void)FMUstate;
    return unsupported(c, "fmi2DeSerializeFMUstate");
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[]) {
    (void)vUnknown_ref;
    (void)nUnknown;
    (void)vKnown_ref;
    (void)nKnown;
    (void)dvKnown;
    (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

/* ---- co-simulation ----------------------------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives (canInterpolateInputs=\"false\")");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder=\"0\")");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    Instance *s = (Instance *)c;
    char why[160];
    (void)noSetFMUStatePriorToCurrentPoint;
    if (s == NULL) return fmi2Error;
    if (s->phase != STEP_COMPLETE) return fail(s, "fmi2DoStep", "only allowed after fmi2ExitInitializationMode");
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize)) {
        snprintf(why, sizeof why, "communicationStepSize must be > 0 s, got %g", communicationStepSize);
        return fail(s, "fmi2DoStep", why);
    }
    /* Importers accumulate t + h in floating point: accept a communication point within a
     * relative 1e-9 of the instance's time. */
    if (fabs(currentCommunicationPoint - s->time) > 1e-9 * fmax(1.0, fabs(s->time))) {
        snprintf(why, sizeof why, "currentCommunicationPoint %.17g s is not the instance's time %.17g s",
                 currentCommunicationPoint, s->time);
        return fail(s, "fmi2DoStep", why);
    }
    /* No state: the output follows the inputs, held over the step. */
    s->time = currentCommunicationPoint + communicationStepSize;
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) {
    return unsupported(c, "fmi2CancelStep (fmi2DoStep never returns fmi2Pending)");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Status *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetStatus (fmi2DoStep never returns fmi2Pending)");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real *value) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (kind != fmi2LastSuccessfulTime || value == NULL) return unsupported(c, "fmi2GetRealStatus (only fmi2LastSuccessfulTime)");
    *value = s->time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Integer *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetIntegerStatus");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean *value) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (kind != fmi2Terminated || value == NULL) return unsupported(c, "fmi2GetBooleanStatus (only fmi2Terminated)");
    *value = fmi2False; /* the FMU never asks to end the simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind kind, fmi2String *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetStringStatus");
}
