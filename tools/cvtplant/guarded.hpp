#pragma once
// A subcommand body run with the offline modules' errors turned into the
// command line's exit codes (docs/cli.md): their bad-input errors exit 2,
// their failed runs exit 1.
#include <stdexcept>

#include "commands.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/validation/errors.hpp"

namespace cvtcli {

template <class F>
int guarded(F&& body) {
  try {
    return body();
  } catch (const cvt::validation::InputError& e) {
    throw UsageError{e.what()};
  } catch (const cvt::validation::RunError& e) {
    throw RunError{e.what()};
  } catch (const cvt::analysis::InputError& e) {
    throw UsageError{e.what()};
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  } catch (const std::runtime_error& e) {
    throw RunError{e.what()};
  }
}

}  // namespace cvtcli
