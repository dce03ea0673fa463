// FMU states, faults, refused calls and independent instances
// (docs/fmu.md#state, #faults, #tests).
#include <doctest/doctest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cvtplant/plant/rom_watchdog.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "importer.hpp"

using namespace fmutest;

namespace {

std::string fmu_of(const std::string& scene, int version, const std::string& dir) {
  const std::string out = dir + "/plant.fmu";
  REQUIRE(run(cvtplant() + " fmu --scene " + scene + " --fmi " + std::to_string(version) + " --out " + out +
              " > /dev/null 2>&1") == 0);
  return out;
}

// A built-in scene's FMU of one FMI version, packaged and unpacked in a
// fresh temp_dir(name), its library loaded and one instance made; tests
// take the parts apart with a structured binding.
template <class Api, class Instance>
struct Loaded {
  std::string dir;
  Unpacked fmu;
  Api api;
  Instance inst;
  Loaded(const char* name, const char* scene, int version)
      : dir(temp_dir(name)), fmu(fmu_of(scene, version, dir), dir + "/unpacked"), api(fmu.binary()), inst(api, fmu) {}
};
using Loaded3 = Loaded<Api3, Instance3>;
using Loaded2 = Loaded<Api2, Instance2>;

// The outputs a test follows, as bit patterns.
const char* const kWatched[] = {"omega1", "omega2", "F_ax", "slip", "r1", "F_ax2", "E_residual", "torque_transmitted"};

std::vector<double> outputs(Instance3& inst) {
  std::vector<double> v;
  for (const char* n : kWatched) v.push_back(inst.real(n));
  v.push_back(inst.real("time"));
  return v;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void steps(Instance3& inst, double frame, long from, long n, int k = 1) {
  for (long i = from; i < from + n; i += k) REQUIRE_MESSAGE(inst.step(static_cast<double>(i) * frame, k * frame) == fmi3OK, inst.log.all());
}

}  // namespace

// The second process of the serialised-state test: `cvt_fmu_tests resume
// FMU_DIR STATE_FILE FRAMES` restores the state and prints the outputs.
int resume_in_new_process(int argc, char** argv) {
  if (argc != 5) return 2;
  const Unpacked fmu(std::string(argv[2]) + "/../plant.fmu", std::string(argv[2]) + "-resume");
  const Api3 api(fmu.binary());
  Instance3 inst(api, fmu, "resumed");
  std::ifstream in(argv[3], std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fmi3FMUState st = nullptr;
  if (api.fmi3DeserializeFMUState(inst.get(), reinterpret_cast<const fmi3Byte*>(bytes.data()), bytes.size(), &st) !=
          fmi3OK ||
      api.fmi3SetFMUState(inst.get(), st) != fmi3OK) {
    std::fprintf(stderr, "%s", inst.log.all().c_str());
    return 1;
  }
  const long frames = std::atol(argv[4]);
  const double t0 = inst.real("time");
  const long f0 = std::lround(t0 / fmu.frame_s);
  for (long i = f0; i < f0 + frames; ++i)
    if (inst.step(static_cast<double>(i) * fmu.frame_s, fmu.frame_s) != fmi3OK) return 1;
  for (double v : outputs(inst)) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    std::printf("%016llx\n", static_cast<unsigned long long>(b));
  }
  api.fmi3FreeFMUState(inst.get(), &st);
  return 0;
}

TEST_SUITE("importer") {
  TEST_CASE("FMU state: get/set and serialise/deserialise continue bit-identically, also in another process") {
    Loaded3 loaded("fmu-state", "ratio-control", 3);
    auto& [dir, fmu, api, a] = loaded;
    REQUIRE(a.init() == fmi3OK);
    const double h = fmu.frame_s;
    steps(a, h, 0, 300);
    fmi3FMUState st = nullptr;
    REQUIRE(api.fmi3GetFMUState(a.get(), &st) == fmi3OK);
    // Change an input after the state was taken: the state keeps the old one.
    steps(a, h, 300, 200);
    const std::vector<double> ref = outputs(a);
    REQUIRE(a.set("inputs.tau_in", 90.0) == fmi3OK);
    steps(a, h, 500, 50);
    CHECK(!same(outputs(a), ref));

    REQUIRE(api.fmi3SetFMUState(a.get(), st) == fmi3OK);
    CHECK(a.real("time") == doctest::Approx(300 * h));
    steps(a, h, 300, 200);
    CHECK(same(outputs(a), ref));

    // Serialised, restored into a second instance of this process.
    size_t size = 0;
    REQUIRE(api.fmi3SerializedFMUStateSize(a.get(), st, &size) == fmi3OK);
    std::vector<fmi3Byte> bytes(size);
    REQUIRE(api.fmi3SerializeFMUState(a.get(), st, bytes.data(), size) == fmi3OK);
    Instance3 b(api, fmu, "second");
    fmi3FMUState st_b = nullptr;
    REQUIRE(api.fmi3DeserializeFMUState(b.get(), bytes.data(), size, &st_b) == fmi3OK);
    REQUIRE(api.fmi3SetFMUState(b.get(), st_b) == fmi3OK);
    steps(b, h, 300, 200);
    CHECK(same(outputs(b), ref));

    // And in a new process (other addresses): the same bits.
    const std::string file = dir + "/state.bin";
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(size));
    const std::string out = dir + "/resumed.txt";
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    REQUIRE(n > 0);
    self[n] = '\0';
    REQUIRE(run(std::string(self) + " resume " + dir + "/unpacked " + file + " 200 > " + out) == 0);
    std::ifstream in(out);
    std::vector<double> resumed;
    for (std::string line; std::getline(in, line);) {
      const unsigned long long bits = std::stoull(line, nullptr, 16);
      double v;
      std::memcpy(&v, &bits, sizeof v);
      resumed.push_back(v);
    }
    CHECK(same(resumed, ref));

    // A state that is not this FMU's, or cut short, is refused.
    bytes[9] ^= 0xFF;
    fmi3FMUState bad = nullptr;
    CHECK(api.fmi3DeserializeFMUState(b.get(), bytes.data(), size, &bad) == fmi3Error);
    CHECK(b.log.has("another FMU"));
    bytes[9] ^= 0xFF;
    CHECK(api.fmi3DeserializeFMUState(b.get(), bytes.data(), size - 3, &bad) == fmi3Error);
    CHECK(b.log.has("truncated"));
    CHECK(api.fmi3FreeFMUState(b.get(), &st_b) == fmi3OK);
    CHECK(st_b == nullptr);
    CHECK(api.fmi3FreeFMUState(a.get(), &st) == fmi3OK);
  }

