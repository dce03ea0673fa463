// The model description against the rules of the FMI 3.0 and 2.0 standards
// (docs/fmu.md#tests): names, value references, units, declared types,
// causality and variability, start values and ranges, the model structure.
// On the FMU `cvtplant fmu` writes and on the descriptions of every
// built-in scene in both versions.
#include <doctest/doctest.h>

#include <pugixml.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "cvtplant/fmu/packager.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "importer.hpp"

namespace {

const std::set<std::string> kCausalities3 = {"structuralParameter", "parameter", "calculatedParameter", "input",
                                             "output",              "local",     "independent"};
const std::set<std::string> kCausalities2 = {"parameter", "calculatedParameter", "input", "output", "local",
                                             "independent"};
const std::set<std::string> kVariabilities = {"constant", "fixed", "tunable", "discrete", "continuous"};
const std::set<std::string> kBaseUnitAttrs = {"kg", "m", "s", "A", "K", "mol", "cd", "rad", "factor", "offset"};

bool is_structured_name(const std::string& n) {
  static const std::regex re("[A-Za-z_][A-Za-z0-9_]*(\\.[A-Za-z_][A-Za-z0-9_]*)*");
  return std::regex_match(n, re);
}
bool is_c_identifier(const std::string& n) {
  static const std::regex re("[A-Za-z_][A-Za-z0-9_]*");
  return std::regex_match(n, re);
}

// Units: unique names, SI base units only (no factor or offset), display
// units unique per unit. Returns unit -> its display units.
std::map<std::string, std::set<std::string>> check_units(pugi::xml_node root) {
  std::map<std::string, std::set<std::string>> units;
  for (pugi::xml_node u : root.child("UnitDefinitions").children("Unit")) {
    const std::string name = u.attribute("name").value();
    INFO("unit " << name);
    CHECK(!name.empty());
    CHECK(units.count(name) == 0);
    pugi::xml_node b = u.child("BaseUnit");
    CHECK(b);
    for (pugi::xml_attribute a : b.attributes()) {
      CHECK(kBaseUnitAttrs.count(a.name()) == 1);
      CHECK(std::string(a.name()) != "factor");
      CHECK(std::string(a.name()) != "offset");
    }
    std::set<std::string>& d = units[name];
    for (pugi::xml_node du : u.children("DisplayUnit")) {
      CHECK(d.insert(du.attribute("name").value()).second);
      CHECK(std::isfinite(du.attribute("factor").as_double(1.0)));
    }
  }
  return units;
}

struct Checked {
  int variables = 0, outputs = 0, inputs = 0, parameters = 0;
};

// One variable's type-independent rules.
void check_common(const std::string& causality, const std::string& variability, const std::string& type,
                  bool has_start, const std::string& initial, bool is_float) {
  if (variability == "continuous") CHECK(is_float);  // only floating-point variables are continuous
  if (causality == "parameter") {
    CHECK((variability == "fixed" || variability == "tunable"));
    CHECK(has_start);
    CHECK((initial.empty() || initial == "exact"));
  }
  if (causality == "input") {
    CHECK((variability == "discrete" || variability == "continuous"));
    CHECK(has_start);
    CHECK(initial.empty());
  }
  if (causality == "output") {
    CHECK((variability == "constant" || variability == "discrete" || variability == "continuous"));
    CHECK(((initial.empty() || initial == "calculated") ? !has_start : true));
  }
  if (causality == "independent") {
    INFO("independent variable of type " << type);
    CHECK(is_float);
    CHECK(variability == "continuous");
    CHECK(!has_start);
    CHECK(initial.empty());
  }
}

void check_range(pugi::xml_node t, bool has_start) {
  const double lo = t.attribute("min").as_double(-INFINITY), hi = t.attribute("max").as_double(INFINITY);
  CHECK(lo <= hi);
  if (has_start) {
    const double s = t.attribute("start").as_double(NAN);
    CHECK(std::isfinite(s));
    CHECK(s >= lo);
    CHECK(s <= hi);
  }
}

Checked check_fmi3(const pugi::xml_document& doc, const std::string& dir) {
  Checked c;
  pugi::xml_node root = doc.child("fmiModelDescription");
  REQUIRE(root);
  CHECK(std::string(root.attribute("fmiVersion").value()) == "3.0");
  CHECK(!std::string(root.attribute("modelName").value()).empty());
  CHECK(!std::string(root.attribute("instantiationToken").value()).empty());
  CHECK(std::string(root.attribute("variableNamingConvention").value()) == "structured");
  CHECK(!root.child("ModelExchange"));
  CHECK(!root.child("ScheduledExecution"));
  pugi::xml_node cs = root.child("CoSimulation");
  REQUIRE(cs);
  const std::string id = cs.attribute("modelIdentifier").value();
  CHECK(is_c_identifier(id));
  if (!dir.empty()) CHECK(std::filesystem::is_regular_file(dir + "/binaries/x86_64-linux/" + id + ".so"));
  const double h = cs.attribute("fixedInternalStepSize").as_double();
  CHECK(h > 0);
  const double step = root.child("DefaultExperiment").attribute("stepSize").as_double();
  CHECK(std::fabs(step / h - std::round(step / h)) < 1e-9);
  const auto units = check_units(root);
  std::map<std::string, std::set<std::int64_t>> enums;
  for (pugi::xml_node t : root.child("TypeDefinitions").children()) {
    const std::string name = t.attribute("name").value();
    CHECK(enums.count(name) == 0);
    std::set<std::int64_t>& values = enums[name];
    std::set<std::string> items;
    if (std::string(t.name()) == "EnumerationType")
      for (pugi::xml_node it : t.children("Item")) {
        CHECK(values.insert(it.attribute("value").as_llong()).second);
        CHECK(items.insert(it.attribute("name").value()).second);
      }
  }
  std::set<std::string> names;
  std::map<std::uint32_t, std::string> by_vr;
  std::vector<std::uint32_t> outputs;
  int independents = 0;
  for (pugi::xml_node v : root.child("ModelVariables").children()) {
    ++c.variables;
    const std::string type = v.name(), name = v.attribute("name").value();
    INFO("variable " << name);
    CHECK(is_structured_name(name));
    CHECK(names.insert(name).second);
    CHECK(v.attribute("valueReference"));
    const auto vr = static_cast<std::uint32_t>(v.attribute("valueReference").as_ullong());
    CHECK(by_vr.emplace(vr, v.attribute("causality").value()).second);
    CHECK(!std::string(v.attribute("description").value()).empty());
    const std::string causality = v.attribute("causality").as_string("local");
    const std::string variability = v.attribute("variability").as_string(type == "Float64" ? "continuous" : "discrete");
    CHECK(kCausalities3.count(causality) == 1);
    CHECK(kVariabilities.count(variability) == 1);
    const bool is_float = type == "Float64" || type == "Float32";
    check_common(causality, variability, type, static_cast<bool>(v.attribute("start")), v.attribute("initial").value(),
                 is_float);
    if (causality == "independent") ++independents;
    if (causality == "output") {
      ++c.outputs;
      outputs.push_back(vr);
    }
    c.inputs += causality == "input";
    c.parameters += causality == "parameter";
    if (is_float) {
      // SI: every real carries a defined unit (and a display unit of it).
      const std::string unit = v.attribute("unit").value();
      CHECK(units.count(unit) == 1);
      if (v.attribute("displayUnit")) CHECK(units.at(unit).count(v.attribute("displayUnit").value()) == 1);
      check_range(v, static_cast<bool>(v.attribute("start")));
    } else if (type == "Enumeration") {
      CHECK(enums.count(v.attribute("declaredType").value()) == 1);
    } else {
      CHECK(type == "Boolean");
      if (v.attribute("start")) {
        const std::string s = v.attribute("start").value();
        CHECK((s == "true" || s == "false"));
      }
    }
  }
  CHECK(independents == 1);
  // ModelStructure: every output once, in the order of ModelVariables; every
  // dependency a known input; the initial unknowns known outputs.
  pugi::xml_node ms = root.child("ModelStructure");
  std::vector<std::uint32_t> listed;
  for (pugi::xml_node o : ms.children("Output")) {
    listed.push_back(static_cast<std::uint32_t>(o.attribute("valueReference").as_ullong()));
    CHECK(o.attribute("dependencies"));
    std::istringstream deps(o.attribute("dependencies").value());
    for (std::uint32_t d; deps >> d;) CHECK(by_vr.count(d) == 1);
  }
  CHECK(listed == outputs);
  std::set<std::uint32_t> initial;
  for (pugi::xml_node o : ms.children("InitialUnknown")) {
    const auto vr = static_cast<std::uint32_t>(o.attribute("valueReference").as_ullong());
    CHECK(by_vr.count(vr) == 1);
    CHECK(initial.insert(vr).second);
  }
  for (std::uint32_t vr : outputs) CHECK(initial.count(vr) == 1);  // outputs are calculated at initialisation
  return c;
}

Checked check_fmi2(const pugi::xml_document& doc, const std::string& dir) {
  Checked c;
  pugi::xml_node root = doc.child("fmiModelDescription");
  REQUIRE(root);
  CHECK(std::string(root.attribute("fmiVersion").value()) == "2.0");
  CHECK(!std::string(root.attribute("guid").value()).empty());
  CHECK(!std::string(root.attribute("modelName").value()).empty());
  CHECK(!root.child("ModelExchange"));
  pugi::xml_node cs = root.child("CoSimulation");
  REQUIRE(cs);
  const std::string id = cs.attribute("modelIdentifier").value();
  CHECK(is_c_identifier(id));
  if (!dir.empty()) {
    CHECK(std::filesystem::is_regular_file(dir + "/binaries/linux64/" + id + ".so"));
    for (pugi::xml_node f : cs.child("SourceFiles").children("File"))
      CHECK(std::filesystem::is_regular_file(dir + "/sources/" + f.attribute("name").value()));
  }
  const auto units = check_units(root);
  std::set<std::string> types;
  for (pugi::xml_node t : root.child("TypeDefinitions").children("SimpleType")) {
    CHECK(types.insert(t.attribute("name").value()).second);
    std::set<long long> values;
    for (pugi::xml_node it : t.child("Enumeration").children("Item")) CHECK(values.insert(it.attribute("value").as_llong()).second);
  }
  std::set<std::string> names;
  std::set<std::uint32_t> vrs;
  std::vector<std::size_t> outputs;
  std::map<std::size_t, std::string> causality_of;
  std::size_t index = 0;
  int independents = 0;
  for (pugi::xml_node v : root.child("ModelVariables").children("ScalarVariable")) {
    ++index;
    ++c.variables;
    const std::string name = v.attribute("name").value();
    INFO("variable " << name);
    CHECK(is_structured_name(name));
    CHECK(names.insert(name).second);
    CHECK(vrs.insert(static_cast<std::uint32_t>(v.attribute("valueReference").as_ullong())).second);
    CHECK(!std::string(v.attribute("description").value()).empty());
    int elements = 0;
    pugi::xml_node t;
    for (pugi::xml_node e : v.children()) {
      const std::string n = e.name();
      if (n == "Real" || n == "Integer" || n == "Boolean" || n == "String" || n == "Enumeration") {
        ++elements;
        t = e;
      }
    }
    CHECK(elements == 1);
    const std::string type = t.name();
    const std::string causality = v.attribute("causality").as_string("local");
    const std::string variability = v.attribute("variability").as_string("continuous");
    CHECK(kCausalities2.count(causality) == 1);
    CHECK(kVariabilities.count(variability) == 1);
    causality_of[index] = causality;
    check_common(causality, variability, type, static_cast<bool>(t.attribute("start")), v.attribute("initial").value(),
                 type == "Real");
    if (causality == "independent") ++independents;
    if (causality == "output") outputs.push_back(index);
    c.outputs += causality == "output";
    c.inputs += causality == "input";
    c.parameters += causality == "parameter";
    if (type == "Real") {
      const std::string unit = t.attribute("unit").value();
      CHECK(units.count(unit) == 1);
      if (t.attribute("displayUnit")) CHECK(units.at(unit).count(t.attribute("displayUnit").value()) == 1);
      check_range(t, static_cast<bool>(t.attribute("start")));
    }
    if (type == "Enumeration") CHECK(types.count(t.attribute("declaredType").value()) == 1);
  }
  CHECK(independents <= 1);
  pugi::xml_node ms = root.child("ModelStructure");
  std::vector<std::size_t> listed;
  for (pugi::xml_node u : ms.child("Outputs").children("Unknown")) {
    const std::size_t i = u.attribute("index").as_ullong();
    listed.push_back(i);
    CHECK(causality_of[i] == "output");
    std::istringstream deps(u.attribute("dependencies").value());
    for (std::size_t d; deps >> d;) CHECK((causality_of[d] == "input" || causality_of[d] == "local"));
  }
  CHECK(listed == outputs);
  std::size_t previous = 0;
  std::set<std::size_t> initial;
  for (pugi::xml_node u : ms.child("InitialUnknowns").children("Unknown")) {
    const std::size_t i = u.attribute("index").as_ullong();
    CHECK(i > previous);  // ascending, each once
    previous = i;
    CHECK(i >= 1);
    CHECK(i <= index);
    initial.insert(i);
  }
  for (std::size_t i : outputs) CHECK(initial.count(i) == 1);
  return c;
}

}  // namespace

