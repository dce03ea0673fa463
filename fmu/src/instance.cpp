#include "instance.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <new>

namespace cvt::fmu {

namespace {

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::instantiated: return "the instantiated mode (before initialisation)";
    case Mode::initialization: return "initialisation mode";
    case Mode::step: return "step mode";
    case Mode::terminated: return "the terminated mode";
  }
  return "?";
}

const char* type_name(VarType t) {
  switch (t) {
    case VarType::float64: return "Float64 (FMI 2.0: Real)";
    case VarType::boolean: return "Boolean";
    case VarType::enumeration: return "Enumeration (FMI 3.0: Int64, FMI 2.0: Integer)";
  }
  return "?";
}

bool finite(double v) { return v == v && v - v == 0.0; }

void copy_text(char* dst, std::size_t cap, const char* src) {
  std::size_t n = std::strlen(src);
  if (n >= cap) n = cap - 1;
  std::memcpy(dst, src, n);
  dst[n] = '\0';
}

// The layout fingerprint of a serialised state: a state restores into the
// same binary only (docs/fmu.md#state).
std::uint64_t build_fingerprint() {
  const char* compiler = __VERSION__;
  std::uint64_t h = fnv1a(compiler, std::strlen(compiler));
  const std::uint64_t sizes[] = {sizeof(void*), kEngineSize, kEngineAlign, sizeof(Scene)};
  return fnv1a(reinterpret_cast<const char*>(sizes), sizeof sizes, h);
}

constexpr char kStateMagic[8] = {'C', 'V', 'T', 'F', 'M', 'U', 'S', '1'};

}  // namespace

// A saved FMU state: the core and a copy of the engine, plant and all.
struct Instance::Saved {
  const Instance* owner = nullptr;
  Core core{};
  alignas(kEngineAlign) unsigned char engine_storage[kEngineSize];
  Engine* engine = nullptr;
};

void Instance::log(Status st, const char* category, const char* fmt, ...) {
  if (st == Status::ok && !(logging_on_ && log_events_)) return;
  char msg[768];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (sink_.log3 != nullptr) sink_.log3(sink_.env, static_cast<fmi3Status>(st), category, msg);
  if (sink_.log2 != nullptr) sink_.log2(sink_.env, name_, static_cast<fmi2Status>(st), category, "%s", msg);
}

bool Instance::open(const char* name, int fmi_version, const char* token, const char* resource_dir,
                    const LogSink& sink, bool logging_on, const Allocator& alloc) {
  sink_ = sink;
  alloc_ = alloc;
  logging_on_ = logging_on;
  fmi_version_ = fmi_version;
  copy_text(name_, sizeof name_, name != nullptr ? name : "");
  if (name == nullptr || name[0] == '\0') {
    log(Status::error, "logStatusError", "instantiate: the instance name must not be empty");
    return false;
  }
  if (resource_dir == nullptr || resource_dir[0] == '\0') {
    log(Status::error, "logStatusError",
        "instantiate: no resource location given; the plant's scene is resources/scene.txt of the FMU");
    return false;
  }
  char path[4096];
  const std::size_t len = std::strlen(resource_dir);
  const bool slash = len > 0 && resource_dir[len - 1] == '/';
  if (std::snprintf(path, sizeof path, "%s%sscene.txt", resource_dir, slash ? "" : "/") >= static_cast<int>(sizeof path)) {
    log(Status::error, "logStatusError", "instantiate: resource path too long");
    return false;
  }
  static_assert(kMaxSceneText < 65536, "read on the stack");
  char text[kMaxSceneText + 1];
  std::FILE* f = std::fopen(path, "rb");
  if (f == nullptr) {
    log(Status::error, "logStatusError", "instantiate: cannot open %s", path);
    return false;
  }
  const std::size_t n = std::fread(text, 1, sizeof text, f);
  std::fclose(f);
  if (n > kMaxSceneText) {
    log(Status::error, "logStatusError", "instantiate: %s is larger than %zu bytes", path, kMaxSceneText);
    return false;
  }
  const SceneTextIssue issue = read_scene_text(text, n, base_, scene_name_);
  if (!issue.ok) {
    log(Status::error, "logStatusError", "instantiate: %s:%d: %s", path, issue.line, issue.message);
    return false;
  }
  instantiation_token(text, n, token_);
  if (token == nullptr || std::strcmp(token, token_) != 0) {
    log(Status::error, "logStatusError",
        "instantiate: the instantiation token %s is not this FMU's %s (a model description of another FMU?)",
        token != nullptr ? token : "(none)", token_);
    return false;
  }
  const char* why = "";
  engine_ = make_engine(base_, engine_storage_, &why);
  if (engine_ == nullptr) {
    log(Status::error, "logStatusError", "instantiate: %s", why);
    return false;
  }
  nvars_ = fmu_variables(base_, vars_);
  for (auto& i : index_) i = -1;
  for (int i = 0; i < nvars_; ++i) index_[vars_[i].vr] = static_cast<std::int16_t>(i);
  reset_core();
  log(Status::ok, "logEvents", "instantiated the plant of scene %s (%s, features %lu)", scene_name_,
      scalar_kind_name(base_.scalar), static_cast<unsigned long>(base_.features));
  return true;
}

