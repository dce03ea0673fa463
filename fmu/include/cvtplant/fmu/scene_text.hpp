#pragma once
// The scene an FMU carries (resources/scene.txt, docs/fmu.md#files): the
// packager writes it from a cvt::Scene, the FMU reads it at instantiation.
// One "key value" per line; numbers as the 16 hex digits of their IEEE-754
// bits, so every value comes back exactly and no locale can change the
// reading. Heap-free both ways (the FMU may run on a target toolchain).
//
//   cvtplant-fmu-scene 1
//   name ratio-control
//   features 19
//   scalar double | float | fixed
//   method ros2
//   substeps 1
//   frame_s 3f50624dd2f1a9fc
//   t_end_s 4024000000000000
//   energy_ledger 1
//   friction.law constant | case1 | case2
//   friction.sign atan | tanh | exact
//   inputs.tau_in ...        (the inputs' start values)
//   params.r1_m ...          (every row of scene/scene_params.hpp)
//   end
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "cvtplant/fmu/variables.hpp"
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_params.hpp"

namespace cvt::fmu {

inline constexpr int kSceneTextVersion = 1;
inline constexpr std::size_t kMaxSceneText = 16384;
inline constexpr std::size_t kMaxSceneName = 96;

namespace scene_text_detail {
inline const char* law_name(FrictionLaw l) {
  return l == FrictionLaw::case1 ? "case1" : l == FrictionLaw::case2 ? "case2" : "constant";
}
inline const char* sign_name(SignFunction f) {
  return f == SignFunction::tanh ? "tanh" : f == SignFunction::exact ? "exact" : "atan";
}
inline std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
inline bool parse_bits(const char* s, double& v) {
  std::uint64_t b = 0;
  int n = 0;
  for (; s[n] != '\0'; ++n) {
    const char c = s[n];
    const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (d < 0 || n >= 16) return false;
    b = (b << 4) | static_cast<std::uint64_t>(d);
  }
  if (n != 16) return false;
  std::memcpy(&v, &b, sizeof v);
  return true;
}
inline bool parse_uint(const char* s, long max, long& v) {
  if (*s == '\0') return false;
  v = 0;
  for (; *s != '\0'; ++s) {
    if (*s < '0' || *s > '9') return false;
    v = v * 10 + (*s - '0');
    if (v > max) return false;
  }
  return true;
}
}  // namespace scene_text_detail

// Writes the scene's text into out (cap bytes); returns its length, or 0 if
// it did not fit or the name has a line break.
inline std::size_t write_scene_text(const Scene& s, const char* name, char* out, std::size_t cap) {
  using namespace scene_text_detail;
  std::size_t n = 0;
  bool ok = std::strchr(name, '\n') == nullptr && std::strlen(name) < kMaxSceneName;
  auto put = [&](const char* fmt, auto... args) {
    if (!ok) return;
    const int k = std::snprintf(out + n, cap - n, fmt, args...);
    if (k < 0 || static_cast<std::size_t>(k) >= cap - n) ok = false;
    else n += static_cast<std::size_t>(k);
  };
  auto real = [&](const char* key, double v) { put("%s %016llx\n", key, static_cast<unsigned long long>(bits_of(v))); };
  put("cvtplant-fmu-scene %d\n", kSceneTextVersion);
  put("name %s\n", name);
  put("features %lu\n", static_cast<unsigned long>(s.features));
  put("scalar %s\n", scalar_kind_name(s.scalar));
  put("method %s\n", method_name(s.method));
  put("substeps %d\n", s.substeps);
  real("frame_s", s.frame_s);
  real("t_end_s", s.t_end_s);
  put("energy_ledger %d\n", s.energy_ledger ? 1 : 0);
  put("friction.law %s\n", law_name(s.params.friction.law));
  put("friction.sign %s\n", sign_name(s.params.friction.sign));
  for (int i = 0; i < input_count; ++i) real(input_name(i), input_start(i, s));
  for (const SceneParamInfo& p : kSceneParams) real(p.name, p.get(s));
  put("%s", "end\n");
  return ok ? n : 0;
}

// The outcome of reading a scene text: ok, or the line and what is wrong.
struct SceneTextIssue {
  bool ok = true;
  int line = 0;
  const char* message = "";
};

// Reads text (n bytes) into s (its inputs as constant profiles at their start
// values) and the name into name (kMaxSceneName bytes). Every key must be
// there exactly once; the scene is not validated here (the FMU does that
// when it builds the plant).
inline SceneTextIssue read_scene_text(const char* text, std::size_t n, Scene& s, char* name) {
  using namespace scene_text_detail;
  constexpr int kFixedKeys = 10;  // the header and "end" apart
  constexpr int kKeys = kFixedKeys + input_count + kSceneParamCount;
  bool seen[kKeys] = {};
  s = Scene{};
  s.log = 0;
  s.name = "";
  s.summary = "";
  name[0] = '\0';
  double inputs[input_count] = {};
  int line = 0;
  bool header = false, end = false;
  std::size_t pos = 0;
  char buf[160];
  auto fail = [&](const char* why) { return SceneTextIssue{false, line, why}; };
  while (pos < n && !end) {
    std::size_t len = 0;
    while (pos < n && text[pos] != '\n') {
      if (len + 1 >= sizeof buf) return SceneTextIssue{false, line + 1, "line too long"};
      buf[len++] = text[pos++];
    }
    if (pos >= n) return SceneTextIssue{false, line + 1, "the last line has no end of line"};
    ++pos;
    ++line;
    buf[len] = '\0';
    if (header && std::strcmp(buf, "end") == 0) {
      end = true;
      continue;
    }
    char* sp = std::strchr(buf, ' ');
    if (sp == nullptr) return fail("expected 'key value'");
    *sp = '\0';
    const char* key = buf;
    const char* val = sp + 1;
    if (!header) {
      long v = 0;
      if (std::strcmp(key, "cvtplant-fmu-scene") != 0 || !parse_uint(val, 1000, v))
        return fail("not a cvtplant FMU scene (header 'cvtplant-fmu-scene N')");
      if (v != kSceneTextVersion) return fail("scene text of another version");
      header = true;
      continue;
    }
    int k = -1;
    long iv = 0;
    double dv = 0;
    if (std::strcmp(key, "name") == 0) {
      k = 0;
      if (std::strlen(val) >= kMaxSceneName) return fail("name too long");
      std::memcpy(name, val, std::strlen(val) + 1);
    } else if (std::strcmp(key, "features") == 0) {
      k = 1;
      if (!parse_uint(val, 0xFFFF, iv)) return fail("features: expected a number");
      s.features = static_cast<std::uint32_t>(iv);
    } else if (std::strcmp(key, "scalar") == 0) {
      k = 2;
      if (std::strcmp(val, "double") == 0) s.scalar = ScalarKind::f64;
      else if (std::strcmp(val, "float") == 0) s.scalar = ScalarKind::f32;
      else if (std::strcmp(val, "fixed") == 0) s.scalar = ScalarKind::q16_16;
      else return fail("scalar: double, float or fixed");
    } else if (std::strcmp(key, "method") == 0) {
      k = 3;
      if (!parse_method(val, s.method)) return fail("method: unknown integrator");
    } else if (std::strcmp(key, "substeps") == 0) {
      k = 4;
      if (!parse_uint(val, 10000, iv)) return fail("substeps: expected a number");
      s.substeps = static_cast<int>(iv);
    } else if (std::strcmp(key, "frame_s") == 0) {
      k = 5;
      if (!parse_bits(val, s.frame_s)) return fail("frame_s: expected 16 hex digits");
    } else if (std::strcmp(key, "t_end_s") == 0) {
      k = 6;
      if (!parse_bits(val, s.t_end_s)) return fail("t_end_s: expected 16 hex digits");
    } else if (std::strcmp(key, "energy_ledger") == 0) {
      k = 7;
      if (!parse_uint(val, 1, iv)) return fail("energy_ledger: 0 or 1");
      s.energy_ledger = iv == 1;
    } else if (std::strcmp(key, "friction.law") == 0) {
      k = 8;
      if (std::strcmp(val, "constant") == 0) s.params.friction.law = FrictionLaw::constant;
      else if (std::strcmp(val, "case1") == 0) s.params.friction.law = FrictionLaw::case1;
      else if (std::strcmp(val, "case2") == 0) s.params.friction.law = FrictionLaw::case2;
      else return fail("friction.law: constant, case1 or case2");
    } else if (std::strcmp(key, "friction.sign") == 0) {
      k = 9;
      if (std::strcmp(val, "atan") == 0) s.params.friction.sign = SignFunction::atan;
      else if (std::strcmp(val, "tanh") == 0) s.params.friction.sign = SignFunction::tanh;
      else if (std::strcmp(val, "exact") == 0) s.params.friction.sign = SignFunction::exact;
      else return fail("friction.sign: atan, tanh or exact");
    } else {
      for (int i = 0; i < input_count && k < 0; ++i)
        if (std::strcmp(key, input_name(i)) == 0) {
          k = kFixedKeys + i;
          if (!parse_bits(val, dv)) return fail("expected 16 hex digits");
          inputs[i] = dv;
        }
      for (int i = 0; i < kSceneParamCount && k < 0; ++i)
        if (std::strcmp(key, kSceneParams[i].name) == 0) {
          k = kFixedKeys + input_count + i;
          if (!parse_bits(val, dv)) return fail("expected 16 hex digits");
          kSceneParams[i].set(s, dv);
        }
      if (k < 0) return fail("unknown key");
    }
    if (seen[k]) return fail("key given twice");
    seen[k] = true;
  }
  if (!header) return SceneTextIssue{false, 1, "empty scene text"};
  if (!end) return SceneTextIssue{false, line, "no 'end' line"};
  for (int k = 0; k < kKeys; ++k)
    if (!seen[k]) return SceneTextIssue{false, line, "a key is missing"};
  s.tau_in = constant_profile(inputs[input_tau_in]);
  s.tau_load = constant_profile(inputs[input_tau_load]);
  s.clamp = constant_profile(inputs[input_clamp]);
  // The driven clamping's start is its set-up value params.driven_clamp_N
  // (input_start); the line is there so every input has one.
  return SceneTextIssue{};
}

}  // namespace cvt::fmu
