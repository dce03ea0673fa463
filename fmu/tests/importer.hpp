#pragma once
// The project's own FMU importer (docs/fmu.md#tests): unpacks an FMU,
// reads its model description, loads its shared object with dlopen and
// resolves every function of the FMI version by name (a missing one is an
// error), and drives instances. Strict: every call's status is returned to
// the test, and every message the FMU logs is kept.
#include <pugixml.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cvtplant/fmu/fmi2_api.h"
#include "cvtplant/fmu/fmi3_api.h"

namespace fmutest {

// Unpacks `fmu` (a zip) into `dir` (created, emptied first).
void unzip(const std::string& fmu, const std::string& dir);

struct VarInfo {
  std::uint32_t vr = 0;
  std::string name, type, causality, variability, unit;
  std::size_t index = 0;  // 1-based position in ModelVariables (FMI 2.0's index)
};

// An unpacked FMU and its model description.
struct Unpacked {
  std::string dir;
  int version = 0;
  pugi::xml_document md;
  std::string model_identifier, token;
  double frame_s = 0;  // fixedInternalStepSize (FMI 3.0) or the DefaultExperiment's stepSize
  std::vector<VarInfo> vars;
  std::map<std::string, VarInfo> by_name;

  Unpacked(const std::string& fmu, const std::string& dir);
  const VarInfo& var(const std::string& name) const;
  std::string binary() const;
  std::string resources() const { return dir + "/resources/"; }
};

// Messages an instance logged.
struct Log {
  std::vector<std::pair<int, std::string>> messages;
  bool has(const std::string& part) const;
  std::string all() const;
};

// The FMI 3.0 functions of a shared object, every one of them resolved.
struct Api3 {
  void* so = nullptr;
#define CVT_FN(name) decltype(&::name) name = nullptr;
#include "fmi3_functions.inc"
#undef CVT_FN
  explicit Api3(const std::string& path);
  ~Api3();
  Api3(const Api3&) = delete;
  Api3& operator=(const Api3&) = delete;
};

struct Api2 {
  void* so = nullptr;
#define CVT_FN(name) decltype(&::name) name = nullptr;
#include "fmi2_functions.inc"
#undef CVT_FN
  explicit Api2(const std::string& path);
  ~Api2();
  Api2(const Api2&) = delete;
  Api2& operator=(const Api2&) = delete;
};

// One FMI 3.0 co-simulation instance.
class Instance3 {
 public:
  Instance3(const Api3& api, const Unpacked& fmu, const char* name = "plant", const char* token = nullptr);
  ~Instance3();
  Instance3(const Instance3&) = delete;
  Instance3& operator=(const Instance3&) = delete;
  bool ok() const { return inst_ != nullptr; }
  fmi3Instance get() const { return inst_; }
  const Api3& api() const { return api_; }
  Log log;

  fmi3Status init(double start = 0, bool stop_defined = false, double stop = 0);
  fmi3Status set(const std::string& name, double v);
  fmi3Status set_bool(const std::string& name, bool v);
  double real(const std::string& name);
  bool boolean(const std::string& name);
  std::int64_t enumeration(const std::string& name);
  fmi3Status step(double t, double h);
  fmi3Status last = fmi3OK;

 private:
  const Api3& api_;
  const Unpacked& fmu_;
  fmi3Instance inst_ = nullptr;
};

// One FMI 2.0 co-simulation instance.
class Instance2 {
 public:
  Instance2(const Api2& api, const Unpacked& fmu, const char* name = "plant");
  ~Instance2();
  Instance2(const Instance2&) = delete;
  Instance2& operator=(const Instance2&) = delete;
  bool ok() const { return inst_ != nullptr; }
  fmi2Component get() const { return inst_; }
  Log log;

  fmi2Status init(double start = 0);
  fmi2Status set(const std::string& name, double v);
  double real(const std::string& name);
  fmi2Status step(double t, double h);
  fmi2Status last = fmi2OK;

 private:
  const Api2& api_;
  const Unpacked& fmu_;
  fmi2CallbackFunctions cb_{};
  fmi2Component inst_ = nullptr;
};

// `cvtplant run ... --csv FILE`, read back: the header and every row's
// numbers (the fault column as its name).
struct CsvRun {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<std::string> faults;
  int column(const std::string& name) const;
};
CsvRun read_csv(const std::string& path);

// Runs a shell command; its exit status.
int run(const std::string& command);
std::string temp_dir(const std::string& name);
std::string cvtplant();  // the command line program (environment CVTPLANT)

}  // namespace fmutest