void Instance::reset_core() {
  core_ = Core{};
  core_.scene = base_;
  for (int i = 0; i < input_count; ++i) core_.inputs[i] = input_start(i, base_);
  const char* why = "";
  engine_ = make_engine(base_, engine_storage_, &why);  // an engine without a plant
}

const Variable* Instance::find(std::uint32_t vr) const {
  if (vr >= kVrEnd || index_[vr] < 0) return nullptr;
  return &vars_[index_[vr]];
}

const Variable* Instance::lookup(std::uint32_t vr, VarType type, const char* type_name_of_call) {
  const Variable* v = find(vr);
  if (v == nullptr) {
    log(Status::error, "logStatusError", "value reference %u is no variable of this FMU (modelDescription.xml)",
        static_cast<unsigned>(vr));
    return nullptr;
  }
  if (v->type != type) {
    log(Status::error, "logStatusError", "%s: variable %s (value reference %u) is a %s", type_name_of_call, v->name,
        static_cast<unsigned>(vr), type_name(v->type));
    return nullptr;
  }
  return v;
}

double Instance::time_s() const { return core_.start_s + static_cast<double>(core_.frames) * core_.scene.frame_s; }

const char* Instance::field_variable(const char* field) const {
  if (std::strcmp(field, "beta0_deg") == 0) return "params.beta0_rad";
  if (std::strcmp(field, "tau_in") == 0) return "inputs.tau_in";
  if (std::strcmp(field, "tau_load") == 0) return "inputs.tau_load";
  if (std::strcmp(field, "clamp") == 0) return "inputs.clamp";
  if (std::strcmp(field, "initial") == 0) return "initial.*";
  for (const SceneParamInfo& p : kSceneParams) {
    const char* dot = std::strchr(p.name, '.');
    if (dot != nullptr && std::strcmp(dot + 1, field) == 0) return p.name;
  }
  return field;
}

Status Instance::ensure_plant() {
  if (engine_->loaded() && !core_.stale) return Status::ok;
  Scene s = core_.scene;
  // The inputs as the scene's profiles: the scene dispatch checks them
  // against a fixed-point plant's range like any scene's.
  s.tau_in = constant_profile(core_.inputs[input_tau_in]);
  s.tau_load = constant_profile(core_.inputs[input_tau_load]);
  s.clamp = constant_profile(core_.inputs[input_clamp]);
  const SceneIssue issue = engine_->load(s, core_.inputs);
  if (!issue.ok) {
    log(Status::error, "logStatusError", "the plant cannot be built: %s: %s", field_variable(issue.field),
        issue.message);
    return Status::error;
  }
  core_.stale = false;
  core_.frames = 0;
  return Status::ok;
}