  TEST_CASE("FMI 2.0 FMU state: restored bit-identically") {
    Loaded2 loaded("fmu-state2", "tip-in", 2);
    auto& [dir, fmu, api, a] = loaded;
    REQUIRE(a.init() == fmi2OK);
    const double h = fmu.frame_s;
    for (long i = 0; i < 200; ++i) REQUIRE(a.step(i * h, h) == fmi2OK);
    fmi2FMUstate st = nullptr;
    REQUIRE(api.fmi2GetFMUstate(a.get(), &st) == fmi2OK);
    for (long i = 200; i < 400; ++i) REQUIRE(a.step(i * h, h) == fmi2OK);
    const double w = a.real("omega1"), r = a.real("E_residual");
    size_t size = 0;
    REQUIRE(api.fmi2SerializedFMUstateSize(a.get(), st, &size) == fmi2OK);
    std::vector<fmi2Byte> bytes(size);
    REQUIRE(api.fmi2SerializeFMUstate(a.get(), st, bytes.data(), size) == fmi2OK);
    fmi2FMUstate st2 = nullptr;
    REQUIRE(api.fmi2DeSerializeFMUstate(a.get(), bytes.data(), size, &st2) == fmi2OK);
    REQUIRE(api.fmi2SetFMUstate(a.get(), st2) == fmi2OK);
    for (long i = 200; i < 400; ++i) REQUIRE(a.step(i * h, h) == fmi2OK);
    const double w2 = a.real("omega1"), r2 = a.real("E_residual");
    CHECK(std::memcmp(&w, &w2, sizeof w) == 0);
    CHECK(std::memcmp(&r, &r2, sizeof r) == 0);
    CHECK(api.fmi2FreeFMUstate(a.get(), &st) == fmi2OK);
    CHECK(api.fmi2FreeFMUstate(a.get(), &st2) == fmi2OK);
  }

