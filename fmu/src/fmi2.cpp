// The FMI 2.0 co-simulation functions over the instance (instance.hpp,
// docs/fmu.md). Every function of the standard is exported; those of model
// exchange return fmi2Error with a logged reason (docs/fmu.md#not-offered).
#include <cstdlib>
#include <cstring>
#include <new>

#include "cvtplant/fmu/fmi2_api.h"
#include "instance.hpp"

using cvt::fmu::Instance;
using cvt::fmu::Status;

namespace {

Instance* as_instance(fmi2Component c) { return static_cast<Instance*>(c); }
fmi2Status st2(Status s) { return static_cast<fmi2Status>(s); }

void* zeroed(std::size_t n, std::size_t size) { return std::calloc(n, size); }
void release(void* p) { std::free(p); }

void refuse(const fmi2CallbackFunctions* f, fmi2String name, const char* message) {
  if (f != nullptr && f->logger != nullptr)
    f->logger(f->componentEnvironment, name != nullptr ? name : "", fmi2Error, "logStatusError", "%s", message);
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// FMI 2.0 passes the resources as a URI (file:///path/resources or
// file:/path/resources); the path, percent-decoded, into out.
bool uri_to_path(const char* uri, char* out, std::size_t cap) {
  if (uri == nullptr) return false;
  const char* p = uri;
  if (std::strncmp(p, "file://", 7) == 0) {
    p += 7;
    if (std::strncmp(p, "localhost/", 10) == 0) p += 9;
  } else if (std::strncmp(p, "file:", 5) == 0) {
    p += 5;
  }
  if (*p != '/') return false;
  std::size_t n = 0;
  for (; *p != '\0'; ++p) {
    char c = *p;
    if (c == '%') {
      const int a = hex_digit(p[1]), b = a < 0 ? -1 : hex_digit(p[2]);
      if (b < 0) return false;
      c = static_cast<char>(a * 16 + b);
      p += 2;
    }
    if (n + 1 >= cap) return false;
    out[n++] = c;
  }
  out[n] = '\0';
  return true;
}

}  // namespace

#define CVT_INSTANCE(c)           \
  Instance* self = as_instance(c); \
  if (self == nullptr) return fmi2Error

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
  CVT_INSTANCE(c);
  return st2(self->set_debug_logging(loggingOn != fmi2False, nCategories, categories));
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean loggingOn) {
  if (fmuType != fmi2CoSimulation) {
    refuse(functions, instanceName, "fmi2Instantiate: this FMU offers co-simulation only (docs/fmu.md#not-offered)");
    return nullptr;
  }
  char path[4096];
  if (!uri_to_path(fmuResourceLocation, path, sizeof path)) {
    refuse(functions, instanceName,
           "fmi2Instantiate: fmuResourceLocation must be a file URI of the FMU's resources folder (file:///...)");
    return nullptr;
  }
  cvt::fmu::Allocator alloc{&zeroed, &release};
  if (functions != nullptr && functions->allocateMemory != nullptr && functions->freeMemory != nullptr)
    alloc = cvt::fmu::Allocator{functions->allocateMemory, functions->freeMemory};
  void* mem = alloc.allocate(1, sizeof(Instance));
  if (mem == nullptr) {
    refuse(functions, instanceName, "fmi2Instantiate: out of memory");
    return nullptr;
  }
  Instance* self = ::new (mem) Instance();
  cvt::fmu::LogSink sink;
  if (functions != nullptr) {
    sink.log2 = functions->logger;
    sink.env = functions->componentEnvironment;
  }
  if (!self->open(instanceName, 2, fmuGUID, path, sink, loggingOn != fmi2False, alloc)) {
    alloc.release(mem);
    return nullptr;
  }
  return self;
}

void fmi2FreeInstance(fmi2Component c) {
  Instance* self = as_instance(c);
  if (self == nullptr) return;
  const cvt::fmu::Allocator a = self->allocator();
  a.release(self);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  CVT_INSTANCE(c);
  return st2(self->setup_experiment(startTime, stopTimeDefined != fmi2False, stopTime));
}
fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  CVT_INSTANCE(c);
  return st2(self->enter_initialization());
}
fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  CVT_INSTANCE(c);
  return st2(self->exit_initialization());
}
fmi2Status fmi2Terminate(fmi2Component c) {
  CVT_INSTANCE(c);
  return st2(self->terminate());
}
fmi2Status fmi2Reset(fmi2Component c) {
  CVT_INSTANCE(c);
  return st2(self->reset());
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  CVT_INSTANCE(c);
  static_assert(sizeof(fmi2ValueReference) == sizeof(std::uint32_t), "value references are 32 bits");
  return st2(self->get_float64(reinterpret_cast<const std::uint32_t*>(vr), nvr, value, nvr));
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  CVT_INSTANCE(c);
  return st2(self->set_float64(reinterpret_cast<const std::uint32_t*>(vr), nvr, value, nvr));
}