Status Instance::set_debug_logging(bool on, std::size_t n, const char* const* categories) {
  bool events = n == 0;
  for (std::size_t i = 0; i < n; ++i) {
    const char* c = categories[i];
    if (c == nullptr || (std::strcmp(c, "logEvents") != 0 && std::strcmp(c, "logStatusWarning") != 0 &&
                         std::strcmp(c, "logStatusError") != 0)) {
      log(Status::error, "logStatusError",
          "setDebugLogging: unknown log category '%s' (logEvents, logStatusWarning, logStatusError)",
          c != nullptr ? c : "(null)");
      return Status::error;
    }
    if (std::strcmp(c, "logEvents") == 0) events = true;
  }
  logging_on_ = on;
  log_events_ = events;
  return Status::ok;
}

Status Instance::setup_experiment(double start_s, bool stop_defined, double stop_s) {
  if (core_.mode != Mode::instantiated) {
    log(Status::error, "logStatusError", "the experiment is set up before initialisation, not in %s",
        mode_name(core_.mode));
    return Status::error;
  }
  if (!finite(start_s) || (stop_defined && !(finite(stop_s) && stop_s >= start_s))) {
    log(Status::error, "logStatusError", "start time %g s and stop time %g s: finite, stop not before start",
        start_s, stop_s);
    return Status::error;
  }
  core_.start_s = start_s;
  core_.stop_defined = stop_defined;
  core_.stop_s = stop_s;
  return Status::ok;
}

Status Instance::enter_initialization() {
  if (core_.mode != Mode::instantiated) {
    log(Status::error, "logStatusError", "initialisation mode is entered once, from the instantiated mode, not from %s",
        mode_name(core_.mode));
    return Status::error;
  }
  core_.mode = Mode::initialization;
  core_.stale = true;
  return Status::ok;
}

Status Instance::exit_initialization() {
  if (core_.mode != Mode::initialization) {
    log(Status::error, "logStatusError", "exitInitializationMode in %s", mode_name(core_.mode));
    return Status::error;
  }
  // The plant starts from the inputs and parameters as they are now.
  core_.stale = true;
  if (const Status st = ensure_plant(); st != Status::ok) return st;
  core_.mode = Mode::step;
  log(Status::ok, "logEvents", "initialised at t = %g s; frames of %g s", core_.start_s, core_.scene.frame_s);
  return Status::ok;
}

Status Instance::do_step(double t_s, double h_s, double* last_successful_s) {
  if (last_successful_s != nullptr) *last_successful_s = time_s();
  if (core_.mode != Mode::step) {
    log(Status::error, "logStatusError", "doStep in %s: a step needs step mode (after exitInitializationMode)",
        mode_name(core_.mode));
    return Status::error;
  }
  if (core_.failed) {
    log(Status::error, "logStatusError",
        "doStep after the plant faulted (%s at t = %.9g s): restore an earlier FMU state or reset the instance",
        rom_fault_name(engine_->fault()), time_s());
    return Status::error;
  }
  const double frame = core_.scene.frame_s;
  const double now = time_s();
  if (!(finite(h_s) && h_s > 0)) {
    log(Status::error, "logStatusError", "doStep: communication step %g s: must be a positive number", h_s);
    return Status::error;
  }
  const double k_real = h_s / frame;
  const double k_round = std::floor(k_real + 0.5);
  if (!(k_round >= 1.0) || k_round > 1e15 || std::fabs(h_s - k_round * frame) > 1e-6 * frame) {
    log(Status::error, "logStatusError",
        "doStep: communication step %.17g s is not a whole number of the plant's frames of %g s (%.9g frames); the "
        "plant steps in whole frames only (fixedInternalStepSize)",
        h_s, frame, k_real);
    return Status::error;
  }
  if (!finite(t_s) || std::fabs(t_s - now) > 0.01 * frame) {
    log(Status::error, "logStatusError",
        "doStep: communication point %.17g s is not the FMU's time %.17g s (the end of the last step)", t_s, now);
    return Status::error;
  }
  const long k = static_cast<long>(k_round);
  if (core_.stop_defined && now + static_cast<double>(k) * frame > core_.stop_s + 0.01 * frame) {
    log(Status::error, "logStatusError", "doStep: the step to %.9g s goes beyond the stop time %.9g s",
        now + static_cast<double>(k) * frame, core_.stop_s);
    return Status::error;
  }
  for (long i = 0; i < k; ++i) {
    const RomFault f = engine_->step(core_.inputs);
    if (f != RomFault::none) {
      core_.failed = true;
      if (last_successful_s != nullptr) *last_successful_s = time_s();
      log(Status::error, "logStatusError",
          "plant fault %s in the frame from t = %.9g s (frame %ld): %s. The plant keeps its last good state (the "
          "outputs read it and `fault` names the fault); restore an earlier FMU state or reset the instance",
          rom_fault_name(f), time_s(), core_.frames + 1, rom_fault_description(f));
      return Status::error;
    }
    ++core_.frames;
  }
  if (last_successful_s != nullptr) *last_successful_s = time_s();
  return Status::ok;
}

