// The scene's parameter rows (scene/scene_params.hpp), which are the FMU's
// parameters, against validate_scene and the scene-file reader: a row's
// declared range is the one validation holds, and its name is a key a scene
// file takes (docs/fmu.md#variables).
#include <doctest/doctest.h>

#include <pugixml.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_params.hpp"
#include "importer.hpp"

namespace {

// A valid scene on which the row applies.
cvt::Scene scene_for(const cvt::SceneParamInfo& p) {
  namespace f = cvt::rom_feature;
  cvt::Scene s = *cvt::find_builtin_scene("ratio-control");  // axial, road load, wedging
  if ((p.features & (f::tension | f::polygon | f::deformation)) != 0u) {
    s = *cvt::find_builtin_scene("clamp-step");  // axial, road load
    if ((p.features & f::tension) != 0u) s = *cvt::find_builtin_scene("seed-case1");  // tension, fixed sheaves
    s.features |= p.features;
    s.substeps = 8;  // polygon: resolve the link passing
  }
  if (p.law == cvt::SceneParamLaw::case2) s.params.friction = cvt::friction_presets::table2_case2<double>();
  if (p.law == cvt::SceneParamLaw::case1) s.params.friction = cvt::friction_presets::table2_case1<double>();
  REQUIRE(cvt::scene_param_applies(p, s));
  const cvt::SceneIssue base = cvt::validate_scene(s);
  REQUIRE_MESSAGE(base.ok, base.field << ": " << base.message);
  return s;
}

// The validate_scene field that names the row.
std::string field_of(const cvt::SceneParamInfo& p) {
  const std::string n = p.name;
  if (n == "params.beta0_rad") return "beta0_deg";
  if (n.rfind("initial.", 0) == 0) return "initial";
  return n.substr(n.find('.') + 1);
}

// Rows whose declared bound is the widest of a range that depends on other
// values (their own comment in scene_params.hpp), or whose field validation
// also checks against others (beta0 with wedging or tension, the ripple's
// amplitude): only the outside is checked.
const std::set<std::string> kDependent = {"params.center_distance_m", "friction.a", "params.pitch_m",
                                          "params.beta0_rad", "params.ripple_gain",
                                          "params.radial_travel_m",   "initial.omega1_rad_s",
                                          "initial.omega2_rad_s",     "initial.radius_offset_m"};

}  // namespace

TEST_SUITE("scene_params") {
  TEST_CASE("each row's range is the one validate_scene holds") {
    int checked = 0;
    for (const cvt::SceneParamInfo& p : cvt::kSceneParams) {
      if (p.kind == cvt::SceneParamKind::flag) continue;
      INFO(p.name);
      const cvt::Scene base = scene_for(p);
      const std::string field = field_of(p);
      auto issue_at = [&](double v) {
        cvt::Scene s = base;
        p.set(s, v);
        if (v == v) CHECK(p.get(s) == v);  // the row reads what it wrote
        return cvt::validate_scene(s);
      };
      auto refused = [&](double v) {
        const cvt::SceneIssue i = issue_at(v);
        INFO("value " << v << ": " << (i.ok ? "accepted" : i.field));
        CHECK(!i.ok);
        CHECK(field == i.field);
      };
      auto not_refused = [&](double v) {
        const cvt::SceneIssue i = issue_at(v);
        INFO("value " << v << ": " << (i.ok ? "accepted" : std::string(i.field) + ": " + i.message));
        CHECK((i.ok || field != i.field));
      };
      for (int side = 0; side < 2; ++side) {
        const double bound = side == 0 ? p.min : p.max;
        if (!std::isfinite(bound)) continue;
        const bool open = side == 0 ? p.min_open : p.max_open;
        const double outward = side == 0 ? -INFINITY : INFINITY;
        const double outside = open ? bound : std::nextafter(bound, outward);
        refused(outside);
        if (kDependent.count(p.name) == 0) not_refused(open ? std::nextafter(bound, -outward) : bound);
        ++checked;
      }
      // Non-finite values never pass (validation, or the FMU's own check).
      if (std::isfinite(p.min) || std::isfinite(p.max)) refused(NAN);
    }
    CHECK(checked >= 60);
  }

  TEST_CASE("every row is a scene-file key; the FMU's parameters start at the file's values") {
    const std::string dir = fmutest::temp_dir("fmu-params");
    const cvt::Scene* s = cvt::find_builtin_scene("ratio-control");
    const std::string file = dir + "/all.toml";
    {
      std::ofstream o(file);
      o << "base = \"ratio-control\"\nname = \"all-keys\"\n";
      std::string table;
      for (const cvt::SceneParamInfo& p : cvt::kSceneParams) {
        std::string name = p.name;
        const std::string t = name.substr(0, name.find('.'));
        std::string key = name.substr(name.find('.') + 1);
        double v = p.get(*s);
        if (key == "beta0_rad") {
          key = "beta0_deg";
          v = v * 180.0 / 3.14159265358979323846;
        }
        if (t != table) o << "[" << (table = t) << "]\n";
        char buf[48];
        std::snprintf(buf, sizeof buf, "%.17g", v);
        if (p.kind == cvt::SceneParamKind::flag) o << key << " = " << (v != 0 ? "true" : "false") << "\n";
        else o << key << " = " << (std::strchr(buf, '.') || std::strchr(buf, 'e') ? buf : std::string(buf) + ".0") << "\n";
      }
    }
    const std::string out = dir + "/all.fmu";
    REQUIRE(fmutest::run(fmutest::cvtplant() + " fmu --scene " + file + " --out " + out + " > " + dir + "/out.txt 2>&1") == 0);
    const fmutest::Unpacked fmu(out, dir + "/unpacked");
    int compared = 0;
    for (pugi::xml_node v : fmu.md.child("fmiModelDescription").child("ModelVariables").children("Float64")) {
      if (std::string(v.attribute("causality").value()) != "parameter") continue;
      const std::string name = v.attribute("name").value();
      for (const cvt::SceneParamInfo& p : cvt::kSceneParams)
        if (name == p.name) {
          INFO(name);
          if (name == "params.beta0_rad") CHECK(v.attribute("start").as_double() == doctest::Approx(p.get(*s)).epsilon(1e-15));
          else CHECK(v.attribute("start").as_double() == p.get(*s));
          ++compared;
        }
    }
    CHECK(compared >= 35);
  }
}