// Integers, booleans: converted in blocks on the stack.
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  CVT_INSTANCE(c);
  for (size_t i = 0; i < nvr; i += 64) {
    const size_t k = nvr - i < 64 ? nvr - i : 64;
    std::int64_t v[64];
    const Status s = self->get_enum(reinterpret_cast<const std::uint32_t*>(vr) + i, k, v, k);
    if (s != Status::ok) return st2(s);
    for (size_t j = 0; j < k; ++j) value[i + j] = static_cast<fmi2Integer>(v[j]);
  }
  return fmi2OK;
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer[]) {
  CVT_INSTANCE(c);
  return st2(self->set_enum(reinterpret_cast<const std::uint32_t*>(vr), nvr, nvr));
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
  CVT_INSTANCE(c);
  for (size_t i = 0; i < nvr; i += 64) {
    const size_t k = nvr - i < 64 ? nvr - i : 64;
    bool v[64];
    const Status s = self->get_boolean(reinterpret_cast<const std::uint32_t*>(vr) + i, k, v, k);
    if (s != Status::ok) return st2(s);
    for (size_t j = 0; j < k; ++j) value[i + j] = v[j] ? fmi2True : fmi2False;
  }
  return fmi2OK;
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
  CVT_INSTANCE(c);
  // In one call to the instance, which checks every value before it takes
  // any: a refused call changes nothing.
  constexpr size_t kMax = 1024;
  if (nvr > kMax) return st2(self->unsupported("fmi2SetBoolean", "more than 1024 values in one call"));
  bool v[kMax];
  for (size_t j = 0; j < nvr; ++j) v[j] = value[j] != fmi2False;
  return st2(self->set_boolean(reinterpret_cast<const std::uint32_t*>(vr), nvr, v, nvr));
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
  CVT_INSTANCE(c);
  return st2(self->no_variables("String", reinterpret_cast<const std::uint32_t*>(vr), nvr));
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
  CVT_INSTANCE(c);
  return st2(self->no_variables("String", reinterpret_cast<const std::uint32_t*>(vr), nvr));
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  CVT_INSTANCE(c);
  return st2(self->get_state(state));
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  CVT_INSTANCE(c);
  return st2(self->set_state(state));
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  CVT_INSTANCE(c);
  return st2(self->free_state(state));
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  CVT_INSTANCE(c);
  return st2(self->serialized_size(state, size));
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte out[], size_t size) {
  CVT_INSTANCE(c);
  return st2(self->serialize(state, reinterpret_cast<unsigned char*>(out), size));
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte in[], size_t size, fmi2FMUstate* state) {
  CVT_INSTANCE(c);
  return st2(self->deserialize(reinterpret_cast<const unsigned char*>(in), size, state));
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2GetDirectionalDerivative", "providesDirectionalDerivative=false"));
}

#define CVT_MODEL_EXCHANGE(CALL)                                                               \
  {                                                                                            \
    CVT_INSTANCE(c);                                                                           \
    return st2(self->unsupported(CALL, "model exchange is not offered (co-simulation only)")); \
  }
fmi2Status fmi2EnterEventMode(fmi2Component c) CVT_MODEL_EXCHANGE("fmi2EnterEventMode")
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo*) CVT_MODEL_EXCHANGE("fmi2NewDiscreteStates")
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) CVT_MODEL_EXCHANGE("fmi2EnterContinuousTimeMode")
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean, fmi2Boolean*, fmi2Boolean*)
    CVT_MODEL_EXCHANGE("fmi2CompletedIntegratorStep")
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real) CVT_MODEL_EXCHANGE("fmi2SetTime")
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real[], size_t)
    CVT_MODEL_EXCHANGE("fmi2SetContinuousStates")
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real[], size_t) CVT_MODEL_EXCHANGE("fmi2GetDerivatives")
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real[], size_t) CVT_MODEL_EXCHANGE("fmi2GetEventIndicators")
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real[], size_t) CVT_MODEL_EXCHANGE("fmi2GetContinuousStates")
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real[], size_t)
    CVT_MODEL_EXCHANGE("fmi2GetNominalsOfContinuousStates")
#undef CVT_MODEL_EXCHANGE

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2SetRealInputDerivatives",
                               "canInterpolateInputs=false: inputs are held over each frame"));
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                        fmi2Real[]) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2GetRealOutputDerivatives", "maxOutputDerivativeOrder=0"));
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  CVT_INSTANCE(c);
  return st2(self->do_step(currentCommunicationPoint, communicationStepSize, nullptr));
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2CancelStep", "steps are synchronous (canRunAsynchronuously=false)"));
}
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2GetStatus", "steps are synchronous: doStep's return is the status"));
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  CVT_INSTANCE(c);
  if (s != fmi2LastSuccessfulTime || value == nullptr)
    return st2(self->unsupported("fmi2GetRealStatus", "only fmi2LastSuccessfulTime is a real status"));
  *value = self->time_s();
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2GetIntegerStatus", "no integer status"));
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  CVT_INSTANCE(c);
  if (s != fmi2Terminated || value == nullptr)
    return st2(self->unsupported("fmi2GetBooleanStatus", "only fmi2Terminated is a boolean status"));
  *value = fmi2False;  // the FMU never asks to end the simulation; a plant fault is an error
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  CVT_INSTANCE(c);
  return st2(self->unsupported("fmi2GetStringStatus", "no string status (steps are synchronous)"));
}

}  // extern "C"