Status Instance::terminate() {
  if (core_.mode != Mode::initialization && core_.mode != Mode::step) {
    log(Status::error, "logStatusError", "terminate in %s", mode_name(core_.mode));
    return Status::error;
  }
  core_.mode = Mode::terminated;
  return Status::ok;
}

Status Instance::reset() {
  reset_core();
  return Status::ok;
}

Status Instance::plant_for_outputs() {
  if (core_.mode == Mode::initialization) return ensure_plant();
  if (engine_->loaded()) return Status::ok;
  log(Status::error, "logStatusError", "no outputs: the plant was never built (initialisation did not complete)");
  return Status::error;
}

bool Instance::can_get(const char* what) {
  if (core_.mode == Mode::instantiated) {
    log(Status::error, "logStatusError", "%s before initialisation mode: values are read from enterInitializationMode on",
        what);
    return false;
  }
  return true;
}

double Instance::read(const Variable& v) {
  switch (v.source) {
    case VarSource::time: return time_s();
    case VarSource::input: return core_.inputs[v.index];
    case VarSource::fault: return static_cast<double>(static_cast<int>(engine_->fault()));
    case VarSource::signal: return engine_->signal(static_cast<RomSignal>(v.index));
    case VarSource::param: return kSceneParams[v.index].get(core_.scene);
  }
  return 0.0;
}

Status Instance::check_value(const Variable& v, double value) {
  if (v.causality == Causality::output || v.causality == Causality::independent) {
    log(Status::error, "logStatusError", "%s is %s: it cannot be set", v.name,
        v.causality == Causality::output ? "an output" : "the independent variable");
    return Status::error;
  }
  if (v.causality == Causality::parameter && core_.mode != Mode::instantiated && core_.mode != Mode::initialization) {
    log(Status::error, "logStatusError",
        "%s is a fixed parameter: it is set before exitInitializationMode, not in %s", v.name, mode_name(core_.mode));
    return Status::error;
  }
  if (v.causality == Causality::input && core_.mode == Mode::terminated) {
    log(Status::error, "logStatusError", "%s: inputs are not set after terminate", v.name);
    return Status::error;
  }
  if (!finite(value)) {
    log(Status::error, "logStatusError", "%s = %g: not a finite number; the value is not taken", v.name, value);
    return Status::error;
  }
  if (value < v.min || value > v.max) {
    log(Status::error, "logStatusError", "%s = %.17g is outside its range [%.17g, %.17g] %s; the value is not taken",
        v.name, value, v.min, v.max, v.unit != nullptr ? v.unit : "");
    return Status::error;
  }
  return Status::ok;
}

Status Instance::set_value(const Variable& v, double value) {
  if (v.source == VarSource::input) {
    core_.inputs[v.index] = value;
    if (core_.mode != Mode::step) core_.stale = true;
  } else {
    kSceneParams[v.index].set(core_.scene, value);
    core_.stale = true;
  }
  return Status::ok;
}

Status Instance::get_float64(const std::uint32_t* vr, std::size_t n, double* v, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "getFloat64: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  if (n == 0) return Status::ok;
  if (!can_get("getFloat64")) return Status::error;
  for (std::size_t i = 0; i < n; ++i)
    if (lookup(vr[i], VarType::float64, "getFloat64") == nullptr) return Status::error;
  for (std::size_t i = 0; i < n; ++i) {
    const Variable& var = *find(vr[i]);
    if (var.source == VarSource::signal)
      if (const Status st = plant_for_outputs(); st != Status::ok) return st;
    v[i] = read(var);
  }
  return Status::ok;
}

