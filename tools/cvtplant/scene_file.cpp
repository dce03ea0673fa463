#include "scene_file.hpp"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <type_traits>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "cvtplant/files/names.hpp"
#include "cvtplant/friction/friction_fields.hpp"
#include "cvtplant/plant/rom_features.hpp"
#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"

namespace cvtcli {

namespace {

// The value of `name` in a table of named values, into out; false if none.
template <class E, std::size_t N>
bool named_value(const cvt::NamedValue<E> (&table)[N], const std::string& name, E& out) {
  for (const auto& e : table)
    if (name == e.name) {
      out = e.value;
      return true;
    }
  return false;
}

// "a, b, c": the names of such a table, for messages.
template <class E, std::size_t N>
std::string names_of(const cvt::NamedValue<E> (&table)[N]) {
  std::string s;
  for (const auto& e : table) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

// The features' names are the plant's (plant/rom_features.hpp).
using FeatureName = cvt::RomFeatureName;
constexpr const FeatureName (&kFeatureNames)[std::size(cvt::kRomFeatureNames)] = cvt::kRomFeatureNames;
constexpr FeatureName kLogNames[] = {{"torques", cvt::rom_log::torques},
                                     {"friction", cvt::rom_log::friction},
                                     {"ratios", cvt::rom_log::ratios},
                                     {"energy", cvt::rom_log::energy},
                                     {"states", cvt::rom_log::states},
                                     {"tension", cvt::rom_log::tension}};

// Reads one TOML document into a Scene, remembering where every key was.
class Reader {
 public:
  Reader(std::string path, const toml::table& root) : path_(std::move(path)), root_(root) {}

  [[noreturn]] void fail(const toml::source_region& where, const std::string& field, const std::string& why) const {
    throw UsageError{path_ + ":" + std::to_string(where.begin.line) + ": " + field + ": " + why};
  }
  [[noreturn]] void fail_field(const std::string& field, const std::string& why) const {
    const auto it = lines_.find(field);
    const long line = it == lines_.end() ? 1 : it->second;
    throw UsageError{path_ + ":" + std::to_string(line) + ": " + field + ": " + why};
  }

  // Rejects keys this reader does not know (a typo must not be ignored).
  void check_known(const toml::table& t, const std::string& prefix, const std::set<std::string>& known) const {
    for (const auto& [k, node] : t) {
      const std::string key(k.str());
      if (known.count(key) == 0) fail(node.source(), quoted(prefix + key), "unknown field");
    }
  }

  double number(const toml::table& t, const std::string& prefix, const char* key, double fallback) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    lines_[key] = n->source().begin.line;
    lines_[prefix + key] = n->source().begin.line;
    if (const auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
      if (!std::isfinite(*v)) fail(n->source(), prefix + key, "must be finite");
      return *v;
    }
    fail(n->source(), prefix + key, "expected a number");
  }
  bool boolean(const toml::table& t, const std::string& prefix, const char* key, bool fallback) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    lines_[prefix + key] = n->source().begin.line;
    if (!n->is_boolean()) fail(n->source(), prefix + key, "expected true or false");
    return *n->value<bool>();
  }
  std::string text(const toml::table& t, const std::string& prefix, const char* key, const std::string& fallback) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    lines_[prefix + key] = n->source().begin.line;
    if (!n->is_string()) fail(n->source(), prefix + key, "expected a string");
    return *n->value<std::string>();
  }
  const toml::table* table(const toml::table& t, const std::string& prefix, const char* key) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return nullptr;
    lines_[prefix + key] = n->source().begin.line;
    if (!n->is_table()) fail(n->source(), prefix + key, "expected a table [" + prefix + key + "]");
    return n->as_table();
  }
  std::uint32_t name_list(const toml::table& t, const char* key, const FeatureName* names, int count,
                          std::uint32_t fallback) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    lines_[key] = n->source().begin.line;
    if (!n->is_array()) fail(n->source(), key, "expected an array of names");
    std::uint32_t bits = 0;
    for (const toml::node& e : *n->as_array()) {
      if (!e.is_string()) fail(e.source(), key, "expected an array of names");
      const std::string s = *e.value<std::string>();
      bool found = false;
      for (int i = 0; i < count; ++i)
        if (s == names[i].name) {
          bits |= names[i].bit;
          found = true;
        }
      if (!found) {
        std::string all;
        for (int i = 0; i < count; ++i) all += std::string(i ? ", " : "") + names[i].name;
        fail(e.source(), key, "unknown name " + quoted(s) + " (known: " + all + ")");
      }
    }
    return bits;
  }

  cvt::Profile profile(const toml::table& inputs, const char* key, const cvt::Profile& fallback) {
    const std::string prefix = std::string("inputs.") + key + ".";
    const toml::node* n = inputs.get(key);
    if (n == nullptr) return fallback;
    lines_[key] = n->source().begin.line;
    lines_[std::string("inputs.") + key] = n->source().begin.line;
    if (n->is_integer() || n->is_floating_point()) return cvt::constant_profile(number(inputs, "inputs.", key, 0));
    if (!n->is_table()) fail(n->source(), std::string("inputs.") + key, "expected a number or a table");
    const toml::table& t = *n->as_table();
    const std::string kind = text(t, prefix, "kind", "constant");
    cvt::Profile p;
    if (kind == "constant") {
      check_known(t, prefix, {"kind", "value"});
      p = cvt::constant_profile(number(t, prefix, "value", 0));
    } else if (kind == "step") {
      check_known(t, prefix, {"kind", "before", "after", "t_s"});
      p = cvt::step_profile(number(t, prefix, "before", 0), number(t, prefix, "after", 0), number(t, prefix, "t_s", 0));
    } else if (kind == "ramp") {
      check_known(t, prefix, {"kind", "from", "to", "t0_s", "t1_s"});
      p = cvt::ramp_profile(number(t, prefix, "from", 0), number(t, prefix, "to", 0), number(t, prefix, "t0_s", 0),
                            number(t, prefix, "t1_s", 0));
    } else if (kind == "sine") {
      check_known(t, prefix, {"kind", "offset", "amplitude", "freq_hz", "t0_s"});
      p = cvt::sine_profile(number(t, prefix, "offset", 0), number(t, prefix, "amplitude", 0),
                            number(t, prefix, "freq_hz", 0), number(t, prefix, "t0_s", 0));
    } else if (kind == "table") {
      check_known(t, prefix, {"kind", "t_s", "value"});
      p.kind = cvt::ProfileKind::table;
      const toml::array* ts = t.get_as<toml::array>("t_s");
      const toml::array* vs = t.get_as<toml::array>("value");
      if (ts == nullptr || vs == nullptr) fail(t.source(), prefix + "t_s", "a table needs arrays t_s and value");
      lines_[prefix + "t_s"] = ts->source().begin.line;
      if (ts->size() != vs->size()) fail(vs->source(), prefix + "value", "t_s and value must have the same length");
      if (ts->size() < 1 || ts->size() > static_cast<std::size_t>(cvt::kMaxProfilePoints))
        fail(ts->source(), prefix + "t_s", "a table needs 1..16 points");
      p.n = static_cast<int>(ts->size());
      for (int i = 0; i < p.n; ++i) {
        const auto a = (*ts)[static_cast<std::size_t>(i)].value<double>();
        const auto b = (*vs)[static_cast<std::size_t>(i)].value<double>();
        if (!a || !b) fail(ts->source(), prefix + "t_s", "table entries must be numbers");
        p.t_s[i] = *a;
        p.v[i] = *b;
      }
    } else {
      fail(t.source(), prefix + "kind", "unknown profile kind " + quoted(kind) + " (constant, step, ramp, sine, table)");
    }
    lines_[std::string(key)] = t.source().begin.line;
    return p;
  }

  // The key of a row of scene/scene_params.hpp (the one list of the scene's
  // parameter keys) in table `table` ("params", "friction", "initial"), or
  // "" for another table's row. beta0 is the one key in other units: the
  // file takes degrees.
  static std::string row_key(const cvt::SceneParamInfo& r, const std::string& table) {
    const std::string name = r.name;
    if (name.compare(0, table.size() + 1, table + ".") != 0) return "";
    const std::string key = name.substr(table.size() + 1);
    return key == "beta0_rad" ? "beta0_deg" : key;
  }

  // Every row of `table` that t sets, into s; `also`: the table's keys that
  // are not rows, read by the caller before the rows.
  void rows(const toml::table& t, const std::string& table, cvt::Scene& s, std::set<std::string> also = {}) {
    const std::string pre = table + ".";
    for (const cvt::SceneParamInfo& r : cvt::kSceneParams)
      if (const std::string key = row_key(r, table); !key.empty()) also.insert(key);
    check_known(t, pre, also);
    if (table == "friction") friction_choices(t, s.params.friction);
    for (const cvt::SceneParamInfo& r : cvt::kSceneParams) {
      const std::string key = row_key(r, table);
      if (key.empty()) continue;
      if (r.kind == cvt::SceneParamKind::flag)
        r.set(s, boolean(t, pre, key.c_str(), r.get(s) != 0.0) ? 1.0 : 0.0);
      else if (key == "beta0_deg")
        r.set(s, number(t, pre, key.c_str(), r.get(s) / cvt::kDegToRad) * cvt::kDegToRad);
      else
        r.set(s, number(t, pre, key.c_str(), r.get(s)));
    }
  }

  // [friction]'s keys that are not numbers: a preset (applied first), the
  // law and the sign function, by name.
  void friction_choices(const toml::table& t, cvt::FrictionParams<double>& f) {
    const std::string pre = "friction.";
    if (const toml::node* n = t.get("preset")) {
      const std::string preset = text(t, pre, "preset", "");
      if (!preset.empty() && !named_value(cvt::kFrictionPresetNames, preset, f))
        fail(n->source(), pre + "preset", "unknown preset " + quoted(preset) + " (" + names_of(cvt::kFrictionPresetNames) + ")");
    }
    choice(t, "law", f.law);
    choice(t, "sign", f.sign);
  }
  template <class E>
  void choice(const toml::table& t, const char* key, E& value) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return;
    const std::string name = text(t, "friction.", key, "");
    if (!name.empty() && !named_value(value_names(value), name, value))
      fail(n->source(), std::string("friction.") + key,
           "unknown " + std::string(key) + " " + quoted(name) + " (" + names_of(value_names(value)) + ")");
  }

  // A parameter file (`cvtplant calibrate --out`): [params] only, applied to s.
  void read_params_only(cvt::Scene& s) {
    check_known(root_, "", {"params"});
    // A file without values would leave the plant as it is without a word:
    // almost surely the wrong file.
    const toml::table* t = table(root_, "", "params");
    if (t == nullptr) fail(root_.source(), "params", "no [params] table: not a parameter file");
    if (t->empty()) fail(t->source(), "params", "the [params] table is empty");
    rows(*t, "params", s);
    const cvt::SceneIssue issue = cvt::validate_scene(s);
    if (!issue.ok) fail_field(field_key(issue.field), issue.message);
  }

  void read(LoadedScene& out) {
    cvt::Scene& s = out.scene;
    check_known(root_, "", {"name", "summary", "base", "features", "t_end_s", "frame_s", "substeps", "integrator",
                            "energy_ledger", "scalar", "log", "params", "friction", "initial", "inputs",
                            "reference_set"});
    const std::string base = text(root_, "", "base", "");
    if (!base.empty()) {
      const cvt::Scene* b = cvt::find_builtin_scene(base.c_str());
      if (b == nullptr) fail(root_.get("base")->source(), "base", "no built-in scene " + quoted(base) + " (see cvtplant scenes)");
      s = *b;
      out.reference_set = b->reference_set;
    }
    out.name = text(root_, "", "name", base.empty() ? std::string("unnamed") : base);
    // The name becomes file names (validate's DIR/NAME.csv) and report
    // headings: one rule for it (docs/cli.md#names).
    if (const std::string why = cvt::files::name_problem(out.name); !why.empty())
      fail_field("name", cvtcli::quoted(out.name) + ": " + why);
    out.summary = text(root_, "", "summary", "");
    for (const char c : out.summary)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        fail_field("summary", "holds a control character (a summary is one line)");
    // The reference's parameter set (docs/validation.md#parameter-sets).
    out.reference_set = text(root_, "", "reference_set", out.reference_set);
    // The names of cvt::mbd::parameter_set_by_name (this reader links no
    // reference; `validate` maps the name through it).
    if (out.reference_set != "seed" && out.reference_set != "production")
      fail_field("reference_set", "unknown parameter set " + cvtcli::quoted(out.reference_set) + " (seed, production)");
    s.features = name_list(root_, "features", kFeatureNames, static_cast<int>(std::size(kFeatureNames)), s.features);
    s.log = name_list(root_, "log", kLogNames, static_cast<int>(std::size(kLogNames)), s.log);
    s.t_end_s = number(root_, "", "t_end_s", s.t_end_s);
    s.frame_s = number(root_, "", "frame_s", s.frame_s);
    const double sub = number(root_, "", "substeps", s.substeps);
    if (sub != std::floor(sub) || sub < 1 || sub > 10000) fail_field("substeps", "must be an integer in 1..10000");
    s.substeps = static_cast<int>(sub);
    const std::string integ = text(root_, "", "integrator", cvt::method_name(s.method));
    if (!cvt::parse_method(integ.c_str(), s.method))
      fail_field("integrator", "unknown method " + quoted(integ) +
                                   " (euler, semi-implicit-euler, heun, rk4, linear-implicit-euler, ros2)");
    s.energy_ledger = boolean(root_, "", "energy_ledger", s.energy_ledger);
    // Without the ledger the default log leaves out its energy group; a log
    // that names it is refused by validate_scene.
    if (!s.energy_ledger && !root_.contains("log")) s.log &= ~cvt::rom_log::energy;
    const std::string scalar = text(root_, "", "scalar", cvt::scalar_kind_name(s.scalar));
    if (scalar == "double") s.scalar = cvt::ScalarKind::f64;
    else if (scalar == "float") s.scalar = cvt::ScalarKind::f32;
    else if (scalar == "fixed") s.scalar = cvt::ScalarKind::q16_16;
    else fail_field("scalar", "unknown scalar " + quoted(scalar) + " (double, float, fixed)");

    if (const toml::table* t = table(root_, "", "params")) rows(*t, "params", s);
    if (const toml::table* t = table(root_, "", "friction")) rows(*t, "friction", s, {"preset", "law", "sign"});
    if (const toml::table* t = table(root_, "", "initial")) rows(*t, "initial", s);
    if (const toml::table* t = table(root_, "", "inputs")) {
      check_known(*t, "inputs.", {"tau_in", "tau_load", "clamp"});
      s.tau_in = profile(*t, "tau_in", s.tau_in);
      s.tau_load = profile(*t, "tau_load", s.tau_load);
      s.clamp = profile(*t, "clamp", s.clamp);
    }
    const cvt::SceneIssue issue = cvt::validate_scene(s);
    if (!issue.ok) fail_field(field_key(issue.field), issue.message);
  }

 private:
  // validate_scene reports bare keys; map them to the dotted file keys.
  std::string field_key(const std::string& f) const {
    for (const char* pre : {"params.", "friction.", "initial.", "inputs.", ""}) {
      if (lines_.count(pre + f)) return pre + f;
    }
    return f;
  }

  std::string path_;
  const toml::table& root_;
  std::map<std::string, long> lines_;
};

}  // namespace

