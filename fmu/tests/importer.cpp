#include "importer.hpp"

#include <dlfcn.h>
#include <zip.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace fmutest {

void unzip(const std::string& fmu, const std::string& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  int err = 0;
  zip_t* z = zip_open(fmu.c_str(), ZIP_RDONLY, &err);
  if (z == nullptr) throw std::runtime_error("not a zip: " + fmu);
  const zip_int64_t n = zip_get_num_entries(z, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const std::string name = zip_get_name(z, static_cast<zip_uint64_t>(i), 0);
    if (name.empty() || name.back() == '/') continue;
    if (name.find("..") != std::string::npos || name[0] == '/') throw std::runtime_error("unsafe entry " + name);
    const fs::path out = fs::path(dir) / name;
    fs::create_directories(out.parent_path());
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    if (f == nullptr) throw std::runtime_error("cannot read " + name);
    std::ofstream o(out, std::ios::binary);
    char buf[65536];
    zip_int64_t k;
    while ((k = zip_fread(f, buf, sizeof buf)) > 0) o.write(buf, k);
    zip_fclose(f);
  }
  zip_close(z);
}

Unpacked::Unpacked(const std::string& fmu, const std::string& d) : dir(d) {
  unzip(fmu, dir);
  const pugi::xml_parse_result r = md.load_file((dir + "/modelDescription.xml").c_str());
  if (!r) throw std::runtime_error(std::string("modelDescription.xml: ") + r.description());
  pugi::xml_node root = md.child("fmiModelDescription");
  const std::string v = root.attribute("fmiVersion").value();
  version = v == "3.0" ? 3 : v == "2.0" ? 2 : 0;
  if (version == 0) throw std::runtime_error("fmiVersion " + v);
  pugi::xml_node cs = root.child("CoSimulation");
  model_identifier = cs.attribute("modelIdentifier").value();
  token = root.attribute(version == 3 ? "instantiationToken" : "guid").value();
  frame_s = version == 3 ? cs.attribute("fixedInternalStepSize").as_double()
                         : root.child("DefaultExperiment").attribute("stepSize").as_double();
  std::size_t index = 0;
  for (pugi::xml_node n : root.child("ModelVariables").children()) {
    VarInfo vi;
    vi.index = ++index;
    vi.name = n.attribute("name").value();
    vi.vr = static_cast<std::uint32_t>(n.attribute("valueReference").as_ullong());
    vi.causality = n.attribute("causality").value();
    vi.variability = n.attribute("variability").value();
    pugi::xml_node t = version == 3 ? n : n.first_child();
    vi.type = version == 3 ? n.name() : t.name();
    vi.unit = t.attribute("unit").value();
    vars.push_back(vi);
    by_name[vi.name] = vi;
  }
}

const VarInfo& Unpacked::var(const std::string& name) const {
  const auto it = by_name.find(name);
  if (it == by_name.end()) throw std::runtime_error("no variable " + name);
  return it->second;
}

std::string Unpacked::binary() const {
  return dir + (version == 3 ? "/binaries/x86_64-linux/" : "/binaries/linux64/") + model_identifier + ".so";
}

bool Log::has(const std::string& part) const {
  for (const auto& m : messages)
    if (m.second.find(part) != std::string::npos) return true;
  return false;
}
std::string Log::all() const {
  std::string s;
  for (const auto& m : messages) s += "[" + std::to_string(m.first) + "] " + m.second + "\n";
  return s;
}

namespace {
void* open_so(const std::string& path) {
  // RTLD_LOCAL: two FMUs (or two builds of one) in a process keep apart.
  void* so = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (so == nullptr) throw std::runtime_error(std::string("dlopen: ") + dlerror());
  return so;
}
template <class F>
void resolve(void* so, const char* name, F& fn, std::string& missing) {
  fn = reinterpret_cast<F>(dlsym(so, name));
  if (fn == nullptr) missing += std::string(missing.empty() ? "" : ", ") + name;
}
}  // namespace

Api3::Api3(const std::string& path) : so(open_so(path)) {
  std::string missing;
#define CVT_FN(name) resolve(so, #name, this->name, missing);
#include "fmi3_functions.inc"
#undef CVT_FN
  if (!missing.empty()) throw std::runtime_error("FMI 3.0 functions not exported: " + missing);
}
Api3::~Api3() { dlclose(so); }

Api2::Api2(const std::string& path) : so(open_so(path)) {
  std::string missing;
#define CVT_FN(name) resolve(so, #name, this->name, missing);
#include "fmi2_functions.inc"
#undef CVT_FN
  if (!missing.empty()) throw std::runtime_error("FMI 2.0 functions not exported: " + missing);
}
Api2::~Api2() { dlclose(so); }

namespace {
void log3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String, fmi3String message) {
  static_cast<Log*>(env)->messages.emplace_back(static_cast<int>(status), message != nullptr ? message : "");
}
void log2(fmi2ComponentEnvironment env, fmi2String, fmi2Status status, fmi2String, fmi2String fmt, ...) {
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  static_cast<Log*>(env)->messages.emplace_back(static_cast<int>(status), buf);
}
}  // namespace