Status Instance::set_float64(const std::uint32_t* vr, std::size_t n, const double* v, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "setFloat64: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  // All checked before any is taken: a refused call changes nothing.
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = lookup(vr[i], VarType::float64, "setFloat64");
    if (var == nullptr) return Status::error;
    if (const Status st = check_value(*var, v[i]); st != Status::ok) return st;
  }
  for (std::size_t i = 0; i < n; ++i) set_value(*find(vr[i]), v[i]);
  return Status::ok;
}

Status Instance::get_boolean(const std::uint32_t* vr, std::size_t n, bool* v, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "getBoolean: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  if (n == 0) return Status::ok;
  if (!can_get("getBoolean")) return Status::error;
  for (std::size_t i = 0; i < n; ++i)
    if (lookup(vr[i], VarType::boolean, "getBoolean") == nullptr) return Status::error;
  for (std::size_t i = 0; i < n; ++i) {
    const Variable& var = *find(vr[i]);
    if (var.source == VarSource::signal)
      if (const Status st = plant_for_outputs(); st != Status::ok) return st;
    v[i] = read(var) != 0.0;
  }
  return Status::ok;
}

Status Instance::set_boolean(const std::uint32_t* vr, std::size_t n, const bool* v, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "setBoolean: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = lookup(vr[i], VarType::boolean, "setBoolean");
    if (var == nullptr) return Status::error;
    if (const Status st = check_value(*var, v[i] ? 1.0 : 0.0); st != Status::ok) return st;
  }
  for (std::size_t i = 0; i < n; ++i) set_value(*find(vr[i]), v[i] ? 1.0 : 0.0);
  return Status::ok;
}

Status Instance::get_enum(const std::uint32_t* vr, std::size_t n, std::int64_t* v, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "get: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  if (n == 0) return Status::ok;
  if (!can_get("get of the fault code")) return Status::error;
  for (std::size_t i = 0; i < n; ++i)
    if (lookup(vr[i], VarType::enumeration, fmi_version_ == 3 ? "getInt64" : "getInteger") == nullptr)
      return Status::error;
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::int64_t>(read(*find(vr[i])));
  return Status::ok;
}

Status Instance::set_enum(const std::uint32_t* vr, std::size_t n, std::size_t nv) {
  if (nv != n) {
    log(Status::error, "logStatusError", "set: %zu values for %zu scalar variables", nv, n);
    return Status::error;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = lookup(vr[i], VarType::enumeration, fmi_version_ == 3 ? "setInt64" : "setInteger");
    if (var == nullptr) return Status::error;
    return check_value(*var, 0.0);  // the one enumeration is an output
  }
  return Status::ok;
}

Status Instance::no_variables(const char* type, const std::uint32_t* vr, std::size_t n) {
  if (n == 0) return Status::ok;
  const Variable* v = find(vr[0]);
  if (v == nullptr)
    log(Status::error, "logStatusError", "value reference %u is no variable of this FMU", static_cast<unsigned>(vr[0]));
  else
    log(Status::error, "logStatusError", "%s: variable %s (value reference %u) is a %s; this FMU has no %s variables",
        type, v->name, static_cast<unsigned>(vr[0]), type_name(v->type), type);
  return Status::error;
}

Status Instance::unsupported(const char* function, const char* why) {
  log(Status::error, "logStatusError", "%s: not offered by this FMU: %s (docs/fmu.md)", function, why);
  return Status::error;
}

// --- FMU states (docs/fmu.md#state) ---

