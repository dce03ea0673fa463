#include "cvtplant/fmu/packager.hpp"

#include <pugixml.hpp>
#include <zip.h>

#include <array>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>

#include "cvtplant/fmu/scene_text.hpp"
#include "cvtplant/fmu/variables.hpp"

// The payload built by fmu/CMakeLists.txt: the runtime's shared object and
// the FMU's sources, embedded by payload_blob.cpp.
extern "C" const unsigned char cvt_fmu_payload_begin[];
extern "C" const unsigned char cvt_fmu_payload_end[];

namespace cvt::fmu {

namespace {

// The SI base units of every unit a variable names (FMI's BaseUnit: kg, m,
// s, A, K, mol, cd, rad exponents), and a display unit where engineers read
// another (deg, rpm).
struct UnitInfo {
  std::array<int, 8> exp;
  const char* display = nullptr;
  double factor = 1.0;
};
const char* const kBaseNames[8] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};

UnitInfo unit_info(const std::string& u) {
  static const std::map<std::string, UnitInfo> units = {
      {"1", {{0, 0, 0, 0, 0, 0, 0, 0}}},
      {"s", {{0, 0, 1, 0, 0, 0, 0, 0}}},
      {"rad", {{0, 0, 0, 0, 0, 0, 0, 1}, "deg", 180.0 / 3.14159265358979323846}},
      {"rad/s", {{0, 0, -1, 0, 0, 0, 0, 1}, "rpm", 60.0 / (2.0 * 3.14159265358979323846)}},
      {"m", {{0, 1, 0, 0, 0, 0, 0, 0}}},
      {"m/s", {{0, 1, -1, 0, 0, 0, 0, 0}}},
      {"s/m", {{0, -1, 1, 0, 0, 0, 0, 0}}},
      {"kg", {{1, 0, 0, 0, 0, 0, 0, 0}}},
      {"kg/m", {{1, -1, 0, 0, 0, 0, 0, 0}}},
      {"kg.m2", {{1, 2, 0, 0, 0, 0, 0, 0}}},
      {"N", {{1, 1, -2, 0, 0, 0, 0, 0}}},
      {"N/m", {{1, 0, -2, 0, 0, 0, 0, 0}}},
      {"N.s/m", {{1, 0, -1, 0, 0, 0, 0, 0}}},
      {"N.m", {{1, 2, -2, 0, 0, 0, 0, 0}}},
      {"J", {{1, 2, -2, 0, 0, 0, 0, 0}}},
      {"N.m.s/rad", {{1, 2, -1, 0, 0, 0, 0, -1}}},
      {"N.m.s2/rad2", {{1, 2, 0, 0, 0, 0, 0, -2}}},
  };
  const auto it = units.find(u);
  if (it == units.end()) throw PackageError("no SI base units known for the unit '" + u + "' (fmu/src/packager.cpp)");
  return it->second;
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

const char* causality_name(Causality c) {
  switch (c) {
    case Causality::independent: return "independent";
    case Causality::input: return "input";
    case Causality::output: return "output";
    case Causality::parameter: return "parameter";
  }
  return "?";
}
const char* variability_name(Variability v) {
  switch (v) {
    case Variability::fixed: return "fixed";
    case Variability::discrete: return "discrete";
    case Variability::continuous: return "continuous";
  }
  return "?";
}

struct Model {
  std::vector<Variable> vars;
  std::string id, token, scene_text;
};

Model model_of(const PackageRequest& r) {
  Model m;
  Variable v[kMaxVariables];
  const int n = fmu_variables(r.scene, v);
  m.vars.assign(v, v + n);
  m.id = model_identifier(r.name);
  std::vector<char> text(kMaxSceneText);
  const std::size_t len = write_scene_text(r.scene, r.name.c_str(), text.data(), text.size());
  if (len == 0) throw PackageError("the scene's name '" + r.name + "' cannot be written (a line break, or too long)");
  m.scene_text.assign(text.data(), len);
  char token[40];
  instantiation_token(m.scene_text.data(), m.scene_text.size(), token);
  m.token = token;
  return m;
}

std::string description_of(const PackageRequest& r) {
  std::string d = "CVT plant (cvtplant) of scene " + r.name;
  if (!r.summary.empty()) d += ": " + r.summary;
  return d;
}

const char* kFaultType = "cvtplant.Fault";

void add_units(pugi::xml_node root, const Model& m) {
  std::map<std::string, UnitInfo> used;
  for (const Variable& v : m.vars)
    if (v.unit != nullptr) used.emplace(v.unit, unit_info(v.unit));
  pugi::xml_node defs = root.append_child("UnitDefinitions");
  for (const auto& [name, info] : used) {
    pugi::xml_node u = defs.append_child("Unit");
    u.append_attribute("name") = name.c_str();
    pugi::xml_node b = u.append_child("BaseUnit");
    for (int k = 0; k < 8; ++k)
      if (info.exp[static_cast<std::size_t>(k)] != 0)
        b.append_attribute(kBaseNames[k]) = info.exp[static_cast<std::size_t>(k)];
    if (info.display != nullptr) {
      pugi::xml_node d = u.append_child("DisplayUnit");
      d.append_attribute("name") = info.display;
      d.append_attribute("factor") = num(info.factor).c_str();
    }
  }
}

// The watchdog's faults as the enumeration's items of `parent` (both FMI versions).
void add_fault_items(pugi::xml_node parent) {
  for (int i = 0; i < 256; ++i) {
    const RomFault f = static_cast<RomFault>(i);
    if (std::string(rom_fault_name(f)) == "?") break;
    pugi::xml_node it = parent.append_child("Item");
    it.append_attribute("name") = rom_fault_name(f);
    it.append_attribute("value") = i;
    it.append_attribute("description") = rom_fault_description(f);
  }
}

void add_log_categories(pugi::xml_node root) {
  pugi::xml_node cats = root.append_child("LogCategories");
  const char* names[][2] = {
      {"logEvents", "initialisation and other events (with logging on)"},
      {"logStatusWarning", "warnings"},
      {"logStatusError", "errors: plant faults, refused calls and values (always logged)"}};
  for (const auto& c : names) {
    pugi::xml_node n = cats.append_child("Category");
    n.append_attribute("name") = c[0];
    n.append_attribute("description") = c[1];
  }
}

void add_experiment(pugi::xml_node root, const Scene& s) {
  pugi::xml_node e = root.append_child("DefaultExperiment");
  e.append_attribute("startTime") = "0";
  e.append_attribute("stopTime") = num(s.t_end_s).c_str();
  e.append_attribute("stepSize") = num(s.frame_s).c_str();
}

void put_bounds(pugi::xml_node n, const Variable& v) {
  if (v.min != -kNoBound) n.append_attribute("min") = num(v.min).c_str();
  if (v.max != kNoBound) n.append_attribute("max") = num(v.max).c_str();
}

// The XML declaration and the root element `name` of an FMI `version` file.
pugi::xml_node fmi_root(pugi::xml_document& doc, const char* name, const char* version) {
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = doc.append_child(name);
  root.append_attribute("fmiVersion") = version;
  return root;
}

// A variable's attributes common to both versions, in their order.
void put_variable(pugi::xml_node n, const Variable& v) {
  n.append_attribute("name") = v.name;
  n.append_attribute("valueReference") = v.vr;
  n.append_attribute("description") = v.description;
  n.append_attribute("causality") = causality_name(v.causality);
  n.append_attribute("variability") = variability_name(v.variability);
}

// A variable's type attributes: the fault type, unit and display unit,
// bounds and start value (on the variable in FMI 3.0, on its type element in 2.0).
void put_value(pugi::xml_node t, const Variable& v) {
  if (v.type == VarType::enumeration) t.append_attribute("declaredType") = kFaultType;
  if (v.type == VarType::float64 && v.unit != nullptr) {
    t.append_attribute("unit") = v.unit;
    const UnitInfo u = unit_info(v.unit);
    if (u.display != nullptr) t.append_attribute("displayUnit") = u.display;
  }
  if (v.type == VarType::float64) put_bounds(t, v);
  if (v.has_start)
    t.append_attribute("start") = v.type == VarType::boolean ? (v.start != 0 ? "true" : "false") : num(v.start).c_str();
}

std::string xml_text(const pugi::xml_document& doc) {
  std::ostringstream o;
  doc.save(o, "  ", pugi::format_default, pugi::encoding_utf8);
  return o.str();
}

std::string fmi3_description(const PackageRequest& r, const Model& m) {
  pugi::xml_document doc;
  pugi::xml_node root = fmi_root(doc, "fmiModelDescription", "3.0");
  root.append_attribute("modelName") = r.name.c_str();
  root.append_attribute("description") = description_of(r).c_str();
  root.append_attribute("instantiationToken") = m.token.c_str();
  root.append_attribute("generationTool") = "cvtplant fmu";
  root.append_attribute("variableNamingConvention") = "structured";
  pugi::xml_node cs = root.append_child("CoSimulation");
  cs.append_attribute("modelIdentifier") = m.id.c_str();
  cs.append_attribute("canHandleVariableCommunicationStepSize") = "true";
  cs.append_attribute("fixedInternalStepSize") = num(r.scene.frame_s).c_str();
  cs.append_attribute("canGetAndSetFMUState") = "true";
  cs.append_attribute("canSerializeFMUState") = "true";
  cs.append_attribute("canBeInstantiatedOnlyOncePerProcess") = "false";
  cs.append_attribute("providesDirectionalDerivatives") = "false";
  cs.append_attribute("providesAdjointDerivatives") = "false";
  cs.append_attribute("providesPerElementDependencies") = "false";
  cs.append_attribute("maxOutputDerivativeOrder") = "0";
  cs.append_attribute("providesIntermediateUpdate") = "false";
  cs.append_attribute("mightReturnEarlyFromDoStep") = "false";
  cs.append_attribute("canReturnEarlyAfterIntermediateUpdate") = "false";
  cs.append_attribute("hasEventMode") = "false";
  cs.append_attribute("providesEvaluateDiscreteStates") = "false";
  add_units(root, m);
  pugi::xml_node types = root.append_child("TypeDefinitions");
  pugi::xml_node et = types.append_child("EnumerationType");
  et.append_attribute("name") = kFaultType;
  et.append_attribute("description") = "the plant's watchdog faults (docs/rom.md#watchdog)";
  add_fault_items(et);
  add_log_categories(root);
  add_experiment(root, r.scene);
  pugi::xml_node vars = root.append_child("ModelVariables");
  for (const Variable& v : m.vars) {
    const char* tag = v.type == VarType::float64 ? "Float64" : v.type == VarType::boolean ? "Boolean" : "Enumeration";
    pugi::xml_node n = vars.append_child(tag);
    put_variable(n, v);
    put_value(n, v);
  }
  pugi::xml_node ms = root.append_child("ModelStructure");
  for (const Variable& v : m.vars)
    if (v.causality == Causality::output) {
      // Outputs read the plant after the last step: no input reaches them
      // before the next doStep (no direct feedthrough).
      pugi::xml_node o = ms.append_child("Output");
      o.append_attribute("valueReference") = v.vr;
      o.append_attribute("dependencies") = "";
    }
  for (const Variable& v : m.vars)
    if (v.causality == Causality::output) ms.append_child("InitialUnknown").append_attribute("valueReference") = v.vr;
  return xml_text(doc);
}

// The files a build of sources/ compiles: one per file of fmu/src, each
// naming this scene's plant first (sources_unit), so a build needs no
// definitions of its own.
const char* const kSources[] = {"cvtplant_fmu_instance.cpp", "cvtplant_fmu_fmi3.cpp", "cvtplant_fmu_fmi2.cpp"};
const char* const kSourceOf[] = {"fmu/src/instance.cpp", "fmu/src/fmi3.cpp", "fmu/src/fmi2.cpp"};

std::string sources_unit(const PackageRequest& r, const char* file) {
  std::ostringstream o;
  o << "// The FMU's plant for scene " << r.name << " only: its features and scalar (written by cvtplant fmu).\n"
    << "#define EIGEN_MPL2_ONLY\n"
    << "#define CVT_FMU_FEATURES " << r.scene.features << "\n"
    << "#define CVT_FMU_SCALAR " << static_cast<int>(r.scene.scalar) << "\n"
    << "#include \"" << file << "\"\n";
  return o.str();
}

std::string fmi2_description(const PackageRequest& r, const Model& m) {
  pugi::xml_document doc;
  pugi::xml_node root = fmi_root(doc, "fmiModelDescription", "2.0");
  root.append_attribute("modelName") = r.name.c_str();
  root.append_attribute("guid") = m.token.c_str();
  root.append_attribute("description") = description_of(r).c_str();
  root.append_attribute("generationTool") = "cvtplant fmu";
  root.append_attribute("variableNamingConvention") = "structured";
  root.append_attribute("numberOfEventIndicators") = "0";
  pugi::xml_node cs = root.append_child("CoSimulation");
  cs.append_attribute("modelIdentifier") = m.id.c_str();
  cs.append_attribute("canHandleVariableCommunicationStepSize") = "true";
  cs.append_attribute("canInterpolateInputs") = "false";
  cs.append_attribute("maxOutputDerivativeOrder") = "0";
  cs.append_attribute("canRunAsynchronuously") = "false";
  cs.append_attribute("canBeInstantiatedOnlyOncePerProcess") = "false";
  cs.append_attribute("canNotUseMemoryManagementFunctions") = "false";
  cs.append_attribute("canGetAndSetFMUstate") = "true";
  cs.append_attribute("canSerializeFMUstate") = "true";
  cs.append_attribute("providesDirectionalDerivative") = "false";
  pugi::xml_node src = cs.append_child("SourceFiles");
  for (const char* f : kSources) src.append_child("File").append_attribute("name") = f;
  add_units(root, m);
  pugi::xml_node types = root.append_child("TypeDefinitions");
  pugi::xml_node st = types.append_child("SimpleType");
  st.append_attribute("name") = kFaultType;
  st.append_attribute("description") = "the plant's watchdog faults (docs/rom.md#watchdog)";
  pugi::xml_node en = st.append_child("Enumeration");
  add_fault_items(en);
  add_log_categories(root);
  add_experiment(root, r.scene);
  pugi::xml_node vars = root.append_child("ModelVariables");
  for (const Variable& v : m.vars) {
    pugi::xml_node sv = vars.append_child("ScalarVariable");
    put_variable(sv, v);
    const char* tag = v.type == VarType::float64 ? "Real" : v.type == VarType::boolean ? "Boolean" : "Enumeration";
    put_value(sv.append_child(tag), v);
  }
  pugi::xml_node ms = root.append_child("ModelStructure");
  pugi::xml_node outs = ms.append_child("Outputs");
  pugi::xml_node init = ms.append_child("InitialUnknowns");
  for (std::size_t i = 0; i < m.vars.size(); ++i)
    if (m.vars[i].causality == Causality::output) {
      pugi::xml_node u = outs.append_child("Unknown");
      u.append_attribute("index") = static_cast<unsigned>(i + 1);
      u.append_attribute("dependencies") = "";
      init.append_child("Unknown").append_attribute("index") = static_cast<unsigned>(i + 1);
    }
  return xml_text(doc);
}

std::string build_description(const Model& m) {
  pugi::xml_document doc;
  pugi::xml_node root = fmi_root(doc, "fmiBuildDescription", "3.0");
  pugi::xml_node bc = root.append_child("BuildConfiguration");
  bc.append_attribute("modelIdentifier") = m.id.c_str();
  bc.append_attribute("description") =
      "the plant of this scene only (its features and scalar); a GCC or Clang C++17 compiler. -ffp-contract=off "
      "keeps the results bit-identical to the binaries (docs/fmu.md#sources)";
  pugi::xml_node set = bc.append_child("SourceFileSet");
  set.append_attribute("language") = "C++17";
  set.append_attribute("compilerOptions") = "-O2 -ffp-contract=off -fno-fast-math -fno-exceptions -fno-rtti";
  for (const char* f : kSources) set.append_child("SourceFile").append_attribute("name") = f;
  set.append_child("IncludeDirectory").append_attribute("name") = ".";
  return xml_text(doc);
}

std::string cmake_lists(const PackageRequest& r, const Model& m) {
  std::ostringstream o;
  o << "# Builds this FMU's binary from its sources (the plant of scene " << r.name
    << " only), as buildDescription.xml describes:\n"
       "#   cmake -S sources -B build && cmake --build build\n"
       "# gives build/"
    << m.id
    << ".so (or .dll, .dylib). -ffp-contract=off keeps the results bit-identical to the\n"
       "# binary cvtplant ships.\n"
       "cmake_minimum_required(VERSION 3.16)\n"
       "project(" << m.id << " CXX)\n"
       "add_library(" << m.id << " SHARED";
  for (const char* f : kSources) o << " " << f;
  o << ")\n"
       "set_target_properties("
    << m.id
    << " PROPERTIES PREFIX \"\" CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON CXX_VISIBILITY_PRESET hidden)\n"
       "target_include_directories("
    << m.id
    << " PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})\n"
       "target_compile_options("
    << m.id << " PRIVATE -ffp-contract=off -fno-fast-math -fno-exceptions -fno-rtti)\n";
  return o.str();
}

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

std::string documentation(const PackageRequest& r, const Model& m) {
  std::ostringstream o;
  const Scene& s = r.scene;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(r.name)
    << " (cvtplant FMU)</title></head><body>\n"
    << "<h1>" << html_escape(r.name) << "</h1>\n<p>" << html_escape(description_of(r)) << "</p>\n"
    << "<p>FMI " << (r.fmi_version == 3 ? "3.0" : "2.0") << " co-simulation. The plant steps in fixed frames of "
    << num(s.frame_s) << " s (" << s.substeps << " " << method_name(s.method) << " step(s) per frame, "
    << scalar_kind_name(s.scalar)
    << "); a communication step must be a whole number of frames, else doStep returns an error and logs why. "
       "Inputs are held over each frame (zero-order hold). Outputs are the plant's after the last step: they do not "
       "depend on inputs set since (no direct feedthrough).</p>\n"
    << "<h2>Faults</h2>\n<p>The plant's watchdog (speed beyond its range, non-finite or saturated states, "
       "unexplained energy growth, ...) makes doStep return an error with a logged message naming the fault. The "
       "plant keeps its last good state: the outputs stay readable and <code>fault</code> names the fault. Restore "
       "an earlier FMU state (get/set or serialised) or reset the instance to go on.</p>\n"
    << "<h2>Variables</h2>\n<table border=\"1\" cellpadding=\"3\">\n"
       "<tr><th>name</th><th>value reference</th><th>causality</th><th>unit</th><th>start</th><th>range</th>"
       "<th>description</th></tr>\n";
  for (const Variable& v : m.vars) {
    o << "<tr><td><code>" << v.name << "</code></td><td>" << v.vr << "</td><td>" << causality_name(v.causality)
      << "</td><td>" << (v.unit != nullptr ? v.unit : "") << "</td><td>";
    if (v.has_start) o << (v.type == VarType::boolean ? (v.start != 0 ? "true" : "false") : num(v.start));
    o << "</td><td>";
    if (v.type == VarType::float64 && (v.min != -kNoBound || v.max != kNoBound))
      o << "[" << (v.min == -kNoBound ? "-inf" : num(v.min)) << ", " << (v.max == kNoBound ? "inf" : num(v.max))
        << "]";
    o << "</td><td>" << html_escape(v.description) << "</td></tr>\n";
  }
  o << "</table>\n<h2>Not offered</h2>\n<p>Model exchange, scheduled execution, event mode, clocks, intermediate "
       "updates and early return, directional and adjoint derivatives, output derivatives, input interpolation: the "
       "plant is a fixed-step frame stepper whose watchdog, actuators and end stops act per frame.</p>\n"
    << "<p>sources/ builds the same binary for another platform: see sources/buildDescription.xml"
    << (r.fmi_version == 3 ? "" : " (FMI 3.0 FMUs)") << " and sources/CMakeLists.txt.</p>\n</body></html>\n";
  return o.str();
}

struct ZipCloser {
  void operator()(zip_t* z) const {
    if (z != nullptr) zip_discard(z);
  }
};

}  // namespace

std::string model_identifier(const std::string& scene_name) {
  std::string id = "cvtplant_";
  for (char c : scene_name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    id += ok ? c : '_';
  }
  return id;
}

std::vector<FmuFile> generated_files(const PackageRequest& r) {
  if (r.fmi_version != 2 && r.fmi_version != 3) throw PackageError("FMI version 2 or 3");
  const Model m = model_of(r);
  std::vector<FmuFile> f;
  f.push_back({"modelDescription.xml", r.fmi_version == 3 ? fmi3_description(r, m) : fmi2_description(r, m)});
  f.push_back({"resources/scene.txt", m.scene_text});
  f.push_back({"documentation/index.html", documentation(r, m)});
  f.push_back({"sources/CMakeLists.txt", cmake_lists(r, m)});
  for (std::size_t i = 0; i < std::size(kSources); ++i)
    f.push_back({std::string("sources/") + kSources[i], sources_unit(r, kSourceOf[i])});
  if (r.fmi_version == 3) f.push_back({"sources/buildDescription.xml", build_description(m)});
  return f;
}

PackageSummary write_fmu(const PackageRequest& r, const std::string& out) {
  const Model m = model_of(r);
  const std::vector<FmuFile> files = generated_files(r);
  PackageSummary sum;
  sum.model_identifier = m.id;
  sum.token = m.token;
  sum.binary_path = std::string("binaries/") + (r.fmi_version == 3 ? "x86_64-linux/" : "linux64/") + m.id + ".so";
  for (const Variable& v : m.vars) {
    ++sum.variables;
    sum.inputs += v.causality == Causality::input;
    sum.outputs += v.causality == Causality::output;
    sum.parameters += v.causality == Causality::parameter;
  }

  zip_error_t zerr;
  zip_error_init(&zerr);
  const std::size_t payload_size = static_cast<std::size_t>(cvt_fmu_payload_end - cvt_fmu_payload_begin);
  zip_source_t* psrc = zip_source_buffer_create(cvt_fmu_payload_begin, payload_size, 0, &zerr);
  if (psrc == nullptr) throw PackageError("the embedded payload cannot be read");
  std::unique_ptr<zip_t, ZipCloser> payload(zip_open_from_source(psrc, ZIP_RDONLY, &zerr));
  if (!payload) {
    zip_source_free(psrc);
    throw PackageError("the embedded payload is not a zip");
  }
  int err = 0;
  const std::string tmp = out + ".tmp-cvtplant";
  std::remove(tmp.c_str());
  std::unique_ptr<zip_t, ZipCloser> z(zip_open(tmp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err));
  if (!z) throw PackageError("cannot create " + tmp);
  auto added = [&](zip_int64_t idx, const std::string& name) {
    if (idx < 0) throw PackageError("cannot add " + name + ": " + zip_strerror(z.get()));
    zip_file_set_mtime(z.get(), static_cast<zip_uint64_t>(idx), 315619200, 0);
  };
  for (const FmuFile& f : files) {
    zip_source_t* s = zip_source_buffer(z.get(), f.text.data(), f.text.size(), 0);
    if (s == nullptr) throw PackageError("out of memory");
    const zip_int64_t idx = zip_file_add(z.get(), f.path.c_str(), s, ZIP_FL_ENC_UTF_8);
    if (idx < 0) zip_source_free(s);
    added(idx, f.path);
  }
  const zip_int64_t n = zip_get_num_entries(payload.get(), 0);
  bool have_binary = false;
  for (zip_int64_t i = 0; i < n; ++i) {
    const std::string name = zip_get_name(payload.get(), static_cast<zip_uint64_t>(i), ZIP_FL_ENC_RAW);
    std::string target;
    if (name == "binary/cvtplant_fmu.so") {
      target = sum.binary_path;
      have_binary = true;
    } else if (name.rfind("sources/", 0) == 0) {
      target = name;
    } else if (name.rfind("licenses/", 0) == 0) {
      target = "documentation/" + name;
    } else {
      continue;
    }
    // The compressed bytes as they are: nothing is inflated and deflated again.
    zip_source_t* s = zip_source_zip(z.get(), payload.get(), static_cast<zip_uint64_t>(i), ZIP_FL_COMPRESSED, 0, -1);
    if (s == nullptr) throw PackageError("cannot copy " + name + " from the payload");
    const zip_int64_t idx = zip_file_add(z.get(), target.c_str(), s, ZIP_FL_ENC_UTF_8);
    if (idx < 0) zip_source_free(s);
    added(idx, target);
  }
  if (!have_binary) throw PackageError("the embedded payload has no binary");
  zip_t* raw = z.release();
  if (zip_close(raw) != 0) {
    const std::string why = zip_strerror(raw);
    zip_discard(raw);
    std::remove(tmp.c_str());
    throw PackageError("cannot write " + out + ": " + why);
  }
  if (std::rename(tmp.c_str(), out.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw PackageError("cannot write " + out);
  }
  if (std::FILE* f = std::fopen(out.c_str(), "rb")) {
    std::fseek(f, 0, SEEK_END);
    sum.bytes = static_cast<std::size_t>(std::ftell(f));
    std::fclose(f);
  }
  return sum;
}

}  // namespace cvt::fmu