TEST_SUITE("model_description") {
  TEST_CASE("the FMU cvtplant writes: FMI 3.0 and 2.0 descriptions follow the standards' rules") {
    for (int version : {3, 2}) {
      const std::string dir = fmutest::temp_dir("fmu-md" + std::to_string(version));
      const std::string out = dir + "/plant.fmu";
      REQUIRE(fmutest::run(fmutest::cvtplant() + " fmu --scene ratio-control --fmi " + std::to_string(version) +
                           " --out " + out + " > /dev/null") == 0);
      const fmutest::Unpacked fmu(out, dir + "/unpacked");
      const Checked c = version == 3 ? check_fmi3(fmu.md, fmu.dir) : check_fmi2(fmu.md, fmu.dir);
      // ratio-control: tau_in, tau_load, clamp, clamp_driven; the fault and
      // every signal of its groups; its parameters.
      CHECK(c.inputs == 4);
      CHECK(c.outputs >= 25);
      CHECK(c.parameters >= 35);
      CHECK(std::filesystem::is_regular_file(fmu.dir + "/documentation/index.html"));
      CHECK(std::filesystem::is_regular_file(fmu.dir + "/resources/scene.txt"));
      CHECK(std::filesystem::is_regular_file(fmu.dir + "/sources/Eigen/Core"));
      CHECK(std::filesystem::is_regular_file(fmu.dir + "/sources/cvtplant/scene/plant_set.hpp"));
      if (version == 3) {
        pugi::xml_document bd;
        REQUIRE(bd.load_file((fmu.dir + "/sources/buildDescription.xml").c_str()));
        pugi::xml_node bc = bd.child("fmiBuildDescription").child("BuildConfiguration");
        CHECK(std::string(bc.attribute("modelIdentifier").value()) == fmu.model_identifier);
        for (pugi::xml_node f : bc.child("SourceFileSet").children("SourceFile"))
          CHECK(std::filesystem::is_regular_file(fmu.dir + "/sources/" + f.attribute("name").value()));
        for (pugi::xml_node d : bc.child("SourceFileSet").children("IncludeDirectory"))
          CHECK(std::filesystem::is_directory(fmu.dir + "/sources/" + d.attribute("name").value()));
      }
    }
  }

  TEST_CASE("every built-in scene's description, both versions") {
    for (const cvt::Scene& s : cvt::kBuiltinScenes) {
      for (int version : {3, 2}) {
        cvt::fmu::PackageRequest r;
        r.scene = s;
        r.name = s.name;
        r.fmi_version = version;
        INFO(s.name << ", FMI " << version);
        for (const cvt::fmu::FmuFile& f : cvt::fmu::generated_files(r))
          if (f.path == "modelDescription.xml") {
            pugi::xml_document doc;
            REQUIRE(doc.load_string(f.text.c_str()));
            const Checked c = version == 3 ? check_fmi3(doc, "") : check_fmi2(doc, "");
            CHECK(c.outputs >= 20);
          }
      }
    }
  }
}
