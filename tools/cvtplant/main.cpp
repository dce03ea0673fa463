// The offline front door: `cvtplant <subcommand> ...` (docs/cli.md).
#include <cstdio>
#include <exception>
#include <vector>

#include "commands.hpp"
#include "registry.hpp"

int main(int argc, char** argv) {
  CLI::App app{"cvtplant: CVT plant models, scenes and nonlinear analysis (offline tools)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cvtplant 0.1.0");

  std::vector<std::pair<CLI::App*, cvtcli::Action>> actions;
  for (const cvtcli::Registrar reg : cvtcli::registrars()) {
    cvtcli::Action act = reg(app);
    actions.emplace_back(app.get_subcommands({}).back(), std::move(act));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, exit 2, whatever CLI11's own code would be (docs/cli.md).
    std::string where = "cvtplant";
    for (auto* sub : app.get_subcommands()) where += " " + sub->get_name();
    std::fprintf(stderr, "%s: error: %s (see --help)\n", where.c_str(), e.what());
    return 2;
  }

  for (auto& [sub, act] : actions) {
    if (!sub->parsed()) continue;
    try {
      return act();
    } catch (const cvtcli::UsageError& e) {
      std::fprintf(stderr, "cvtplant %s: error: %s\n", sub->get_name().c_str(), e.message.c_str());
      return 2;
    } catch (const cvtcli::RunError& e) {
      std::fprintf(stderr, "cvtplant %s: failed: %s\n", sub->get_name().c_str(), e.message.c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cvtplant %s: internal error: %s\n", sub->get_name().c_str(), e.what());
      return 1;
    }
  }
  return 2;
}