Instance3::Instance3(const Api3& api, const Unpacked& fmu, const char* name, const char* token)
    : api_(api), fmu_(fmu) {
  inst_ = api.fmi3InstantiateCoSimulation(name, token != nullptr ? token : fmu.token.c_str(),
                                          fmu.resources().c_str(), false, false, false, false, nullptr, 0, &log,
                                          &log3, nullptr);
}
Instance3::~Instance3() {
  if (inst_ != nullptr) api_.fmi3FreeInstance(inst_);
}
fmi3Status Instance3::init(double start, bool stop_defined, double stop) {
  last = api_.fmi3EnterInitializationMode(inst_, false, 0.0, start, stop_defined, stop);
  if (last != fmi3OK) return last;
  return last = api_.fmi3ExitInitializationMode(inst_);
}
fmi3Status Instance3::set(const std::string& name, double v) {
  const fmi3ValueReference vr = fmu_.var(name).vr;
  return last = api_.fmi3SetFloat64(inst_, &vr, 1, &v, 1);
}
fmi3Status Instance3::set_bool(const std::string& name, bool v) {
  const fmi3ValueReference vr = fmu_.var(name).vr;
  return last = api_.fmi3SetBoolean(inst_, &vr, 1, &v, 1);
}
double Instance3::real(const std::string& name) {
  const fmi3ValueReference vr = fmu_.var(name).vr;
  double v = 0;
  last = api_.fmi3GetFloat64(inst_, &vr, 1, &v, 1);
  return v;
}
bool Instance3::boolean(const std::string& name) {
  const fmi3ValueReference vr = fmu_.var(name).vr;
  bool v = false;
  last = api_.fmi3GetBoolean(inst_, &vr, 1, &v, 1);
  return v;
}
std::int64_t Instance3::enumeration(const std::string& name) {
  const fmi3ValueReference vr = fmu_.var(name).vr;
  std::int64_t v = -1;
  last = api_.fmi3GetInt64(inst_, &vr, 1, &v, 1);
  return v;
}
fmi3Status Instance3::step(double t, double h) {
  bool event = true, terminate = true, early = true;
  double last_t = -1;
  last = api_.fmi3DoStep(inst_, t, h, true, &event, &terminate, &early, &last_t);
  return last;
}

Instance2::Instance2(const Api2& api, const Unpacked& fmu, const char* name) : api_(api), fmu_(fmu) {
  cb_.logger = &log2;
  cb_.allocateMemory = &std::calloc;
  cb_.freeMemory = &std::free;
  cb_.componentEnvironment = &log;
  const std::string uri = "file://" + fs::absolute(fmu.resources()).string();
  inst_ = api.fmi2Instantiate(name, fmi2CoSimulation, fmu.token.c_str(), uri.c_str(), &cb_, fmi2False, fmi2False);
}
Instance2::~Instance2() {
  if (inst_ != nullptr) api_.fmi2FreeInstance(inst_);
}
fmi2Status Instance2::init(double start) {
  last = api_.fmi2SetupExperiment(inst_, fmi2False, 0.0, start, fmi2False, 0.0);
  if (last != fmi2OK) return last;
  last = api_.fmi2EnterInitializationMode(inst_);
  if (last != fmi2OK) return last;
  return last = api_.fmi2ExitInitializationMode(inst_);
}
fmi2Status Instance2::set(const std::string& name, double v) {
  const fmi2ValueReference vr = fmu_.var(name).vr;
  return last = api_.fmi2SetReal(inst_, &vr, 1, &v);
}
double Instance2::real(const std::string& name) {
  const fmi2ValueReference vr = fmu_.var(name).vr;
  double v = 0;
  last = api_.fmi2GetReal(inst_, &vr, 1, &v);
  return v;
}
fmi2Status Instance2::step(double t, double h) { return last = api_.fmi2DoStep(inst_, t, h, fmi2True); }

int CsvRun::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

CsvRun read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  CsvRun r;
  std::string line;
  std::getline(in, line);
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) r.header.push_back(cell);
  const std::size_t fault_col = r.header.size() - 1;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::vector<double> row;
    std::string cell;
    for (std::size_t i = 0; std::getline(ls, cell, ','); ++i) {
      if (i == fault_col) r.faults.push_back(cell);
      else row.push_back(std::strtod(cell.c_str(), nullptr));
    }
    r.rows.push_back(row);
  }
  return r;
}

int run(const std::string& command) {
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string temp_dir(const std::string& name) {
  const char* base = std::getenv("CVT_FMU_TEST_DIR");
  const fs::path d = fs::path(base != nullptr ? base : fs::temp_directory_path().string()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string cvtplant() {
  const char* c = std::getenv("CVTPLANT");
  if (c == nullptr) throw std::runtime_error("set CVTPLANT to the cvtplant program");
  return c;
}

}  // namespace fmutest
