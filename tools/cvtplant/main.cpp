// The offline front door: `cvtplant <subcommand> ...` (docs/cli.md).
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <vector>

#include "commands.hpp"
#include "cvtplant/files/interrupt.hpp"
#include "cvtplant/files/paths.hpp"
#include "cvtplant/files/replace.hpp"
#include "io_util.hpp"
#include "options.hpp"
#include "registry.hpp"

namespace {

// Edit distance, for "did you mean" on a mistyped subcommand.
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// A word where a subcommand is expected that names none: the message lists
// them and suggests the nearest. Empty if the command line is fine here.
std::string unknown_subcommand(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string where = "cvtplant";
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') return {};
    const auto subs = level->get_subcommands([](CLI::App*) { return true; });
    if (subs.empty()) return {};
    CLI::App* next = nullptr;
    std::string names, best;
    std::size_t best_d = 1000;
    for (CLI::App* s : subs) {
      if (s->get_name() == word) next = s;
      names += (names.empty() ? "" : ", ") + s->get_name();
      const std::size_t d = distance(word.substr(0, 64), s->get_name());
      if (d < best_d) best_d = d, best = s->get_name();
    }
    if (next == nullptr) {
      std::string msg = where + ": error: unknown subcommand " + cvtcli::quoted(word);
      if (best_d <= 2 || (best.size() > 4 && best.rfind(word.substr(0, 3), 0) == 0 && word.size() >= 3))
        msg += " (did you mean '" + best + "'?)";
      return msg + "; subcommands: " + names;
    }
    level = next;
    where += " " + word;
  }
  return {};
}

// Data written to stdout must have reached it: a closed pipe or a full disk
// fails the run (exit 1) instead of passing silently. A run that already
// failed (exit 1) has said so once.
int finish_stdout(const std::string& where, int code) {
  cvtcli::output_ok(stdout);
  errno = 0;
  std::cout.flush();
  const bool bad = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout.good();
  if (bad && code != 1) {
    std::fprintf(stderr, "%s: failed: writing to stdout failed: %s\n", where.c_str(),
                 cvtcli::write_error_reason(errno).c_str());
    return 1;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // A reader that closes the pipe early (`| head`) makes writes fail with
  // EPIPE, which the run reports, instead of killing the process silently.
  std::signal(SIGPIPE, SIG_IGN);
  // SIGINT and SIGTERM stop a long run between rows, with its summary
  // (docs/cli.md#interruption); a second one ends the process at once.
  cvt::files::catch_interrupts();

  CLI::App app{"cvtplant: CVT plant models, scenes and nonlinear analysis (offline tools)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cvtplant 0.1.0");

  std::vector<std::pair<CLI::App*, cvtcli::Action>> actions;
  for (const cvtcli::Registrar reg : cvtcli::registrars()) {
    cvtcli::Action act = reg(app);
    actions.emplace_back(app.get_subcommands({}).back(), std::move(act));
  }

  if (const std::string msg = unknown_subcommand(app, argc, argv); !msg.empty()) {
    std::fprintf(stderr, "%s\n", msg.c_str());
    return 2;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return finish_stdout("cvtplant", app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return finish_stdout("cvtplant", app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return finish_stdout("cvtplant", app.exit(e));
  } catch (const CLI::ParseError& e) {
    // One line, exit 2, whatever CLI11's own code would be (docs/cli.md).
    std::string where = "cvtplant";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      where += " " + sub->get_name();
    }
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "%s: error: %s (see --help)\n", where.c_str(), what.c_str());
    return 2;
  }

  for (auto& [sub, act] : actions) {
    if (!sub->parsed()) continue;
    std::string where = "cvtplant " + sub->get_name();
    const CLI::App* leaf = sub;
    for (const CLI::App* s = sub; !s->get_subcommands().empty();) {
      s = s->get_subcommands().front();
      where += " " + s->get_name();
      leaf = s;
    }
    int code = 1;
    try {
      code = act();
    } catch (const cvtcli::UsageError& e) {
      std::fprintf(stderr, "%s: error: %s\n", where.c_str(), e.message.c_str());
      code = 2;
    } catch (const cvtcli::RunError& e) {
      std::fprintf(stderr, "%s: failed: %s\n", where.c_str(), e.message.c_str());
      code = 1;
    } catch (const cvtcli::Interrupted& e) {
      // Whole rows are written and flushed; the summary says "interrupted".
      if (!e.summary_written) {
        const CLI::Option* json = leaf->get_option_no_throw("--json");
        if (json != nullptr && json->count() > 0)
          cvtcli::print_json({{"subcommand", where.substr(std::string("cvtplant ").size())},
                              {"status", "interrupted"},
                              {"interrupted_at", e.at}});
      }
      std::fprintf(stderr, "%s: interrupted at %s (%s)\n", where.c_str(), e.at.c_str(),
                   cvt::files::interrupt_signal_name());
      code = cvt::files::interrupted_exit_status();
    } catch (const cvt::files::PathError& e) {
      std::fprintf(stderr, "%s: error: %s\n", where.c_str(), e.what());
      code = 2;
    } catch (const cvt::files::WriteError& e) {
      std::fprintf(stderr, "%s: failed: %s\n", where.c_str(), e.what());
      code = 1;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "%s: failed: out of memory (lower the run's size, see --max-memory-mb)\n", where.c_str());
      code = 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: internal error: %s\n", where.c_str(), e.what());
      code = 1;
    }
    return finish_stdout(where, code);
  }
  return 2;
}
