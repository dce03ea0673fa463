// libFuzzer target for the scene-file reader (docs/cli.md#fuzzing): TOML
// syntax (toml++, compiled into the target so the parser is instrumented
// too), the field readers and cvt::validate_scene. Properties checked on
// every input, beyond "no crash, no sanitizer report, no hang":
//  - the reader either accepts the document or throws UsageError, never any
//    other exception;
//  - a refusal is one line, names the input ("<fuzz>:LINE: ..." or "--scene:
//    ...") and never echoes more than a bounded part of the input;
//  - an accepted scene passes validate_scene again and has a positive,
//    bounded frame count and finite profile bounds, and its name follows the
//    one rule for names that become file names (docs/cli.md#names).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "commands.hpp"
#include "scene_file.hpp"
#include "cvtplant/files/names.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace {

[[noreturn]] void violated() { __builtin_trap(); }

// Quoted input is cut to 200 characters (options.cpp), the line number and
// the field name add little: a message far longer echoes the input.
constexpr std::size_t kMaxMessage = 2048;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* in, size_t n) {
  if (n > cvtcli::kMaxSceneFileBytes) return -1;  // the file reader refuses these before parsing
  const std::string text(reinterpret_cast<const char*>(in), n);
  try {
    const auto loaded = cvtcli::parse_scene_text(text, "<fuzz>");
    const cvt::Scene& s = loaded->scene;
    if (!cvt::validate_scene(s).ok) violated();
    if (!cvt::files::name_problem(loaded->name).empty()) violated();
    const long frames = cvt::scene_frames(s);
    if (frames < 1 || frames > 1000000000000L) violated();
    for (const cvt::Profile* p : {&s.tau_in, &s.tau_load, &s.clamp}) {
      const double b = cvt::profile_bound(*p);
      if (!(b >= 0 && b < 1.8e308)) violated();
    }
  } catch (const cvtcli::UsageError& e) {
    if (e.message.empty() || e.message.size() > kMaxMessage) violated();
    if (e.message.find('\n') != std::string::npos) violated();
    if (e.message.rfind("<fuzz>", 0) != 0 && e.message.rfind("--scene", 0) != 0) violated();
  } catch (...) {
    violated();
  }
  return 0;
}