  TEST_CASE("a plant fault is fmi3Error with the fault named, at the frame cvtplant run faults; a state restores") {
    const std::string dir = temp_dir("fmu-fault");
    // gross-slip's driver accelerates; a speed limit of 25 rad/s ends it early.
    const std::string scene = dir + "/slip.toml";
    std::ofstream(scene) << "base = \"gross-slip\"\nname = \"gross-slip-limited\"\n[params]\nspeed_limit_rad_s = 25\n";
    const Unpacked fmu(fmu_of(scene, 3, dir), dir + "/unpacked");
    const std::string csv = dir + "/run.csv";
    CHECK(run(cvtplant() + " run --scene " + scene + " --csv " + csv + " > /dev/null 2>&1") == 1);
    const CsvRun cli = read_csv(csv);
    REQUIRE(cli.faults.back() == "speed-out-of-range");
    const long fault_frame = static_cast<long>(cli.rows.size()) - 1;  // the last row is the faulted frame
    const double t_last_good = cli.rows[cli.rows.size() - 2][0];
    const Api3 api(fmu.binary());
    Instance3 inst(api, fmu);
    REQUIRE(inst.init() == fmi3OK);
    const double h = fmu.frame_s;
    fmi3FMUState before = nullptr;
    long i = 0;
    fmi3Status s = fmi3OK;
    for (; i < 100000 && s == fmi3OK; ++i) {
      if (i == fault_frame - 10) REQUIRE(api.fmi3GetFMUState(inst.get(), &before) == fmi3OK);
      s = inst.step(static_cast<double>(i) * h, h);
    }
    CHECK(s == fmi3Error);
    CHECK(i == fault_frame);
    CHECK(inst.log.has("plant fault speed-out-of-range"));
    CHECK(inst.enumeration("fault") == static_cast<int>(cvt::RomFault::speed_out_of_range));
    CHECK(inst.real("time") == t_last_good);
    CHECK(std::isfinite(inst.real("omega1")));
    CHECK(std::fabs(inst.real("omega1")) <= 25.0);
    // No further step until a state is restored or the instance reset.
    CHECK(inst.step(inst.real("time"), h) == fmi3Error);
    CHECK(inst.log.has("after the plant faulted"));
    REQUIRE(before != nullptr);
    REQUIRE(api.fmi3SetFMUState(inst.get(), before) == fmi3OK);
    CHECK(inst.enumeration("fault") == 0);
    CHECK(inst.step((fault_frame - 10) * h, 5 * h) == fmi3OK);
    // Reset: a fresh start that runs like the first.
    REQUIRE(api.fmi3Reset(inst.get()) == fmi3OK);
    REQUIRE(inst.init() == fmi3OK);
    CHECK(inst.step(0.0, 10 * h) == fmi3OK);
    CHECK(api.fmi3FreeFMUState(inst.get(), &before) == fmi3OK);
  }

