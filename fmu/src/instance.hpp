#pragma once
// One FMU instance, whatever the FMI version (docs/fmu.md): its variables,
// the modes of the co-simulation state machine, the plant (engine.hpp) and
// its saved states. The FMI 3.0 and 2.0 functions (fmi3.cpp, fmi2.cpp) are
// thin layers over it. Heap-free but for the instance and its saved states,
// which the FMI layers allocate (FMI 2.0: through the importer's functions).
#include <cstddef>
#include <cstdint>

#include "cvtplant/fmu/fmi2_api.h"
#include "cvtplant/fmu/fmi3_api.h"
#include "cvtplant/fmu/scene_text.hpp"
#include "cvtplant/fmu/variables.hpp"
#include "engine.hpp"

namespace cvt::fmu {

// The status codes of both versions (fmi3Status and fmi2Status agree on 0..4).
enum class Status : int { ok = 0, warning = 1, discard = 2, error = 3, fatal = 4 };

enum class Mode : std::uint8_t { instantiated, initialization, step, terminated };

// Where the instance's messages go: the importer's callback of the version
// it was instantiated with (either may be absent).
struct LogSink {
  fmi3LogMessageCallback log3 = nullptr;
  fmi2CallbackLogger log2 = nullptr;
  void* env = nullptr;
};

// How the instance and its saved states are allocated (zeroed memory).
struct Allocator {
  void* (*allocate)(std::size_t n, std::size_t size) = nullptr;
  void (*release)(void* p) = nullptr;
};

class Instance {
 public:
  // Reads resources/scene.txt from `resource_dir` (a directory path with or
  // without the trailing '/'), checks the token and builds the variables.
  // False, with the reason logged, if anything is wrong.
  bool open(const char* name, int fmi_version, const char* token, const char* resource_dir, const LogSink& sink,
            bool logging_on, const Allocator& alloc);

  const char* name() const { return name_; }
  const Allocator& allocator() const { return alloc_; }

  Status set_debug_logging(bool on, std::size_t n, const char* const* categories);
  Status setup_experiment(double start_s, bool stop_defined, double stop_s);
  Status enter_initialization();
  Status exit_initialization();
  Status do_step(double t_s, double h_s, double* last_successful_s);
  Status terminate();
  Status reset();
  double time_s() const;

  Status get_float64(const std::uint32_t* vr, std::size_t n, double* v, std::size_t nv);
  Status set_float64(const std::uint32_t* vr, std::size_t n, const double* v, std::size_t nv);
  // Booleans as 0/1 bytes (FMI 3.0 bool, FMI 2.0 int: the layers convert).
  Status get_boolean(const std::uint32_t* vr, std::size_t n, bool* v, std::size_t nv);
  Status set_boolean(const std::uint32_t* vr, std::size_t n, const bool* v, std::size_t nv);
  // The enumeration (the fault code), FMI 3.0 Int64 and FMI 2.0 Integer.
  Status get_enum(const std::uint32_t* vr, std::size_t n, std::int64_t* v, std::size_t nv);
  Status set_enum(const std::uint32_t* vr, std::size_t n, std::size_t nv);
  // A value type this FMU has no variable of: fine for no references, else
  // an error naming the first.
  Status no_variables(const char* type, const std::uint32_t* vr, std::size_t n);
  // A function this FMU does not offer (docs/fmu.md#not-offered).
  Status unsupported(const char* function, const char* why);

  Status get_state(void** state);
  Status set_state(const void* state);
  Status free_state(void** state);
  Status serialized_size(const void* state, std::size_t* size);
  Status serialize(const void* state, unsigned char* out, std::size_t size);
  Status deserialize(const unsigned char* in, std::size_t size, void** state);

  // Messages: errors and warnings always reach the importer's logger;
  // the rest only with logging on (docs/fmu.md#log).
  void log(Status st, const char* category, const char* fmt, ...) __attribute__((format(printf, 4, 5)));

 private:
  // Everything an FMU state saves besides the plant.
  struct Core {
    Scene scene{};
    double inputs[input_count] = {};
    double start_s = 0, stop_s = 0;
    bool stop_defined = false;
    Mode mode = Mode::instantiated;
    bool failed = false;    // the plant faulted: no step until a state is restored or reset
    bool stale = true;      // parameters or inputs changed since the plant was built (initialisation)
    // Frames stepped without a fault: the FMU's time is start + frames x
    // frame_s, the last good frame's after a fault.
    long frames = 0;
  };
  struct Saved;

  const Variable* find(std::uint32_t vr) const;
  const Variable* lookup(std::uint32_t vr, VarType type, const char* type_name);
  bool can_get(const char* what);
  Status ensure_plant();
  Status plant_for_outputs();
  Status check_value(const Variable& v, double value);
  Status set_value(const Variable& v, double value);
  double read(const Variable& v);
  const char* field_variable(const char* field) const;
  void reset_core();
  std::size_t serial_size(const Saved& s) const;

  char name_[128] = {};
  int fmi_version_ = 3;
  char token_[40] = {};
  char scene_name_[kMaxSceneName] = {};
  LogSink sink_{};
  Allocator alloc_{};
  bool logging_on_ = false;
  bool log_events_ = true;
  Scene base_{};  // the resource's scene: the start values
  Variable vars_[kMaxVariables];
  int nvars_ = 0;
  std::int16_t index_[kVrEnd];
  Core core_{};
  alignas(kEngineAlign) unsigned char engine_storage_[kEngineSize];
  Engine* engine_ = nullptr;
};

}  // namespace cvt::fmu