namespace {

// toml++ reports syntax errors by throwing (tools build with exceptions on);
// a refusal names the file and line.
toml::table parse_toml_text(const std::string& text, const std::string& path) {
  // Scene and parameter files are ASCII: Debian 12's toml++ reaches an
  // unreachable branch (undefined behaviour) when it tests some non-ASCII
  // characters for whitespace (U+00A1..U+0499 among them), found by the
  // scene-file fuzzer. A file with such a byte is refused, naming its line.
  long line = 1;
  for (const char ch : text) {
    if (ch == '\n') ++line;
    if (static_cast<unsigned char>(ch) >= 0x80)
      throw UsageError{path + ":" + std::to_string(line) +
                       ": not ASCII: scene and parameter files are plain ASCII text"};
  }
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw UsageError{path + ":" + std::to_string(e.source().begin.line) + ": syntax: " +
                     quoted(std::string(e.description()), 200)};
  }
}

}  // namespace

void apply_params_file(const std::string& path, cvt::Scene& s) {
  const toml::table root = parse_toml_text(read_input_file(path, kMaxSceneFileBytes, "parameter file"), path);
  Reader r(path, root);
  r.read_params_only(s);
}

std::shared_ptr<LoadedScene> load_scene_file(const std::string& path) {
  return parse_scene_text(read_input_file(path, kMaxSceneFileBytes, "--scene"), path);
}