  TEST_CASE("bad calls: an error status and a logged reason, nothing changed") {
    const std::string dir = temp_dir("fmu-bad");
    const Unpacked fmu(fmu_of("ratio-control", 3, dir), dir + "/unpacked");
    const Api3 api(fmu.binary());
    const double h = fmu.frame_s;
    Log log;
    auto logger = [](fmi3InstanceEnvironment env, fmi3Status st, fmi3String, fmi3String m) {
      static_cast<Log*>(env)->messages.emplace_back(st, m);
    };
    // Instantiation: a wrong token, model exchange, event mode, no resources.
    CHECK(api.fmi3InstantiateCoSimulation("x", "{wrong}", fmu.resources().c_str(), false, false, false, false, nullptr,
                                          0, &log, logger, nullptr) == nullptr);
    CHECK(log.has("instantiation token"));
    CHECK(api.fmi3InstantiateModelExchange("x", fmu.token.c_str(), fmu.resources().c_str(), false, false, &log,
                                           logger) == nullptr);
    CHECK(log.has("co-simulation only"));
    CHECK(api.fmi3InstantiateCoSimulation("x", fmu.token.c_str(), fmu.resources().c_str(), false, false, true, false,
                                          nullptr, 0, &log, logger, nullptr) == nullptr);
    CHECK(log.has("no event mode"));
    CHECK(api.fmi3InstantiateCoSimulation("x", fmu.token.c_str(), "/nonexistent/", false, false, false, false, nullptr,
                                          0, &log, logger, nullptr) == nullptr);
    CHECK(log.has("cannot open"));
    CHECK(api.fmi3InstantiateCoSimulation("", fmu.token.c_str(), fmu.resources().c_str(), false, false, false, false,
                                          nullptr, 0, &log, logger, nullptr) == nullptr);

    Instance3 inst(api, fmu);
    REQUIRE(inst.ok());
    const fmi3ValueReference w1 = fmu.var("omega1").vr, tau = fmu.var("inputs.tau_in").vr,
                             j1 = fmu.var("params.J1_kgm2").vr, stick = fmu.var("stick1").vr;
    double v = 0;
    // Out of order.
    CHECK(inst.step(0.0, h) == fmi3Error);
    CHECK(inst.log.has("doStep in the instantiated mode"));
    CHECK(api.fmi3GetFloat64(inst.get(), &w1, 1, &v, 1) == fmi3Error);
    CHECK(inst.log.has("before initialisation mode"));
    CHECK(api.fmi3ExitInitializationMode(inst.get()) == fmi3Error);
    CHECK(api.fmi3Terminate(inst.get()) == fmi3Error);
    // Values: NaN, out of range, the wrong type, unknown references, counts.
    CHECK(inst.set("inputs.tau_in", std::nan("")) == fmi3Error);
    CHECK(inst.log.has("not a finite number"));
    CHECK(inst.set("inputs.clamp", -1.0) == fmi3Error);
    CHECK(inst.log.has("inputs.clamp = -1 is outside its range"));
    CHECK(inst.set("params.J1_kgm2", -1.0) == fmi3Error);
    CHECK(inst.set("params.beta0_rad", 1.5) == fmi3Error);
    CHECK(inst.set("omega1", 1.0) == fmi3Error);
    CHECK(inst.log.has("omega1 is an output"));
    CHECK(inst.set("time", 1.0) == fmi3Error);
    bool b = true;
    CHECK(api.fmi3SetBoolean(inst.get(), &tau, 1, &b, 1) == fmi3Error);
    CHECK(inst.log.has("is a Float64"));
    const fmi3ValueReference unknown = 999;
    CHECK(api.fmi3SetFloat64(inst.get(), &unknown, 1, &v, 1) == fmi3Error);
    CHECK(inst.log.has("value reference 999 is no variable"));
    const double two[2] = {1, 2};
    CHECK(api.fmi3SetFloat64(inst.get(), &tau, 1, two, 2) == fmi3Error);
    fmi3Int32 i32 = 0;
    CHECK(api.fmi3GetInt32(inst.get(), &w1, 1, &i32, 1) == fmi3Error);
    CHECK(inst.log.has("no Int32 variables"));
    // A batch with one bad value takes none of them.
    const fmi3ValueReference pair[2] = {tau, fmu.var("inputs.clamp").vr};
    const double vals[2] = {77.0, -5.0};
    CHECK(api.fmi3SetFloat64(inst.get(), pair, 2, vals, 2) == fmi3Error);
    // Not offered.
    CHECK(api.fmi3EnterEventMode(inst.get()) == fmi3Error);
    CHECK(api.fmi3GetDirectionalDerivative(inst.get(), &w1, 1, &tau, 1, &v, 1, &v, 1) == fmi3Error);
    CHECK(api.fmi3EnterContinuousTimeMode(inst.get()) == fmi3Error);
    CHECK(inst.log.has("model exchange is not offered"));
    CHECK(api.fmi3SetDebugLogging(inst.get(), true, 1, std::vector<fmi3String>{"logNothing"}.data()) == fmi3Error);

    // A parameter within its declared range that validation refuses: the
    // plant is not built, initialisation does not end, the reason names it.
    REQUIRE(api.fmi3EnterInitializationMode(inst.get(), false, 0, 0, true, 1.0) == fmi3OK);
    CHECK(inst.set("params.J1_kgm2", 0.0) == fmi3OK);
    CHECK(api.fmi3ExitInitializationMode(inst.get()) == fmi3Error);
    CHECK(inst.log.has("params.J1_kgm2: must be > 0"));
    CHECK(inst.set("params.J1_kgm2", 0.05) == fmi3OK);
    REQUIRE(api.fmi3ExitInitializationMode(inst.get()) == fmi3OK);
    CHECK(inst.real("inputs.tau_in") == 60.0);  // the refused batch left it
    // Step mode: parameters are fixed, steps are whole frames at the FMU's time.
    CHECK(inst.set("params.J1_kgm2", 0.06) == fmi3Error);
    CHECK(inst.log.has("fixed parameter"));
    CHECK(inst.step(0.0, 1.5 * h) == fmi3Error);
    CHECK(inst.log.has("not a whole number of the plant's frames"));
    CHECK(inst.step(0.0, 0.0) == fmi3Error);
    CHECK(inst.step(0.0, std::nan("")) == fmi3Error);
    CHECK(inst.step(5 * h, h) == fmi3Error);
    CHECK(inst.log.has("is not the FMU's time"));
    CHECK(inst.step(0.0, 2.0) == fmi3Error);
    CHECK(inst.log.has("beyond the stop time"));
    CHECK(inst.real("time") == 0.0);
    // After all that, the instance runs.
    CHECK(inst.step(0.0, 3 * h) == fmi3OK);
    CHECK(inst.real("time") == doctest::Approx(3 * h));
    CHECK(api.fmi3GetBoolean(inst.get(), &stick, 1, &b, 1) == fmi3OK);
    CHECK(api.fmi3Terminate(inst.get()) == fmi3OK);
    CHECK(inst.set("inputs.tau_in", 1.0) == fmi3Error);
    CHECK(inst.step(3 * h, h) == fmi3Error);
    // Every refusal above was logged as an error.
    int errors = 0;
    for (const auto& m : inst.log.messages) errors += m.first == fmi3Error;
    CHECK(errors >= 25);
    (void)j1;
  }