Status Instance::get_state(void** state) {
  if (state == nullptr) {
    log(Status::error, "logStatusError", "getFMUState: no place for the state (null pointer)");
    return Status::error;
  }
  Saved* s = static_cast<Saved*>(*state);
  if (s != nullptr && s->owner != this) {
    log(Status::error, "logStatusError", "getFMUState: the state to overwrite belongs to another instance");
    return Status::error;
  }
  if (s == nullptr) {
    void* mem = alloc_.allocate(1, sizeof(Saved));
    if (mem == nullptr) {
      log(Status::error, "logStatusError", "getFMUState: out of memory");
      return Status::error;
    }
    s = ::new (mem) Saved();
  }
  s->owner = this;
  s->core = core_;
  s->engine = engine_->copy_into(s->engine_storage);
  *state = s;
  return Status::ok;
}

Status Instance::set_state(const void* state) {
  const Saved* s = static_cast<const Saved*>(state);
  if (s == nullptr || s->owner != this || s->engine == nullptr) {
    log(Status::error, "logStatusError", "setFMUState: not a state of this instance");
    return Status::error;
  }
  core_ = s->core;
  engine_ = s->engine->copy_into(engine_storage_);
  return Status::ok;
}

Status Instance::free_state(void** state) {
  if (state == nullptr || *state == nullptr) return Status::ok;
  Saved* s = static_cast<Saved*>(*state);
  if (s->owner != this) {
    log(Status::error, "logStatusError", "freeFMUState: not a state of this instance");
    return Status::error;
  }
  s->owner = nullptr;
  alloc_.release(s);
  *state = nullptr;
  return Status::ok;
}

// Serialised: magic, version of the layout, the token's and the build's
// fingerprints, the core (mode, flags, times, frames, inputs, every parameter row),
// then the plant's bytes.
namespace {
struct Writer {
  unsigned char* p;
  std::size_t n = 0;
  template <class V>
  void put(const V& v) {
    if (p != nullptr) std::memcpy(p + n, &v, sizeof v);
    n += sizeof v;
  }
  void bytes(const void* b, std::size_t k) {
    if (p != nullptr && k > 0) std::memcpy(p + n, b, k);
    n += k;
  }
};
struct Reader {
  const unsigned char* p;
  std::size_t size, n = 0;
  bool ok = true;
  template <class V>
  void get(V& v) {
    if (!ok || n + sizeof v > size) {
      ok = false;
      return;
    }
    std::memcpy(&v, p + n, sizeof v);
    n += sizeof v;
  }
};
}  // namespace

std::size_t Instance::serial_size(const Saved& s) const {
  Writer w{nullptr};
  w.bytes(kStateMagic, sizeof kStateMagic);
  w.put(std::uint64_t{});  // token
  w.put(std::uint64_t{});  // build
  w.put(std::uint8_t{});   // mode
  w.put(std::uint8_t{});   // flags
  w.put(double{});
  w.put(double{});
  w.put(std::int64_t{});   // frames
  for (int i = 0; i < input_count; ++i) w.put(double{});
  for (int i = 0; i < kSceneParamCount; ++i) w.put(double{});
  w.put(std::uint64_t{});  // plant bytes
  return w.n + s.engine->image_size();
}

Status Instance::serialized_size(const void* state, std::size_t* size) {
  const Saved* s = static_cast<const Saved*>(state);
  if (s == nullptr || s->owner != this || size == nullptr) {
    log(Status::error, "logStatusError", "serializedFMUStateSize: not a state of this instance");
    return Status::error;
  }
  *size = serial_size(*s);
  return Status::ok;
}

Status Instance::serialize(const void* state, unsigned char* out, std::size_t size) {
  const Saved* s = static_cast<const Saved*>(state);
  if (s == nullptr || s->owner != this || out == nullptr) {
    log(Status::error, "logStatusError", "serializeFMUState: not a state of this instance");
    return Status::error;
  }
  if (size != serial_size(*s)) {
    log(Status::error, "logStatusError", "serializeFMUState: %zu bytes given, the state has %zu", size,
        serial_size(*s));
    return Status::error;
  }
  Writer w{out};
  w.bytes(kStateMagic, sizeof kStateMagic);
  w.put(fnv1a(token_, std::strlen(token_)));
  w.put(build_fingerprint());
  w.put(static_cast<std::uint8_t>(s->core.mode));
  w.put(static_cast<std::uint8_t>((s->core.stop_defined ? 1u : 0u) | (s->core.failed ? 2u : 0u) |
                                  (s->core.stale ? 4u : 0u) | (s->engine->loaded() ? 8u : 0u)));
  w.put(s->core.start_s);
  w.put(s->core.stop_s);
  w.put(static_cast<std::int64_t>(s->core.frames));
  for (int i = 0; i < input_count; ++i) w.put(s->core.inputs[i]);
  for (int i = 0; i < kSceneParamCount; ++i) w.put(kSceneParams[i].get(s->core.scene));
  const std::uint64_t k = s->engine->image_size();
  w.put(k);
  s->engine->image(out + w.n);
  return Status::ok;
}

