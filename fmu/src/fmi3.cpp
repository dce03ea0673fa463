// The FMI 3.0 co-simulation functions over the instance (instance.hpp,
// docs/fmu.md). Every function of the standard is exported; those of model
// exchange, scheduled execution, event mode and clocks return fmi3Error
// with a logged reason (docs/fmu.md#not-offered).
#include <cstdlib>
#include <new>

#include "cvtplant/fmu/fmi3_api.h"
#include "instance.hpp"

using cvt::fmu::Instance;
using cvt::fmu::Status;

namespace {

Instance* as_instance(fmi3Instance i) { return static_cast<Instance*>(i); }
fmi3Status st3(Status s) { return static_cast<fmi3Status>(s); }

void* zeroed(std::size_t n, std::size_t size) { return std::calloc(n, size); }
void release(void* p) { std::free(p); }

// Messages from instantiations that produce no instance.
void refuse(fmi3InstanceEnvironment env, fmi3LogMessageCallback log, const char* message) {
  if (log != nullptr) log(env, fmi3Error, "logStatusError", message);
}

}  // namespace

#define CVT_INSTANCE(inst)        \
  Instance* self = as_instance(inst); \
  if (self == nullptr) return fmi3Error

extern "C" {

const char* fmi3GetVersion(void) { return "3.0"; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
  CVT_INSTANCE(instance);
  return st3(self->set_debug_logging(loggingOn, nCategories, categories));
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                          fmi3InstanceEnvironment env, fmi3LogMessageCallback logMessage) {
  refuse(env, logMessage,
         "fmi3InstantiateModelExchange: this FMU offers co-simulation only (the plant is a fixed-step frame stepper, "
         "docs/fmu.md#not-offered)");
  return nullptr;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                               fmi3InstanceEnvironment env, fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback, fmi3LockPreemptionCallback,
                                               fmi3UnlockPreemptionCallback) {
  refuse(env, logMessage, "fmi3InstantiateScheduledExecution: this FMU offers co-simulation only (docs/fmu.md)");
  return nullptr;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean, const fmi3ValueReference[], size_t,
                                         fmi3InstanceEnvironment env, fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback) {
  if (eventModeUsed) {
    refuse(env, logMessage,
           "fmi3InstantiateCoSimulation: eventModeUsed, but this FMU has no event mode (hasEventMode=false)");
    return nullptr;
  }
  void* mem = zeroed(1, sizeof(Instance));
  if (mem == nullptr) {
    refuse(env, logMessage, "fmi3InstantiateCoSimulation: out of memory");
    return nullptr;
  }
  Instance* self = ::new (mem) Instance();
  cvt::fmu::LogSink sink;
  sink.log3 = logMessage;
  sink.env = env;
  if (!self->open(instanceName, 3, instantiationToken, resourcePath, sink, loggingOn,
                  cvt::fmu::Allocator{&zeroed, &release})) {
    release(mem);
    return nullptr;
  }
  return self;
}

void fmi3FreeInstance(fmi3Instance instance) {
  Instance* self = as_instance(instance);
  if (self == nullptr) return;
  const cvt::fmu::Allocator a = self->allocator();
  a.release(self);  // trivially destructible
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean, fmi3Float64, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
  CVT_INSTANCE(instance);
  if (const Status s = self->setup_experiment(startTime, stopTimeDefined, stopTime); s != Status::ok) return st3(s);
  return st3(self->enter_initialization());
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->exit_initialization());
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3EnterEventMode", "no event mode (hasEventMode=false)"));
}

fmi3Status fmi3Terminate(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->terminate());
}

fmi3Status fmi3Reset(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->reset());
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Float64 v[],
                          size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->get_float64(vr, n, v, nv));
}
fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Float64 v[],
                          size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->set_float64(vr, n, v, nv));
}
fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Boolean v[],
                          size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->get_boolean(vr, n, v, nv));
}
fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Boolean v[],
                          size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->set_boolean(vr, n, v, nv));
}
fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Int64 v[], size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->get_enum(vr, n, v, nv));
}
fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Int64[],
                        size_t nv) {
  CVT_INSTANCE(instance);
  return st3(self->set_enum(vr, n, nv));
}