  TEST_CASE("FMI 2.0 bad calls: instantiation, resource URI, steps") {
    Loaded2 loaded("fmu-bad2", "tip-in", 2);
    auto& [dir, fmu, api, inst] = loaded;
    REQUIRE(inst.ok());
    fmi2CallbackFunctions cb{};
    CHECK(api.fmi2Instantiate("x", fmi2ModelExchange, fmu.token.c_str(), "file:///tmp", &cb, 0, 0) == nullptr);
    CHECK(api.fmi2Instantiate("x", fmi2CoSimulation, fmu.token.c_str(), "http://example/x", &cb, 0, 0) == nullptr);
    CHECK(inst.step(0.0, fmu.frame_s) == fmi2Error);
    CHECK(inst.log.has("doStep in"));
    REQUIRE(inst.init() == fmi2OK);
    CHECK(inst.step(0.0, 0.7 * fmu.frame_s) == fmi2Error);
    CHECK(inst.set("inputs.tau_in", std::nan("")) == fmi2Error);
    CHECK(inst.step(0.0, fmu.frame_s) == fmi2OK);
    fmi2Real t = 0;
    CHECK(api.fmi2GetRealStatus(inst.get(), fmi2LastSuccessfulTime, &t) == fmi2OK);
    CHECK(t == doctest::Approx(fmu.frame_s));
    CHECK(api.fmi2GetDerivatives(inst.get(), &t, 1) == fmi2Error);
  }