std::shared_ptr<LoadedScene> parse_scene_text(const std::string& text, const std::string& path) {
  const toml::table root = parse_toml_text(text, path);
  // An empty document would run the all-default scene: almost surely the
  // wrong file (or /dev/null), so it is refused.
  if (root.empty()) throw UsageError{"--scene: " + quoted(path, 200) + " has no keys: not a scene file"};
  auto out = std::make_shared<LoadedScene>();
  Reader r(path, root);
  r.read(*out);
  out->source = path;
  out->scene.name = out->name.c_str();
  out->scene.summary = out->summary.c_str();
  return out;
}

std::shared_ptr<LoadedScene> resolve_scene(const std::string& name_or_path) {
  if (const cvt::Scene* b = cvt::find_builtin_scene(name_or_path.c_str())) {
    auto out = std::make_shared<LoadedScene>();
    out->scene = *b;
    out->name = b->name;
    out->summary = b->summary;
    out->source = "built-in";
    out->reference_set = b->reference_set;
    out->scene.name = out->name.c_str();
    out->scene.summary = out->summary.c_str();
    return out;
  }
  struct stat st {};
  if (::stat(name_or_path.c_str(), &st) != 0)
    throw UsageError{"--scene: " + quoted(name_or_path, 200) +
                     " is neither a built-in scene (see `cvtplant scenes`) nor a readable file"};
  return load_scene_file(name_or_path);
}