// The value types this FMU has no variables of.
#define CVT_NO_VARIABLES(NAME, TYPE)                                                                         \
  fmi3Status fmi3Get##NAME(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, TYPE[], size_t) { \
    CVT_INSTANCE(instance);                                                                                  \
    return st3(self->no_variables(#NAME, vr, n));                                                            \
  }                                                                                                          \
  fmi3Status fmi3Set##NAME(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const TYPE[],     \
                           size_t) {                                                                         \
    CVT_INSTANCE(instance);                                                                                  \
    return st3(self->no_variables(#NAME, vr, n));                                                            \
  }
CVT_NO_VARIABLES(Float32, fmi3Float32)
CVT_NO_VARIABLES(Int8, fmi3Int8)
CVT_NO_VARIABLES(UInt8, fmi3UInt8)
CVT_NO_VARIABLES(Int16, fmi3Int16)
CVT_NO_VARIABLES(UInt16, fmi3UInt16)
CVT_NO_VARIABLES(Int32, fmi3Int32)
CVT_NO_VARIABLES(UInt32, fmi3UInt32)
CVT_NO_VARIABLES(UInt64, fmi3UInt64)
CVT_NO_VARIABLES(String, fmi3String)
#undef CVT_NO_VARIABLES

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, size_t[], fmi3Binary[],
                         size_t) {
  CVT_INSTANCE(instance);
  return st3(self->no_variables("Binary", vr, n));
}
fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const size_t[],
                         const fmi3Binary[], size_t) {
  CVT_INSTANCE(instance);
  return st3(self->no_variables("Binary", vr, n));
}
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Clock[]) {
  CVT_INSTANCE(instance);
  return st3(self->no_variables("Clock", vr, n));
}
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Clock[]) {
  CVT_INSTANCE(instance);
  return st3(self->no_variables("Clock", vr, n));
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference, size_t*) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetNumberOfVariableDependencies",
                               "providesPerElementDependencies=false; ModelStructure lists the dependencies"));
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference, size_t[], fmi3ValueReference[],
                                       size_t[], fmi3DependencyKind[], size_t) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetVariableDependencies",
                               "providesPerElementDependencies=false; ModelStructure lists the dependencies"));
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* state) {
  CVT_INSTANCE(instance);
  return st3(self->get_state(state));
}
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState state) {
  CVT_INSTANCE(instance);
  return st3(self->set_state(state));
}
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* state) {
  CVT_INSTANCE(instance);
  return st3(self->free_state(state));
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState state, size_t* size) {
  CVT_INSTANCE(instance);
  return st3(self->serialized_size(state, size));
}
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState state, fmi3Byte out[], size_t size) {
  CVT_INSTANCE(instance);
  return st3(self->serialize(state, out, size));
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte in[], size_t size, fmi3FMUState* state) {
  CVT_INSTANCE(instance);
  return st3(self->deserialize(in, size, state));
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference[], size_t,
                                        const fmi3ValueReference[], size_t, const fmi3Float64[], size_t,
                                        fmi3Float64[], size_t) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetDirectionalDerivative", "providesDirectionalDerivatives=false"));
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference[], size_t,
                                    const fmi3ValueReference[], size_t, const fmi3Float64[], size_t, fmi3Float64[],
                                    size_t) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetAdjointDerivative", "providesAdjointDerivatives=false"));
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3EnterConfigurationMode", "no structural parameters"));
}
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3ExitConfigurationMode", "no structural parameters"));
}
fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3Float64[],
                                  fmi3IntervalQualifier[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetIntervalDecimal", "no clocks"));
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3UInt64[],
                                   fmi3UInt64[], fmi3IntervalQualifier[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetIntervalFraction", "no clocks"));
}
fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3Float64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetShiftDecimal", "no clocks"));
}
fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3UInt64[],
                                fmi3UInt64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetShiftFraction", "no clocks"));
}
fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3SetIntervalDecimal", "no clocks"));
}
fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                                   const fmi3UInt64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3SetIntervalFraction", "no clocks"));
}
fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3SetShiftDecimal", "no clocks"));
}
fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                                const fmi3UInt64[]) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3SetShiftFraction", "no clocks"));
}
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3EvaluateDiscreteStates", "no event mode"));
}
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*,
                                    fmi3Boolean*, fmi3Float64*) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3UpdateDiscreteStates", "no event mode"));
}

#define CVT_MODEL_EXCHANGE(CALL)                                                                   \
  {                                                                                                \
    CVT_INSTANCE(instance);                                                                        \
    return st3(self->unsupported(CALL, "model exchange is not offered (co-simulation only)"));     \
  }
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance) CVT_MODEL_EXCHANGE("fmi3EnterContinuousTimeMode")
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance, fmi3Boolean, fmi3Boolean*, fmi3Boolean*)
    CVT_MODEL_EXCHANGE("fmi3CompletedIntegratorStep")
fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64) CVT_MODEL_EXCHANGE("fmi3SetTime")
fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64[], size_t)
    CVT_MODEL_EXCHANGE("fmi3SetContinuousStates")
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64[], size_t)
    CVT_MODEL_EXCHANGE("fmi3GetContinuousStateDerivatives")
fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64[], size_t)
    CVT_MODEL_EXCHANGE("fmi3GetEventIndicators")
fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64[], size_t)
    CVT_MODEL_EXCHANGE("fmi3GetContinuousStates")
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64[], size_t)
    CVT_MODEL_EXCHANGE("fmi3GetNominalsOfContinuousStates")
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t*)
    CVT_MODEL_EXCHANGE("fmi3GetNumberOfEventIndicators")
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t*)
    CVT_MODEL_EXCHANGE("fmi3GetNumberOfContinuousStates")
#undef CVT_MODEL_EXCHANGE

fmi3Status fmi3EnterStepMode(fmi3Instance instance) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3EnterStepMode",
                               "step mode follows exitInitializationMode directly (no event mode)"));
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Int32[],
                                    fmi3Float64[], size_t) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3GetOutputDerivatives", "maxOutputDerivativeOrder=0"));
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean, fmi3Boolean* eventHandlingNeeded, fmi3Boolean* terminateSimulation,
                      fmi3Boolean* earlyReturn, fmi3Float64* lastSuccessfulTime) {
  CVT_INSTANCE(instance);
  double last = 0;
  const Status s = self->do_step(currentCommunicationPoint, communicationStepSize, &last);
  if (eventHandlingNeeded != nullptr) *eventHandlingNeeded = false;
  if (terminateSimulation != nullptr) *terminateSimulation = false;
  if (earlyReturn != nullptr) *earlyReturn = false;
  if (lastSuccessfulTime != nullptr) *lastSuccessfulTime = last;
  return st3(s);
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference, fmi3Float64) {
  CVT_INSTANCE(instance);
  return st3(self->unsupported("fmi3ActivateModelPartition", "scheduled execution is not offered"));
}

}  // extern "C"