Status Instance::deserialize(const unsigned char* in, std::size_t size, void** state) {
  if (in == nullptr || state == nullptr) {
    log(Status::error, "logStatusError", "deserializeFMUState: null argument");
    return Status::error;
  }
  Reader r{in, size};
  char magic[sizeof kStateMagic];
  for (char& c : magic) r.get(c);
  std::uint64_t token = 0, build = 0, k = 0;
  std::uint8_t mode = 0, flags = 0;
  r.get(token);
  r.get(build);
  if (!r.ok || std::memcmp(magic, kStateMagic, sizeof magic) != 0) {
    log(Status::error, "logStatusError", "deserializeFMUState: not a serialised state of a cvtplant FMU");
    return Status::error;
  }
  if (token != fnv1a(token_, std::strlen(token_))) {
    log(Status::error, "logStatusError", "deserializeFMUState: the state is of another FMU (instantiation token)");
    return Status::error;
  }
  if (build != build_fingerprint()) {
    log(Status::error, "logStatusError",
        "deserializeFMUState: the state was saved by another build of this FMU (a state restores into the binary "
        "that saved it)");
    return Status::error;
  }
  Core core{};
  core.scene = base_;
  r.get(mode);
  r.get(flags);
  r.get(core.start_s);
  r.get(core.stop_s);
  std::int64_t frames = 0;
  r.get(frames);
  core.frames = static_cast<long>(frames);
  for (double& u : core.inputs) r.get(u);
  for (int i = 0; i < kSceneParamCount; ++i) {
    double v = 0;
    r.get(v);
    kSceneParams[i].set(core.scene, v);
  }
  r.get(k);
  if (!r.ok || mode > static_cast<std::uint8_t>(Mode::terminated) || frames < 0 || r.n + k != size) {
    log(Status::error, "logStatusError", "deserializeFMUState: %zu bytes: truncated or malformed", size);
    return Status::error;
  }
  core.mode = static_cast<Mode>(mode);
  core.stop_defined = (flags & 1u) != 0;
  core.failed = (flags & 2u) != 0;
  core.stale = (flags & 4u) != 0;
  const bool loaded = (flags & 8u) != 0;
  void* mem = alloc_.allocate(1, sizeof(Saved));
  if (mem == nullptr) {
    log(Status::error, "logStatusError", "deserializeFMUState: out of memory");
    return Status::error;
  }
  Saved* s = ::new (mem) Saved();
  s->owner = this;
  s->core = core;
  const char* why = "";
  s->engine = make_engine(base_, s->engine_storage, &why);
  bool ok = s->engine != nullptr;
  if (ok && loaded) {
    // The plant of the state's parameters, then its bytes over it.
    Scene sc = core.scene;
    sc.tau_in = constant_profile(core.inputs[input_tau_in]);
    sc.tau_load = constant_profile(core.inputs[input_tau_load]);
    sc.clamp = constant_profile(core.inputs[input_clamp]);
    ok = s->engine->load(sc, core.inputs).ok && s->engine->restore_image(in + r.n, static_cast<std::size_t>(k));
  } else if (ok) {
    ok = k == 0;
  }
  if (!ok) {
    alloc_.release(s);
    log(Status::error, "logStatusError", "deserializeFMUState: the plant of the state cannot be rebuilt");
    return Status::error;
  }
  *state = s;
  return Status::ok;
}

}  // namespace cvt::fmu