  TEST_CASE("several instances in one process are independent") {
    const std::string dir = temp_dir("fmu-many");
    const Unpacked fmu(fmu_of("ratio-control", 3, dir), dir + "/unpacked");
    const Api3 api(fmu.binary());
    const double h = fmu.frame_s;
    // Alone: tau_in 60 and 40 N m.
    std::vector<double> alone[2];
    for (int k = 0; k < 2; ++k) {
      Instance3 inst(api, fmu);
      REQUIRE(inst.set("inputs.tau_in", k == 0 ? 60.0 : 40.0) == fmi3OK);
      REQUIRE(inst.init() == fmi3OK);
      steps(inst, h, 0, 400);
      alone[k] = outputs(inst);
    }
    // Interleaved, step by step, and a third instance created and freed in between.
    Instance3 a(api, fmu, "a"), b(api, fmu, "b");
    REQUIRE(a.set("inputs.tau_in", 60.0) == fmi3OK);
    REQUIRE(b.set("inputs.tau_in", 40.0) == fmi3OK);
    REQUIRE(a.init() == fmi3OK);
    REQUIRE(b.init() == fmi3OK);
    for (long i = 0; i < 400; ++i) {
      REQUIRE(a.step(i * h, h) == fmi3OK);
      if (i == 200) {
        Instance3 c(api, fmu, "c");
        REQUIRE(c.set("inputs.tau_in", 10.0) == fmi3OK);
        REQUIRE(c.init() == fmi3OK);
        steps(c, h, 0, 20);
      }
      REQUIRE(b.step(i * h, h) == fmi3OK);
    }
    CHECK(same(outputs(a), alone[0]));
    CHECK(same(outputs(b), alone[1]));
    CHECK(!same(alone[0], alone[1]));
  }
}

TEST_SUITE("importer") {
  TEST_CASE("the driven clamping input reaches F_ax2 through the actuator's first-order lag (closed form)") {
    Loaded3 loaded("fmu-driven", "ratio-control", 3);
    auto& [dir, fmu, api, inst] = loaded;
    REQUIRE(inst.ok());
    REQUIRE(api.fmi3EnterInitializationMode(inst.get(), false, 0, 0, false, 0) == fmi3OK);
    const double f0 = inst.real("params.driven_clamp_N"), tau = inst.real("params.actuator_tau_s");
    CHECK(inst.real("inputs.clamp_driven") == f0);  // its start is the set-up value
    CHECK(inst.real("F_ax2") == f0);
    REQUIRE(api.fmi3ExitInitializationMode(inst.get()) == fmi3OK);
    CHECK(!inst.boolean("stop_underdrive"));
    CHECK(!inst.boolean("stop_overdrive"));
    // docs/rom.md#driven-clamping: F += (F_cmd - F)(1 - exp(-frame/tau)) once a frame.
    const double cmd = 5000.0, h = fmu.frame_s;
    REQUIRE(inst.set("inputs.clamp_driven", cmd) == fmi3OK);
    for (int n = 1; n <= 40; ++n) {
      REQUIRE(inst.step((n - 1) * h, h) == fmi3OK);
      const double want = cmd + (f0 - cmd) * std::exp(-n * h / tau);
      INFO("frame " << n);
      CHECK(inst.real("F_ax2") == doctest::Approx(want).epsilon(1e-12));
    }
    // Saturated at clamp_max_N, like the driver's actuator.
    const double fmax = inst.real("params.clamp_max_N");
    const double before = inst.real("F_ax2");
    REQUIRE(inst.set("inputs.clamp_driven", 10 * fmax) == fmi3OK);
    REQUIRE(inst.step(40 * h, h) == fmi3OK);
    CHECK(inst.real("F_ax2") == doctest::Approx(fmax + (before - fmax) * std::exp(-h / tau)).epsilon(1e-12));
  }
}

TEST_SUITE("importer") {
  TEST_CASE("q16.16: inputs stay within +-32767 (off the rail, where the watchdog would fault input-saturated)") {
    const std::string dir = temp_dir("fmu-fixed-range");
    const std::string scene = dir + "/fixed.toml";
    std::ofstream(scene) << "base = \"clamp-step\"\nname = \"clamp-step-fixed\"\nscalar = \"fixed\"\n";
    const Unpacked fmu(fmu_of(scene, 3, dir), dir + "/unpacked");
    const Api3 api(fmu.binary());
    Instance3 inst(api, fmu);
    REQUIRE(inst.init() == fmi3OK);
    CHECK(inst.set("inputs.clamp", 32767.0) == fmi3OK);
    CHECK(inst.set("inputs.clamp", 32768.0) == fmi3Error);
    CHECK(inst.log.has("outside its range"));
    CHECK(inst.set("inputs.tau_in", -32768.0) == fmi3Error);
    CHECK(inst.real("inputs.clamp") == 32767.0);
    CHECK(inst.step(0.0, fmu.frame_s) == fmi3OK);
    CHECK(inst.enumeration("fault") == 0);
  }
}