void check_scene(const cvt::Scene& s, const LoadedScene& loaded, const std::vector<SceneFlag>& flags) {
  const cvt::SceneIssue issue = cvt::validate_scene(s);
  if (issue.ok) return;
  const std::string field = issue.field;
  const auto flag_of = [&](const std::string& f) -> const SceneFlag* {
    for (const SceneFlag& g : flags)
      if (g.given && f == g.field) return &g;
    return nullptr;
  };
  // The frame must fit in the run: whichever of the two the user set is named.
  if (field == "frame_s" && s.frame_s > s.t_end_s && (flag_of("frame_s") || flag_of("t_end_s"))) {
    const SceneFlag* dt = flag_of("frame_s");
    const SceneFlag* te = flag_of("t_end_s");
    const std::string dt_text = exact_number(s.frame_s) + " s";
    const std::string te_text = exact_number(s.t_end_s) + " s";
    if (dt != nullptr)
      throw UsageError{std::string(dt->flag) + ": " + dt_text + " is above " +
                       (te != nullptr ? std::string(te->flag) + " " + te_text
                                      : "the scene's t_end_s " + te_text + " (scene " + loaded.name + ")") +
                       ": a frame must fit in the run"};
    throw UsageError{std::string(te->flag) + ": " + te_text + " is below the scene's frame_s " + dt_text + " (scene " +
                     loaded.name + "): a frame must fit in the run"};
  }
  if (const SceneFlag* g = flag_of(field))
    throw UsageError{std::string(g->flag) + " " + exact_number(g->value) + ": " + issue.message};
  throw UsageError{"scene " + loaded.name + ": " + field + ": " + issue.message};
}

std::string feature_names(std::uint32_t features) {
  std::string s;
  for (const FeatureName& f : kFeatureNames)
    if (features & f.bit) s += (s.empty() ? "" : ",") + std::string(f.name);
  return s.empty() ? "none" : s;
}

}  // namespace cvtcli
